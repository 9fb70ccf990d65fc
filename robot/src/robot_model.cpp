#include "arcplan/robot/robot_model.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>

#include <console_bridge/console.h>
#include <tinyxml.h>
#include <urdf_parser/urdf_parser.h>

#include "arcplan/common/error.h"
#include "arcplan/common/resources.h"
#include "arcplan/common/text_formatting.h"
#include "arcplan/robot/package_path.h"
#include "arcplan/robot/pose.h"
#include "xml_text.h"

namespace arcplan::robot {
namespace {

// urdfdom reports its parse errors through console_bridge; collect them so the exception we
// throw carries urdfdom's own explanation instead of a bare "parse failed".
class CollectingOutputHandler : public console_bridge::OutputHandler {
public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) messages.push_back(text);
  }
  std::vector<std::string> messages;
};

std::mutex consoleBridgeMutex;  // console_bridge's output handler is process-global

Eigen::Isometry3d toIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.translation() << pose.position.x, pose.position.y, pose.position.z;
  transform.linear() = Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
                           .normalized()
                           .toRotationMatrix();
  return transform;
}

std::string where(const std::filesystem::path& file) { return file.empty() ? std::string("URDF") : file.string(); }

CollisionGeometry convertCollision(const urdf::Collision& collision, const std::string& linkName,
                                   const std::filesystem::path& sourceFile) {
  CollisionGeometry geometry;
  geometry.origin = toIsometry(collision.origin);
  if (!collision.geometry)
    throw Error(where(sourceFile) + ": link '" + linkName + "' has a <collision> without <geometry>");
  switch (collision.geometry->type) {
    case urdf::Geometry::MESH: {
      const auto& mesh = static_cast<const urdf::Mesh&>(*collision.geometry);
      geometry.shape = CollisionGeometry::Shape::Mesh;
      try {
        geometry.meshFile = resolveResourceUri(mesh.filename, sourceFile);
      } catch (const Error& e) {
        throw Error(where(sourceFile) + ": link '" + linkName + "': " + e.what());
      }
      geometry.meshScale << mesh.scale.x, mesh.scale.y, mesh.scale.z;
      break;
    }
    case urdf::Geometry::BOX: {
      const auto& box = static_cast<const urdf::Box&>(*collision.geometry);
      geometry.shape = CollisionGeometry::Shape::Box;
      geometry.boxSize << box.dim.x, box.dim.y, box.dim.z;
      break;
    }
    case urdf::Geometry::SPHERE:
      geometry.shape = CollisionGeometry::Shape::Sphere;
      geometry.radius = static_cast<const urdf::Sphere&>(*collision.geometry).radius;
      break;
    case urdf::Geometry::CYLINDER: {
      const auto& cylinder = static_cast<const urdf::Cylinder&>(*collision.geometry);
      geometry.shape = CollisionGeometry::Shape::Cylinder;
      geometry.radius = cylinder.radius;
      geometry.length = cylinder.length;
      break;
    }
  }
  return geometry;
}

Link convertLink(const urdf::Link& source, const std::filesystem::path& sourceFile) {
  Link link;
  link.name = source.name;
  if (source.inertial) {
    link.hasInertial = true;
    const auto& in = *source.inertial;
    const Eigen::Isometry3d frame = toIsometry(in.origin);
    Eigen::Matrix3d inertia;
    inertia << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
    link.inertial.mass = in.mass;
    link.inertial.centerOfMass = frame.translation();
    // URDF gives the tensor in the rotated inertial frame; arcplan keeps it in link axes.
    link.inertial.inertiaAboutCom = frame.linear() * inertia * frame.linear().transpose();
  }
  for (const auto& collision : source.collision_array) {
    if (collision) link.collisions.push_back(convertCollision(*collision, source.name, sourceFile));
  }
  return link;
}

std::string knownLinks(const urdf::ModelInterface& urdf) {
  std::vector<std::string> names;
  for (const auto& [name, link] : urdf.links_) names.push_back(name);
  std::sort(names.begin(), names.end());
  return joinText(names, ", ");
}

