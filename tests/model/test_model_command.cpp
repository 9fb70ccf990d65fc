// `arcplan model ...` end to end: simulate logs, compare, diagnose, fit --add --save, history,
// the JSON contract (docs/model.md), and clear errors without half-written output on bad input.
#include <cmath>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "arcplan/model/measurements.h"
#include "arcplan/model/model_spec.h"
#include "arcplan/robot/robot_model.h"
#include "model/push_simulation.h"
#include "support/command.h"

namespace {

using arcplan::testing::CommandResult;
using arcplan::testing::freshTempDirectory;
using arcplan::testing::readFile;
using arcplan::testing::runArcplan;
using arcplan::testing::temporaryFilesBelow;

void write(const std::filesystem::path& file, const std::string& text) { std::ofstream(file) << text; }

nlohmann::json readJson(const std::filesystem::path& file) { return nlohmann::json::parse(readFile(file)); }

class ModelCommand : public ::testing::Test {
protected:
  static void SetUpTestSuite() {
    dir = freshTempDirectory("model_command");
    write(dir / "base.yaml",
          "kind: joint_current\nload_torque: target_moment\neffects: [drive_gain, offset, coulomb, viscous]\n");
    write(dir / "truth.yaml",
          "kind: joint_current\nload_torque: target_moment\neffects: [drive_gain, offset, coulomb, viscous, "
          "load_friction]\n");
    const auto result =
        runArcplan({"model", "simulate", "--model", (dir / "truth.yaml").string(), "--data", (dir / "fit.csv").string(),
                    "--validate", (dir / "val.csv").string(), "--duration", "12", "--rate", "200", "--seed", "4"});
    ASSERT_EQ(result.exitCode, 0) << result.err;
  }
  CommandResult model(std::vector<std::string> arguments) {
    arguments.insert(arguments.begin(), "model");
    return runArcplan(arguments);
  }
  static std::filesystem::path dir;
};
std::filesystem::path ModelCommand::dir;

TEST_F(ModelCommand, SimulateWritesRtdeLogsWithTheSignalsTheLoopNeeds) {
  const auto log = arcplan::model::readLog(dir / "fit.csv");
  EXPECT_EQ(log.rows(), 2401u);  // 12 s at 200 Hz, both ends
  EXPECT_EQ(log.jointCount(), 6);
  for (const auto* signal : {"target_q", "target_qd", "target_qdd", "target_moment", "actual_q", "actual_qd",
                             "actual_current", "joint_temperatures"}) {
    EXPECT_TRUE(log.has(signal)) << signal;
  }
  EXPECT_NEAR(log.time[1] - log.time[0], 0.005, 1e-12);
  // A different seed gives a different trajectory.
  const auto other = arcplan::model::readLog(dir / "val.csv");
  EXPECT_GT((other.vector("actual_q") - log.vector("actual_q")).cwiseAbs().maxCoeff(), 0.1);
  // record.py style is space-separated.
  const auto record = model({"simulate", "--model", (dir / "base.yaml").string(), "--data",
                             (dir / "record.csv").string(), "--duration", "1", "--rate", "100", "--format", "record"});
  ASSERT_EQ(record.exitCode, 0) << record.err;
  EXPECT_EQ(readFile(dir / "record.csv").substr(0, 19), "timestamp target_q_");
}

TEST_F(ModelCommand, SimulateFollowsAPlannedTrajectoryFile) {
  // The layout `arcplan scale --traj-csv` writes: t, q0..q5, then velocities (ignored: re-derived).
  std::string text = "t,q0,q1,q2,q3,q4,q5,qd0,qd1,qd2,qd3,qd4,qd5\n";
  for (int k = 0; k <= 400; ++k) {
    const double t = 0.005 * k;
    text += std::to_string(t);
    for (int j = 0; j < 6; ++j) text += "," + std::to_string(0.3 * std::sin(t + j) - (j == 1 || j == 3 ? 1.57 : 0.0));
    text += ",0,0,0,0,0,0\n";
  }
  write(dir / "planned.csv", text);
  const auto result =
      model({"simulate", "--model", (dir / "base.yaml").string(), "--data", (dir / "planned_log.csv").string(),
             "--trajectory", (dir / "planned.csv").string(), "--rate", "500"});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const auto log = arcplan::model::readLog(dir / "planned_log.csv");
  ASSERT_EQ(log.rows(), 1001u);  // 2 s at 500 Hz
  for (std::size_t k = 100; k < 900; k += 50) {
    const double t = log.time[static_cast<Eigen::Index>(k)];
    EXPECT_NEAR(log.vector("target_q")(static_cast<Eigen::Index>(k), 2), 0.3 * std::sin(t + 2), 1e-5);
    EXPECT_NEAR(log.vector("target_qd")(static_cast<Eigen::Index>(k), 2), 0.3 * std::cos(t + 2), 1e-3);
  }
}

TEST_F(ModelCommand, TheLoopCompareDiagnoseFitHistoryFollowsTheJsonContract) {
  const auto session = freshTempDirectory("model_session");
  const auto base = (dir / "base.yaml").string(), data = (dir / "fit.csv").string(), val = (dir / "val.csv").string();

  const auto compare = model({"compare", "--model", base, "--data", data, "--validate", val, "--json",
                              (session / "compare.json").string(), "--out", session.string()});
  ASSERT_EQ(compare.exitCode, 0) << compare.err;
  EXPECT_NE(compare.out.find("overall NRMSE"), std::string::npos);
  const auto comparison = readJson(session / "compare.json");
  for (const auto* key : {"channels", "overall_nrmse", "validation", "worst_windows", "regimes"}) {
    EXPECT_TRUE(comparison.contains(key)) << key;
  }
  const auto& channel = comparison["channels"]["actual_current_1"];
  EXPECT_TRUE(channel.contains("rmse") && channel.contains("nrmse") && channel.contains("r2"));
  EXPECT_TRUE(comparison["validation"]["channels"]["actual_current_1"].contains("rmse"));
  EXPECT_FALSE(comparison["worst_windows"].empty());
  EXPECT_TRUE(comparison["regimes"]["actual_current_1"].contains("power_flow"));

  const auto diagnose = model(
      {"diagnose", "--model", base, "--data", data, "--validate", val, "--json", (session / "diagnose.json").string()});
  ASSERT_EQ(diagnose.exitCode, 0) << diagnose.err;
  const auto diagnosis = readJson(session / "diagnose.json");
  ASSERT_FALSE(diagnosis["ranking"].empty());
  const auto& top = diagnosis["ranking"][0];
  EXPECT_EQ(top["effect"], "load_friction");
  for (const auto* key : {"effect", "joints", "heldout_reduction", "score", "explanation"})
    EXPECT_TRUE(top.contains(key)) << key;
  EXPECT_GT(top["heldout_reduction"].get<double>(), 0.0);
  EXPECT_LE(top["heldout_reduction"].get<double>(), 1.0);
  EXPECT_NE(diagnose.out.find("grows with |load torque|"), std::string::npos) << diagnose.out;

  const auto saved = session / "with_load_friction.yaml";
  const auto fit = model({"fit", "--model", base, "--data", data, "--validate", val, "--add", "load_friction", "--save",
                          saved.string(), "--json", (session / "fit.json").string(), "--out", session.string()});
  ASSERT_EQ(fit.exitCode, 0) << fit.err;
  const auto step = readJson(session / "fit.json");
  EXPECT_EQ(step["added"], nlohmann::json::array({"load_friction"}));
  for (const auto* when : {"before", "after"}) {
    for (const auto* set : {"train", "validation"}) {
      EXPECT_TRUE(step[when][set].contains("overall_nrmse")) << when << " " << set;
      EXPECT_TRUE(step[when][set]["channels"]["actual_current_0"].contains("rmse"));
    }
  }
  EXPECT_LT(step["after"]["validation"]["overall_nrmse"].get<double>(),
            step["before"]["validation"]["overall_nrmse"].get<double>());
  const auto savedSpec = arcplan::model::loadModelFile(saved);
  ASSERT_TRUE(savedSpec.hasEffect("load_friction"));
  EXPECT_EQ(savedSpec.effects.back().parameters.at("mu1").size(), 6u);

  // The saved model predicts new data without refitting.
  const auto keep = model({"compare", "--model", saved.string(), "--data", val, "--keep-parameters"});
  EXPECT_EQ(keep.exitCode, 0) << keep.err;

  const auto history = model({"history", "--out", session.string(), "--json", (session / "history.json").string()});
  ASSERT_EQ(history.exitCode, 0) << history.err;
  EXPECT_NE(history.out.find("fit +load_friction"), std::string::npos) << history.out;
  const auto steps = readJson(session / "history.json")["steps"];
  ASSERT_EQ(steps.size(), 2u);
  EXPECT_LT(steps[1]["validation"]["overall_nrmse"].get<double>(),
            steps[0]["validation"]["overall_nrmse"].get<double>());
  const bool plotted = std::filesystem::exists(session / "history.png");
  EXPECT_TRUE(plotted || history.out.find("plots skipped") != std::string::npos) << history.out;
  // With `--json -` the table and the plot line stay off stdout: it parses as the one document.
  const auto historyStdout = model({"history", "--out", session.string(), "--json", "-"});
  ASSERT_EQ(historyStdout.exitCode, 0) << historyStdout.err;
  EXPECT_EQ(nlohmann::json::parse(historyStdout.out)["steps"].size(), 2u) << historyStdout.out;
}

TEST_F(ModelCommand, HeaderlessLogsLoadThroughTheColumnMap) {
  // The simulated log rewritten in the 31-column layout of the real UR10e logs.
  const auto log = arcplan::model::readLog(dir / "fit.csv");
  std::string text;
  for (std::size_t r = 0; r < log.rows(); ++r) {
    text += std::to_string(log.time[r]);
    for (const auto* signal : {"actual_q", "actual_qd", "actual_current", "actual_current", "target_moment"}) {
      for (int j = 0; j < 6; ++j) text += "," + std::to_string(log.vector(signal)(r, j));
    }
    text += "\n";
  }
  write(dir / "headerless.csv", text);
  const auto result = model({"compare", "--model", (dir / "base.yaml").string(), "--data",
                             (dir / "headerless.csv").string(), "--columns", "ur10e_real", "--rows", "100-"});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.out.find("kept 2302 of 2302 rows"), std::string::npos) << result.out;
}

