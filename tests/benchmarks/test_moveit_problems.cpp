// Suites of MoveIt problems (benchmarks/moveit_problems.h): family folders, the exact-mesh check of
// every start and goal, and the per-family validity table `bench` prints (docs/benchmarks.md).
#include <gtest/gtest.h>

#include "arcplan/benchmarks/moveit_problems.h"
#include "arcplan/benchmarks/suite.h"
#include "arcplan/common/atomic_file.h"
#include "arcplan/robot/robot_model.h"
#include "support/command.h"
#include "support/ur5e_moveit_problems.h"

namespace arcplan::benchmarks {
namespace {

// From the home posture, the shoulder panned by 0.5 rad.
const std::string kRequest = testing::jointGoalRequest({0.5, -1.57, 1.57, -1.57, -1.57, 0});

// A ball of radius 5 cm on the floor at the base axis: inside the UR10e's base link (radius 0.09 m,
// up to z = 0.18 m above base_link, docs/collision.md) whatever the joints, so both ends collide.
const char* kBallAtTheBase = R"(world:
  collision_objects:
    - id: ball
      header: {frame_id: base_link}
      pose: {position: [0, 0, 0.05], orientation: [0, 0, 0, 1]}
      primitives: [{type: sphere, dimensions: [0.05]}]
      primitive_poses: [{position: [0, 0, 0], orientation: [0, 0, 0, 1]}]
)";

TEST(MoveItProblems, EveryEndIsCheckedAndTheInvalidOnesAreReportedPerFamily) {
  const auto dir = testing::freshTempDirectory("moveit_problems");
  std::filesystem::create_directories(dir / "problems" / "alpha");
  std::filesystem::create_directories(dir / "problems" / "beta");
  writeFileAtomically(dir / "problems" / "alpha" / "scene0001.yaml", "world: {collision_objects: []}\n");
  writeFileAtomically(dir / "problems" / "alpha" / "request0001.yaml", kRequest);
  writeFileAtomically(dir / "problems" / "beta" / "scene0007.yaml", kBallAtTheBase);
  writeFileAtomically(dir / "problems" / "beta" / "request0007.yaml", kRequest);
  writeFileAtomically(dir / "suite.yaml", "name: moveit-two\nmoveit_problems: {folder: problems, urdf: " +
                                              robot::ur10eUrdfPath().string() + "}\nplanners: [RRTConnect]\n");
  const Suite suite = loadSuite(dir / "suite.yaml");
  ASSERT_EQ(suite.problems.size(), 1u);
  EXPECT_EQ(suite.problems[0].name, "alpha-0001");
  EXPECT_EQ(suite.problems[0].kind, "alpha");
  ASSERT_EQ(suite.excludedProblems.size(), 1u);
  const ExcludedProblem& excluded = suite.excludedProblems[0];
  EXPECT_EQ(excluded.name, "beta-0007");
  EXPECT_NE(excluded.start.find("base_link_inertia"), std::string::npos) << excluded.start;
  EXPECT_NE(excluded.goal.find("ball"), std::string::npos) << excluded.goal;

  const std::string table = validityTable(suite);
  EXPECT_NE(table.find("| alpha | 1 | 1 | 0 | 0 |  |"), std::string::npos) << table;
  EXPECT_NE(table.find("| beta | 1 | 0 | 1 | 1 | "), std::string::npos) << table;
  EXPECT_NE(table.find("start: base_link_inertia–ball (1)"), std::string::npos) << table;
  EXPECT_NE(table.find("goal: base_link_inertia–ball (1)"), std::string::npos) << table;
}

TEST(MoveItProblems, ASuiteWithoutThemHasNoValidityTable) {
  EXPECT_EQ(validityTable(loadSuite(findSuite("thesis"))), "");
}

}  // namespace
}  // namespace arcplan::benchmarks
