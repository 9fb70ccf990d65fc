#pragma once
// A planner's median run as a campaign keeps it for its plot problems (campaign.h):
// paths/<suite>/<problem>/<planner>.csv — '#' comment lines ("# run: 3"), a header naming the columns
// (t, tcp_speed, x, y, z and, from campaigns that record them, the joints q0..q5), then one sample
// per line. The one reader and writer of that file, for the campaign, `bench compare` and the report.
#include <filesystem>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "arcplan/robot/ur_inverse_kinematics.h"

namespace arcplan::benchmarks {

struct MedianRun {
  std::string planner;                       // the file name without .csv
  std::map<std::string, std::string> notes;  // comment lines "key: value" ("run" -> "3")
  std::vector<double> time, tcpSpeed;        // s, m/s
  std::vector<Eigen::Vector3d> tcp;          // m
  std::vector<robot::Vector6> joints;        // rad; empty when the file has no q0..q5 columns
};

// Throws arcplan::Error naming the file and line for a missing column or a malformed number.
MedianRun readMedianRun(const std::filesystem::path& file);

// The file's text: the notes as comment lines, the header with q0..q5 when the run has joints, the
// samples with 9 significant digits.
void writeMedianRun(std::ostream& out, const MedianRun& run);

}  // namespace arcplan::benchmarks