TEST_F(ModelCommand, GearboxDataGivesForceTransferDiagrams) {
  const auto out = freshTempDirectory("model_gearbox");
  write(out / "ftd.yaml", "kind: gearbox_ftd\neffects: [drive_gain, offset]\n");
  const auto result = model({"fit", "--model", (out / "ftd.yaml").string(), "--data",
                             std::string(ARCPLAN_TEST_DATA_DIR) + "/thesis/force_transfer_diagrams.csv", "--add",
                             "load_friction", "--out", out.string()});
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const bool plotted = std::filesystem::exists(out / "fit_data_force_transfer.png");
  EXPECT_TRUE(plotted || result.out.find("plots skipped") != std::string::npos) << result.out;
}

// docs/cli.md: `--json -` puts one document on stdout and nothing else (the text is dropped). history,
// which needs a session, and the plots' lines: TheLoopCompareDiagnoseFitHistoryFollowsTheJsonContract.
TEST_F(ModelCommand, JsonToStdoutIsOneDocumentAndNothingElse) {
  const auto session = freshTempDirectory("model_json_stdout");
  const auto base = (dir / "base.yaml").string(), data = (dir / "fit.csv").string(), val = (dir / "val.csv").string();
  const std::vector<std::vector<std::string>> commands{
      {"compare", "--model", base, "--data", data, "--validate", val},
      {"diagnose", "--model", base, "--data", data, "--validate", val, "--no-discovery"},
      {"fit", "--model", base, "--data", data, "--add", "load_friction"},
      {"simulate", "--model", base, "--data", (session / "sim.csv").string(), "--duration", "1", "--rate", "50"}};
  for (auto arguments : commands) {
    arguments.insert(arguments.end(), {"--json", "-"});
    const auto result = model(arguments);
    ASSERT_EQ(result.exitCode, 0) << arguments[0] << ": " << result.err;
    // parse() refuses anything before or after the one document.
    nlohmann::json document;
    ASSERT_NO_THROW(document = nlohmann::json::parse(result.out)) << arguments[0] << ":\n" << result.out;
    EXPECT_TRUE(document.is_object()) << arguments[0];
  }
}

