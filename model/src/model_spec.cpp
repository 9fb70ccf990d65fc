#include "arcplan/model/model_spec.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "arcplan/common/atomic_file.h"
#include "arcplan/common/error.h"
#include "arcplan/common/text_parsing.h"
#include "arcplan/common/yaml_reading.h"
#include "arcplan/model/effect.h"

namespace arcplan::model {
namespace {

constexpr double kMaxJoint = 1000.0;  // far beyond any arm; keeps indices in int range

// "coulomb:1,2" as data, without resolving the id.
EffectSpec effectFromText(const std::string& text);

// Positions, numbers and keys are read like every arcplan YAML file (common/yaml_reading.h).
YamlReader reader(const std::filesystem::path& source) { return YamlReader(source.empty() ? "model" : source); }

std::string at(const std::filesystem::path& source, const YAML::Node& node) { return reader(source).position(node); }

double number(const YAML::Node& node, const std::filesystem::path& source, const std::string& field) {
  return reader(source).number(node, field);
}

// Stored per-channel values: .nan marks a channel the effect does not apply to, so NaN is allowed.
std::vector<double> numbers(const YAML::Node& node, const std::filesystem::path& source, const std::string& field) {
  if (!node.IsSequence()) reader(source).fail(node, field, "expected a list of numbers");
  std::vector<double> values;
  for (const auto& item : node) {
    double value = 0.0;
    if (!item.IsScalar() || !YAML::convert<double>::decode(item, value)) {
      reader(source).fail(item, field, "expected a list of numbers");
    }
    values.push_back(value);
  }
  return values;
}

std::vector<int> jointList(const YAML::Node& node, const std::filesystem::path& source, const std::string& field) {
  std::vector<int> joints;
  for (double value : numbers(node, source, field)) {
    if (value < 0 || value > kMaxJoint || value != std::floor(value)) {
      reader(source).fail(node, field, "joint indices are 0-based integers");
    }
    joints.push_back(static_cast<int>(value));
  }
  return joints;
}

void checkKeys(const YAML::Node& map, const std::vector<std::string>& allowed, const std::filesystem::path& source,
               const std::string& field) {
  reader(source).checkKeys(map, field, allowed);
}

EffectSpec parseEffect(const YAML::Node& node, const std::filesystem::path& source, std::size_t index) {
  const std::string where = "effects[" + std::to_string(index) + "]";
  EffectSpec spec;
  if (node.IsScalar()) {
    try {
      spec = effectFromText(node.as<std::string>());
    } catch (const Error& e) {
      throw Error(at(source, node) + ": " + where + ": " + e.what());
    }
    return spec;
  }
  if (!node.IsMap() || !node["id"]) {
    throw Error(at(source, node) + ": " + where + ": expected an effect id or a map with 'id'");
  }
  spec.id = node["id"].as<std::string>();
  for (const auto& entry : node) {
    const auto key = entry.first.as<std::string>();
    const std::string field = where + "." + key;
    if (key == "id") continue;
    if (key == "joints") {
      spec.joints = jointList(entry.second, source, field);
    } else if (key == "expression") {
      if (entry.second.IsSequence()) {
        for (const auto& e : entry.second) spec.expressions.push_back(e.as<std::string>());
      } else {
        spec.expressions.push_back(entry.second.as<std::string>());
      }
    } else if (key == "explanation") {
      spec.explanation = entry.second.as<std::string>();
    } else if (key == "parameters" || key == "standard_errors") {
      if (!entry.second.IsMap())
        throw Error(at(source, entry.second) + ": " + field + ": expected name: [values per joint]");
      auto& target = key == "parameters" ? spec.parameters : spec.standardErrors;
      for (const auto& parameter : entry.second) {
        const auto name = parameter.first.as<std::string>();
        target[name] = numbers(parameter.second, source, field + "." + name);
      }
    } else {
      spec.options[key] = number(entry.second, source, field);
    }
  }
  return spec;
}

// The one place a parsed effect entry is checked: its id (or expression) resolves to an effect,
// its options and stored parameters are the effect's own, it applies to the kind and is new.
void validateEffect(const EffectSpec& spec, const ModelSpec& model) {
  const auto effect = createEffect(spec);
  const auto names = effect->parameterNames();
  const auto nonlinear = effect->nonlinearParameter();
  for (const auto* values : {&spec.parameters, &spec.standardErrors}) {
    for (const auto& [name, list] : *values) {
      if (std::find(names.begin(), names.end(), name) == names.end() && !(nonlinear && nonlinear->name == name)) {
        std::string known;
        for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
        if (nonlinear) known += ", " + nonlinear->name;
        throw Error("unknown parameter '" + name + "' (parameters: " + known + ")");
      }
    }
  }
  if (!effect->appliesTo(model.kind)) {
    throw Error("effect '" + spec.id + "' does not apply to kind " + toString(model.kind));
  }
  if (model.hasEffect(spec.id)) throw Error("effect '" + spec.id + "' is listed twice");
}

ModelKind parseKind(const YAML::Node& node, const std::filesystem::path& source) {
  const auto text = node.as<std::string>();
  if (text == "joint_current") return ModelKind::JointCurrent;
  if (text == "joint_tracking") return ModelKind::JointTracking;
  if (text == "gearbox_ftd") return ModelKind::GearboxFtd;
  throw Error(at(source, node) + ": kind: unknown kind '" + text +
              "' (expected joint_current, joint_tracking or gearbox_ftd)");
}

LoadTorqueSource parseLoadTorque(const YAML::Node& node, const std::filesystem::path& source) {
  const auto text = node.as<std::string>();
  if (text == "target_moment") return LoadTorqueSource::TargetMoment;
  if (text == "rigid_body") return LoadTorqueSource::RigidBody;
  throw Error(at(source, node) + ": load_torque: unknown source '" + text + "' (expected target_moment or rigid_body)");
}

// `robot: ur10e` (arcplan's own, the default) or `robot: {urdf: FILE}` (relative to the model file), as
// in scene files.
std::filesystem::path parseRobot(const YAML::Node& node, const std::filesystem::path& source) {
  if (node.IsScalar() && node.as<std::string>() == "ur10e") return {};
  if (!node.IsMap() || !node["urdf"] || !node["urdf"].IsScalar()) {
    reader(source).fail(node, "robot", "expected 'ur10e' (built in) or a mapping {urdf: FILE}");
  }
  checkKeys(node, {"urdf"}, source, "robot");
  std::filesystem::path urdf = node["urdf"].as<std::string>();
  if (urdf.is_relative() && !source.empty()) urdf = source.parent_path() / urdf;
  return urdf;
}

Eigen::Vector3d vector3(const YAML::Node& node, const std::filesystem::path& source, const std::string& field) {
  const auto values = numbers(node, source, field);
  if (values.size() != 3) throw Error(at(source, node) + ": " + field + ": expected 3 numbers");
  return {values[0], values[1], values[2]};
}

void emitList(YAML::Emitter& out, const std::vector<double>& values) {
  out << YAML::Flow << YAML::BeginSeq;
  for (double v : values) out << v;  // NaN (effect not applied on that channel) is written as .nan
  out << YAML::EndSeq;
}

}  // namespace

std::string toString(ModelKind kind) {
  switch (kind) {
    case ModelKind::JointCurrent:
      return "joint_current";
    case ModelKind::JointTracking:
      return "joint_tracking";
    case ModelKind::GearboxFtd:
      return "gearbox_ftd";
  }
  return "?";
}

std::string toString(LoadTorqueSource source) {
  return source == LoadTorqueSource::TargetMoment ? "target_moment" : "rigid_body";
}

bool ModelSpec::hasEffect(const std::string& id) const {
  return std::any_of(effects.begin(), effects.end(), [&](const EffectSpec& e) { return e.id == id; });
}

EffectSpec parseEffectArgument(const std::string& text) {
  EffectSpec spec = effectFromText(text);
  createEffect(spec);  // throws for an unknown id
  return spec;
}

namespace {

EffectSpec effectFromText(const std::string& text) {
  EffectSpec spec;
  const auto colon = text.find(':');
  spec.id = std::string(trim(text.substr(0, colon)));
  if (spec.id.empty()) throw Error("effect '" + text + "': empty effect name");
  if (colon != std::string::npos) {
    for (double value : parseNumberList(text.substr(colon + 1), "effect '" + text + "' joints")) {
      if (value < 0 || value > kMaxJoint || value != std::floor(value)) {
        throw Error("effect '" + text + "': joints are 0-based integers");
      }
      spec.joints.push_back(static_cast<int>(value));
    }
  }
  return spec;
}

}  // namespace

ModelSpec parseModelYaml(const std::string& yaml, const std::filesystem::path& source) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml);
  } catch (const YAML::Exception& e) {
    throw Error(reader(source).position(e.mark) + ": malformed YAML: " + e.msg);
  }
  if (!root.IsMap()) throw Error(at(source, root) + ": a model file is a map with at least 'kind' and 'effects'");
  ModelSpec spec;
  spec.source = source;
  try {
    checkKeys(root,
              {"name", "kind", "load_torque", "joints", "robot", "gravity", "payload", "derivative_cutoff_hz",
               "velocity_smoothing", "reference_temperature", "effects"},
              source, "model");
    if (!root["kind"])
      throw Error(at(source, root) + ": missing 'kind' (joint_current, joint_tracking or gearbox_ftd)");
    spec.kind = parseKind(root["kind"], source);
    if (root["name"]) spec.name = root["name"].as<std::string>();
    if (root["load_torque"]) spec.loadTorque = parseLoadTorque(root["load_torque"], source);
    if (root["joints"]) {
      const double joints = number(root["joints"], source, "joints");
      if (joints < 1 || joints > kMaxJoint || joints != std::floor(joints)) {
        throw Error(at(source, root["joints"]) + ": joints: expected a positive integer");
      }
      spec.joints = static_cast<int>(joints);
    }
    if (root["robot"]) spec.urdf = parseRobot(root["robot"], source);
    if (root["gravity"]) spec.dynamics.gravity = vector3(root["gravity"], source, "gravity");
    if (const auto payload = root["payload"]) {
      if (!payload.IsMap()) throw Error(at(source, payload) + ": payload: expected {mass, center_of_mass}");
      checkKeys(payload, {"mass", "center_of_mass"}, source, "payload");
      if (payload["mass"]) spec.dynamics.payload.mass = number(payload["mass"], source, "payload.mass");
      if (payload["center_of_mass"]) {
        spec.dynamics.payload.centerOfMass = vector3(payload["center_of_mass"], source, "payload.center_of_mass");
      }
    }
    if (root["derivative_cutoff_hz"])
      spec.derivativeCutoffHz = number(root["derivative_cutoff_hz"], source, "derivative_cutoff_hz");
    if (root["velocity_smoothing"])
      spec.velocitySmoothing = number(root["velocity_smoothing"], source, "velocity_smoothing");
    if (spec.velocitySmoothing <= 0.0)
      throw Error(at(source, root["velocity_smoothing"]) + ": velocity_smoothing must be positive");
    if (root["reference_temperature"]) {
      spec.referenceTemperature = number(root["reference_temperature"], source, "reference_temperature");
    }
    const auto effects = root["effects"];
    if (!effects) throw Error(at(source, root) + ": missing 'effects' (a list, possibly empty: effects: [])");
    if (!effects.IsSequence()) throw Error(at(source, effects) + ": effects: expected a list");
    for (std::size_t i = 0; i < effects.size(); ++i) {
      auto effect = parseEffect(effects[i], source, i);
      try {
        validateEffect(effect, spec);
      } catch (const Error& e) {
        throw Error(at(source, effects[i]) + ": effects[" + std::to_string(i) + "]: " + e.what());
      }
      spec.effects.push_back(std::move(effect));
    }
  } catch (const YAML::Exception& e) {
    throw Error(reader(source).position(e.mark) + ": " + e.msg);
  }
  return spec;
}

