#include "arcplan/trajectory/timed_trajectory.h"

#include <iomanip>

#include "arcplan/common/atomic_file.h"

namespace arcplan::trajectory {

void writeTimedTrajectoryCsv(const std::filesystem::path& file, const TimedTrajectory& trajectory) {
  AtomicOutputFile output(file);
  auto& out = output.stream();
  out << "t";
  for (const char* name : {"q", "qd", "qdd"}) {
    for (int j = 0; j < 6; ++j) out << "," << name << j;
  }
  out << ",tcp_speed,tcp_x,tcp_y,tcp_z\n" << std::setprecision(10);
  for (std::size_t i = 0; i < trajectory.time.size(); ++i) {
    out << trajectory.time[i];
    for (const auto* vector : {&trajectory.position[i], &trajectory.velocity[i], &trajectory.acceleration[i]}) {
      for (int j = 0; j < 6; ++j) out << "," << (*vector)[j];
    }
    const auto& tcp = trajectory.tcpPosition[i];
    out << "," << trajectory.tcpSpeed[i] << "," << tcp.x() << "," << tcp.y() << "," << tcp.z() << "\n";
  }
  output.commit();
}

}  // namespace arcplan::trajectory