// Pushes (tests/model/push_simulation.h) in the validation log: fit leaves their windows out unless
// --keep-events, as diagnose does.
TEST_F(ModelCommand, FitKeepEventsScoresOnEverySample) {
  const auto out = freshTempDirectory("model_fit_events");
  auto log = arcplan::model::readLog(dir / "val.csv");
  const Eigen::VectorXd gains = Eigen::VectorXd::Constant(6, 0.1);  // A per N·m, about the UR10e's
  arcplan::testing::addPushes(log, arcplan::robot::ur10e(),
                              {{3.0, 3.8, {40.0, 0.0, 0.0}}, {7.0, 8.5, {0.0, -50.0, 20.0}}}, gains);
  arcplan::model::writeLog(log, out / "pushed.csv");
  auto eventsLeftOut = [&](bool keepEvents) {
    std::vector<std::string> arguments{"fit",
                                       "--model",
                                       (dir / "base.yaml").string(),
                                       "--data",
                                       (dir / "fit.csv").string(),
                                       "--validate",
                                       (out / "pushed.csv").string(),
                                       "--add",
                                       "load_friction",
                                       "--json",
                                       "-"};
    if (keepEvents) arguments.push_back("--keep-events");
    const auto result = model(arguments);
    EXPECT_EQ(result.exitCode, 0) << result.err;
    const auto document = nlohmann::json::parse(result.out);
    return document["events_left_out"]["data"].size() + document["events_left_out"]["validation"].size();
  };
  EXPECT_GT(eventsLeftOut(false), 0u);
  EXPECT_EQ(eventsLeftOut(true), 0u);
}

