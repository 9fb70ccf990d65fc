// Reading what campaigns and model sessions leave behind: median-run CSVs, model series CSVs, and
// benchmark databases with and without arcplan's columns.
#include <fstream>

#include <gtest/gtest.h>
#include <sqlite3.h>

#include "arcplan/benchmarks/benchmark_database.h"
#include "arcplan/benchmarks/median_run.h"
#include "arcplan/report/campaign_report.h"
#include "arcplan/report/model_series.h"
#include "support/command.h"
#include "support/error_message.h"

namespace {

using arcplan::testing::errorMessageOf;
using arcplan::testing::freshTempDirectory;

std::filesystem::path writeText(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file) << text;
  return file;
}

TEST(MedianRun, ReadsProfilePathAndJoints) {
  const auto file = writeText(freshTempDirectory("median_run") / "RRT.csv",
                              "# planner: RRT\n# run: 4\nt,tcp_speed,x,y,z,q0,q1,q2,q3,q4,q5\n"
                              "0,0,0.1,0.2,0.3,0,1,2,3,4,5\n0.5,0.25,0.2,0.2,0.3,0.5,1,2,3,4,5\n");
  const auto run = arcplan::benchmarks::readMedianRun(file);
  EXPECT_EQ(run.planner, "RRT");
  EXPECT_EQ(run.notes.at("run"), "4");
  ASSERT_EQ(run.time.size(), 2u);
  EXPECT_DOUBLE_EQ(run.tcpSpeed[1], 0.25);
  EXPECT_DOUBLE_EQ(run.tcp[1].x(), 0.2);
  ASSERT_EQ(run.joints.size(), 2u);
  EXPECT_DOUBLE_EQ(run.joints[1][0], 0.5);
  EXPECT_DOUBLE_EQ(run.joints[1][5], 5.0);
}

