#include <cstdlib>
#include <fstream>

#include <gtest/gtest.h>

#include "arcplan/common/error.h"
#include "arcplan/robot/mesh.h"
#include "arcplan/robot/robot_model.h"
#include "arcplan/robot/srdf.h"
#include "support/command.h"

namespace {

using arcplan::Error;
using arcplan::robot::loadRobotModel;
using arcplan::robot::ur10e;

void writeText(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file) << text;
}

// A closed tetrahedron, ASCII STL, outward normals.
const char* kTetrahedronStl = R"(solid tetra
facet normal 0 0 -1
 outer loop
  vertex 0 0 0
  vertex 0 1 0
  vertex 1 0 0
 endloop
endfacet
facet normal 0 -1 0
 outer loop
  vertex 0 0 0
  vertex 1 0 0
  vertex 0 0 1
 endloop
endfacet
facet normal -1 0 0
 outer loop
  vertex 0 0 0
  vertex 0 0 1
  vertex 0 1 0
 endloop
endfacet
facet normal 0.577 0.577 0.577
 outer loop
  vertex 1 0 0
  vertex 0 1 0
  vertex 0 0 1
 endloop
endfacet
endsolid tetra
)";

std::string oneLinkUrdf(const std::string& meshUri) {
  return R"(<?xml version="1.0"?>
<robot name="probe">
  <link name="base_link"/>
  <link name="tool0">
    <collision><geometry><mesh filename=")" +
         meshUri + R"(" scale="2 2 2"/></geometry></collision>
  </link>
  <joint name="j" type="revolute">
    <parent link="base_link"/><child link="tool0"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
</robot>)";
}

class ScopedEnvironment {
public:
  ScopedEnvironment(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) previous_ = old;
    setenv(name, value.c_str(), 1);
  }
  ~ScopedEnvironment() {
    if (previous_)
      setenv(name_, previous_->c_str(), 1);
    else
      unsetenv(name_);
  }

private:
  const char* name_;
  std::optional<std::string> previous_;
};

TEST(RobotModel, Ur10eChainJointsAndLimits) {
  const auto& model = ur10e();
  ASSERT_EQ(model.dof(), 6);
  const std::vector<std::string> names{"shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint",
                                       "wrist_1_joint",      "wrist_2_joint",       "wrist_3_joint"};
  const double speeds[6] = {2.0944, 2.0944, 3.1416, 3.1416, 3.1416, 3.1416};  // facts §3
  const double efforts[6] = {330, 330, 150, 54, 54, 54};
  for (int j = 0; j < 6; ++j) {
    EXPECT_EQ(model.joints()[j].name, names[j]);
    EXPECT_NEAR(model.joints()[j].limits.velocity, speeds[j], 1e-4);
    EXPECT_DOUBLE_EQ(model.joints()[j].limits.effort, efforts[j]);
    const double range = j == 2 ? M_PI : 2 * M_PI;
    EXPECT_NEAR(model.joints()[j].limits.lower, -range, 1e-12);
    EXPECT_NEAR(model.joints()[j].limits.upper, range, 1e-12);
  }
  EXPECT_EQ(model.links()[model.tipLink()].name, "tool0");
  EXPECT_EQ(model.links()[model.baseLink()].name, "base_link");
}

TEST(RobotModel, Ur10eInertials) {
  const auto& model = ur10e();
  double totalMass = 0.0;
  for (const auto& link : model.links()) totalMass += link.hasInertial ? link.inertial.mass : 0.0;
  EXPECT_NEAR(totalMass, 33.104, 1e-9);  // facts §2
  // The shoulder tensor is given in a frame turned by rpy (pi/2, 0, 0): in link axes its y and z
  // diagonal entries swap (Rx(pi/2) maps y to z).
  const auto& shoulder = model.links()[model.linkIndex("shoulder_link")].inertial;
  EXPECT_NEAR(shoulder.inertiaAboutCom(0, 0), 0.03408, 1e-12);
  EXPECT_NEAR(shoulder.inertiaAboutCom(1, 1), 0.02156, 1e-12);
  EXPECT_NEAR(shoulder.inertiaAboutCom(2, 2), 0.03529, 1e-12);
  EXPECT_LT((shoulder.centerOfMass - Eigen::Vector3d(0.021, -0.027, 0.0)).norm(), 1e-12);
}