TEST_F(ModelCommand, EveryModelSubcommandHasHelp) {
  for (const auto* sub : {"compare", "diagnose", "fit", "simulate", "history"}) {
    const auto result = model({sub, "--help"});
    EXPECT_EQ(result.exitCode, 0) << sub;
    EXPECT_NE(result.out.find("--json"), std::string::npos) << sub;
  }
}

// Bad input: a clear message, exit code 1, and no output file (complete or partial).
class ModelCommandErrors : public ModelCommand {
protected:
  void expectFailure(std::vector<std::string> arguments, const std::string& message) {
    const auto out = freshTempDirectory("model_errors");
    const auto json = out / "result.json", saved = out / "saved.yaml";
    arguments.insert(arguments.end(), {"--json", json.string()});
    if (arguments[0] == "fit") arguments.insert(arguments.end(), {"--save", saved.string()});
    const auto result = model(arguments);
    EXPECT_EQ(result.exitCode, 1) << result.out;
    EXPECT_NE(result.err.find(message), std::string::npos) << result.err;
    EXPECT_NE(result.err.find("arcplan: error:"), std::string::npos);
    EXPECT_FALSE(std::filesystem::exists(json));
    EXPECT_FALSE(std::filesystem::exists(saved));
    EXPECT_TRUE(temporaryFilesBelow(out).empty());
  }
};

TEST_F(ModelCommandErrors, UnknownColumn) {
  write(dir / "raw.csv", "0,1,2,3,4,5,6\n1,1,2,3,4,5,6\n");
  expectFailure({"compare", "--model", (dir / "base.yaml").string(), "--data", (dir / "raw.csv").string(), "--columns",
                 "timestamp=1, actual_torque=2-7"},
                "unknown column 'actual_torque'");
  expectFailure({"compare", "--model", (dir / "base.yaml").string(), "--data", (dir / "raw.csv").string(), "--columns",
                 "ur10e_real"},
                "unknown column");
}

