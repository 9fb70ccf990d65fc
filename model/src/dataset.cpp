#include "arcplan/model/dataset.h"

#include <algorithm>
#include <sstream>

#include "arcplan/common/error.h"
#include "arcplan/model/signal_processing.h"
#include "arcplan/robot/dynamics.h"

namespace arcplan::model {
namespace {

const std::vector<std::string> kRobotSignals{"rb_gravity", "rb_inertial", "payload_m",
                                             "payload_mx", "payload_my",  "payload_mz"};

bool isRobotSignal(const std::string& name) {
  return std::find(kRobotSignals.begin(), kRobotSignals.end(), name) != kRobotSignals.end();
}

std::string filterNote(const ModelSpec& spec) {
  std::ostringstream text;
  text << "zero-phase filter: resampled at the median step, 2nd-order Butterworth forward-backward, cut-off "
       << spec.derivativeCutoffHz << " Hz, central differences";
  return text.str();
}

void checkRobotJoints(const robot::RobotModel& robot, int joints, const std::string& source) {
  if (robot.dof() != joints) {
    throw Error(source + ": mismatched joint count: the log has " + std::to_string(joints) + " joints but robot '" +
                robot.name() + "' has " + std::to_string(robot.dof()));
  }
}

}  // namespace

std::shared_ptr<const robot::RobotModel> modelRobot(const ModelSpec& spec) {
  if (spec.urdf.empty())
    return std::shared_ptr<const robot::RobotModel>(&robot::ur10e(), [](const robot::RobotModel*) {});
  if (!std::filesystem::exists(spec.urdf)) {
    throw Error(spec.source.string() + ": urdf: file " + spec.urdf.string() + " does not exist");
  }
  return std::make_shared<const robot::RobotModel>(robot::loadRobotModel(spec.urdf));
}

bool Dataset::hasSignal(const std::string& name) const {
  if (channels_.empty()) return false;
  if (channels_.front().signals.count(name)) return true;
  return isRobotSignal(name) && (kind() != ModelKind::GearboxFtd) && channels_.front().signals.count("qdd");
}

const Eigen::VectorXd& Dataset::signal(const std::string& name, int channel) const {
  const auto& signals = channels_[channel].signals;
  const auto it = signals.find(name);
  if (it != signals.end()) return it->second;
  if (isRobotSignal(name) && hasSignal(name)) {
    if (robotSignals_.empty()) computeRobotSignals();
    return robotSignals_[channel].at(name);
  }
  std::string available;
  for (const auto& n : signalNames()) available += (available.empty() ? "" : ", ") + n;
  std::string hint;
  if (name == "temperature") hint = " (needs joint_temperatures_* columns)";
  if (name == "target_q" || name == "target_qd") hint = " (needs target_q_* columns)";
  if (name == "tau") hint = " (needs target_moment_* columns, or load_torque: rigid_body)";
  throw Error(source_ + ": signal '" + name + "' is not available for " + toString(kind()) + hint +
              "; available: " + available);
}

std::vector<std::string> Dataset::signalNames() const {
  std::vector<std::string> names;
  if (channels_.empty()) return names;
  for (const auto& [name, values] : channels_.front().signals) names.push_back(name);
  for (const auto& name : kRobotSignals) {
    if (hasSignal(name) && !channels_.front().signals.count(name)) names.push_back(name);
  }
  return names;
}

void Dataset::computeRobotSignals() const {
  if (!robot_) robot_ = modelRobot(settings_);
  const int joints = channelCount();
  checkRobotJoints(*robot_, joints, source_);
  const Eigen::Index n = samples(0);
  robotSignals_.assign(static_cast<std::size_t>(joints), {});
  for (int j = 0; j < joints; ++j) {
    for (const auto& name : kRobotSignals) robotSignals_[j][name] = Eigen::VectorXd(n);
  }
  robot::DynamicsData data(*robot_);
  Eigen::VectorXd q(joints), qd(joints), qdd(joints);
  for (Eigen::Index k = 0; k < n; ++k) {
    for (int j = 0; j < joints; ++j) {
      q[j] = channels_[j].signals.at("q")[k];
      qd[j] = channels_[j].signals.at("qd")[k];
      qdd[j] = channels_[j].signals.at("qdd")[k];
    }
    const Eigen::VectorXd gravity = robot::gravityTorque(*robot_, q, data, settings_.dynamics);
    const Eigen::VectorXd full = robot::inverseDynamics(*robot_, q, qd, qdd, data, settings_.dynamics);
    const auto payload = robot::payloadRegressor(*robot_, q, qd, qdd, data, settings_.dynamics.gravity);
    for (int j = 0; j < joints; ++j) {
      auto& out = robotSignals_[j];
      out["rb_gravity"][k] = gravity[j];
      out["rb_inertial"][k] = full[j] - gravity[j];
      out["payload_m"][k] = payload(j, 0);
      out["payload_mx"][k] = payload(j, 1);
      out["payload_my"][k] = payload(j, 2);
      out["payload_mz"][k] = payload(j, 3);
    }
  }
}

Dataset makeJointDataset(const Log& log, const ModelSpec& spec) {
  if (spec.kind == ModelKind::GearboxFtd) {
    throw Error(log.source.string() +
                ": kind gearbox_ftd needs force-transfer data (gearbox, ratio, direction, "
                "tau_out_Nm, tau_in_Nm columns), not a joint log");
  }
  Dataset dataset;
  dataset.settings_ = spec;
  dataset.source_ = log.source.string();
  dataset.quality_ = log.quality;
  const bool current = spec.kind == ModelKind::JointCurrent;
  // Newer controllers log the current also (or only) as a torque; the amps are used when present.
  const std::string measuredSignal =
      !current ? "actual_q"
               : (log.has("actual_current") || !log.has("actual_current_as_torque") ? "actual_current"
                                                                                    : "actual_current_as_torque");
  const Eigen::MatrixXd& measured = log.vector(measuredSignal);
  if (measuredSignal == "actual_current_as_torque") {
    dataset.notes_.push_back("measured: actual_current_as_torque (the motor current as a joint torque, N·m)");
  }
  const int joints = static_cast<int>(measured.cols());
  if (log.rows() < 10) {
    throw Error(log.source.string() + ": only " + std::to_string(log.rows()) + " valid rows; a fit needs at least 10");
  }
  const std::string positionSignal = current ? "actual_q" : "target_q";
  const std::string velocitySignal = current ? "actual_qd" : "target_qd";
  const Eigen::MatrixXd& q = log.vector(positionSignal);
  Eigen::MatrixXd qd;
  if (log.has(velocitySignal)) {
    qd = log.vector(velocitySignal);
  } else {
    qd = smoothDerivative(log.time, q, spec.derivativeCutoffHz);
    dataset.notes_.push_back("qd derived from " + positionSignal + " (" + filterNote(spec) + ")");
  }
  const Eigen::MatrixXd qdd = smoothDerivative(log.time, qd, spec.derivativeCutoffHz);
  dataset.notes_.push_back("qdd derived from " + (log.has(velocitySignal) ? velocitySignal : std::string("qd")) + " (" +
                           filterNote(spec) + ")");

  Eigen::MatrixXd tau;
  if (spec.loadTorque == LoadTorqueSource::TargetMoment) {
    if (current) {
      if (!log.has("target_moment")) {
        throw Error(log.missing("target_moment") +
                    "; load_torque: target_moment needs it, or use load_torque: rigid_body to compute the load "
                    "torque from the URDF");
      }
      tau = log.vector("target_moment");
    } else if (log.has("target_moment")) {
      tau = log.vector("target_moment");
    }
  } else {
    dataset.robot_ = modelRobot(spec);
    checkRobotJoints(*dataset.robot_, joints, dataset.source_);
    robot::DynamicsData data(*dataset.robot_);
    tau.resize(q.rows(), joints);
    for (Eigen::Index k = 0; k < q.rows(); ++k) {
      tau.row(k) = robot::inverseDynamics(*dataset.robot_, q.row(k).transpose(), qd.row(k).transpose(),
                                          qdd.row(k).transpose(), data, spec.dynamics)
                       .transpose();
    }
    dataset.notes_.push_back("tau: rigid-body inverse dynamics of " + dataset.robot_->name() + " on q, qd, qdd");
  }
  for (int j = 0; j < joints; ++j) {
    Dataset::Channel channel;
    channel.name = measuredSignal + "_" + std::to_string(j);
    channel.measured = measured.col(j);
    channel.base = current ? Eigen::VectorXd::Zero(measured.rows()) : Eigen::VectorXd(log.vector("target_q").col(j));
    channel.signals["time"] = log.time;
    channel.signals["q"] = q.col(j);
    channel.signals["qd"] = qd.col(j);
    channel.signals["qdd"] = qdd.col(j);
    if (tau.size() > 0) channel.signals["tau"] = tau.col(j);
    if (log.has("joint_temperatures")) channel.signals["temperature"] = log.vector("joint_temperatures").col(j);
    if (!current) {
      channel.signals["target_q"] = log.vector("target_q").col(j);
      channel.signals["target_qd"] = qd.col(j);
    }
    dataset.channels_.push_back(std::move(channel));
  }
  return dataset;
}

Dataset makeGearboxDataset(const std::vector<ForceTransferPoint>& points, const ModelSpec& spec,
                           const std::string& source) {
  if (spec.kind != ModelKind::GearboxFtd) {
    throw Error(source + ": force-transfer data can only be compared with kind: gearbox_ftd (the model is " +
                toString(spec.kind) + ")");
  }
  Dataset dataset;
  dataset.settings_ = spec;
  dataset.source_ = source;
  dataset.timeOrdered_ = false;
  dataset.quality_.dataRows = dataset.quality_.keptRows = points.size();
  std::vector<std::string> order;
  std::map<std::string, std::vector<const ForceTransferPoint*>> byChannel;
  for (const auto& point : points) {
    const std::string name = point.gearbox + (point.direct ? "/direct" : "/indirect");
    if (!byChannel.count(name)) order.push_back(name);
    byChannel[name].push_back(&point);
  }
  for (const auto& name : order) {
    const auto& members = byChannel[name];
    const auto n = static_cast<Eigen::Index>(members.size());
    Dataset::Channel channel;
    channel.name = name;
    channel.measured.resize(n);
    channel.base.resize(n);
    Eigen::VectorXd tau(n), direction(n), index(n), series(n);
    for (Eigen::Index k = 0; k < n; ++k) {
      const auto& p = *members[k];
      channel.measured[k] = p.inputTorque;
      channel.base[k] = p.outputTorque / p.ratio;
      tau[k] = p.outputTorque;
      direction[k] = p.direct ? 1.0 : -1.0;
      index[k] = static_cast<double>(k);
      series[k] = p.series;
    }
    channel.signals["time"] = index;
    channel.signals["tau"] = tau;
    channel.signals["qd"] = direction;
    channel.signals["series"] = series;
    dataset.channels_.push_back(std::move(channel));
  }
  dataset.notes_.push_back(
      "base prediction: ideal ratio, input torque = output torque / ratio; qd = +1 DIRECT, -1 INDIRECT");
  return dataset;
}

Dataset makeSimulationDataset(const ModelSpec& spec, std::vector<Dataset::Channel> channels, std::string source) {
  Dataset dataset;
  dataset.settings_ = spec;
  dataset.source_ = std::move(source);
  dataset.channels_ = std::move(channels);
  dataset.quality_.dataRows = dataset.quality_.keptRows =
      dataset.channels_.empty() ? 0 : static_cast<std::size_t>(dataset.channels_.front().measured.size());
  return dataset;
}

Dataset selectSamples(const Dataset& data, const std::vector<bool>& keep) {
  const auto kept = static_cast<Eigen::Index>(std::count(keep.begin(), keep.end(), true));
  auto select = [&](const Eigen::VectorXd& values) {
    Eigen::VectorXd result(kept);
    Eigen::Index out = 0;
    for (Eigen::Index k = 0; k < values.size(); ++k) {
      if (keep[static_cast<std::size_t>(k)]) result[out++] = values[k];
    }
    return result;
  };
  Dataset result;
  result.settings_ = data.settings_;
  result.source_ = data.source_;
  result.quality_ = data.quality_;
  result.notes_ = data.notes_;
  result.timeOrdered_ = data.timeOrdered_;
  result.robot_ = data.robot_;
  result.runStarts_.clear();
  const auto& starts = data.runStarts_;
  Eigen::Index out = 0;
  for (std::size_t k = 0, next = 0; k < keep.size(); ++k) {
    const bool runBegins = next < starts.size() && starts[next] == static_cast<Eigen::Index>(k);
    if (runBegins) ++next;
    if (!keep[k]) continue;
    if (out == 0 || runBegins || !keep[k - 1]) result.runStarts_.push_back(out);
    ++out;
  }
  if (result.runStarts_.empty()) result.runStarts_.push_back(0);
  for (const auto& channel : data.channels_) {
    Dataset::Channel selected{channel.name, select(channel.measured), select(channel.base), {}};
    for (const auto& [name, values] : channel.signals) selected.signals[name] = select(values);
    result.channels_.push_back(std::move(selected));
  }
  for (const auto& signals : data.robotSignals_) {
    result.robotSignals_.emplace_back();
    for (const auto& [name, values] : signals) result.robotSignals_.back()[name] = select(values);
  }
  return result;
}

Dataset joinRuns(const std::vector<Dataset>& runs) {
  if (runs.size() == 1) return runs.front();
  Dataset joined;
  joined.settings_ = runs.front().settings_;
  joined.timeOrdered_ = runs.front().timeOrdered_;
  joined.robot_ = runs.front().robot_;
  joined.channels_ = runs.front().channels_;
  joined.runStarts_.clear();
  for (auto& channel : joined.channels_) {
    for (auto& [name, values] : channel.signals) values.resize(0);
    channel.measured.resize(0);
    channel.base.resize(0);
  }
  auto append = [](Eigen::VectorXd& to, const Eigen::VectorXd& values) {
    to.conservativeResize(to.size() + values.size());
    to.tail(values.size()) = values;
  };
  double shift = 0.0;
  for (const auto& run : runs) {
    if (run.channelCount() != joined.channelCount() || run.kind() != joined.kind()) {
      throw Error(run.source_ + ": mismatched joint count: " + std::to_string(run.channelCount()) + " channels, but " +
                  runs.front().source_ + " has " + std::to_string(joined.channelCount()));
    }
    const Eigen::VectorXd& time = run.channels_.front().signals.at("time");
    if (!joined.source_.empty()) {
      const Eigen::VectorXd& sofar = joined.channels_.front().signals.at("time");
      const double step = time.size() > 1 ? time[1] - time[0] : 0.0;
      shift = sofar[sofar.size() - 1] + step - time[0];
    }
    const Eigen::Index offset = joined.channels_.front().measured.size();
    for (Eigen::Index start : run.runStarts_) joined.runStarts_.push_back(offset + start);
    for (int c = 0; c < joined.channelCount(); ++c) {
      auto& to = joined.channels_[c];
      const auto& from = run.channels_[c];
      append(to.measured, from.measured);
      append(to.base, from.base);
      for (auto& [name, values] : to.signals) {
        if (!from.signals.count(name)) {
          throw Error(run.source_ + ": has no signal '" + name + "', which " + runs.front().source_ + " has");
        }
        append(values, name == "time" ? Eigen::VectorXd(from.signals.at(name).array() + shift) : from.signals.at(name));
      }
    }
    joined.source_ += (joined.source_.empty() ? "" : " + ") + run.source_;
    joined.quality_.dataRows += run.quality_.dataRows;
    joined.quality_.keptRows += run.quality_.keptRows;
    for (const auto& d : run.quality_.dropped) joined.quality_.dropped.push_back(d);
    for (const auto& note : run.quality_.notes) joined.quality_.notes.push_back(note);
    for (const auto& note : run.notes_) {
      if (std::find(joined.notes_.begin(), joined.notes_.end(), note) == joined.notes_.end()) {
        joined.notes_.push_back(note);
      }
    }
  }
  joined.notes_.push_back(std::to_string(runs.size()) + " runs joined end to end (each run's time shifted to follow " +
                          "the previous one)");
  return joined;
}

Dataset loadDataset(const std::filesystem::path& file, const ModelSpec& spec, const LogReadOptions& options) {
  if (spec.kind == ModelKind::GearboxFtd) return makeGearboxDataset(readForceTransferData(file), spec, file.string());
  return makeJointDataset(readLog(file, options), spec);
}

}  // namespace arcplan::model