TEST(RobotModel, Ur10eHasCollisionMeshesForEveryArmLink) {
  const auto& model = ur10e();
  for (const char* name : {"base_link_inertia", "shoulder_link", "upper_arm_link", "forearm_link", "wrist_1_link",
                           "wrist_2_link", "wrist_3_link"}) {
    const auto& link = model.links()[model.linkIndex(name)];
    ASSERT_EQ(link.collisions.size(), 1u) << name;
    EXPECT_TRUE(std::filesystem::exists(link.collisions[0].meshFile)) << name;
  }
}

TEST(RobotModel, MalformedXmlNamesFileAndLine) {
  const auto dir = arcplan::testing::freshTempDirectory("malformed_urdf");
  writeText(dir / "broken.urdf", "<?xml version=\"1.0\"?>\n<robot name=\"x\">\n  <link name=\"a\">\n</robot>\n");
  try {
    loadRobotModel(dir / "broken.urdf");
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("broken.urdf:"), std::string::npos) << message;
    EXPECT_NE(message.find("malformed XML"), std::string::npos) << message;
  }
}

TEST(RobotModel, UnknownTipListsLinks) {
  try {
    loadRobotModel(arcplan::robot::ur10eUrdfPath(), {"base_link", "gripper", std::nullopt});
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("'gripper' not found"), std::string::npos) << message;
    EXPECT_NE(message.find("wrist_3_link"), std::string::npos) << message;
  }
}

TEST(RobotModel, MissingMeshNamesTheUriAndLink) {
  const auto dir = arcplan::testing::freshTempDirectory("missing_mesh");
  writeText(dir / "probe.urdf", oneLinkUrdf("meshes/absent.stl"));
  try {
    loadRobotModel(dir / "probe.urdf");
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("absent.stl"), std::string::npos) << message;
    EXPECT_NE(message.find("tool0"), std::string::npos) << message;
  }
}

TEST(RobotModel, RelativeMeshPathAndScale) {
  const auto dir = arcplan::testing::freshTempDirectory("relative_mesh");
  writeText(dir / "meshes" / "tetra.stl", kTetrahedronStl);
  writeText(dir / "probe.urdf", oneLinkUrdf("meshes/tetra.stl"));
  const auto model = loadRobotModel(dir / "probe.urdf");
  const auto& geometry = model.links()[model.tipLink()].collisions.at(0);
  EXPECT_EQ(std::filesystem::canonical(geometry.meshFile), std::filesystem::canonical(dir / "meshes" / "tetra.stl"));
  EXPECT_EQ(geometry.meshScale, Eigen::Vector3d(2, 2, 2));
}

TEST(RobotModel, PackageUrisSearchArcplanPathBeforeRosPath) {
  const auto dir = arcplan::testing::freshTempDirectory("package_uri");
  writeText(dir / "arcplan_root" / "probe_description" / "meshes" / "tetra.stl", kTetrahedronStl);
  writeText(dir / "ros_root" / "probe_description" / "meshes" / "tetra.stl", kTetrahedronStl);
  writeText(dir / "probe.urdf", oneLinkUrdf("package://probe_description/meshes/tetra.stl"));
  {
    ScopedEnvironment ros("ROS_PACKAGE_PATH", (dir / "ros_root").string());
    ScopedEnvironment arcplanPath("ARCPLAN_PACKAGE_PATH", "/nonexistent:" + (dir / "arcplan_root").string());
    const auto model = loadRobotModel(dir / "probe.urdf");
    EXPECT_EQ(model.links()[model.tipLink()].collisions.at(0).meshFile,
              dir / "arcplan_root" / "probe_description" / "meshes" / "tetra.stl");
  }
  {
    ScopedEnvironment ros("ROS_PACKAGE_PATH", (dir / "ros_root").string());
    ScopedEnvironment arcplanPath("ARCPLAN_PACKAGE_PATH", "");
    const auto model = loadRobotModel(dir / "probe.urdf");
    EXPECT_EQ(model.links()[model.tipLink()].collisions.at(0).meshFile,
              dir / "ros_root" / "probe_description" / "meshes" / "tetra.stl");
  }
  {
    ScopedEnvironment ros("ROS_PACKAGE_PATH", "");
    ScopedEnvironment arcplanPath("ARCPLAN_PACKAGE_PATH", "");
    EXPECT_THROW(loadRobotModel(dir / "probe.urdf"), Error);
  }
}

