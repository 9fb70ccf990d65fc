#include "arcplan/robot/ur_description.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "arcplan/common/error.h"
#include "arcplan/common/resources.h"
#include "arcplan/common/text_formatting.h"
#include "ur_description_files.h"

namespace arcplan::robot {
namespace {

// Every number with all its digits: the URDF text is only a carrier between the YAML and RobotModel.
std::string numbers(const Eigen::Vector3d& v) {
  std::ostringstream out;
  out.precision(17);
  out << v.x() << ' ' << v.y() << ' ' << v.z();
  return out.str();
}

std::string origin(const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy) {
  return "<origin xyz=\"" + numbers(xyz) + "\" rpy=\"" + numbers(rpy) + "\"/>";
}

std::string collision(const std::filesystem::path& mesh, const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy) {
  return "<collision>" + origin(xyz, rpy) + "<geometry><mesh filename=\"" + mesh.string() +
         "\"/></geometry></collision>";
}

std::string inertial(double mass, const detail::XyzRpy& frame, const Eigen::Vector3d& diagonal,
                     const Eigen::Vector3d& offDiagonal) {
  std::ostringstream out;
  out.precision(17);
  out << "<inertial><mass value=\"" << mass << "\"/>" << origin(frame.xyz, frame.rpy) << "<inertia ixx=\""
      << diagonal.x() << "\" ixy=\"" << offDiagonal.x() << "\" ixz=\"" << offDiagonal.y() << "\" iyy=\"" << diagonal.y()
      << "\" iyz=\"" << offDiagonal.z() << "\" izz=\"" << diagonal.z() << "\"/></inertial>";
  return out.str();
}

std::string fixedJoint(const std::string& parent, const std::string& child, const Eigen::Vector3d& rpy) {
  return "<link name=\"" + child + "\"/><joint name=\"" + parent + "-" + child + "\" type=\"fixed\"><parent link=\"" +
         parent + "\"/><child link=\"" + child + "\"/>" + origin(Eigen::Vector3d::Zero(), rpy) + "</joint>";
}

std::string limitElement(const detail::UrJointLimit& limit) {
  std::ostringstream out;
  out.precision(17);
  out << "<limit";
  if (limit.hasPositionLimits) out << " lower=\"" << limit.lower << "\" upper=\"" << limit.upper << "\"";
  out << " effort=\"" << limit.effort << "\" velocity=\"" << limit.velocity << "\"/>";
  return out.str();
}

// The mesh origins of UR's xacro macro (ur_macro.xacro): the base and shoulder meshes turned by pi
// about z, the arm meshes standing on their link's z at the physical offsets, the wrists at theirs.
struct MeshPlacement {
  Eigen::Vector3d xyz, rpy;
};

std::array<MeshPlacement, 6> meshPlacements(const detail::UrPhysicalParameters& physical,
                                            const detail::UrVisualParameters& visual) {
  const Eigen::Vector3d armTurn(M_PI_2, 0.0, -M_PI_2), wristTurn(M_PI_2, 0.0, 0.0);
  return {{{Eigen::Vector3d::Zero(), Eigen::Vector3d(0.0, 0.0, M_PI)},
           {Eigen::Vector3d(0.0, 0.0, physical.shoulderOffset), armTurn},
           {Eigen::Vector3d(0.0, 0.0, physical.elbowOffset), armTurn},
           {Eigen::Vector3d(0.0, 0.0, visual.wristOffsets[0]), wristTurn},
           {Eigen::Vector3d(0.0, 0.0, visual.wristOffsets[1]), Eigen::Vector3d::Zero()},
           {Eigen::Vector3d(0.0, 0.0, visual.wristOffsets[2]), wristTurn}}};
}

std::string urdfText(const std::string& type, const detail::UrKinematics& kinematics,
                     const std::array<detail::UrJointLimit, 6>& limits, const detail::UrPhysicalParameters& physical,
                     const detail::UrVisualParameters& visual) {
  std::string urdf = "<robot name=\"" + type + "\"><link name=\"base_link\"/>";
  // A solid cylinder of the base's mass: I = m(3r² + l²)/12 about x and y, m r²/2 about z.
  const double m = physical.baseMass, r = physical.baseRadius, l = physical.baseLength;
  const double across = m * (3.0 * r * r + l * l) / 12.0;
  urdf += "<link name=\"base_link_inertia\">" +
          collision(visual.baseMesh, Eigen::Vector3d::Zero(), Eigen::Vector3d(0.0, 0.0, M_PI)) +
          inertial(m, {}, Eigen::Vector3d(across, across, m * r * r / 2.0), Eigen::Vector3d::Zero()) + "</link>";
  urdf +=
      "<joint name=\"base_link-base_link_inertia\" type=\"fixed\"><parent link=\"base_link\"/>"
      "<child link=\"base_link_inertia\"/>" +
      origin(Eigen::Vector3d::Zero(), Eigen::Vector3d(0.0, 0.0, M_PI)) + "</joint>";
  const auto placements = meshPlacements(physical, visual);
  std::string parent = "base_link_inertia";
  for (std::size_t j = 0; j < 6; ++j) {
    const std::string link = std::string(detail::kUrLinkSections[j]) + "_link";
    const auto& in = physical.links[j];
    urdf +=
        "<link name=\"" + link + "\">" + collision(visual.linkMeshes[j], placements[j].xyz, placements[j].rpy) +
        inertial(in.mass, in.frame, Eigen::Vector3d(in.ixx, in.iyy, in.izz), Eigen::Vector3d(in.ixy, in.ixz, in.iyz)) +
        "</link>";
    urdf += std::string("<joint name=\"") + detail::kUrJointNames[j] + "\" type=\"" +
            (limits[j].hasPositionLimits ? "revolute" : "continuous") + "\"><parent link=\"" + parent +
            "\"/><child link=\"" + link + "\"/>" + origin(kinematics[j].xyz, kinematics[j].rpy) +
            "<axis xyz=\"0 0 1\"/>" + limitElement(limits[j]) + "</joint>";
    parent = link;
  }
  urdf += fixedJoint("wrist_3_link", "ft_frame", Eigen::Vector3d(M_PI, 0.0, 0.0));
  urdf += fixedJoint("base_link", "base", Eigen::Vector3d(0.0, 0.0, M_PI));
  urdf += fixedJoint("wrist_3_link", "flange", Eigen::Vector3d(0.0, -M_PI_2, -M_PI_2));
  urdf += fixedJoint("flange", "tool0", Eigen::Vector3d(M_PI_2, 0.0, M_PI_2));
  return urdf + "</robot>";
}

}  // namespace

std::filesystem::path defaultUrDescriptionFolder() { return sharedDataDirectory() / "ur_description"; }

std::vector<std::string> urTypesIn(const std::filesystem::path& folder) {
  std::vector<std::string> types;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(folder / "config", error)) {
    if (std::filesystem::is_regular_file(entry.path() / "default_kinematics.yaml")) {
      types.push_back(entry.path().filename().string());
    }
  }
  std::sort(types.begin(), types.end());
  return types;
}

