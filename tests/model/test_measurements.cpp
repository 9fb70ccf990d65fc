// Reading robot logs: RTDE CSV in both styles, headerless logs through a column map, and the
// report of rows that were dropped.
#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "arcplan/common/error.h"
#include "arcplan/model/measurements.h"
#include "support/command.h"
#include "support/error_message.h"

namespace {

using arcplan::testing::errorMessageOf;

using arcplan::Error;
using arcplan::model::LogReadOptions;
using arcplan::model::parseColumnMap;
using arcplan::model::readLog;

std::filesystem::path writeText(const std::string& name, const std::string& text) {
  const auto dir = arcplan::testing::freshTempDirectory("measurements_" + name);
  const auto file = dir / name;
  std::ofstream(file) << text;
  return file;
}

TEST(Measurements, ReadsUrRtdeCommaSeparatedWithHeader) {
  const auto file = writeText("rtde.csv",
                              "timestamp,actual_q_0,actual_q_1,actual_current_0,actual_current_1,robot_mode\n"
                              "0.000,0.1,0.2,1.5,-0.5,7\n"
                              "0.002,0.11,0.21,1.6,-0.4,7\n");
  const auto log = readLog(file);
  EXPECT_EQ(log.rows(), 2u);
  EXPECT_EQ(log.jointCount(), 2);
  EXPECT_DOUBLE_EQ(log.time[1], 0.002);
  EXPECT_DOUBLE_EQ(log.vector("actual_q")(1, 1), 0.21);
  EXPECT_DOUBLE_EQ(log.vector("actual_current")(0, 0), 1.5);
  EXPECT_FALSE(log.has("robot_mode"));  // unknown RTDE fields are skipped
  EXPECT_EQ(log.lines, (std::vector<std::size_t>{2, 3}));
}

TEST(Measurements, ReadsRecordPySpaceSeparatedWithHeader) {
  const auto file = writeText("record.csv",
                              "timestamp target_q_0 target_q_1 speed_scaling\n"
                              "10.0  1.0 2.0 1\n"
                              "10.008 1.5\t2.5 1\n");
  const auto log = readLog(file);
  EXPECT_EQ(log.rows(), 2u);
  EXPECT_DOUBLE_EQ(log.vector("target_q")(1, 0), 1.5);
  EXPECT_DOUBLE_EQ(log.vector("target_q")(1, 1), 2.5);
  EXPECT_DOUBLE_EQ(log.scalars.at("speed_scaling")[0], 1.0);
}

TEST(Measurements, ReadsHeaderlessLogsThroughAColumnMap) {
  // The layout of the real UR10e logs: 31 columns.
  std::string row1 = "100.0", row2 = "100.01";
  for (int c = 2; c <= 31; ++c) {
    row1 += "," + std::to_string(c);
    row2 += "," + std::to_string(c + 100);
  }
  const auto file = writeText("real.csv", row1 + "\n" + row2 + "\n");
  LogReadOptions options;
  options.columns = parseColumnMap("ur10e_real");
  const auto log = readLog(file, options);
  EXPECT_EQ(log.jointCount(), 6);
  EXPECT_DOUBLE_EQ(log.vector("actual_q")(0, 0), 2.0);          // column 2
  EXPECT_DOUBLE_EQ(log.vector("actual_qd")(0, 5), 13.0);        // column 13
  EXPECT_DOUBLE_EQ(log.vector("actual_current")(1, 0), 114.0);  // column 14
  EXPECT_DOUBLE_EQ(log.vector("target_current")(0, 0), 20.0);
  EXPECT_DOUBLE_EQ(log.vector("target_moment")(1, 5), 131.0);  // column 31
}

TEST(Measurements, LineNumbersCountTheCommentsAndBlankLinesBeforeTheFirstRow) {
  // A headerless log after a comment and a blank line, the last row without its newline: the first
  // row is line 3, the unparseable one line 4, the last line 5.
  const auto file = writeText("commented.csv", "# recorded on the real arm\n\n0.0,1\n0.1,x\n0.2,3");
  LogReadOptions options;
  options.columns = parseColumnMap("timestamp=1, actual_q=2");
  const auto log = readLog(file, options);
  ASSERT_EQ(log.rows(), 2u);
  EXPECT_EQ(log.lines, (std::vector<std::size_t>{3, 5}));
  EXPECT_DOUBLE_EQ(log.vector("actual_q")(0, 0), 1.0);
  EXPECT_DOUBLE_EQ(log.vector("actual_q")(1, 0), 3.0);
  EXPECT_EQ(log.quality.summary(), "kept 2 of 3 rows; dropped 1 (unparseable value: 1, line 4)");
}

TEST(Measurements, DropsAndReportsRowsThatCannotBeTrusted) {
  const auto file = writeText("bad.csv",
                              "timestamp,actual_q_0,actual_current_0\n"  // line 1
                              "0.0,0.1,1.0\n"                            // 2 ok
                              "0.0,0.1,1.0\n"                            // 3 duplicate timestamp
                              "0.1,0.2,1e280\n"                          // 4 corrupted magnitude
                              "0.2,nan,1.0\n"                            // 5 NaN
                              "0.3,0.4\n"                                // 6 short row
                              "0.4,abc,1.0\n"                            // 7 unparseable
                              "0.5,0.4,1.0\n"                            // 8 ok
                              "0.45,0.5,1.1\n"                           // 9 backward timestamp
                              "0.6,0.6,1.2\n"                            // 10 ok
                              "0.7,0.6,-2e300\n");                       // 11 corrupted
  const auto log = readLog(file);
  EXPECT_EQ(log.rows(), 3u);
  EXPECT_EQ(log.lines, (std::vector<std::size_t>{2, 8, 10}));
  EXPECT_EQ(log.quality.dataRows, 10u);
  EXPECT_EQ(log.quality.keptRows, 3u);
  EXPECT_DOUBLE_EQ(log.vector("actual_current")(2, 0), 1.2);
  std::map<std::string, std::vector<std::size_t>> byReason;
  for (const auto& d : log.quality.dropped) {
    EXPECT_EQ(d.count, d.firstLines.size());
    byReason[d.reason] = d.firstLines;
  }
  EXPECT_EQ(byReason["duplicate or backward timestamp"], (std::vector<std::size_t>{3, 9}));
  EXPECT_EQ(byReason["corrupted value (magnitude above 1e12)"], (std::vector<std::size_t>{4, 11}));
  EXPECT_EQ(byReason["NaN or infinite value"], (std::vector<std::size_t>{5}));
  EXPECT_EQ(byReason["short row"], (std::vector<std::size_t>{6}));
  EXPECT_EQ(byReason["unparseable value"], (std::vector<std::size_t>{7}));
  const auto summary = log.quality.summary();
  EXPECT_NE(summary.find("kept 3 of 10 rows; dropped 7"), std::string::npos) << summary;
  EXPECT_NE(summary.find("lines 4,11"), std::string::npos) << summary;
}

TEST(Measurements, ReportsAtMostFiveLinesPerReasonButCountsAll) {
  std::string text = "timestamp,actual_q_0\n0,0\n";
  for (int i = 0; i < 12; ++i) text += "0,0\n";  // twelve duplicates of t = 0
  text += "1,1\n";
  const auto log = readLog(writeText("many.csv", text));
  ASSERT_EQ(log.quality.dropped.size(), 1u);
  EXPECT_EQ(log.quality.dropped[0].count, 12u);
  EXPECT_EQ(log.quality.dropped[0].firstLines, (std::vector<std::size_t>{3, 4, 5, 6, 7}));
}

TEST(Measurements, LineRangeSelectsPartOfTheFile) {
  std::string text = "timestamp,actual_q_0\n";
  for (int i = 0; i < 10; ++i) text += std::to_string(i) + "," + std::to_string(10 * i) + "\n";
  LogReadOptions options;
  std::tie(options.firstLine, options.lastLine) = arcplan::model::parseLineRange("4-7", "--rows");
  const auto log = readLog(writeText("range.csv", text), options);
  ASSERT_EQ(log.rows(), 4u);
  EXPECT_DOUBLE_EQ(log.time[0], 2.0);  // line 4 holds t = 2
  EXPECT_DOUBLE_EQ(log.time[3], 5.0);
  EXPECT_NE(errorMessageOf([] { arcplan::model::parseLineRange("7-4", "--rows"); }).find("--rows"), std::string::npos);
}

TEST(Measurements, WrittenLogsReadBackIdentically) {
  arcplan::model::Log log;
  log.time = Eigen::VectorXd::LinSpaced(5, 0.0, 0.008);
  log.vectors["actual_q"] = Eigen::MatrixXd::Random(5, 6);
  log.vectors["actual_current"] = Eigen::MatrixXd::Random(5, 6) * 1e-3;
  log.scalars["speed_scaling"] = Eigen::VectorXd::Ones(5);
  for (const auto style : {arcplan::model::CsvStyle::UrRtde, arcplan::model::CsvStyle::RecordPy}) {
    const auto file = arcplan::testing::freshTempDirectory("roundtrip") / "log.csv";
    arcplan::model::writeLog(log, file, style);
    const auto back = readLog(file);
    EXPECT_EQ(back.rows(), 5u);
    EXPECT_EQ((back.vector("actual_q") - log.vectors["actual_q"]).cwiseAbs().maxCoeff(), 0.0);  // shortest exact repr
    EXPECT_EQ((back.vector("actual_current") - log.vectors["actual_current"]).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_DOUBLE_EQ(back.scalars.at("speed_scaling")[4], 1.0);
  }
}

TEST(Measurements, BadInputGivesClearErrors) {
  // Unknown column in a column map.
  EXPECT_NE(
      errorMessageOf([] { parseColumnMap("timestamp=1, actual_torque=2-7"); }).find("unknown column 'actual_torque'"),
      std::string::npos);
  // A column map wider than the rows.
  LogReadOptions wide;
  wide.columns = parseColumnMap("timestamp=1, actual_q=2-7");
  const auto narrow = writeText("narrow.csv", "0,1,2,3\n1,1,2,3\n");
  EXPECT_NE(errorMessageOf([&] { readLog(narrow, wide); }).find("unknown column"), std::string::npos);
  // Mismatched joint counts.
  EXPECT_NE(errorMessageOf([] {
              parseColumnMap("timestamp=1, actual_q=2-7, actual_current=8-12");
            }).find("mismatched joint count"),
            std::string::npos);
  const auto mismatched = writeText("mismatch.csv", "timestamp,actual_q_0,actual_q_1,actual_current_0\n0,1,2,3\n");
  const auto mismatchMessage = errorMessageOf([&] { readLog(mismatched); });
  EXPECT_NE(mismatchMessage.find("mismatched joint count"), std::string::npos) << mismatchMessage;
  EXPECT_NE(mismatchMessage.find("mismatch.csv"), std::string::npos);
  // Empty logs: no lines at all, or a header without rows.
  EXPECT_NE(errorMessageOf([] { readLog(writeText("empty.csv", "")); }).find("empty"), std::string::npos);
  EXPECT_NE(errorMessageOf([] { readLog(writeText("header.csv", "timestamp,actual_q_0\n")); }).find("no data rows"),
            std::string::npos);
  // Every row invalid: the message carries the drop report.
  const auto allBad =
      errorMessageOf([] { readLog(writeText("allbad.csv", "timestamp,actual_q_0\n0,nan\n1,1e300\n")); });
  EXPECT_NE(allBad.find("no valid rows"), std::string::npos) << allBad;
  EXPECT_NE(allBad.find("NaN"), std::string::npos) << allBad;
  // Headerless without a map; missing file; no timestamp column.
  EXPECT_NE(errorMessageOf([] { readLog(writeText("nomap.csv", "0,1\n1,2\n")); }).find("--columns"), std::string::npos);
  EXPECT_NE(errorMessageOf([] { readLog("/nonexistent/log.csv"); }).find("does not exist"), std::string::npos);
  EXPECT_NE(errorMessageOf([] { readLog(writeText("notime.csv", "actual_q_0\n1\n")); }).find("timestamp"),
            std::string::npos);
}

}  // namespace