TEST(MedianRun, WhatIsWrittenReadsBack) {
  arcplan::benchmarks::MedianRun run;
  run.notes = {{"planner", "arc"}, {"run", "3"}};
  run.time = {0.0, 0.123456789};
  run.tcpSpeed = {0.0, 0.25};
  run.tcp = {Eigen::Vector3d(0.4, -0.4, 0.25), Eigen::Vector3d(0.41, -0.39, 0.2512345678)};
  run.joints = {arcplan::robot::Vector6::Constant(-1.0), arcplan::robot::Vector6::LinSpaced(-1.5, 1.0)};
  const auto file = freshTempDirectory("median_run_written") / "arc.csv";
  std::ofstream out(file);
  arcplan::benchmarks::writeMedianRun(out, run);
  out.close();
  const auto read = arcplan::benchmarks::readMedianRun(file);
  EXPECT_EQ(read.planner, "arc");
  EXPECT_EQ(read.notes, run.notes);
  ASSERT_EQ(read.time.size(), 2u);
  ASSERT_EQ(read.joints.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {  // 9 significant digits
    EXPECT_NEAR(read.time[i], run.time[i], 1e-9);
    EXPECT_NEAR(read.tcpSpeed[i], run.tcpSpeed[i], 1e-9);
    EXPECT_TRUE(read.tcp[i].isApprox(run.tcp[i], 1e-8));
    EXPECT_TRUE(read.joints[i].isApprox(run.joints[i], 1e-8));
  }
}

TEST(MedianRun, WithoutJointColumnsHasNoJoints) {
  const auto file = writeText(freshTempDirectory("median_run_old") / "arc.csv", "t,tcp_speed,x,y,z\n0,0,1,2,3\n");
  EXPECT_TRUE(arcplan::benchmarks::readMedianRun(file).joints.empty());
}

TEST(MedianRun, NamesFileAndLineOfBadInput) {
  const auto folder = freshTempDirectory("median_run_bad");
  const auto badNumber = writeText(folder / "a.csv", "t,tcp_speed,x,y,z\n0,0,1,2,3\n0.1,fast,1,2,3\n");
  EXPECT_EQ(errorMessageOf([&] { arcplan::benchmarks::readMedianRun(badNumber); }),
            badNumber.string() + ":3: column tcp_speed: 'fast' is not a number");
  const auto noHeader = writeText(folder / "b.csv", "time,speed\n0,0\n");
  EXPECT_EQ(errorMessageOf([&] { arcplan::benchmarks::readMedianRun(noHeader); }),
            noHeader.string() + ":1: expected a header with the columns t, tcp_speed, x, y, z");
}

TEST(ModelSeries, GroupsChannelsAndStrides) {
  std::string text = "channel,index,time,measured,predicted,base,q,qd,qdd,tau,temperature\n";
  for (int k = 0; k < 10; ++k) {
    for (const char* channel : {"j0", "j1"}) {
      text += std::string(channel) + "," + std::to_string(k) + "," + std::to_string(0.1 * k) + ",1,2,0," +
              std::to_string(k) + ",0.5,0,3,\n";
    }
  }
  const auto file = writeText(freshTempDirectory("model_series") / "compare_data_series.csv", text);
  const auto series = arcplan::report::readModelSeries(file, 4);
  ASSERT_EQ(series.size(), 2u);
  EXPECT_EQ(series[1].channel, "j1");
  // 10 samples, at most 4: every third (0, 3, 6, 9).
  ASSERT_EQ(series[0].time.size(), 4u);
  EXPECT_DOUBLE_EQ(series[0].signals.at("q")[3], 9.0);
  EXPECT_EQ(series[0].signals.count("temperature"), 0u);  // empty in the log: not a signal
  EXPECT_EQ(series[0].signals.size(), 4u);
}

// A database shaped like ompl_benchmark_statistics' output for a log without arcplan's properties.
std::filesystem::path plainOmplDatabase(const std::filesystem::path& file) {
  sqlite3* db = nullptr;
  EXPECT_EQ(sqlite3_open(file.string().c_str(), &db), SQLITE_OK);
  const char* sql =
      "CREATE TABLE experiments (id INTEGER PRIMARY KEY, name VARCHAR(512), totaltime REAL, timelimit REAL, version "
      "VARCHAR(128));"
      "CREATE TABLE plannerConfigs (id INTEGER PRIMARY KEY, name VARCHAR(512), settings TEXT);"
      "CREATE TABLE runs (id INTEGER PRIMARY KEY, experimentid INTEGER, plannerid INTEGER, time REAL, memory REAL,"
      " solved BOOLEAN, solution_length REAL);"
      "INSERT INTO experiments VALUES (1, 'kitchen', 10, 1, 'OMPL 1.5.2');"
      "INSERT INTO plannerConfigs VALUES (1, 'geometric_RRT', ''), (2, 'geometric_PRM', ''), (3, 'control_KPIECE1', "
      "'');"
      "INSERT INTO runs VALUES (1, 1, 1, 0.5, 10, 1, 3.0), (2, 1, 1, 1.0, 11, 0, NULL), (3, 1, 2, 0.2, 12, 1, 2.5),"
      " (4, 1, 3, 0.7, 13, 1, 4.0);";
  EXPECT_EQ(sqlite3_exec(db, sql, nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(db);
  return file;
}

TEST(BenchmarkDatabase, PlainOmplDatabaseGivesItsOwnColumns) {
  const auto database = plainOmplDatabase(freshTempDirectory("plain_db") / "benchmark.db");
  const auto runs = arcplan::benchmarks::readBenchmarkDatabase(database);
  EXPECT_FALSE(runs.arcplanColumns);
  std::vector<std::string> keys;
  for (const auto& attribute : runs.attributes) keys.push_back(attribute.key);
  EXPECT_EQ(keys, (std::vector<std::string>{"memory", "solution_length", "time"}));
  const auto& rrt = runs.runs.at("kitchen").at("RRT");
  ASSERT_EQ(rrt.size(), 2u);
  EXPECT_TRUE(rrt[0].solved);
  EXPECT_FALSE(rrt[1].solved);
  EXPECT_EQ(rrt[1].values.count("solution_length"), 0u);
  EXPECT_DOUBLE_EQ(runs.runs.at("kitchen").at("PRM")[0].values.at("time"), 0.2);
  // OMPL's planner-type prefixes are not part of the label, for geometric and control planners alike.
  EXPECT_DOUBLE_EQ(runs.runs.at("kitchen").at("KPIECE1")[0].values.at("solution_length"), 4.0);
  EXPECT_EQ(runs.runs.at("kitchen").size(), 3u);
  EXPECT_EQ(runs.experiments[0]["version"], "OMPL 1.5.2");
}

TEST(CampaignReport, PlainDatabaseSaysWhatIsMissing) {
  const auto folder = freshTempDirectory("plain_campaign");
  plainOmplDatabase(folder / "benchmark.db");
  const auto data = arcplan::report::campaignReportData(folder, folder / "report.html");
  EXPECT_TRUE(data["ranking"].is_null());
  EXPECT_FALSE(data["arcplan_columns"].get<bool>());
  ASSERT_EQ(data["missing"].size(), 2u);  // no arcplan columns, no path data
  EXPECT_NE(data["missing"][0].get<std::string>().find("no arcplan columns"), std::string::npos);
  EXPECT_NE(data["missing"][1].get<std::string>().find("No path data"), std::string::npos);
  EXPECT_EQ(data["runs"]["kitchen"]["RRT"]["solved"], (nlohmann::json{1, 0}));
  EXPECT_EQ(data["links"][0]["href"], "benchmark.db");
}

TEST(BenchmarkDatabase, RejectsFilesThatAreNotBenchmarkDatabases) {
  const auto folder = freshTempDirectory("not_a_db");
  const auto text = writeText(folder / "notes.db", "just text\n");
  EXPECT_NE(
      errorMessageOf([&] { arcplan::benchmarks::readBenchmarkDatabase(text); }).find("not an OMPL benchmark database"),
      std::string::npos);
  EXPECT_EQ(errorMessageOf([&] { arcplan::benchmarks::readBenchmarkDatabase(folder / "none.db"); }),
            "benchmark database " + (folder / "none.db").string() + " not found");
}

}  // namespace