TEST_F(ModelCommandErrors, UnknownEffectName) {
  expectFailure(
      {"fit", "--model", (dir / "base.yaml").string(), "--data", (dir / "fit.csv").string(), "--add", "frobnication"},
      "unknown effect 'frobnication'");
  write(dir / "bad_model.yaml", "kind: joint_current\neffects: [drive_gain, warp_drive]\n");
  expectFailure({"diagnose", "--model", (dir / "bad_model.yaml").string(), "--data", (dir / "fit.csv").string()},
                "unknown effect 'warp_drive'");
}

TEST_F(ModelCommandErrors, EmptyLog) {
  write(dir / "empty.csv", "");
  expectFailure({"compare", "--model", (dir / "base.yaml").string(), "--data", (dir / "empty.csv").string()}, "empty");
  write(dir / "header_only.csv", "timestamp,actual_q_0,actual_current_0,target_moment_0\n");
  expectFailure({"diagnose", "--model", (dir / "base.yaml").string(), "--data", (dir / "header_only.csv").string()},
                "no data rows");
}

TEST_F(ModelCommandErrors, AllRowsInvalid) {
  write(dir / "invalid.csv",
        "timestamp,actual_q_0,actual_qd_0,actual_current_0,target_moment_0\n0,nan,0,0,0\n1,0,0,1e290,0\n1,0,0\n");
  expectFailure(
      {"fit", "--model", (dir / "base.yaml").string(), "--data", (dir / "invalid.csv").string(), "--add", "stribeck"},
      "no valid rows");
}

TEST_F(ModelCommandErrors, MismatchedJointCount) {
  // A five-joint validation log against a six-joint log.
  const auto log = arcplan::model::readLog(dir / "val.csv");
  arcplan::model::Log five = log;
  for (auto& [name, values] : five.vectors) values = values.leftCols(5).eval();
  arcplan::model::writeLog(five, dir / "five.csv");
  expectFailure({"compare", "--model", (dir / "base.yaml").string(), "--data", (dir / "fit.csv").string(), "--validate",
                 (dir / "five.csv").string()},
                "mismatched joint count");
  // Five joints against the six-joint UR10e for the rigid-body load torque.
  write(dir / "rigid.yaml", "kind: joint_current\nload_torque: rigid_body\neffects: [drive_gain]\n");
  expectFailure({"compare", "--model", (dir / "rigid.yaml").string(), "--data", (dir / "five.csv").string()},
                "mismatched joint count");
  // A header whose vectors disagree.
  write(dir / "ragged.csv", "timestamp,actual_q_0,actual_q_1,actual_current_0\n0,1,2,3\n");
  expectFailure({"compare", "--model", (dir / "base.yaml").string(), "--data", (dir / "ragged.csv").string()},
                "mismatched joint count");
}

TEST_F(ModelCommandErrors, ExpressionThatDoesNotParseNamesTheFileAndTheEntry) {
  write(dir / "bad_expression.yaml",
        "kind: joint_current\nload_torque: target_moment\neffects:\n  - drive_gain\n  - {id: drag, expression: "
        "\"qd*(abs(qd)\"}\n");
  expectFailure({"fit", "--model", (dir / "bad_expression.yaml").string(), "--data", (dir / "fit.csv").string(),
                 "--add", "offset"},
                "bad_expression.yaml:5:5: effects[1]: effect 'drag': expression 'qd*(abs(qd)'");
}

TEST_F(ModelCommandErrors, KeptModelWithoutFittedParametersNamesTheFileAndTheParameter) {
  for (const auto* command : {"diagnose", "fit", "compare"}) {
    std::vector<std::string> arguments{
        command, "--model", (dir / "base.yaml").string(), "--data", (dir / "fit.csv").string(), "--keep-parameters"};
    if (std::string(command) == "fit") arguments.insert(arguments.end(), {"--add", "stribeck"});
    expectFailure(arguments, "base.yaml: effects[0] (drive_gain): parameters.per_torque: missing");
  }
}

