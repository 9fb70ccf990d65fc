#pragma once
// The robot as arcplan sees it: a serial kinematic chain read from a URDF (urdfdom), with joint
// limits, link inertials and collision geometry. A RobotModel never changes after loading;
// algorithms that need scratch space take a separate workspace (see kinematics.h).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace arcplan::robot {

struct JointLimits {
  double lower = 0.0;     // rad
  double upper = 0.0;     // rad
  double velocity = 0.0;  // rad/s
  double effort = 0.0;    // N·m
};

// Mass properties of one link, in that link's frame (URDF <inertial>, rotation already applied).
struct Inertial {
  double mass = 0.0;
  Eigen::Vector3d centerOfMass = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertiaAboutCom = Eigen::Matrix3d::Zero();
};

// One <collision> element of a link.
struct CollisionGeometry {
  enum class Shape { Mesh, Box, Sphere, Cylinder };
  Shape shape = Shape::Mesh;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  // in the link frame
  std::filesystem::path meshFile;                            // resolved, absolute (Shape::Mesh)
  Eigen::Vector3d meshScale = Eigen::Vector3d::Ones();
  Eigen::Vector3d boxSize = Eigen::Vector3d::Zero();
  double radius = 0.0;  // sphere, cylinder
  double length = 0.0;  // cylinder (along its local z, centred)
};

// A link whose pose forward kinematics computes. Links are ordered parents before children.
// The transform to the parent is origin·Rot(axis, q[joint]) for a moving joint, origin alone for
// a fixed one. Links hanging off the chain through fixed joints (tool frames, sensor frames) are
// included; links behind other moving joints are not.
struct Link {
  std::string name;
  int parent = -1;  // index into RobotModel::links(), -1 for the chain base
  Eigen::Isometry3d originInParent = Eigen::Isometry3d::Identity();
  int joint = -1;                                   // index of the moving joint into q, -1 if fixed
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // unit joint axis in this link's frame
  bool hasInertial = false;
  Inertial inertial;
  std::vector<CollisionGeometry> collisions;
};

struct Joint {
  std::string name;
  int link = -1;  // the link this joint moves (child link)
  JointLimits limits;
};

// Which part of a description is the robot: the chain from baseLink to tipLink. The tip is the TCP
// (tool centre point): what inverse kinematics solves for and Cartesian planners move along lines.
// With tcpOffset the model gets one more frame, a link named "tcp" fixed to tipLink at that offset,
// and that frame is the tip.
struct ChainSelection {
  std::string baseLink = "base_link";
  std::string tipLink = "tool0";
  std::optional<Eigen::Isometry3d> tcpOffset;
};

struct UrDescriptionSelection;

class RobotModel {
public:
  const std::string& name() const { return name_; }
  const std::vector<Link>& links() const { return links_; }
  const std::vector<Joint>& joints() const { return joints_; }
  int dof() const { return static_cast<int>(joints_.size()); }
  int baseLink() const { return 0; }
  // The TCP (see ChainSelection).
  int tipLink() const { return tipLink_; }
  // Index of a link by name; throws arcplan::Error listing the known links if absent.
  int linkIndex(const std::string& linkName) const;
  const std::filesystem::path& sourceFile() const { return sourceFile_; }
  // True when the joint frames come from a robot's own calibration (a kinematics file given for a
  // UR type): they may then deviate from the nominal geometry by calibration offsets.
  bool calibrated() const { return calibrated_; }

private:
  friend RobotModel loadRobotModel(const std::filesystem::path&, const ChainSelection&);
  friend RobotModel parseRobotModel(const std::string&, const std::filesystem::path&, const ChainSelection&);
  friend RobotModel loadUrDescription(const UrDescriptionSelection&, const ChainSelection&);
  std::string name_;
  std::vector<Link> links_;
  std::vector<Joint> joints_;
  int tipLink_ = -1;
  std::filesystem::path sourceFile_;
  bool calibrated_ = false;
};

// Reads a URDF file. Mesh URIs are resolved through package_path.h. Throws arcplan::Error naming
// the file and what is wrong (malformed XML, missing link, no chain from base to tip, a mesh
// file that does not exist).
RobotModel loadRobotModel(const std::filesystem::path& urdfFile, const ChainSelection& chain = {});
// Same from URDF text; `sourceFile` is used for messages and relative mesh paths.
RobotModel parseRobotModel(const std::string& urdfXml, const std::filesystem::path& sourceFile,
                           const ChainSelection& chain = {});

// arcplan's own UR10e description (data/ur10e/ur10e.urdf), base_link -> tool0.
const RobotModel& ur10e();
std::filesystem::path ur10eUrdfPath();

}  // namespace arcplan::robot