// urdfdom reports why it rejects a description through console_bridge; those messages go into ours.
urdf::ModelInterfaceSharedPtr parseUrdf(const std::string& urdfXml, const std::filesystem::path& sourceFile) {
  std::lock_guard<std::mutex> lock(consoleBridgeMutex);
  CollectingOutputHandler handler;
  console_bridge::useOutputHandler(&handler);
  urdf::ModelInterfaceSharedPtr urdf = urdf::parseURDF(urdfXml);
  console_bridge::restorePreviousOutputHandler();
  if (!urdf) {
    const std::string details = joinText(handler.messages, "; ");
    throw Error(where(sourceFile) + ": invalid URDF: " + (details.empty() ? "urdfdom rejected it" : details));
  }
  return urdf;
}

// The moving chain, base first: a walk up from the tip to the base. urdfdom accepts links whose
// joints form a loop away from the root (found by fuzzing), so the walk is bounded by the link count.
std::vector<urdf::LinkConstSharedPtr> chainLinks(const urdf::ModelInterface& urdf, const ChainSelection& chain,
                                                 const std::filesystem::path& sourceFile) {
  const auto base = urdf.getLink(chain.baseLink);
  if (!base)
    throw Error(where(sourceFile) + ": base link '" + chain.baseLink + "' not found (links: " + knownLinks(urdf) + ")");
  const auto tip = urdf.getLink(chain.tipLink);
  if (!tip)
    throw Error(where(sourceFile) + ": tip link '" + chain.tipLink + "' not found (links: " + knownLinks(urdf) + ")");
  std::vector<urdf::LinkConstSharedPtr> links;
  for (urdf::LinkConstSharedPtr link = tip; link; link = link->getParent()) {
    if (links.size() > urdf.links_.size()) {
      throw Error(where(sourceFile) + ": the joints above tip link '" + chain.tipLink + "' form a loop");
    }
    links.push_back(link);
    if (link->name == chain.baseLink) break;
  }
  if (links.back()->name != chain.baseLink) {
    throw Error(where(sourceFile) + ": tip link '" + chain.tipLink + "' is not below base link '" + chain.baseLink +
                "'");
  }
  std::reverse(links.begin(), links.end());
  return links;
}

// A revolute joint's limits; continuous joints (and revolute ones without limits) get ±2π.
JointLimits limitsOf(const urdf::Joint& joint, const std::filesystem::path& sourceFile) {
  JointLimits limits;
  if (joint.type == urdf::Joint::CONTINUOUS || !joint.limits) {
    limits.lower = -2.0 * M_PI;
    limits.upper = 2.0 * M_PI;
  } else {
    limits.lower = joint.limits->lower;
    limits.upper = joint.limits->upper;
  }
  if (joint.limits) {
    limits.velocity = joint.limits->velocity;
    limits.effort = joint.limits->effort;
  }
  if (limits.lower > limits.upper) {
    throw Error(where(sourceFile) + ": joint '" + joint.name + "' has lower limit above upper limit");
  }
  return limits;
}

// Links and joints in the order RobotModel keeps them: every link after its parent.
struct ChainBuilder {
  std::filesystem::path sourceFile;
  std::vector<Link> links;
  std::vector<Joint> joints;
  std::map<std::string, int> indexOf;

  void add(const urdf::Link& source, int parent) {
    Link link = convertLink(source, sourceFile);
    link.parent = parent;
    if (parent >= 0) attach(link, *source.parent_joint);
    indexOf[source.name] = static_cast<int>(links.size());
    links.push_back(std::move(link));
  }

