// arcplan scale — PCHIP time scaling of a joint path under a TCP speed limit (thesis §4.3), with the
// metrics of docs/metrics.md, the dense timed trajectory and a speed-profile plot.
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <unistd.h>

#include "arcplan/collision/scene.h"
#include "arcplan/common/error.h"
#include "arcplan/common/plotting.h"
#include "arcplan/common/resources.h"
#include "arcplan/common/text_formatting.h"
#include "arcplan/robot/robot_model.h"
#include "arcplan/trajectory/joint_path.h"
#include "arcplan/trajectory/metrics.h"
#include "arcplan/trajectory/time_scaling.h"
#include "cli_support.h"
#include "commands.h"

namespace arcplan::apps {
namespace {

struct ScaleOptions {
  std::string scene;
  RobotSourceOptions robot;
  std::string pathCsv;
  double maxTcpSpeed = 0.25;
  double riseTime = 0.2;
  std::optional<double> maxTcpAcceleration;
  std::string json;
  std::string trajectoryCsv;
  std::string plot;
};

robot::RobotModel loadRobot(const ScaleOptions& options) {
  if (!options.scene.empty() && options.robot.given()) {
    throw UsageError("--scene brings its own robot; give --scene or the robot options, not both");
  }
  const robot::RobotSource source = options.scene.empty() ? robotSourceFrom(options.robot)
                                                          : collision::loadScene(resolveDataPath(options.scene)).robot;
  return source.isBuiltIn() ? robot::ur10e() : robot::loadRobot(source);
}

void printMetrics(const trajectory::TrajectoryMetrics& metrics, const trajectory::TimedTrajectory& trajectory,
                  std::size_t waypoints) {
  std::cout << std::fixed << std::setprecision(4) << "waypoints           " << waypoints << " (dense path "
            << trajectory.densePath.size() << ", PCHIP knots " << trajectory.knots.size() << ", samples "
            << trajectory.time.size() << ")\n"
            << "tcp path length     " << metrics.tcpPathLength << " m\n"
            << "joint path length   " << metrics.jointPathLength << " rad\n"
            << "execution time      " << metrics.executionTime << " s\n"
            << "mean tcp speed      " << metrics.meanTcpSpeed << " m/s\n"
            << "peak tcp speed      " << metrics.peakTcpSpeed << " m/s (limit " << trajectory.tcpSpeedLimit << ")\n"
            << "time above limit    " << metrics.timeAboveLimit << " s\n"
            << "max joint speed     " << std::setprecision(1) << 100.0 * metrics.maxJointSpeedRatio
            << " % of its limit\n";
}

// A plot that was asked for and cannot be drawn fails the command (arcplan::Error), before any
// other output file exists. The script reads the samples from a temporary CSV.
void plotTrajectory(const trajectory::TimedTrajectory& trajectory, const ScaleOptions& options) {
  const std::filesystem::path csv =
      std::filesystem::temp_directory_path() / ("arcplan_scale_" + std::to_string(::getpid()) + ".csv");
  trajectory::writeTimedTrajectoryCsv(csv, trajectory);
  std::vector<std::string> arguments{csv.string(), options.plot,
                                     "--vmax",     formatNumber(trajectory.tcpSpeedLimit, 6),
                                     "--title",    std::filesystem::path(options.pathCsv).filename().string()};
  for (int j = 0; j < 6; ++j) {
    arguments.insert(arguments.end(), {"--joint-limit", formatNumber(trajectory.jointSpeedLimits[j], 10)});
  }
  const PlotOutcome outcome = runPlotScript("plot_trajectory.py", arguments);
  std::error_code ignored;
  std::filesystem::remove(csv, ignored);
  if (!outcome.ok) throw Error("--plot " + options.plot + ": " + outcome.message);
}

void runScale(const ScaleOptions& options) {
  const DropStdout quiet(options.json == "-");
  requirePositive(options.maxTcpSpeed, "--vmax", "m/s");
  requirePositive(options.riseTime, "--rise", "s");
  if (options.maxTcpAcceleration) requirePositive(*options.maxTcpAcceleration, "--max-acc", "m/s²");
  if (!options.plot.empty() && std::filesystem::path(options.plot).extension() != ".png") {
    throw UsageError("--plot: expected a .png file name, got " + options.plot);
  }

  const robot::RobotModel model = loadRobot(options);
  const trajectory::JointPath path = trajectory::readJointPathCsv(options.pathCsv, model);
  trajectory::TimeScalingOptions scaling;
  scaling.maxTcpSpeed = options.maxTcpSpeed;
  scaling.riseTime = options.riseTime;
  scaling.maxTcpAcceleration = options.maxTcpAcceleration;
  const trajectory::TimedTrajectory timed = trajectory::scaleToTcpSpeed(model, path, scaling);
  const trajectory::TrajectoryMetrics metrics = trajectory::computeMetrics(path, timed);

  if (!options.plot.empty()) plotTrajectory(timed, options);
  printMetrics(metrics, timed, path.size());
  if (!options.json.empty()) {
    nlohmann::json document = trajectory::toJson(metrics);
    document["settings"] = {
        {"path_csv", options.pathCsv},
        {"vmax_mps", options.maxTcpSpeed},
        {"rise_time_s", options.maxTcpAcceleration ? nlohmann::json() : nlohmann::json(options.riseTime)},
        {"max_tcp_acceleration_mps2",
         options.maxTcpAcceleration ? nlohmann::json(*options.maxTcpAcceleration) : nlohmann::json()}};
    writeJson(options.json, document);
  }
  if (!options.trajectoryCsv.empty()) trajectory::writeTimedTrajectoryCsv(options.trajectoryCsv, timed);
  if (!options.plot.empty()) std::cout << "plot                " << options.plot << "\n";
}

}  // namespace

void registerScaleCommand(CLI::App& app) {
  auto options = std::make_shared<ScaleOptions>();
  auto* scale = app.add_subcommand("scale", "time-scale a joint path under a TCP speed limit (PCHIP)");
  scale->footer(
      "Time-scales a joint path (PCHIP) so the TCP speed never exceeds --vmax: ramp up over --rise, cruise, brake; "
      "slower where a joint speed limit requires it; checked with forward kinematics every 2 ms.");
  scale->add_option("--scene", options->scene, "scene YAML; its robot is used (default: built-in UR10e)");
  addRobotSourceOptions(*scale, options->robot, "robot URDF instead of a scene");
  scale->add_option("--path-csv", options->pathCsv, "joint path: header q0,...,q5, one waypoint [rad] per line")
      ->required();
  scale->add_option("--vmax", options->maxTcpSpeed, "TCP speed limit [m/s] (ISO/TS 15066 collaborative: 0.25)")
      ->capture_default_str();
  scale->add_option("--rise", options->riseTime, "time to reach --vmax from rest and to brake [s]")
      ->capture_default_str();
  scale->add_option_function<double>(
      "--max-acc", [options](double value) { options->maxTcpAcceleration = value; },
      "TCP acceleration limit [m/s²] for the ramps, instead of --rise");
  scale->add_option("--json", options->json,
                    "write the metrics (docs/metrics.md keys) as JSON to this file ('-' for stdout)");
  scale->add_option("--traj-csv", options->trajectoryCsv,
                    "write the timed trajectory: t, q0..5, qd0..5, qdd0..5, tcp_speed, tcp_x/y/z every <= 2 ms");
  scale->add_option("--plot", options->plot, "PNG of the TCP speed profile, joint positions and velocities");
  scale->callback([options] { runScale(*options); });
}

}  // namespace arcplan::apps