TEST_F(ModelCommandErrors, LogMissingASignalATermNeedsNamesTheLogAndTheSignal) {
  auto log = arcplan::model::readLog(dir / "fit.csv");
  log.vectors.erase("joint_temperatures");
  arcplan::model::writeLog(log, dir / "no_temperature.csv");
  write(dir / "warm.yaml",
        "kind: joint_current\nload_torque: target_moment\neffects: [drive_gain, {id: warm, expression: "
        "\"temperature*qd\"}]\n");
  expectFailure({"compare", "--model", (dir / "warm.yaml").string(), "--data", (dir / "no_temperature.csv").string()},
                "no_temperature.csv: effect 'warm': expression 'temperature*qd' needs signal 'temperature'");
  expectFailure({"fit", "--model", (dir / "base.yaml").string(), "--data", (dir / "no_temperature.csv").string(),
                 "--add", "temperature_friction"},
                "no_temperature.csv: signal 'temperature' is not available");
}

// Out-of-range option values: a usage error (exit 2) naming the option and what it expects, found
// before anything is read or written.
TEST_F(ModelCommandErrors, OutOfRangeOptionValuesAreUsageErrors) {
  const auto out = freshTempDirectory("model_usage_errors");
  const auto json = (out / "result.json").string(), log = (out / "log.csv").string();
  const auto base = (dir / "base.yaml").string(), data = (dir / "fit.csv").string();
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
      {{"diagnose", "--folds", "0"}, "--folds must be an integer >= 2"},
      {{"diagnose", "--folds", "1"}, "--folds must be an integer >= 2"},
      {{"diagnose", "--folds", "-1"}, "--folds must be an integer >= 2"},
      {{"diagnose", "--min-reduction", "nan"}, "--min-reduction must be a fraction from 0 to 1"},
      {{"diagnose", "--min-reduction", "-0.1"}, "--min-reduction must be a fraction from 0 to 1"},
      {{"diagnose", "--min-reduction", "1.5"}, "--min-reduction must be a fraction from 0 to 1"},
      {{"simulate", "--rate", "nan"}, "--rate must be a positive number"},
      {{"simulate", "--duration", "-1"}, "--duration must be a positive number"},
      {{"simulate", "--duration", "inf"}, "--duration must be a positive number"},
      {{"simulate", "--harmonics", "0"}, "--harmonics must be an integer >= 1"},
      {{"simulate", "--noise", "nan"}, "--noise must be a standard deviation >= 0"},
      {{"simulate", "--noise", "-0.1"}, "--noise must be a standard deviation >= 0"}};
  for (auto [arguments, message] : cases) {
    const auto where = arguments[0] == "simulate" ? log : data;
    arguments.insert(arguments.end(), {"--model", base, "--data", where, "--json", json});
    const auto result = model(arguments);
    EXPECT_EQ(result.exitCode, 2) << arguments[1] << " " << arguments[2] << ": " << result.err;
    EXPECT_NE(result.err.find(message), std::string::npos) << result.err;
    EXPECT_NE(result.err.find("got " + arguments[2] + "\n"), std::string::npos) << result.err;
    EXPECT_TRUE(result.out.empty()) << result.out;
    EXPECT_TRUE(arcplan::testing::filesBelow(out).empty()) << arguments[1] << " " << arguments[2];
  }
}

TEST_F(ModelCommandErrors, SimulateWritesNothingWhenItFails) {
  write(dir / "gearbox.yaml", "kind: gearbox_ftd\neffects: [drive_gain]\n");
  const auto out = freshTempDirectory("model_simulate_errors");
  const auto result = model({"simulate", "--model", (dir / "gearbox.yaml").string(), "--data", (out / "a.csv").string(),
                             "--validate", (out / "b.csv").string()});
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_NE(result.err.find("gearbox_ftd"), std::string::npos) << result.err;
  EXPECT_FALSE(std::filesystem::exists(out / "a.csv"));
  EXPECT_FALSE(std::filesystem::exists(out / "b.csv"));
}

}  // namespace