  // The joint that moves `link` relative to its parent: revolute and continuous joints are the
  // robot's joints, fixed joints only place the link.
  void attach(Link& link, const urdf::Joint& joint) {
    link.originInParent = toIsometry(joint.parent_to_joint_origin_transform);
    if (joint.type == urdf::Joint::FIXED) return;
    if (joint.type != urdf::Joint::REVOLUTE && joint.type != urdf::Joint::CONTINUOUS) {
      throw Error(where(sourceFile) + ": joint '" + joint.name +
                  "' on the chain is neither revolute, continuous nor fixed (arcplan supports serial revolute arms)");
    }
    link.axis = Eigen::Vector3d(joint.axis.x, joint.axis.y, joint.axis.z);
    if (link.axis.norm() < 1e-12) throw Error(where(sourceFile) + ": joint '" + joint.name + "' has a zero axis");
    link.axis.normalize();
    link.joint = static_cast<int>(joints.size());
    joints.push_back({joint.name, static_cast<int>(links.size()), limitsOf(joint, sourceFile)});
  }

  // Links rigidly attached to the chain (through fixed joints only) move with it: added
  // breadth-first so parents come before children.
  void addFixedChildren(const urdf::ModelInterface& urdf) {
    for (std::size_t next = 0; next < links.size(); ++next) {
      for (const auto& child : urdf.getLink(links[next].name)->child_links) {
        if (indexOf.count(child->name) != 0) continue;
        if (child->parent_joint && child->parent_joint->type == urdf::Joint::FIXED) add(*child, static_cast<int>(next));
      }
    }
  }
};

}  // namespace

int RobotModel::linkIndex(const std::string& linkName) const {
  for (std::size_t i = 0; i < links_.size(); ++i) {
    if (links_[i].name == linkName) return static_cast<int>(i);
  }
  std::vector<std::string> names;
  for (const auto& link : links_) names.push_back(link.name);
  throw Error("unknown link '" + linkName + "' in robot '" + name_ + "' (links: " + joinText(names, ", ") + ")");
}

RobotModel parseRobotModel(const std::string& urdfXml, const std::filesystem::path& sourceFile,
                           const ChainSelection& chain) {
  {
    // Syntax first, with TinyXML (urdfdom's own XML parser), so that the message has a line and column.
    TiXmlDocument document;
    detail::parseXml(urdfXml, where(sourceFile), document);
  }
  const urdf::ModelInterfaceSharedPtr urdf = parseUrdf(urdfXml, sourceFile);
  const auto chainSources = chainLinks(*urdf, chain, sourceFile);

  ChainBuilder builder{sourceFile, {}, {}, {}};
  for (std::size_t i = 0; i < chainSources.size(); ++i) {
    builder.add(*chainSources[i], i == 0 ? -1 : builder.indexOf.at(chainSources[i - 1]->name));
  }
  builder.addFixedChildren(*urdf);

  RobotModel model;
  model.name_ = urdf->getName();
  model.sourceFile_ = sourceFile;
  model.links_ = std::move(builder.links);
  model.joints_ = std::move(builder.joints);
  model.tipLink_ = builder.indexOf.at(chain.tipLink);
  if (chain.tcpOffset) {
    if (builder.indexOf.count("tcp") != 0) {
      throw Error(where(sourceFile) + ": a TCP offset adds a frame named 'tcp', but the robot has a link 'tcp'");
    }
    Link tcp;
    tcp.name = "tcp";
    tcp.parent = model.tipLink_;
    tcp.originInParent = *chain.tcpOffset;
    model.tipLink_ = static_cast<int>(model.links_.size());
    model.links_.push_back(std::move(tcp));
  }
  return model;
}

RobotModel loadRobotModel(const std::filesystem::path& urdfFile, const ChainSelection& chain) {
  std::ifstream in(urdfFile, std::ios::binary);
  if (!in) throw Error("cannot open URDF file " + urdfFile.string());
  std::ostringstream text;
  text << in.rdbuf();
  return parseRobotModel(text.str(), std::filesystem::absolute(urdfFile), chain);
}

std::filesystem::path ur10eUrdfPath() { return dataDirectory() / "ur10e" / "ur10e.urdf"; }

const RobotModel& ur10e() {
  static const RobotModel model = loadRobotModel(ur10eUrdfPath());
  return model;
}

}  // namespace arcplan::robot
