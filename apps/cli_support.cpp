#include "cli_support.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <thread>

#include "arcplan/collision/collision_model.h"
#include "arcplan/common/atomic_file.h"
#include "arcplan/common/text_formatting.h"
#include "arcplan/common/text_parsing.h"
#include "arcplan/robot/pose.h"

namespace arcplan::apps {

void writeJson(const std::filesystem::path& file, const nlohmann::json& document) {
  const std::string text = document.dump(2) + "\n";
  if (file == "-") {
    std::cout.flush();  // what was printed before stays before the document
    std::fwrite(text.data(), 1, text.size(), stdout);
    std::fflush(stdout);
    return;
  }
  writeFileAtomically(file, text);
}

void addWorkersOption(CLI::App& command, unsigned& workers) {
  workers = std::max(1u, std::thread::hardware_concurrency());  // 0 when it cannot be determined
  command.add_option("-j,--workers", workers, "worker processes running jobs in parallel (default: all cores)")
      ->capture_default_str();
}

void requireWorkers(unsigned workers) {
  if (workers < 1) throw UsageError("--workers must be at least 1");
}

std::vector<double> parseVector(const std::string& text, const std::string& option, std::size_t count) {
  try {
    return parseNumberList(text, option, count);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
}

void requirePositive(double value, const std::string& option, const std::string& unit) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw UsageError(option + " must be a positive number (" + unit + "), got " + formatNumber(value, 6));
  }
}

void addCollisionModeOption(CLI::App& command) {
  command
      .add_option_function<std::string>(
          "--collision", [](const std::string& mode) { collision::setSpherePrefilterDefault(mode == "prefilter"); },
          "collision checking: prefilter (SIMD spheres in front of FCL, default) or exact-only (FCL for every "
          "query); both give the same answers")
      ->check(CLI::IsMember({"prefilter", "exact-only"}));
}

void addRobotSourceOptions(CLI::App& command, RobotSourceOptions& options, const std::string& urdfHelp) {
  auto* urdf = command.add_option("--urdf", options.urdf, urdfHelp);
  auto* type = command.add_option("--ur-type", options.urType,
                                  "UR type (ur5e, ur10, ...) built from Universal Robots' description parameters");
  type->excludes(urdf);
  command.add_option("--description", options.description,
                     "with --ur-type: the description folder (default: $ARCPLAN_SHARED_DATA/ur_description)");
  command.add_option("--kinematics", options.kinematics,
                     "with --ur-type: the robot's calibration file (default_kinematics.yaml format)");
  command.add_option("--tip", options.tip, "TCP link: what poses and IK refer to")->capture_default_str();
  command.add_option("--tcp-offset", options.tcpOffset, "TCP offset x,y,z,roll,pitch,yaw [m, rad] from --tip");
}

robot::RobotSource robotSourceFrom(const RobotSourceOptions& options) {
  if (options.urType.empty() && (!options.description.empty() || !options.kinematics.empty())) {
    throw UsageError("--description and --kinematics need --ur-type");
  }
  const auto existing = [](const std::string& value, const std::string& option) {
    if (!value.empty() && !std::filesystem::exists(value)) {
      throw Error(option + ": " + value + " does not exist");
    }
    return std::filesystem::path(value);
  };
  robot::RobotSource source;
  source.urdf = existing(options.urdf, "--urdf");
  source.urType = options.urType;
  source.description = existing(options.description, "--description");
  source.kinematics = existing(options.kinematics, "--kinematics");
  source.chain.tipLink = options.tip;
  if (!options.tcpOffset.empty()) {
    const auto v = parseVector(options.tcpOffset, "--tcp-offset", 6);
    source.chain.tcpOffset = robot::poseFromXyzRpy({v[0], v[1], v[2], v[3], v[4], v[5]});
  }
  if (source.isBuiltIn() && (options.tip != "tool0" || source.chain.tcpOffset)) source.urdf = robot::ur10eUrdfPath();
  return source;
}

}  // namespace arcplan::apps
