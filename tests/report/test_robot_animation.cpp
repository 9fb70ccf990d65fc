// The 3D view's data: base64 encoding, link meshes, link-pose frames along a trajectory.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "arcplan/report/robot_animation.h"
#include "arcplan/robot/kinematics.h"
#include "arcplan/robot/mesh.h"
#include "base64.h"
#include "support/base64_decoding.h"
#include "support/error_message.h"
#include "support/robot_files.h"

namespace {

using arcplan::report::linkPoseFrames;
using arcplan::report::robotMeshesJson;
using arcplan::report::detail::base64;
using arcplan::testing::decodeBase64;
using arcplan::testing::decodeBase64Array;

// RFC 4648 §10 test vectors: text and its base64.
const std::vector<std::pair<std::string, std::string>> kRfcVectors{{"", ""},
                                                                   {"f", "Zg=="},
                                                                   {"fo", "Zm8="},
                                                                   {"foo", "Zm9v"},
                                                                   {"foob", "Zm9vYg=="},
                                                                   {"fooba", "Zm9vYmE="},
                                                                   {"foobar", "Zm9vYmFy"}};

TEST(Base64, MatchesTheRfcVectors) {
  for (const auto& [text, encoded] : kRfcVectors) {
    EXPECT_EQ(base64(reinterpret_cast<const unsigned char*>(text.data()), text.size()), encoded) << text;
  }
}

// The tests' own decoder (support/base64_decoding.h), which every check of the report's arrays relies on.
TEST(Base64, TheTestDecoderInvertsTheRfcVectors) {
  for (const auto& [text, encoded] : kRfcVectors) {
    const auto bytes = decodeBase64(encoded);
    EXPECT_EQ(std::string(bytes.begin(), bytes.end()), text) << encoded;
  }
}

TEST(RobotMeshes, EveryMeshedLinkWithItsStlTriangles) {
  const auto& robot = arcplan::robot::ur10e();
  const auto meshes = robotMeshesJson(robot);
  // data/ur10e/meshes holds seven STL files, one per link from base_link_inertia to wrist_3_link.
  ASSERT_EQ(meshes.size(), 7u);
  for (const auto& mesh : meshes) {
    const auto& link = robot.links()[static_cast<std::size_t>(robot.linkIndex(mesh["link"]))];
    ASSERT_EQ(link.collisions.size(), 1u) << mesh["link"];
    const auto stl = arcplan::robot::loadMesh(link.collisions.front().meshFile, link.collisions.front().meshScale);
    const auto positions = decodeBase64Array<float>(mesh["positions"]);
    const auto indices = decodeBase64Array<std::uint32_t>(mesh["indices"]);
    EXPECT_EQ(positions.size(), 3 * stl.vertices.size());
    EXPECT_EQ(indices.size(), 3 * stl.triangles.size());
    EXPECT_EQ(mesh["triangles"], stl.triangles.size());
    for (const auto index : indices) ASSERT_LT(index, stl.vertices.size());
    // The link frame is where the STL is (the UR10e URDF has identity collision origins).
    EXPECT_NEAR(positions[0], stl.vertices[0].x(), 1e-6);
    EXPECT_NEAR(positions[2], stl.vertices[0].z(), 1e-6);
  }
}

// A URDF may give a primitive no volume (urdfdom takes a zero radius or length): the link is listed
// with nothing to draw instead of the report ending; the primitives beside it are still drawn.
TEST(RobotMeshes, APrimitiveWithoutVolumeDrawsNothing) {
  std::string urdf = arcplan::testing::ur10eUrdfText();
  urdf.insert(urdf.rfind("</robot>"),
              "<link name=\"flat\"><collision><geometry><cylinder radius=\"0.05\" length=\"0\"/></geometry></collision>"
              "<collision><geometry><sphere radius=\"0\"/></geometry></collision></link>"
              "<joint name=\"tool0-flat\" type=\"fixed\"><parent link=\"tool0\"/><child link=\"flat\"/></joint>"
              "<link name=\"tip\"><collision><geometry><box size=\"0.02 0.02 0\"/></geometry></collision>"
              "<collision><geometry><sphere radius=\"0.01\"/></geometry></collision></link>"
              "<joint name=\"flat-tip\" type=\"fixed\"><parent link=\"flat\"/><child link=\"tip\"/></joint>");
  const auto robot = arcplan::robot::parseRobotModel(urdf, "flat_primitives.urdf");
  const auto meshes = robotMeshesJson(robot);
  ASSERT_EQ(meshes.size(), 9u);  // the seven STL links, flat and tip
  EXPECT_EQ(meshes[7]["link"], "flat");
  EXPECT_EQ(meshes[7]["triangles"], 0u);
  EXPECT_EQ(meshes[8]["link"], "tip");
  // Only the sphere of radius 0.01: 16 segments, 7 rings of latitude, 2 poles.
  EXPECT_EQ(meshes[8]["vertices"], 16u * 7u + 2u);
  for (const auto value : decodeBase64Array<float>(meshes[8]["positions"])) EXPECT_LE(std::abs(value), 0.01f + 1e-7f);
}

TEST(LinkPoseFrames, SamplesTheMotionAtTheRate) {
  const auto& robot = arcplan::robot::ur10e();
  // Joint 0 turns from 0 to 1 rad in 2 s, the other joints hold a bent-arm pose.
  arcplan::robot::Vector6 start, end;
  start << 0.0, -1.5, 1.5, -1.5, -1.57, 0.0;
  end = start;
  end[0] = 1.0;
  const auto frames = linkPoseFrames(robot, {0.0, 2.0}, {start, end}, 25.0);
  EXPECT_EQ(frames["frames"], 51);  // 0, 0.04, ..., 2.0 s
  EXPECT_DOUBLE_EQ(frames["duration_s"], 2.0);
  const auto poses = decodeBase64Array<float>(frames["poses"]);
  ASSERT_EQ(poses.size(), 51u * 7u * 7u);
  // Frame 25 is t = 1 s, q0 = 0.5 rad: the wrist_3 link origin is the start pose's rotated by 0.5
  // rad about the base z axis (joint 0 turns the whole arm about it).
  arcplan::robot::KinematicsData data(robot);
  arcplan::robot::forwardKinematics(robot, start, data);
  const Eigen::Vector3d atStart =
      data.linkPoses[static_cast<std::size_t>(robot.linkIndex("wrist_3_link"))].translation();
  const Eigen::Vector3d expected = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()) * atStart;
  const std::size_t wrist3 = 6;  // the seventh meshed link
  const std::size_t at = (25 * 7 + wrist3) * 7;
  EXPECT_NEAR(poses[at], expected.x(), 1e-5);
  EXPECT_NEAR(poses[at + 1], expected.y(), 1e-5);
  EXPECT_NEAR(poses[at + 2], expected.z(), 1e-5);
  // Quaternions are unit length.
  EXPECT_NEAR(std::hypot(std::hypot(poses[at + 3], poses[at + 4]), std::hypot(poses[at + 5], poses[at + 6])), 1.0,
              1e-5);
}

TEST(LinkPoseFrames, RejectsMismatchedInput) {
  const auto& robot = arcplan::robot::ur10e();
  EXPECT_NE(arcplan::testing::errorMessageOf([&] {
              linkPoseFrames(robot, {0.0, 1.0}, {arcplan::robot::Vector6::Zero()}, 25.0);
            }).find("2 times for 1 joint vectors"),
            std::string::npos);
}

}  // namespace
