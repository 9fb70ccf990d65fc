// The error contract of the `arcplan` executable (docs/cli.md): every exit code of apps/exit_codes.h,
// once through runCommandLine in-process (each way a command can end) and once end to end through
// the real binary (what a script sees: one `arcplan: error:` line on stderr, nothing half-done).
#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include <gtest/gtest.h>

#include "arcplan/common/error.h"
#include "cli_support.h"
#include "command_line.h"
#include "exit_codes.h"
#include "support/command.h"

namespace arcplan::apps {
namespace {

namespace fs = std::filesystem;
using arcplan::testing::freshTempDirectory;
using arcplan::testing::runArcplan;

const std::string kScene = std::string(ARCPLAN_TEST_DATA_DIR) + "/scenes/thesis_obstacle.yaml";

// What runCommandLine returns and prints when the command `arcplan run` ends with `outcome`.
struct Ended {
  int code;
  std::string err;
};

Ended runEndingWith(const std::function<void()>& outcome, std::vector<const char*> arguments = {"arcplan", "run"}) {
  CLI::App app{"test", "arcplan"};
  app.require_subcommand(1);
  auto* command = app.add_subcommand("run", "a command");
  int count = 0;
  command->add_option("--count", count, "a number");
  command->callback(outcome);
  std::ostringstream captured;
  auto* previous = std::cerr.rdbuf(captured.rdbuf());
  const int code = runCommandLine(app, static_cast<int>(arguments.size()), arguments.data());
  std::cerr.rdbuf(previous);
  return {code, captured.str()};
}

TEST(ExitCodes, TheTableHasDistinctCodesWithMeanings) {
  std::set<int> codes;
  for (const auto& entry : kExitCodes) {
    codes.insert(toInt(entry.code));
    EXPECT_FALSE(std::string(entry.meaning).empty());
  }
  EXPECT_EQ(codes.size(), kExitCodes.size());
  // Scripts rely on these numbers (docs/cli.md, README).
  EXPECT_EQ(toInt(ExitCode::Success), 0);
  EXPECT_EQ(toInt(ExitCode::BadInput), 1);
  EXPECT_EQ(toInt(ExitCode::Usage), 2);
  EXPECT_EQ(toInt(ExitCode::Internal), 3);
  EXPECT_EQ(toInt(ExitCode::Interrupted), 130);
}

TEST(RunCommandLine, SuccessIsZeroAndSilent) {
  const auto ended = runEndingWith([] {});
  EXPECT_EQ(ended.code, 0);
  EXPECT_EQ(ended.err, "");
}

TEST(RunCommandLine, BadInputIsOneWithTheErrorOnOneLine) {
  const auto ended = runEndingWith([] { throw Error("scene.yaml:4: obstacles: expected a list"); });
  EXPECT_EQ(ended.code, 1);
  EXPECT_EQ(ended.err, "arcplan: error: scene.yaml:4: obstacles: expected a list\n");
}

TEST(RunCommandLine, UsageErrorsAreTwo) {
  const auto value = runEndingWith([] { throw UsageError("--count must be at least 1"); });
  EXPECT_EQ(value.code, 2);
  EXPECT_EQ(value.err, "arcplan: error: --count must be at least 1\n");

  // CLI11's own parse errors: same form, and a pointer to the help of the command that was reached.
  const auto unknown = runEndingWith([] {}, {"arcplan", "frobnicate"});
  EXPECT_EQ(unknown.code, 2);
  EXPECT_EQ(unknown.err.rfind("arcplan: error: ", 0), 0u) << unknown.err;
  EXPECT_NE(unknown.err.find("(see 'arcplan --help')"), std::string::npos) << unknown.err;
  const auto type = runEndingWith([] {}, {"arcplan", "run", "--count", "many"});
  EXPECT_EQ(type.code, 2);
  EXPECT_NE(type.err.find("(see 'arcplan run --help')"), std::string::npos) << type.err;
  EXPECT_EQ(std::count(type.err.begin(), type.err.end(), '\n'), 1) << type.err;
}

TEST(RunCommandLine, OtherExceptionsAreInternalErrorsThree) {
  const auto ended = runEndingWith([] { throw std::logic_error("index out of range"); });
  EXPECT_EQ(ended.code, 3);
  EXPECT_EQ(ended.err, "arcplan: internal error: index out of range\n");
}

TEST(RunCommandLine, ACommandCanEndWithACodeOfTheTable) {
  // `bench` ends like this when Ctrl-C stopped it (tests/benchmarks: the real interrupt).
  const auto ended = runEndingWith([] { throw CLI::RuntimeError(toInt(ExitCode::Interrupted)); });
  EXPECT_EQ(ended.code, 130);
}

// --- end to end ------------------------------------------------------------------------------------

void expectOneErrorLine(const arcplan::testing::CommandResult& result, const std::string& expected) {
  EXPECT_EQ(result.err.rfind("arcplan: error: ", 0), 0u) << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_NE(result.err.find(expected), std::string::npos) << result.err;
}

TEST(ArcplanExitCodes, HelpListsTheExitCodesAndSucceeds) {
  const auto result = runArcplan({"--help"});
  EXPECT_EQ(result.exitCode, 0);
  for (const auto& entry : kExitCodes) {
    EXPECT_NE(result.out.find(std::to_string(toInt(entry.code)) + "  " + entry.meaning), std::string::npos)
        << result.out;
  }
}

// Help is all --help prints: `plan --help` reads every planner's declared parameters, and OMPL warns on
// stderr when BITstar's deprecated options are read.
TEST(ArcplanExitCodes, HelpOfEverySubcommandPrintsOnlyTheHelp) {
  for (const char* command : {"robot", "plan", "scale", "model", "bench", "report"}) {
    const auto result = runArcplan({command, "--help"});
    EXPECT_EQ(result.exitCode, 0) << command;
    EXPECT_EQ(result.err, "") << command;
    EXPECT_NE(result.out.find(std::string("arcplan ") + command), std::string::npos) << command << ": " << result.out;
  }
  // The planner parameters are still listed, the BIT* family's included.
  const auto plan = runArcplan({"plan", "--help"});
  EXPECT_NE(plan.out.find("  BITstar:"), std::string::npos) << plan.out;
  EXPECT_NE(plan.out.find("  ABITstar:"), std::string::npos) << plan.out;
}

TEST(ArcplanExitCodes, UnknownSubcommandAndMisspelledOptionAreUsageErrors) {
  const auto unknown = runArcplan({"frobnicate"});
  EXPECT_EQ(unknown.exitCode, 2);
  expectOneErrorLine(unknown, "--help");
  EXPECT_EQ(unknown.out, "");

  const auto misspelled = runArcplan({"plan", "--scen", "x"});
  EXPECT_EQ(misspelled.exitCode, 2);
  expectOneErrorLine(misspelled, "--scen");
  EXPECT_NE(misspelled.err.find("arcplan plan --help"), std::string::npos) << misspelled.err;
}

TEST(ArcplanExitCodes, AWrongJointCountFailsBeforeAnythingIsPrinted) {
  const auto result = runArcplan({"robot", "check", "--scene", kScene, "--joints", "1,2,3"});
  EXPECT_EQ(result.exitCode, 2);
  expectOneErrorLine(result, "--joints: expected 6 comma-separated numbers, got 3");
  EXPECT_EQ(result.out, "");
}

TEST(ArcplanExitCodes, PlanOptionValuesOutOfRangeAreUsageErrors) {
  const auto dir = freshTempDirectory("cli_plan_usage");
  const std::vector<std::string> outputs{"--json", (dir / "out.json").string(), "--path-csv",
                                         (dir / "path.csv").string()};
  const struct {
    std::vector<std::string> arguments;
    std::string message;
  } cases[] = {
      {{"plan", "--scene", kScene, "--time", "0"}, "--time must be a positive number of seconds"},
      {{"plan", "--scene", kScene, "--vmax", "-1"}, "--vmax must be a positive TCP speed in m/s"},
      {{"plan", "--scene", kScene, "--clearance", "-0.01"}, "--clearance must be a distance >= 0 m"},
  };
  for (const auto& c : cases) {
    auto arguments = c.arguments;
    arguments.insert(arguments.end(), outputs.begin(), outputs.end());
    const auto result = runArcplan(arguments);
    EXPECT_EQ(result.exitCode, 2) << c.message;
    expectOneErrorLine(result, c.message);
    EXPECT_EQ(result.out, "");
    EXPECT_TRUE(fs::is_empty(dir)) << c.message;
  }
}

TEST(ArcplanExitCodes, ModelOptionValuesOutOfRangeOrMissingAreUsageErrors) {
  const auto dir = freshTempDirectory("cli_model_usage");
  // The options are checked before the model file is read: a missing model file does not hide them.
  const std::string model = (dir / "no_such_model.yaml").string(), log = (dir / "log.csv").string();
  const struct {
    std::vector<std::string> arguments;
    std::string message;
  } cases[] = {
      {{"model", "simulate", "--model", model, "--data", log, "--format", "csv"},
       "--format: expected rtde or record, got 'csv'"},
      {{"model", "simulate", "--model", model, "--data", log, "--rate", "0"},
       "--rate must be a positive number (Hz), got 0"},
      {{"model", "history", "--out", ""}, "history: give the session directory with --out DIR"},
  };
  for (const auto& c : cases) {
    const auto result = runArcplan(c.arguments);
    EXPECT_EQ(result.exitCode, 2) << c.message;
    expectOneErrorLine(result, c.message);
    EXPECT_TRUE(fs::is_empty(dir)) << c.message;
  }
}

TEST(ArcplanExitCodes, ABadInputFileIsOneAndNamesFileLineAndColumn) {
  const auto dir = freshTempDirectory("cli_bad_csv");
  const fs::path path = dir / "path.csv";
  std::ofstream(path) << "q0,q1,q2,q3,q4,q5\n0,0,0,0,0,0\n0,0,0,0,abc,0\n";
  const auto result = runArcplan({"scale", "--path-csv", path.string(), "--json", (dir / "m.json").string()});
  EXPECT_EQ(result.exitCode, 1);
  expectOneErrorLine(result, path.string() + ":3: column q4: 'abc' is not a number");
  EXPECT_FALSE(fs::exists(dir / "m.json"));
}

TEST(ArcplanExitCodes, APlotThatCannotBeWrittenFailsTheCommand) {
  const auto dir = freshTempDirectory("cli_plot");
  const fs::path path = dir / "path.csv";
  // A 0.2 rad turn of the base joint in the thesis start pose: any valid path does.
  std::ofstream(path) << "q0,q1,q2,q3,q4,q5\n-1.1,-1.5,2.35,-2.4,-1.57,-1.1\n-0.9,-1.5,2.35,-2.4,-1.57,-1.1\n";
  const fs::path plot = dir / "no_such_folder" / "speed.png";
  const auto result = runArcplan({"scale", "--path-csv", path.string(), "--plot", plot.string(), "--json",
                                  (dir / "m.json").string(), "--traj-csv", (dir / "t.csv").string()});
  EXPECT_EQ(result.exitCode, 1) << result.err;
  expectOneErrorLine(result, "--plot " + plot.string());
  EXPECT_EQ(result.err.find("Traceback"), std::string::npos) << result.err;
  EXPECT_FALSE(fs::exists(plot));
  EXPECT_FALSE(fs::exists(dir / "m.json"));
  EXPECT_FALSE(fs::exists(dir / "t.csv"));
}

// docs/cli.md: with `--json -` the document is all that goes to stdout (the text for people is dropped).
TEST(ArcplanJsonOutput, JsonToStdoutIsOneDocumentAndNothingElse) {
  const auto dir = freshTempDirectory("cli_json_stdout");
  const fs::path path = dir / "path.csv";
  std::ofstream(path) << "q0,q1,q2,q3,q4,q5\n-1.1,-1.5,2.35,-2.4,-1.57,-1.1\n-0.9,-1.5,2.35,-2.4,-1.57,-1.1\n";
  const std::vector<std::vector<std::string>> commands{
      {"robot", "fk", "--joints", "0,-1.5,1.5,-1.5,-1.5,0"},
      {"robot", "ik", "--pose", "0.6,0.2,0.4,3.14159,0,0", "--seed", "0,-1.5,1.5,-1.5,-1.5,0"},
      {"robot", "check", "--scene", kScene, "--joints", "-1.1,-1.5,2.35,-2.4,-1.57,-1.1"},
      {"scale", "--path-csv", path.string()},
      {"plan", "--scene", kScene}};
  for (auto arguments : commands) {
    arguments.insert(arguments.end(), {"--json", "-"});
    const auto result = runArcplan(arguments);
    ASSERT_EQ(result.exitCode, 0) << arguments[0] << ": " << result.err;
    nlohmann::json document;  // parse() refuses anything before or after the one document
    ASSERT_NO_THROW(document = nlohmann::json::parse(result.out)) << arguments[0] << ":\n" << result.out;
    EXPECT_TRUE(document.is_object()) << arguments[0];
  }
}

}  // namespace
}  // namespace arcplan::apps
