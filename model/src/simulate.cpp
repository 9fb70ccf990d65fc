#include "arcplan/model/simulate.h"

#include <cmath>
#include <fstream>
#include <map>
#include <random>

#include "arcplan/common/error.h"
#include "arcplan/common/text_parsing.h"
#include "arcplan/model/dataset.h"
#include "arcplan/model/fitting.h"
#include "arcplan/model/signal_processing.h"
#include "arcplan/robot/dynamics.h"

namespace arcplan::model {
namespace {
constexpr double kMaxSamples = 1e7;  // 5.5 h at 500 Hz; beyond it a typo, not a log
}  // namespace

Trajectory excitationTrajectory(const Eigen::VectorXd& center, const ExcitationOptions& options) {
  if (options.duration <= 0.0 || options.rate <= 0.0 || options.harmonics < 1) {
    throw Error("excitation trajectory: duration, rate and harmonics must be positive");
  }
  const auto joints = center.size();
  if (options.duration * options.rate > kMaxSamples) {
    throw Error("excitation trajectory: duration x rate must stay below 1e7 samples");
  }
  const auto samples = static_cast<Eigen::Index>(std::floor(options.duration * options.rate)) + 1;
  Trajectory trajectory;
  trajectory.time = Eigen::VectorXd::LinSpaced(samples, 0.0, static_cast<double>(samples - 1) / options.rate);
  trajectory.q = Eigen::MatrixXd::Zero(samples, joints);
  trajectory.qd = trajectory.q;
  trajectory.qdd = trajectory.q;
  std::mt19937 random(options.seed);
  std::uniform_real_distribution<double> coefficient(-1.0, 1.0);
  for (Eigen::Index j = 0; j < joints; ++j) {
    for (int l = 1; l <= options.harmonics; ++l) {
      const double omega = 2.0 * M_PI * options.baseFrequency * l;
      const double a = coefficient(random), b = coefficient(random);
      for (Eigen::Index k = 0; k < samples; ++k) {
        const double s = std::sin(omega * trajectory.time[k]), c = std::cos(omega * trajectory.time[k]);
        trajectory.q(k, j) += a / omega * s - b / omega * c;
        trajectory.qd(k, j) += a * c + b * s;
        trajectory.qdd(k, j) += omega * (-a * s + b * c);
      }
    }
    // One scale per joint keeps q, qd and qdd consistent.
    const double scale = std::min({options.amplitude / trajectory.q.col(j).cwiseAbs().maxCoeff(),
                                   options.maxSpeed / trajectory.qd.col(j).cwiseAbs().maxCoeff(),
                                   options.maxAcceleration / trajectory.qdd.col(j).cwiseAbs().maxCoeff()});
    trajectory.q.col(j) = (trajectory.q.col(j) * scale).array() + center[j];
    trajectory.qd.col(j) *= scale;
    trajectory.qdd.col(j) *= scale;
  }
  return trajectory;
}

Trajectory readTrajectory(const std::filesystem::path& file, double rate, double cutoffHz) {
  if (!std::filesystem::exists(file)) throw Error("trajectory file " + file.string() + " does not exist");
  std::ifstream in(file);
  std::string line;
  if (!std::getline(in, line)) throw Error(file.string() + " is empty");
  const char separator = line.find(',') != std::string::npos ? ',' : ' ';
  const auto header = splitFields(line, separator);
  int timeColumn = -1;
  std::map<int, int> jointColumn;  // joint -> column
  for (std::size_t c = 0; c < header.size(); ++c) {
    const std::string name(trim(header[c]));
    if (name == "t" || name == "time" || name == "timestamp") timeColumn = static_cast<int>(c);
    for (const std::string prefix : {"q_", "q", "target_q_"}) {
      if (name.rfind(prefix, 0) == 0 && name.size() > prefix.size() && name.size() <= prefix.size() + 3 &&
          name.find_first_not_of("0123456789", prefix.size()) == std::string::npos) {
        jointColumn[std::stoi(name.substr(prefix.size()))] = static_cast<int>(c);
      }
    }
  }
  if (timeColumn < 0) throw Error(file.string() + ":1: no time column (t, time or timestamp)");
  if (jointColumn.empty()) throw Error(file.string() + ":1: no joint position columns (q0.., q_0.. or target_q_0..)");
  const int joints = static_cast<int>(jointColumn.size());
  for (int j = 0; j < joints; ++j) {
    if (!jointColumn.count(j))
      throw Error(file.string() + ":1: joint columns must be numbered 0.." + std::to_string(joints - 1));
  }
  std::vector<double> times;
  std::vector<std::vector<double>> positions;
  std::size_t lineNumber = 1;
  while (std::getline(in, line)) {
    ++lineNumber;
    if (trim(line).empty()) continue;
    const auto fields = splitFields(line, separator);
    if (fields.size() != header.size()) {
      throw Error(file.string() + ":" + std::to_string(lineNumber) + ": expected " + std::to_string(header.size()) +
                  " fields");
    }
    auto value = [&](int column) {
      const auto v = parseDouble(fields[static_cast<std::size_t>(column)]);
      if (!v || !std::isfinite(*v)) {
        throw Error(file.string() + ":" + std::to_string(lineNumber) + ": column " + std::to_string(column + 1) +
                    " is not a finite number");
      }
      return *v;
    };
    const double t = value(timeColumn);
    if (!times.empty() && t <= times.back()) {
      throw Error(file.string() + ":" + std::to_string(lineNumber) + ": time must increase");
    }
    times.push_back(t);
    std::vector<double> row;
    for (int j = 0; j < joints; ++j) row.push_back(value(jointColumn[j]));
    positions.push_back(row);
  }
  if (times.size() < 4) throw Error(file.string() + ": a trajectory needs at least 4 samples");
  if ((times.back() - times.front()) * rate > kMaxSamples) {
    throw Error(file.string() + ": duration x rate must stay below 1e7 samples");
  }
  const Eigen::Map<const Eigen::VectorXd> sourceTime(times.data(), static_cast<Eigen::Index>(times.size()));
  Eigen::MatrixXd sourceQ(static_cast<Eigen::Index>(times.size()), joints);
  for (std::size_t k = 0; k < positions.size(); ++k) {
    for (int j = 0; j < joints; ++j)
      sourceQ(static_cast<Eigen::Index>(k), j) = positions[k][static_cast<std::size_t>(j)];
  }
  const auto samples = static_cast<Eigen::Index>(std::floor((times.back() - times.front()) * rate)) + 1;
  Trajectory trajectory;
  trajectory.time =
      Eigen::VectorXd::LinSpaced(samples, times.front(), times.front() + static_cast<double>(samples - 1) / rate);
  trajectory.q = interpolateLinear(sourceTime, sourceQ, trajectory.time);
  trajectory.qd = smoothDerivative(trajectory.time, trajectory.q, cutoffHz);
  trajectory.qdd = smoothDerivative(trajectory.time, trajectory.qd, cutoffHz);
  return trajectory;
}

Log simulateLog(const ModelSpec& truth, const Trajectory& trajectory, const SimulationOptions& options) {
  if (truth.kind == ModelKind::GearboxFtd) {
    throw Error("simulate makes UR10e joint logs; kind gearbox_ftd has no time series to simulate");
  }
  const auto robot = modelRobot(truth);
  const auto joints = static_cast<int>(trajectory.q.cols());
  if (robot->dof() != joints) {
    throw Error("simulate: mismatched joint count: the trajectory has " + std::to_string(joints) + " joints, robot '" +
                robot->name() + "' has " + std::to_string(robot->dof()));
  }
  const Eigen::Index n = trajectory.time.size();
  const double duration = trajectory.time[n - 1] - trajectory.time[0];
  robot::DynamicsData dynamics(*robot);
  Eigen::MatrixXd moment(n, joints), temperature(n, joints);
  std::mt19937 random(options.seed);
  std::uniform_real_distribution<double> startJitter(-1.0, 1.0);
  std::vector<double> start;
  for (int j = 0; j < joints; ++j) start.push_back(options.temperatureStart + j + startJitter(random));
  for (Eigen::Index k = 0; k < n; ++k) {
    moment.row(k) = robot::inverseDynamics(*robot, trajectory.q.row(k).transpose(), trajectory.qd.row(k).transpose(),
                                           trajectory.qdd.row(k).transpose(), dynamics, truth.dynamics)
                        .transpose();
    const double progress = duration > 0.0 ? (trajectory.time[k] - trajectory.time[0]) / duration : 0.0;
    for (int j = 0; j < joints; ++j)
      temperature(k, j) = start[static_cast<std::size_t>(j)] + options.temperatureRise * progress;
  }

  const bool current = truth.kind == ModelKind::JointCurrent;
  std::vector<Dataset::Channel> channels;
  for (int j = 0; j < joints; ++j) {
    Dataset::Channel channel;
    channel.name = (current ? "actual_current_" : "actual_q_") + std::to_string(j);
    channel.base = current ? Eigen::VectorXd::Zero(n) : Eigen::VectorXd(trajectory.q.col(j));
    channel.measured = Eigen::VectorXd::Zero(n);
    channel.signals["time"] = trajectory.time;
    channel.signals["q"] = trajectory.q.col(j);
    channel.signals["qd"] = trajectory.qd.col(j);
    channel.signals["qdd"] = trajectory.qdd.col(j);
    channel.signals["tau"] = moment.col(j);
    channel.signals["temperature"] = temperature.col(j);
    channel.signals["target_q"] = trajectory.q.col(j);
    channel.signals["target_qd"] = trajectory.qd.col(j);
    channels.push_back(std::move(channel));
  }
  const Dataset data = makeSimulationDataset(truth, std::move(channels), "simulation");
  const FittedModel model = modelFromParameters(truth, data, true);
  const double noise = options.noise >= 0.0 ? options.noise : (current ? 0.05 : 2e-5);
  std::normal_distribution<double> gaussian(0.0, 1.0);
  Eigen::MatrixXd measured(n, joints);
  for (int j = 0; j < joints; ++j) {
    measured.col(j) = predict(model, data, j);
    for (Eigen::Index k = 0; k < n; ++k) measured(k, j) += noise * gaussian(random);
  }

  Log log;
  log.source = "simulation";
  log.time = trajectory.time;
  log.vectors["target_q"] = trajectory.q;
  log.vectors["target_qd"] = trajectory.qd;
  log.vectors["target_qdd"] = trajectory.qdd;
  log.vectors["target_moment"] = moment;
  log.vectors["joint_temperatures"] = temperature;
  if (current) {
    log.vectors["actual_q"] = trajectory.q;
    log.vectors["actual_qd"] = trajectory.qd;
    log.vectors["actual_current"] = measured;
  } else {
    log.vectors["actual_q"] = measured;
    log.vectors["actual_qd"] = smoothDerivative(trajectory.time, measured, truth.derivativeCutoffHz);
  }
  log.quality.dataRows = log.quality.keptRows = static_cast<std::size_t>(n);
  return log;
}

}  // namespace arcplan::model
