#include "ur_description_files.h"

#include <cmath>

#include "arcplan/common/yaml_reading.h"

namespace arcplan::robot::detail {
namespace {

constexpr const char* kTop = "top level";

// A mapping entry that must be a mapping itself.
YAML::Node section(const YamlReader& yaml, const YAML::Node& map, const char* key, const std::string& field) {
  yaml.expectMap(map, field);
  const YAML::Node node = yaml.required(map, key, field);
  yaml.expectMap(node, field == kTop ? key : field + "." + key);
  return node;
}

double numberAt(const YamlReader& yaml, const YAML::Node& map, const char* key, const std::string& field) {
  return yaml.number(yaml.required(map, key, field), field + "." + key);
}

// UR's joint_limits.yaml writes angles as `!degrees 360.0`; an untagged number is in radians.
double angleAt(const YamlReader& yaml, const YAML::Node& map, const char* key, const std::string& field) {
  const YAML::Node node = yaml.required(map, key, field);
  const double value = yaml.number(node, field + "." + key);
  const std::string& tag = node.Tag();
  if (tag == "!degrees") return value * M_PI / 180.0;
  if (tag.empty() || tag == "?" || tag == "!" || tag == "!radians") return value;
  yaml.fail(node, field + "." + key, "unknown tag '" + tag + "'; expected !degrees, !radians or none");
}

bool flagAt(const YamlReader& yaml, const YAML::Node& map, const char* key, const std::string& field) {
  const YAML::Node node = yaml.required(map, key, field);
  bool value = false;
  if (!node.IsScalar() || !YAML::convert<bool>::decode(node, value)) {
    yaml.fail(node, field + "." + key, "expected true or false");
  }
  return value;
}

XyzRpy xyzRpyAt(const YamlReader& yaml, const YAML::Node& node, const std::string& field,
                const std::vector<std::string>& allowedKeys) {
  yaml.checkKeys(node, field, allowedKeys);
  XyzRpy frame;
  frame.xyz << numberAt(yaml, node, "x", field), numberAt(yaml, node, "y", field), numberAt(yaml, node, "z", field);
  frame.rpy << numberAt(yaml, node, "roll", field), numberAt(yaml, node, "pitch", field),
      numberAt(yaml, node, "yaw", field);
  return frame;
}

Eigen::Vector3d rpyAt(const YamlReader& yaml, const YAML::Node& node, const std::string& field) {
  yaml.expectMap(node, field);
  return {numberAt(yaml, node, "roll", field), numberAt(yaml, node, "pitch", field),
          numberAt(yaml, node, "yaw", field)};
}

Eigen::Vector3d xyzAt(const YamlReader& yaml, const YAML::Node& node, const std::string& field) {
  yaml.expectMap(node, field);
  return {numberAt(yaml, node, "x", field), numberAt(yaml, node, "y", field), numberAt(yaml, node, "z", field)};
}

YAML::Node loadRoot(const YamlReader& yaml, const std::string& what, const char* key) {
  const YAML::Node root = yaml.load(what);
  if (!root.IsMap()) yaml.fail(root, what, std::string("expected a mapping with key ") + key);
  return root;
}

}  // namespace

UrKinematics readUrKinematics(const std::filesystem::path& file) {
  const YamlReader yaml(file);
  const YAML::Node root = loadRoot(yaml, "UR kinematics file", "kinematics");
  const YAML::Node kinematics = section(yaml, root, "kinematics", kTop);
  std::vector<std::string> allowed(kUrLinkSections.begin(), kUrLinkSections.end());
  allowed.push_back("hash");  // the calibration's checksum, written by UR's calibration tool
  yaml.checkKeys(kinematics, "kinematics", allowed);
  UrKinematics frames;
  for (std::size_t j = 0; j < 6; ++j) {
    const std::string field = std::string("kinematics.") + kUrLinkSections[j];
    frames[j] = xyzRpyAt(yaml, section(yaml, kinematics, kUrLinkSections[j], "kinematics"), field,
                         {"x", "y", "z", "roll", "pitch", "yaw"});
  }
  return frames;
}

std::array<UrJointLimit, 6> readUrJointLimits(const std::filesystem::path& file) {
  const YamlReader yaml(file);
  const YAML::Node root = loadRoot(yaml, "UR joint limits file", "joint_limits");
  const YAML::Node all = section(yaml, root, "joint_limits", kTop);
  std::array<UrJointLimit, 6> limits;
  for (std::size_t j = 0; j < 6; ++j) {
    const std::string field = std::string("joint_limits.") + kUrJointNames[j];
    const YAML::Node node = section(yaml, all, kUrJointNames[j], "joint_limits");
    UrJointLimit& limit = limits[j];
    limit.hasPositionLimits = !node["has_position_limits"] || flagAt(yaml, node, "has_position_limits", field);
    if (limit.hasPositionLimits) {
      limit.lower = angleAt(yaml, node, "min_position", field);
      limit.upper = angleAt(yaml, node, "max_position", field);
      if (!(limit.lower < limit.upper)) {
        yaml.fail(node, field, "min_position must be below max_position");
      }
    }
    limit.velocity = angleAt(yaml, node, "max_velocity", field);
    limit.effort = numberAt(yaml, node, "max_effort", field);
    if (limit.velocity < 0.0 || limit.effort < 0.0) yaml.fail(node, field, "negative velocity or effort limit");
  }
  return limits;
}

UrPhysicalParameters readUrPhysicalParameters(const std::filesystem::path& file) {
  const YamlReader yaml(file);
  const YAML::Node root = loadRoot(yaml, "UR physical parameters file", "inertia_parameters");
  UrPhysicalParameters physical;
  const YAML::Node offsets = section(yaml, root, "offsets", kTop);
  physical.shoulderOffset = numberAt(yaml, offsets, "shoulder_offset", "offsets");
  physical.elbowOffset = numberAt(yaml, offsets, "elbow_offset", "offsets");

  const std::string field = "inertia_parameters";
  const YAML::Node inertia = section(yaml, root, "inertia_parameters", kTop);
  physical.baseMass = numberAt(yaml, inertia, "base_mass", field);
  const YAML::Node base = section(yaml, section(yaml, inertia, "links", field), "base", field + ".links");
  physical.baseRadius = numberAt(yaml, base, "radius", field + ".links.base");
  physical.baseLength = numberAt(yaml, base, "length", field + ".links.base");
  const YAML::Node centres = section(yaml, inertia, "center_of_mass", field);
  const YAML::Node rotations = section(yaml, inertia, "rotation", field);
  const YAML::Node tensors = section(yaml, inertia, "tensor", field);
  for (std::size_t j = 0; j < 6; ++j) {
    const std::string name = kUrLinkSections[j];
    UrLinkInertia& link = physical.links[j];
    link.mass = numberAt(yaml, inertia, (name + "_mass").c_str(), field);
    if (!(link.mass > 0.0))
      yaml.fail(inertia[name + "_mass"], field + "." + name + "_mass", "expected a positive mass");
    link.frame.xyz = xyzAt(yaml, yaml.required(centres, (name + "_cog").c_str(), field + ".center_of_mass"),
                           field + ".center_of_mass." + name + "_cog");
    link.frame.rpy =
        rpyAt(yaml, yaml.required(rotations, name.c_str(), field + ".rotation"), field + ".rotation." + name);
    const std::string tensorField = field + ".tensor." + name;
    const YAML::Node tensor = section(yaml, tensors, name.c_str(), field + ".tensor");
    link.ixx = numberAt(yaml, tensor, "ixx", tensorField);
    link.ixy = numberAt(yaml, tensor, "ixy", tensorField);
    link.ixz = numberAt(yaml, tensor, "ixz", tensorField);
    link.iyy = numberAt(yaml, tensor, "iyy", tensorField);
    link.iyz = numberAt(yaml, tensor, "iyz", tensorField);
    link.izz = numberAt(yaml, tensor, "izz", tensorField);
  }
  return physical;
}

UrVisualParameters readUrVisualParameters(const std::filesystem::path& file,
                                          const std::filesystem::path& descriptionFolder) {
  const YamlReader yaml(file);
  const YAML::Node root = loadRoot(yaml, "UR visual parameters file", "mesh_files");
  const YAML::Node meshes = section(yaml, root, "mesh_files", kTop);
  const auto collisionMesh = [&](const std::string& name) {
    const std::string field = "mesh_files." + name + ".collision.mesh";
    const YAML::Node link = section(yaml, meshes, name.c_str(), "mesh_files");
    const YAML::Node mesh = section(yaml, section(yaml, link, "collision", "mesh_files." + name), "mesh",
                                    "mesh_files." + name + ".collision");
    const YAML::Node pathNode = yaml.required(mesh, "path", field);
    const std::filesystem::path path = descriptionFolder / yaml.text(pathNode, field + ".path");
    if (!std::filesystem::is_regular_file(path)) {
      yaml.fail(pathNode, field + ".path", "collision mesh " + path.string() + " does not exist");
    }
    return path;
  };
  UrVisualParameters visual;
  visual.baseMesh = collisionMesh("base");
  for (std::size_t j = 0; j < 6; ++j) visual.linkMeshes[j] = collisionMesh(kUrLinkSections[j]);
  for (std::size_t w = 0; w < 3; ++w) {
    const std::string name = kUrLinkSections[3 + w];
    visual.wristOffsets[w] = numberAt(yaml, meshes[name], "visual_offset", "mesh_files." + name);
  }
  return visual;
}

}  // namespace arcplan::robot::detail
