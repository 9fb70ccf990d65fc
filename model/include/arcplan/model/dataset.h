#pragma once
// A log prepared for one model kind: per channel (a joint, or a gearbox and direction) the
// measured values to predict, the kind's base prediction, and the signals effects read.
//
// Signal names (per channel):
//   time         s (gearbox data: the row index; not time-ordered)
//   q, qd, qdd   joint position, velocity, acceleration. joint_current: actual_q / actual_qd (derived
//                from actual_q when absent); joint_tracking: target_q / target_qd. qdd is derived
//                from qd with the zero-phase filter of signal_processing.h. Gearbox: qd = +1 DIRECT,
//                -1 INDIRECT.
//   tau          load torque: target_moment_j, or the rigid-body inverse dynamics (load_torque:
//                rigid_body); gearbox: output torque
//   temperature  joint_temperatures_j (°C), when the log has it
//   target_q, target_qd   joint_tracking only: the commanded motion
//   rb_gravity, rb_inertial        rigid-body torque of the URDF split into gravity g(q) and the
//                                  rest M(q)·qdd + C(q,qd)·qd (computed on first use)
//   payload_m, payload_mx, payload_my, payload_mz   payload regressor columns (robot/dynamics.h)
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "arcplan/model/force_transfer.h"
#include "arcplan/model/measurements.h"
#include "arcplan/model/model_spec.h"
#include "arcplan/robot/robot_model.h"

namespace arcplan::model {

class Dataset {
public:
  struct Channel {
    std::string name;  // "actual_current_2", "actual_q_0", "HFUC-20-2UH-100/direct"
    Eigen::VectorXd measured;
    Eigen::VectorXd base;  // the kind's prediction without effects
    std::map<std::string, Eigen::VectorXd> signals;
  };

  ModelKind kind() const { return settings_.kind; }
  const ModelSpec& settings() const { return settings_; }
  const std::string& source() const { return source_; }
  const LogQuality& quality() const { return quality_; }
  const std::vector<std::string>& notes() const { return notes_; }
  bool timeOrdered() const { return timeOrdered_; }
  // The first sample of every run, 0 first: joinRuns starts one at each run it joins, and
  // selectSamples one after every gap it leaves. Effects with a state along the log (friction with
  // memory) start it afresh there: what the joint did before a run began is not in the log, and a
  // jump of q across a boundary is no motion.
  const std::vector<Eigen::Index>& runStarts() const { return runStarts_; }

  int channelCount() const { return static_cast<int>(channels_.size()); }
  const std::string& channelName(int channel) const { return channels_[channel].name; }
  Eigen::Index samples(int channel) const { return channels_[channel].measured.size(); }
  const Eigen::VectorXd& measured(int channel) const { return channels_[channel].measured; }
  const Eigen::VectorXd& basePrediction(int channel) const { return channels_[channel].base; }

  bool hasSignal(const std::string& name) const;
  // Throws arcplan::Error naming the log and what it would need to provide the signal.
  const Eigen::VectorXd& signal(const std::string& name, int channel) const;
  std::vector<std::string> signalNames() const;

  // Builders (see the functions below).
  friend Dataset makeJointDataset(const Log& log, const ModelSpec& spec);
  friend Dataset makeGearboxDataset(const std::vector<ForceTransferPoint>& points, const ModelSpec& spec,
                                    const std::string& source);
  // For the simulator: the exact signals its truth model predicts from (measured values are zero).
  friend Dataset makeSimulationDataset(const ModelSpec& spec, std::vector<Channel> channels, std::string source);
  friend Dataset selectSamples(const Dataset& data, const std::vector<bool>& keep);
  friend Dataset joinRuns(const std::vector<Dataset>& runs);

private:
  void computeRobotSignals() const;

  ModelSpec settings_;
  std::string source_;
  LogQuality quality_;
  std::vector<std::string> notes_;
  bool timeOrdered_ = true;
  std::vector<Eigen::Index> runStarts_{0};
  std::vector<Channel> channels_;
  mutable std::shared_ptr<const robot::RobotModel> robot_;                    // loaded on first use
  mutable std::vector<std::map<std::string, Eigen::VectorXd>> robotSignals_;  // filled on first use
};

// Joint logs for joint_current / joint_tracking. Throws arcplan::Error when the log lacks a column
// the kind needs, or its joint count differs from the robot's.
Dataset makeJointDataset(const Log& log, const ModelSpec& spec);
// Force-transfer points for gearbox_ftd: one channel per gearbox and direction.
Dataset makeGearboxDataset(const std::vector<ForceTransferPoint>& points, const ModelSpec& spec,
                           const std::string& source);
Dataset makeSimulationDataset(const ModelSpec& spec, std::vector<Dataset::Channel> channels, std::string source);
// The samples where `keep` is true (one flag per sample), every signal alike; source, notes and
// quality stay (the diagnosis leaves event windows out this way). A run starts after every gap.
Dataset selectSamples(const Dataset& data, const std::vector<bool>& keep);
// Several runs of one robot as one dataset, end to end: each run's time is shifted to start one
// sample step after the previous run ends (derivatives were taken per run), and runStarts() marks
// where each begins. The runs must have the same channels.
Dataset joinRuns(const std::vector<Dataset>& runs);

// Reads the file the way the model kind needs it (RTDE/headerless log, or force-transfer CSV).
Dataset loadDataset(const std::filesystem::path& file, const ModelSpec& spec, const LogReadOptions& options = {});

// The robot a model refers to (its URDF, or arcplan's UR10e), shared.
std::shared_ptr<const robot::RobotModel> modelRobot(const ModelSpec& spec);

}  // namespace arcplan::model