TEST(Mesh, LoadsStlAndObjWithScale) {
  const auto dir = arcplan::testing::freshTempDirectory("mesh_formats");
  writeText(dir / "tetra.stl", kTetrahedronStl);
  writeText(dir / "tetra.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  for (const char* name : {"tetra.stl", "tetra.obj"}) {
    const auto mesh = arcplan::robot::loadMesh(dir / name, Eigen::Vector3d(2, 3, 4));
    EXPECT_EQ(mesh.triangles.size(), 4u) << name;
    Eigen::Vector3d maximum = Eigen::Vector3d::Constant(-1e9);
    for (const auto& v : mesh.vertices) maximum = maximum.cwiseMax(v);
    EXPECT_LT((maximum - Eigen::Vector3d(2, 3, 4)).norm(), 1e-6) << name;
  }
}

TEST(Mesh, UnreadableFileIsAnError) {
  const auto dir = arcplan::testing::freshTempDirectory("mesh_garbage");
  writeText(dir / "garbage.stl", "this is not a mesh");
  EXPECT_THROW(arcplan::robot::loadMesh(dir / "garbage.stl"), Error);
  EXPECT_THROW(arcplan::robot::loadMesh(dir / "absent.stl"), Error);
}

TEST(RobotModel, PrismaticJointOnTheChainIsRejected) {
  const auto dir = arcplan::testing::freshTempDirectory("prismatic");
  writeText(dir / "p.urdf", R"(<robot name="p"><link name="base_link"/><link name="tool0"/>
<joint name="slide" type="prismatic"><parent link="base_link"/><child link="tool0"/><axis xyz="1 0 0"/>
<limit lower="0" upper="1" effort="1" velocity="1"/></joint></robot>)");
  try {
    loadRobotModel(dir / "p.urdf");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("slide"), std::string::npos) << e.what();
  }
}

}  // namespace

namespace {

// Found by fuzzing: urdfdom accepts joints that close a loop away from the root.
TEST(RobotModel, JointLoopAboveTheTipIsAnError) {
  const std::string urdf = R"(<robot name="loop"><link name="base_link"/><link name="a"/><link name="tool0"/>
<joint name="j1" type="revolute"><parent link="a"/><child link="tool0"/><axis xyz="0 0 1"/>
<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
<joint name="j2" type="revolute"><parent link="tool0"/><child link="a"/><axis xyz="0 0 1"/>
<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>)";
  try {
    arcplan::robot::parseRobotModel(urdf, "loop.urdf");
    FAIL() << "no error";
  } catch (const arcplan::Error& e) {
    EXPECT_NE(std::string(e.what()).find("loop.urdf: the joints above tip link 'tool0' form a loop"), std::string::npos)
        << e.what();
  }
}

