#include "arcplan/benchmarks/median_run.h"

#include <fstream>
#include <iomanip>

#include "arcplan/common/error.h"
#include "arcplan/common/text_parsing.h"

namespace arcplan::benchmarks {
namespace {

std::size_t columnIndex(const std::vector<std::string>& header, const std::string& name) {
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i] == name) return i;
  }
  return header.size();
}

}  // namespace

MedianRun readMedianRun(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw Error(file.string() + ": cannot open median-run file");
  MedianRun run;
  run.planner = file.stem().string();
  std::vector<std::string> header;
  std::size_t t = 0, speed = 0, x = 0, q0 = 0;
  bool hasJoints = false;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const auto where = [&] { return file.string() + ":" + std::to_string(number) + ": "; };
    const auto text = trim(line);
    if (text.empty()) continue;
    if (text.front() == '#') {
      const auto colon = text.find(':');
      if (colon != std::string_view::npos) {
        run.notes[std::string(trim(text.substr(1, colon - 1)))] = std::string(trim(text.substr(colon + 1)));
      }
      continue;
    }
    const auto fields = splitFields(text, ',');
    if (header.empty()) {
      for (const auto field : fields) header.emplace_back(trim(field));
      t = columnIndex(header, "t");
      speed = columnIndex(header, "tcp_speed");
      x = columnIndex(header, "x");
      if (t == header.size() || speed == header.size() || x + 2 >= header.size() || header[x + 1] != "y" ||
          header[x + 2] != "z") {
        throw Error(where() + "expected a header with the columns t, tcp_speed, x, y, z");
      }
      q0 = columnIndex(header, "q0");
      hasJoints = q0 + 5 < header.size() && header[q0 + 5] == "q5";
      continue;
    }
    if (fields.size() != header.size()) {
      throw Error(where() + std::to_string(fields.size()) + " fields, expected " + std::to_string(header.size()));
    }
    const auto number_at = [&](std::size_t column) {
      const auto value = parseDouble(trim(fields[column]));
      if (!value)
        throw Error(where() + "column " + header[column] + ": '" + std::string(fields[column]) + "' is not a number");
      return *value;
    };
    run.time.push_back(number_at(t));
    run.tcpSpeed.push_back(number_at(speed));
    run.tcp.emplace_back(number_at(x), number_at(x + 1), number_at(x + 2));
    if (hasJoints) {
      robot::Vector6 q;
      for (int j = 0; j < 6; ++j) q[j] = number_at(q0 + static_cast<std::size_t>(j));
      run.joints.push_back(q);
    }
  }
  if (header.empty()) throw Error(file.string() + ": no header line (expected t, tcp_speed, x, y, z)");
  if (run.time.empty()) throw Error(file.string() + ": no samples after the header");
  return run;
}

void writeMedianRun(std::ostream& out, const MedianRun& run) {
  for (const auto& [key, value] : run.notes) out << "# " << key << ": " << value << "\n";
  const bool joints = !run.joints.empty();
  out << "t,tcp_speed,x,y,z" << (joints ? ",q0,q1,q2,q3,q4,q5" : "") << "\n" << std::setprecision(9);
  for (std::size_t i = 0; i < run.time.size(); ++i) {
    out << run.time[i] << "," << run.tcpSpeed[i] << "," << run.tcp[i].x() << "," << run.tcp[i].y() << ","
        << run.tcp[i].z();
    if (joints) {
      for (int j = 0; j < 6; ++j) out << "," << run.joints[i][j];
    }
    out << "\n";
  }
}

}  // namespace arcplan::benchmarks
