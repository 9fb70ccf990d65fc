// `arcplan plan --clearance` on a path that keeps the clearance at its waypoints but not between them:
// exit 1, the CSV not written, the JSON complete and saying so. The path is the thesis arc with motion
// checks off (`check_motions=0`, waypoints only, as MoveIt's Cartesian paths) and waypoints 8 cm of TCP
// path apart, so the straight joint motions between them cut closer to the particle than the arc. The
// clearance asked for lies between the two, both measured here with collision::distance (read as a clearance
// is: collision::clearanceOf, the obstacle distance, self pairs only below 1 mm), not by plan.
#include <algorithm>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/scene.h"
#include "arcplan/common/resources.h"
#include "support/command.h"

namespace {

namespace fs = std::filesystem;
using arcplan::robot::Vector6;
using arcplan::testing::runArcplan;

const std::vector<std::string> kSparseUncheckedArc = {"plan",
                                                      "--scene",
                                                      "scenes/thesis_obstacle.yaml",
                                                      "--planner",
                                                      "arc",
                                                      "--param",
                                                      "auto=0",
                                                      "--param",
                                                      "check_motions=0",
                                                      "--param",
                                                      "resolution=0.1",
                                                      "--param",
                                                      "max_joint_step=0.5",
                                                      "--param",
                                                      "fallback=0"};

std::vector<std::string> withOptions(std::vector<std::string> arguments, const std::vector<std::string>& more) {
  arguments.insert(arguments.end(), more.begin(), more.end());
  return arguments;
}

// The q0..q5 rows of a path CSV (header and comment lines skipped).
std::vector<Vector6> readWaypoints(const fs::path& file) {
  std::istringstream lines(arcplan::testing::readFile(file));
  std::vector<Vector6> waypoints;
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] == '#' || line[0] == 'q') continue;
    std::istringstream fields(line);
    Vector6 q;
    for (int j = 0; j < 6; ++j) {
      std::string field;
      std::getline(fields, field, ',');
      q[j] = std::stod(field);
    }
    waypoints.push_back(q);
  }
  return waypoints;
}

TEST(PlanClearance, APathCloserThanTheClearanceBetweenItsWaypointsExitsOneAndWritesNoCsv) {
  const fs::path dir = arcplan::testing::freshTempDirectory("plan_clearance_judgement");
  // The path, with a clearance every part of it keeps.
  const auto planned =
      runArcplan(withOptions(kSparseUncheckedArc, {"--clearance", "0.01", "--path-csv", (dir / "path.csv").string()}));
  ASSERT_EQ(planned.exitCode, 0) << planned.err;
  const std::vector<Vector6> waypoints = readWaypoints(dir / "path.csv");
  ASSERT_GE(waypoints.size(), 3u);

  // Smallest clearance at the waypoints, and along the straight joint motions between them (100 steps each).
  const auto scene = arcplan::collision::loadScene(arcplan::dataDirectory() / "scenes" / "thesis_obstacle.yaml");
  const auto model = arcplan::collision::makeCollisionModel(scene);
  arcplan::collision::CollisionData data(*model);
  const auto clearanceAt = [&](const Vector6& q) {
    return arcplan::collision::clearanceOf(arcplan::collision::distance(*model, data, q));
  };
  double atWaypoints = std::numeric_limits<double>::infinity(), alongMotions = atWaypoints;
  for (std::size_t i = 0; i < waypoints.size(); ++i) {
    atWaypoints = std::min(atWaypoints, clearanceAt(waypoints[i]));
    if (i == 0) continue;
    for (int step = 1; step < 100; ++step) {
      const double t = step / 100.0;
      alongMotions = std::min(alongMotions, clearanceAt(Vector6((1 - t) * waypoints[i - 1] + t * waypoints[i])));
    }
  }
  // The premise: the motions cut closer than any waypoint lies (0.06894 vs 0.06955 m when written).
  ASSERT_LT(alongMotions, atWaypoints - 2e-4) << "waypoints " << atWaypoints << " m, motions " << alongMotions << " m";

  // Asked to keep a clearance between the two: every waypoint keeps it (the start and goal too, so no
  // approach zone relaxes it), the motions do not.
  const double clearance = (atWaypoints + alongMotions) / 2.0;
  std::ostringstream clearanceText;
  clearanceText.precision(17);
  clearanceText << clearance;
  const fs::path csv = dir / "judged.csv", json = dir / "judged.json";
  const auto judged = runArcplan(withOptions(
      kSparseUncheckedArc, {"--clearance", clearanceText.str(), "--path-csv", csv.string(), "--json", json.string()}));
  EXPECT_EQ(judged.exitCode, 1) << judged.err;
  EXPECT_EQ(judged.err.rfind("arcplan: error: planner arc's path does not keep the clearance of ", 0), 0u)
      << judged.err;
  EXPECT_NE(judged.err.find("no path written"), std::string::npos) << judged.err;
  EXPECT_EQ(std::count(judged.err.begin(), judged.err.end(), '\n'), 1) << judged.err;
  EXPECT_NE(judged.out.find("NOT kept"), std::string::npos) << judged.out;
  EXPECT_FALSE(fs::exists(csv));
  // The JSON is the whole result document (written atomically), saying the clearance was not kept.
  const nlohmann::json document = nlohmann::json::parse(arcplan::testing::readFile(json));
  EXPECT_EQ(document.at("status"), "exact");
  EXPECT_EQ(document.at("clearance_kept"), false);
  EXPECT_DOUBLE_EQ(document.at("clearance_m").get<double>(), clearance);
  EXPECT_EQ(document.at("waypoints").get<std::size_t>(), waypoints.size());
  EXPECT_TRUE(arcplan::testing::temporaryFilesBelow(dir).empty());

  // The same on stdout: the document alone, then exit 1.
  const auto onStdout =
      runArcplan(withOptions(kSparseUncheckedArc, {"--clearance", clearanceText.str(), "--json", "-"}));
  EXPECT_EQ(onStdout.exitCode, 1) << onStdout.err;
  EXPECT_EQ(nlohmann::json::parse(onStdout.out).at("clearance_kept"), false) << onStdout.out;
}

}  // namespace
