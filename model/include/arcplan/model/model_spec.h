#pragma once
// The model file (YAML): what the model predicts, where its load torque comes from and which
// physical effects it contains, optionally with fitted parameters. Example:
//
//   kind: joint_current          # predict actual_current_j from the motion
//   load_torque: target_moment   # or rigid_body: arcplan's inverse dynamics from the URDF inertials
//   effects: [drive_gain, offset, coulomb, viscous]
//
// An effect entry is an id ("coulomb"), an id with joints ("coulomb:1,2"), or a map:
//   - {id: stribeck, joints: [1, 2], stribeck_velocity: 0.05}      # fixes the searched parameter
//   - {id: drag, expression: "qd*abs(qd)", explanation: "air/oil drag"}  # user regressor (muparser)
// `arcplan model fit --save` adds `parameters` and `standard_errors` (per channel lists).
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "arcplan/robot/dynamics.h"

namespace arcplan::model {

enum class ModelKind { JointCurrent, JointTracking, GearboxFtd };
enum class LoadTorqueSource { TargetMoment, RigidBody };

std::string toString(ModelKind kind);
std::string toString(LoadTorqueSource source);

struct EffectSpec {
  std::string id;                         // catalogue id, registered C++ effect, or user effect name
  std::vector<int> joints;                // channels it applies to; empty = all
  std::vector<std::string> expressions;   // user regressor columns over the log's signals
  std::string explanation;                // user text for expression effects
  std::map<std::string, double> options;  // effect-specific numbers (harmonics, fixed nonlinear values)
  // Per-channel values, keyed by parameter name (the nonlinear one included); NaN = not applied.
  std::map<std::string, std::vector<double>> parameters;
  std::map<std::string, std::vector<double>> standardErrors;
};

struct ModelSpec {
  std::string name;
  ModelKind kind = ModelKind::JointCurrent;
  LoadTorqueSource loadTorque = LoadTorqueSource::TargetMoment;
  int joints = 0;                      // expected joint (channel) count of the data; 0 = take the data's
  std::filesystem::path urdf;          // `robot: {urdf: F}`; empty (`robot: ur10e`): arcplan's UR10e
  robot::DynamicsParameters dynamics;  // gravity and a known payload for the rigid-body load torque
  double derivativeCutoffHz = 10.0;    // zero-phase filter of derived velocities/accelerations
  double velocitySmoothing = 0.01;     // rad/s: sgn(qd) is smoothed as tanh(qd / this)
  double referenceTemperature = 25.0;  // °C, T0 of temperature_friction
  std::vector<EffectSpec> effects;
  std::filesystem::path source;  // file it was read from, for messages

  bool hasEffect(const std::string& id) const;
};

// Reads and validates a model file: unknown keys, kinds, load-torque sources and effect ids are
// errors that name the file and the field.
ModelSpec loadModelFile(const std::filesystem::path& file);
ModelSpec parseModelYaml(const std::string& yaml, const std::filesystem::path& source);
std::string toYaml(const ModelSpec& spec);
void saveModelFile(const ModelSpec& spec, const std::filesystem::path& file);  // atomic

// "coulomb" or "coulomb:1,2" (as on the command line). Throws arcplan::Error for an unknown id.
EffectSpec parseEffectArgument(const std::string& text);

}  // namespace arcplan::model
