#pragma once
// The plot data a campaign keeps per plot problem (benchmarks/campaign.h): paths/<suite>/<problem>/
// scene.json (obstacles, start and goal TCP, v_max) and <planner>.csv, the planner's median run —
// '#' comment lines ("# run: 3"), a header naming the columns (t, tcp_speed, x, y, z and, from
// campaigns that record them, the joints q0..q5), then one sample per line.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "arcplan/robot/ur_inverse_kinematics.h"

namespace arcplan::report {

struct MedianRun {
  std::string planner;                       // the file name without .csv
  std::map<std::string, std::string> notes;  // comment lines "key: value" ("run" -> "3")
  std::vector<double> time, tcpSpeed;        // s, m/s
  std::vector<Eigen::Vector3d> tcp;          // m
  std::vector<robot::Vector6> joints;        // rad; empty when the file has no q0..q5 columns
};

// Throws arcplan::Error naming the file and line for a missing column or a malformed number.
MedianRun readMedianRun(const std::filesystem::path& file);

}  // namespace arcplan::report
