// Run folders of one CSV per signal (log_folder.h): alignment on the time column, both naming
// schemes, actual_current_as_torque, and every kind of bad folder named with its file and line.
#include <cmath>
#include <fstream>
#include <functional>

#include <gtest/gtest.h>

#include "arcplan/common/error.h"
#include "arcplan/model/dataset.h"
#include "arcplan/model/log_folder.h"
#include "arcplan/model/measurements.h"
#include "support/command.h"
#include "support/error_message.h"

namespace {

using arcplan::testing::errorMessageOf;
using namespace arcplan::model;

// The value every test file holds for joint j at time t: known without the reader.
double valueAt(int signal, int joint, double t) { return 10.0 * signal + joint + std::sin(3.0 * t + joint); }

struct FileSpec {
  std::string name;
  int signal = 0;  // which valueAt family
  int joints = 6;
  double start = 0.0;   // time of the first row
  double step = 0.008;  // s
  int rows = 200;
  double offset = 0.0;  // added to every time (a file written a few µs after another)
};

std::string fileText(const FileSpec& spec) {
  std::string text;
  char buffer[64];
  for (int r = 0; r < spec.rows; ++r) {
    const double t = spec.start + r * spec.step;
    std::snprintf(buffer, sizeof(buffer), "%.6f", t + spec.offset);
    text += buffer;
    for (int j = 0; j < spec.joints; ++j) {
      std::snprintf(buffer, sizeof(buffer), ", %.6f", valueAt(spec.signal, j, t));
      text += buffer;
    }
    text += "\n";
  }
  return text;
}

std::filesystem::path writeFolder(const std::string& name, const std::vector<FileSpec>& files,
                                  const std::function<void(const std::string&, std::string&)>& edit = {}) {
  const auto dir = arcplan::testing::freshTempDirectory("log_folder_" + name);
  for (const auto& file : files) {
    std::string text = fileText(file);
    if (edit) edit(file.name, text);
    std::ofstream(dir / file.name) << text;
  }
  return dir;
}

// The kufieta layout: q, qd, current and target moment, written a few µs apart.
std::vector<FileSpec> runFiles() {
  return {{"log_q_actual.csv", 1, 6, 0.0, 0.008, 200, 0.0},
          {"log_qd_actual.csv", 2, 6, 0.0, 0.008, 200, 5e-6},
          {"log_i_actual.csv", 3, 6, 0.0, 0.008, 200, 9e-6},
          {"log_m_target.csv", 4, 6, 0.0, 0.008, 200, -4e-6},
          {"log_tcp_force.csv", 5, 6, 0.0, 0.004, 30, 0.0}};  // not a signal arcplan reads: skipped
}

TEST(LogFolder, AlignsOneFilePerSignalOnTheirTimeColumn) {
  const auto dir = writeFolder("aligned", runFiles());
  const Log log = readLog(dir);  // a directory is read as a run folder
  ASSERT_EQ(log.rows(), 200u);
  EXPECT_EQ(log.jointCount(), 6);
  EXPECT_FALSE(log.has("tcp_force"));
  for (std::size_t r : {0u, 77u, 199u}) {
    const double t = 0.008 * static_cast<double>(r);
    EXPECT_NEAR(log.time[static_cast<Eigen::Index>(r)], t, 1e-9);
    EXPECT_NEAR(log.vector("actual_q")(static_cast<Eigen::Index>(r), 2), valueAt(1, 2, t), 1e-6);
    EXPECT_NEAR(log.vector("actual_qd")(static_cast<Eigen::Index>(r), 0), valueAt(2, 0, t), 1e-6);
    EXPECT_NEAR(log.vector("actual_current")(static_cast<Eigen::Index>(r), 5), valueAt(3, 5, t), 1e-6);
    EXPECT_NEAR(log.vector("target_moment")(static_cast<Eigen::Index>(r), 3), valueAt(4, 3, t), 1e-6);
  }
  EXPECT_EQ(log.lines.front(), 1u);
  EXPECT_EQ(log.lines.back(), 200u);
}

TEST(LogFolder, FilesThatStopAFewCyclesApartAreCutToTheTimeEveryFileCovers) {
  auto files = runFiles();
  files[2].rows = 160;     // the current stops 0.32 s before the others
  files[3].start = 0.016;  // and the target moment starts two cycles late
  files[3].rows = 198;
  const Log log = readLog(writeFolder("ends", files));
  // Times 0.016 .. 0.008·159 s: every file has them.
  ASSERT_EQ(log.rows(), 158u);
  EXPECT_NEAR(log.time[0], 0.016, 1e-9);
  EXPECT_NEAR(log.time[157], 0.008 * 159, 1e-9);
  EXPECT_NEAR(log.vector("target_moment")(0, 1), valueAt(4, 1, 0.016), 1e-6);
  EXPECT_EQ(log.quality.dataRows, 200u);
  EXPECT_EQ(log.quality.keptRows, 158u);
  ASSERT_FALSE(log.quality.notes.empty());
  EXPECT_NE(log.quality.notes.back().find("log_q_actual.csv"), std::string::npos);
}

TEST(LogFolder, ReadsRtdeNamesAndTheCurrentAsTorque) {
  const auto dir = writeFolder("rtde_names", {{"log_actual_q.csv", 1, 6, 0.0, 0.002, 100, 0.0},
                                              {"log_actual_qd.csv", 2, 6, 0.0, 0.002, 100, 0.0},
                                              {"log_actual_current_as_torque.csv", 3, 6, 0.0, 0.002, 100, 0.0},
                                              {"log_target_moment.csv", 4, 6, 0.0, 0.002, 100, 0.0}});
  const Log log = readLog(dir);
  ASSERT_TRUE(log.has("actual_current_as_torque"));
  const auto spec = parseModelYaml("kind: joint_current\neffects: [drive_gain, offset]\n", "m.yaml");
  const Dataset data = makeJointDataset(log, spec);
  // Without actual_current the controller's current-as-torque is what the model predicts.
  EXPECT_EQ(data.channelName(4), "actual_current_as_torque_4");
  EXPECT_NEAR(data.measured(4)[10], valueAt(3, 4, 0.02), 1e-6);
  EXPECT_EQ(folderSignal("log_i_actual.csv"), std::optional<std::string>("actual_current"));
  EXPECT_EQ(folderSignal("log_tool_vector.csv"), std::nullopt);
}

TEST(LogFolder, ARowCutShortIsDroppedAndReportedWithItsFileAndLine) {
  // The real UR5 runs end with a line cut off mid-number ("21.").
  const auto dir = writeFolder("cut", runFiles(), [](const std::string& name, std::string& text) {
    if (name == "log_i_actual.csv") text += "1.6\n";
  });
  const Log log = readLog(dir);
  EXPECT_EQ(log.rows(), 200u);
  bool reported = false;
  for (const auto& note : log.quality.notes) {
    reported = reported || (note.find("log_i_actual.csv") != std::string::npos &&
                            note.find("short row: 1, line 201") != std::string::npos);
  }
  EXPECT_TRUE(reported);
}

TEST(LogFolder, AFolderMissingASignalIsAnErrorNamingTheFile) {
  auto files = runFiles();
  files.erase(files.begin() + 2);  // no current
  const auto dir = writeFolder("missing", files);
  const auto spec = parseModelYaml("kind: joint_current\neffects: [drive_gain, offset]\n", "m.yaml");
  const auto message = errorMessageOf([&] { loadDataset(dir, spec); });
  EXPECT_NE(message.find(dir.string()), std::string::npos) << message;
  EXPECT_NE(message.find("log_i_actual.csv"), std::string::npos) << message;
  EXPECT_NE(message.find("log_actual_current.csv"), std::string::npos) << message;
}

TEST(LogFolder, FilesOfDifferentLengthsAreAnError) {
  auto files = runFiles();
  files[1].rows = 60;  // 0.47 s of 1.6 s: not one recording
  const auto message = errorMessageOf([&] { readLog(writeFolder("lengths", files)); });
  EXPECT_NE(message.find("different lengths"), std::string::npos) << message;
  EXPECT_NE(message.find("log_qd_actual.csv"), std::string::npos) << message;
  EXPECT_NE(message.find("lines 1-60"), std::string::npos) << message;
}

TEST(LogFolder, FilesOnDifferentClocksAreAnError) {
  auto rate = runFiles();
  rate[2].step = 0.004;  // the current at 250 Hz
  rate[2].rows = 400;
  const auto message = errorMessageOf([&] { readLog(writeFolder("rate", rate)); });
  EXPECT_NE(message.find("different clocks"), std::string::npos) << message;
  EXPECT_NE(message.find("log_i_actual.csv"), std::string::npos) << message;

  auto phase = runFiles();
  phase[3].offset = 0.004;  // the same rate, half a cycle apart: no sample matches
  const auto shifted = errorMessageOf([&] { readLog(writeFolder("phase", phase)); });
  EXPECT_NE(shifted.find("different clocks"), std::string::npos) << shifted;
  EXPECT_NE(shifted.find("log_m_target.csv"), std::string::npos) << shifted;
  EXPECT_NE(shifted.find("log_q_actual.csv:2:"), std::string::npos)
      << shifted;  // line 1 is before log_m_target.csv starts
}

TEST(LogFolder, ATimeColumnThatGoesBackIsAnErrorNamingFileAndLine) {
  const auto dir = writeFolder("backward", runFiles(), [](const std::string& name, std::string& text) {
    if (name != "log_qd_actual.csv") return;
    // Line 51 gets the time of line 50.
    std::size_t at = 0;
    for (int line = 1; line < 51; ++line) at = text.find('\n', at) + 1;
    text.replace(at, text.find(',', at) - at, "0.392005");
  });
  const auto message = errorMessageOf([&] { readLog(dir); });
  EXPECT_NE(message.find("log_qd_actual.csv:51:"), std::string::npos) << message;
  EXPECT_NE(message.find("must increase"), std::string::npos) << message;
  EXPECT_NE(message.find("line 50"), std::string::npos) << message;
}

TEST(LogFolder, SignalFilesDisagreeingOnTheJointCountAreAnError) {
  auto files = runFiles();
  files[1].joints = 5;
  const auto message = errorMessageOf([&] { readLog(writeFolder("joints", files)); });
  EXPECT_NE(message.find("mismatched joint count"), std::string::npos) << message;
  EXPECT_NE(message.find("log_qd_actual.csv has 5"), std::string::npos) << message;
}

TEST(LogFolder, AFolderWithoutSignalFilesOrWithTwoFilesOfOneSignalIsAnError) {
  const auto empty = arcplan::testing::freshTempDirectory("log_folder_empty");
  std::ofstream(empty / "notes.txt") << "nothing\n";
  EXPECT_NE(errorMessageOf([&] { readLog(empty); }).find("no signal files"), std::string::npos);
  auto files = runFiles();
  files.push_back({"log_actual_q.csv", 1, 6, 0.0, 0.008, 200, 0.0});
  const auto twice = errorMessageOf([&] { readLog(writeFolder("twice", files)); });
  EXPECT_NE(twice.find("both hold actual_q"), std::string::npos) << twice;
}

TEST(LogFolder, BadFolderOnTheCommandLineWritesNothing) {
  auto files = runFiles();
  files[2].step = 0.004;
  files[2].rows = 400;
  const auto dir = writeFolder("cli", files);
  const auto out = arcplan::testing::freshTempDirectory("log_folder_cli_out");
  const auto model = out / "m.yaml";
  std::ofstream(model) << "kind: joint_current\neffects: [drive_gain, offset]\n";
  const auto result =
      arcplan::testing::runArcplan({"model", "compare", "--model", model.string(), "--data", dir.string(), "--json",
                                    (out / "c.json").string(), "--out", (out / "session").string()});
  EXPECT_EQ(result.exitCode, 1) << result.err;
  EXPECT_NE(result.err.find("arcplan: error: "), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("different clocks"), std::string::npos) << result.err;
  EXPECT_FALSE(std::filesystem::exists(out / "c.json"));
  EXPECT_FALSE(std::filesystem::exists(out / "session"));
}

}  // namespace
