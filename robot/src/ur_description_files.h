#pragma once
// The YAML files of Universal Robots' description (UniversalRobots/Universal_Robots_ROS2_Description,
// config/<type>/): what each says, read with file:line:column and field in every error. Internal to
// arcplan::robot; ur_description.cpp builds the robot from them, the fuzz targets call the readers.
#include <array>
#include <filesystem>
#include <string>

#include <Eigen/Core>

namespace arcplan::robot::detail {

// The six moving links in chain order, as the files name their sections.
inline constexpr std::array<const char*, 6> kUrLinkSections = {"shoulder", "upper_arm", "forearm",
                                                               "wrist_1",  "wrist_2",   "wrist_3"};
inline constexpr std::array<const char*, 6> kUrJointNames = {
    "shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint", "wrist_2_joint", "wrist_3_joint"};

// x, y, z (m) and URDF roll, pitch, yaw (rad) of a frame in its parent.
struct XyzRpy {
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
};

// default_kinematics.yaml, or a robot's calibration in the same format: each joint's frame.
using UrKinematics = std::array<XyzRpy, 6>;
UrKinematics readUrKinematics(const std::filesystem::path& file);

struct UrJointLimit {
  bool hasPositionLimits = true;                                  // false: a continuous joint (wrist 3 of some types)
  double lower = 0.0, upper = 0.0, velocity = 0.0, effort = 0.0;  // rad, rad/s, N·m
};
// joint_limits.yaml; angles may carry YAML tags !degrees or !radians.
std::array<UrJointLimit, 6> readUrJointLimits(const std::filesystem::path& file);

struct UrLinkInertia {
  double mass = 0.0;
  XyzRpy frame;  // centre of mass and the axes of the tensor
  double ixx = 0.0, ixy = 0.0, ixz = 0.0, iyy = 0.0, iyz = 0.0, izz = 0.0;
};
struct UrPhysicalParameters {
  double shoulderOffset = 0.0, elbowOffset = 0.0;  // where the arm meshes sit along their link's z
  double baseMass = 0.0, baseRadius = 0.0, baseLength = 0.0;
  std::array<UrLinkInertia, 6> links;
};
UrPhysicalParameters readUrPhysicalParameters(const std::filesystem::path& file);

// visual_parameters.yaml: the collision mesh of the base and each moving link (resolved in
// `descriptionFolder`, the package the file names) and the wrist meshes' offsets along z.
struct UrVisualParameters {
  std::filesystem::path baseMesh;
  std::array<std::filesystem::path, 6> linkMeshes;
  std::array<double, 3> wristOffsets{};  // wrist_1, wrist_2, wrist_3
};
UrVisualParameters readUrVisualParameters(const std::filesystem::path& file,
                                          const std::filesystem::path& descriptionFolder);

}  // namespace arcplan::robot::detail
