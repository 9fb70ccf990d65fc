#include "arcplan/trajectory/joint_path.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>

#include "arcplan/common/atomic_file.h"
#include "arcplan/common/error.h"
#include "arcplan/common/text_formatting.h"
#include "arcplan/common/text_parsing.h"
#include "arcplan/robot/joint_limits.h"

namespace arcplan::trajectory {
namespace {

constexpr const char* kHeader = "q0,q1,q2,q3,q4,q5";
// Waypoints produced by IK at a limit of ±2·pi may differ from it in the last bits.
constexpr double kLimitTolerance = 1e-9;

// Message for the first joint of q outside the model's limits, or empty.
std::string limitViolation(const robot::RobotModel& model, const robot::Vector6& q) {
  const auto j = robot::firstJointOutsideLimits(model, q, kLimitTolerance);
  return j ? robot::outsideLimitsText(model, *j, q[*j], "q" + std::to_string(*j)) : std::string();
}

void requireSixJoints(const robot::RobotModel& model) {
  if (model.dof() != 6) {
    throw Error("joint paths have 6 joints, but robot model " + model.name() + " has " + std::to_string(model.dof()));
  }
}

JointPath readPath(const std::filesystem::path& file, const robot::RobotModel* model) {
  if (model != nullptr) requireSixJoints(*model);
  std::ifstream in(file);
  // Messages name the place as compilers do: "<file>:<line>: column q4: ...".
  const std::string where = file.string();
  if (!in) throw Error(where + ": cannot be opened");
  JointPath path;
  std::string line;
  bool headerSeen = false;
  for (int lineNumber = 1; std::getline(in, line); ++lineNumber) {
    const std::string_view text = trim(line);
    if (text.empty() || text.front() == '#') continue;
    const std::string location = where + ":" + std::to_string(lineNumber);
    const auto fields = splitFields(text, ',');
    if (!headerSeen) {
      std::vector<std::string> names;
      for (const auto field : fields) names.emplace_back(trim(field));
      const std::string header = joinText(names, ",");
      if (header != kHeader) {
        throw Error(location + ": expected the header '" + kHeader + "', found '" + std::string(text) + "'");
      }
      headerSeen = true;
      continue;
    }
    if (fields.size() != 6) {
      throw Error(location + ": expected 6 comma-separated joint angles (q0..q5), found " +
                  std::to_string(fields.size()) + " fields");
    }
    robot::Vector6 q;
    for (int j = 0; j < 6; ++j) {
      const auto value = parseDouble(fields[j]);
      if (!value) {
        throw Error(location + ": column q" + std::to_string(j) + ": '" + std::string(trim(fields[j])) +
                    "' is not a number");
      }
      if (!std::isfinite(*value)) {
        throw Error(location + ": column q" + std::to_string(j) + ": " + std::string(trim(fields[j])) +
                    " is not a finite joint angle");
      }
      q[j] = *value;
    }
    if (model != nullptr) {
      if (const auto problem = limitViolation(*model, q); !problem.empty()) throw Error(location + ": " + problem);
    }
    path.push_back(q);
  }
  if (in.bad()) throw Error(where + ": read error");
  if (!headerSeen)
    throw Error(where + ": empty file, expected the header '" + std::string(kHeader) + "' and waypoints");
  if (path.size() < 2) {
    throw Error(where + ": a path needs at least 2 waypoints, found " + std::to_string(path.size()));
  }
  return path;
}

}  // namespace

JointPath readJointPathCsv(const std::filesystem::path& file) { return readPath(file, nullptr); }

JointPath readJointPathCsv(const std::filesystem::path& file, const robot::RobotModel& model) {
  return readPath(file, &model);
}

void writeJointPathCsv(const std::filesystem::path& file, const JointPath& path) {
  AtomicOutputFile output(file);
  auto& out = output.stream();
  out << std::setprecision(std::numeric_limits<double>::max_digits10) << kHeader << "\n";
  for (const auto& q : path) {
    for (int j = 0; j < 6; ++j) out << (j ? "," : "") << q[j];
    out << "\n";
  }
  output.commit();
}

void validateJointPath(const robot::RobotModel& model, const JointPath& path, const std::string& source) {
  requireSixJoints(model);
  if (path.size() < 2) {
    throw Error(source + ": a path needs at least 2 waypoints, got " + std::to_string(path.size()));
  }
  for (std::size_t i = 0; i < path.size(); ++i) {
    const std::string location = source + ", waypoint " + std::to_string(i);
    if (!path[i].allFinite()) throw Error(location + ": joint angles must be finite numbers");
    if (const auto problem = limitViolation(model, path[i]); !problem.empty()) throw Error(location + ": " + problem);
  }
}

double jointPathLength(const JointPath& path) {
  double length = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) length += (path[i] - path[i - 1]).norm();
  return length;
}

}  // namespace arcplan::trajectory