// Found by fuzzing: TinyXML skips the bytes a UTF-8 lead byte announces, so a sequence cut short at
// the end of the text made it read past the buffer. Such text is rejected before TinyXML sees it.
TEST(RobotModel, TextThatIsNotUtf8IsRejectedWithItsLine) {
  const std::string truncatedSequence =
      "<robot name=\"r\">\n<link name=\"base_link\"/>\n<\xEF"
      "2";
  const std::string overlong = "<robot name=\"\xC0\xAF\"/>";
  const std::string nulByte = std::string("<robot name=\"r\"/>\n") + '\0' + "x";
  const std::string validMultiByte = "<robot name=\"r\xC3\xA9\xE2\x82\xAC\xF0\x9F\x98\x80\"/>";
  struct Case {
    std::string text;
    std::string expected;
  };
  for (const Case& c : {Case{truncatedSequence, "bad.urdf:3: expected UTF-8 text, found byte 0xef"},
                        Case{overlong, "bad.urdf:1: expected UTF-8 text, found byte 0xc0"},
                        Case{nulByte, "bad.urdf:2: expected UTF-8 text, found byte 0x0 at offset 18 (a NUL byte)"}}) {
    try {
      arcplan::robot::parseRobotModel(c.text, "bad.urdf");
      ADD_FAILURE() << "no error for " << c.expected;
    } catch (const arcplan::Error& e) {
      EXPECT_NE(std::string(e.what()).find(c.expected), std::string::npos) << e.what();
    }
  }
  // Well-formed 2-, 3- and 4-byte sequences pass the check and reach urdfdom (which then wants links).
  try {
    arcplan::robot::parseRobotModel(validMultiByte, "good.urdf");
    ADD_FAILURE() << "a robot without links was accepted";
  } catch (const arcplan::Error& e) {
    EXPECT_EQ(std::string(e.what()).find("UTF-8"), std::string::npos) << e.what();
  }
}

}  // namespace

namespace {

TEST(Srdf, DisabledCollisionPairsWithTheirLines) {
  const auto pairs = arcplan::robot::parseSrdfDisabledCollisions(R"(<?xml version="1.0"?>
<robot name="r">
  <group name="arm"><chain base_link="base_link" tip_link="tool0"/></group>
  <disable_collisions link1="base_link" link2="shoulder_link" reason="Adjacent"/>
  <disable_collisions link1="wrist_1_link" link2="wrist_3_link"/>
</robot>)",
                                                                 "r.srdf");
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(pairs[0].link1, "base_link");
  EXPECT_EQ(pairs[0].link2, "shoulder_link");
  EXPECT_EQ(pairs[0].reason, "Adjacent");
  EXPECT_EQ(pairs[0].line, 4);
  EXPECT_EQ(pairs[1].link2, "wrist_3_link");
  EXPECT_EQ(pairs[1].reason, "");
  EXPECT_EQ(pairs[1].line, 5);
}

TEST(Srdf, BadInputNamesFileAndLine) {
  const auto message = [](const std::string& text) {
    try {
      arcplan::robot::parseSrdfDisabledCollisions(text, "r.srdf");
    } catch (const arcplan::Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("<robot>\n<disable_collisions link1=\"a\"/>\n</robot>"),
            "r.srdf:2: <disable_collisions> needs link1 and link2");
  EXPECT_EQ(message("<model/>"), "r.srdf:1: expected an SRDF with root element <robot>");
  EXPECT_NE(message("<robot>\n<disable_collisions link1=\"a\" link2=\"b\">\n</robot>").find("r.srdf:"),
            std::string::npos);
  EXPECT_NE(message("<robot>\n<disable_collisions link1=\"a\" link2=\"b\">\n</robot>").find("malformed XML"),
            std::string::npos);
}

TEST(RobotModel, TcpOffsetFrameMayNotShadowALink) {
  const std::string urdf = R"(<robot name="r"><link name="base_link"/><link name="tcp"/>
<joint name="j" type="fixed"><parent link="base_link"/><child link="tcp"/></joint></robot>)";
  EXPECT_THROW(arcplan::robot::parseRobotModel(urdf, "r.urdf", {"base_link", "tcp", Eigen::Isometry3d::Identity()}),
               Error);
}

}  // namespace