ModelSpec loadModelFile(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file)) throw Error("model file " + file.string() + " does not exist");
  std::ifstream in(file);
  std::ostringstream text;
  text << in.rdbuf();
  return parseModelYaml(text.str(), file);
}

std::string toYaml(const ModelSpec& spec) {
  YAML::Emitter out;
  out.SetDoublePrecision(10);
  out << YAML::BeginMap;
  if (!spec.name.empty()) out << YAML::Key << "name" << YAML::Value << spec.name;
  out << YAML::Key << "kind" << YAML::Value << toString(spec.kind);
  if (spec.kind != ModelKind::GearboxFtd) out << YAML::Key << "load_torque" << YAML::Value << toString(spec.loadTorque);
  if (spec.joints > 0) out << YAML::Key << "joints" << YAML::Value << spec.joints;
  if (!spec.urdf.empty()) {
    out << YAML::Key << "robot" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "urdf" << YAML::Value
        << std::filesystem::absolute(spec.urdf).string() << YAML::EndMap;
  }
  const robot::DynamicsParameters defaults;
  if (spec.dynamics.gravity != defaults.gravity) {
    out << YAML::Key << "gravity" << YAML::Value;
    emitList(out, {spec.dynamics.gravity.x(), spec.dynamics.gravity.y(), spec.dynamics.gravity.z()});
  }
  if (spec.dynamics.payload.mass != 0.0) {
    const auto& c = spec.dynamics.payload.centerOfMass;
    out << YAML::Key << "payload" << YAML::Value << YAML::BeginMap << YAML::Key << "mass" << YAML::Value
        << spec.dynamics.payload.mass << YAML::Key << "center_of_mass" << YAML::Value;
    emitList(out, {c.x(), c.y(), c.z()});
    out << YAML::EndMap;
  }
  const ModelSpec plain;
  if (spec.derivativeCutoffHz != plain.derivativeCutoffHz)
    out << YAML::Key << "derivative_cutoff_hz" << YAML::Value << spec.derivativeCutoffHz;
  if (spec.velocitySmoothing != plain.velocitySmoothing)
    out << YAML::Key << "velocity_smoothing" << YAML::Value << spec.velocitySmoothing;
  if (spec.referenceTemperature != plain.referenceTemperature) {
    out << YAML::Key << "reference_temperature" << YAML::Value << spec.referenceTemperature;
  }
  out << YAML::Key << "effects" << YAML::Value << YAML::BeginSeq;
  for (const auto& effect : spec.effects) {
    const bool simple = effect.joints.empty() && effect.expressions.empty() && effect.explanation.empty() &&
                        effect.options.empty() && effect.parameters.empty();
    if (simple) {
      out << effect.id;
      continue;
    }
    out << YAML::BeginMap << YAML::Key << "id" << YAML::Value << effect.id;
    if (!effect.joints.empty()) out << YAML::Key << "joints" << YAML::Value << YAML::Flow << effect.joints;
    if (effect.expressions.size() == 1) out << YAML::Key << "expression" << YAML::Value << effect.expressions.front();
    if (effect.expressions.size() > 1) out << YAML::Key << "expression" << YAML::Value << effect.expressions;
    if (!effect.explanation.empty()) out << YAML::Key << "explanation" << YAML::Value << effect.explanation;
    for (const auto& [name, value] : effect.options) out << YAML::Key << name << YAML::Value << value;
    for (const auto* group : {&effect.parameters, &effect.standardErrors}) {
      if (group->empty()) continue;
      out << YAML::Key << (group == &effect.parameters ? "parameters" : "standard_errors") << YAML::Value
          << YAML::BeginMap;
      for (const auto& [name, values] : *group) {
        out << YAML::Key << name << YAML::Value;
        emitList(out, values);
      }
      out << YAML::EndMap;
    }
    out << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

void saveModelFile(const ModelSpec& spec, const std::filesystem::path& file) {
  writeFileAtomically(file, toYaml(spec));
}

}  // namespace arcplan::model