RobotModel loadUrDescription(const UrDescriptionSelection& selection, const ChainSelection& chain) {
  // Absolute: the generated URDF names its meshes under this folder and is then read relative to the
  // calibration file's folder, where a relative folder (the default ../shared/data) would point elsewhere.
  const std::filesystem::path folder =
      std::filesystem::absolute(selection.folder.empty() ? defaultUrDescriptionFolder() : selection.folder);
  if (!std::filesystem::is_directory(folder / "config")) {
    throw Error("UR description folder " + folder.string() +
                " not found or without config/ (set ARCPLAN_SHARED_DATA or name the folder with description)");
  }
  const auto types = urTypesIn(folder);
  if (selection.type.empty() || std::find(types.begin(), types.end(), selection.type) == types.end()) {
    throw Error("unknown UR type '" + selection.type + "' in " + folder.string() + " (known: " + joinText(types, ", ") +
                ")");
  }
  const std::filesystem::path config = folder / "config" / selection.type;
  const std::filesystem::path kinematicsFile =
      selection.kinematics.empty() ? config / "default_kinematics.yaml" : selection.kinematics;
  const std::string urdf = urdfText(selection.type, detail::readUrKinematics(kinematicsFile),
                                    detail::readUrJointLimits(config / "joint_limits.yaml"),
                                    detail::readUrPhysicalParameters(config / "physical_parameters.yaml"),
                                    detail::readUrVisualParameters(config / "visual_parameters.yaml", folder));
  RobotModel model = parseRobotModel(urdf, std::filesystem::absolute(kinematicsFile), chain);
  model.calibrated_ = !selection.kinematics.empty();
  return model;
}

}  // namespace arcplan::robot
