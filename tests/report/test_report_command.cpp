// `arcplan report` on bad input: one line naming what is wrong, exit 1, and no report file.
#include <algorithm>
#include <fstream>

#include <gtest/gtest.h>

#include "support/command.h"

namespace {

using arcplan::testing::freshTempDirectory;
using arcplan::testing::runArcplan;

// Bad input: exit 1, one error line containing `fragment`, and no report written.
void expectOneLineError(const arcplan::testing::CommandResult& result, const std::string& fragment,
                        const std::filesystem::path& report) {
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_NE(result.err.find(fragment), std::string::npos) << result.err;
  EXPECT_FALSE(std::filesystem::exists(report));
}

TEST(ReportCommand, FolderThatIsNeitherCampaignNorSession) {
  const auto folder = freshTempDirectory("report_neither");
  std::ofstream(folder / "notes.txt") << "hello\n";
  const auto result = runArcplan({"report", folder.string()});
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_EQ(result.err, "arcplan: error: " + folder.string() +
                            ": neither a campaign folder (benchmark.db) nor a model session folder (session.json)\n");
  EXPECT_FALSE(std::filesystem::exists(folder / "report.html"));
}

TEST(ReportCommand, UnfinishedCampaignIsNamed) {
  const auto folder = freshTempDirectory("report_unfinished");
  std::filesystem::create_directories(folder / "logs");
  expectOneLineError(runArcplan({"report", folder.string()}), "campaign without benchmark.db", folder / "report.html");
}

TEST(ReportCommand, DatabaseThatIsNotOneLeavesNoFile) {
  const auto folder = freshTempDirectory("report_bad_db");
  std::ofstream(folder / "benchmark.db") << "not sqlite\n";
  const auto output = folder / "out.html";
  expectOneLineError(runArcplan({"report", folder.string(), "--out", output.string()}),
                     "not an OMPL benchmark database", output);
}

TEST(ReportCommand, BrokenSessionFileLeavesNoFile) {
  const auto folder = freshTempDirectory("report_bad_session");
  std::ofstream(folder / "session.json") << "{\"steps\": [";
  expectOneLineError(runArcplan({"report", folder.string()}), "session.json", folder / "report.html");
}

TEST(ReportCommand, MissingLibraryIsNamedWithItsPackage) {
  const auto folder = freshTempDirectory("report_no_three");
  std::ofstream(folder / "benchmark.db") << "";
  const auto result = runArcplan({"report", folder.string()}, {{"ARCPLAN_THREE_DIR", (folder / "nowhere").string()}});
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_EQ(result.err,
            "arcplan: error: " + (folder / "nowhere" / "three.min.js").string() +
                ": three.js not found (Debian package libjs-three; scripts/setup installs it, ARCPLAN_THREE_DIR "
                "names another copy)\n");
  EXPECT_FALSE(std::filesystem::exists(folder / "report.html"));
}

}  // namespace
