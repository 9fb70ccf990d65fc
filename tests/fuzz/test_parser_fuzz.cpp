// Every parser of arcplan gets thousands of mutated inputs (deterministic, seeded) derived from
// valid files: each must be parsed or rejected with arcplan::Error — never another exception type,
// never a crash. The same entry points are the libFuzzer targets of scripts/fuzz, which explores
// far longer; this test keeps what it learned from regressing in every CTest run.
#include <random>

#include <gtest/gtest.h>

#include "parser_targets.h"
#include "support/command.h"
#include "support/ur5e_moveit_problems.h"  // every shape and field the MoveIt readers take

namespace {

const std::filesystem::path kData = ARCPLAN_TEST_DATA_DIR;
const std::filesystem::path kSeeds = std::filesystem::path(ARCPLAN_TEST_DATA_DIR) / ".." / "tests" / "fuzz" / "seeds";
const std::filesystem::path kSuites = std::filesystem::path(ARCPLAN_TEST_DATA_DIR) / ".." / "benchmarks" / "suites";

std::string rtdeLog(char separator) {
  std::string text = "timestamp";
  for (const char* signal : {"target_q", "actual_q", "actual_qd", "actual_current", "target_moment"}) {
    for (int j = 0; j < 6; ++j) text += separator + std::string(signal) + "_" + std::to_string(j);
  }
  text += "\n";
  for (int row = 0; row < 12; ++row) {
    text += std::to_string(0.002 * row);
    for (int k = 0; k < 30; ++k) text += separator + std::to_string(0.01 * row + 0.1 * k);
    text += "\n";
  }
  return text;
}

std::string headerlessLog() {
  std::string text;
  for (int row = 0; row < 12; ++row) {
    text += std::to_string(1141.5 + 0.01 * row);
    for (int k = 0; k < 30; ++k) text += "," + std::to_string(-0.5 + 0.01 * row + 0.05 * k);
    text += "\n";
  }
  return text;
}

// A run folder as the log_folder target reads it: "=== NAME" starts a file.
std::string logFolder() {
  std::string text;
  for (const char* signal : {"q_actual", "qd_actual", "i_actual", "m_target"}) {
    text += std::string("=== log_") + signal + ".csv\n";
    for (int row = 0; row < 12; ++row) {
      text += std::to_string(0.008 * row);
      for (int j = 0; j < 6; ++j) text += ", " + std::to_string(0.01 * row + 0.1 * j);
      text += "\n";
    }
  }
  return text;
}

std::vector<std::string> seedsFor(const std::string& target) {
  using arcplan::testing::readFile;
  if (target == "urdf") return {readFile(kData / "ur10e" / "ur10e.urdf")};
  if (target == "scene")
    return {readFile(kData / "scenes" / "thesis_obstacle.yaml"), readFile(kData / "scenes" / "thesis_free.yaml")};
  if (target == "allowed_collisions") return {readFile(kData / "ur10e" / "allowed_collisions.yaml")};
  for (const char* file : {"ur_kinematics", "ur_joint_limits", "ur_physical_parameters", "ur_visual_parameters"}) {
    if (target == file) return {readFile(kSeeds / (target + ".yaml"))};
  }
  if (target == "srdf") return {readFile(kSeeds / "robot.srdf")};
  if (target == "moveit_scene") {
    return {readFile(kSeeds / "moveit_scene.yaml"), arcplan::testing::cageScene(), arcplan::testing::shelfPickScene()};
  }
  if (target == "moveit_request") {
    return {readFile(kSeeds / "moveit_request.yaml"), readFile(kSeeds / "moveit_pose_request.yaml"),
            arcplan::testing::shelfPickRequest()};
  }
  if (target == "moveit_text_scene") return {readFile(kSeeds / "moveit.scene")};
  if (target == "joint_path") return {"q0,q1,q2,q3,q4,q5\n# a comment\n0,0,0,0,0,0\n0.1,-0.2,0.3,-0.4,0.5,-0.6\n"};
  if (target == "rtde_log") return {rtdeLog(','), rtdeLog(' ')};
  if (target == "headerless_log") return {headerlessLog()};
  if (target == "log_folder") return {logFolder()};
  if (target == "column_map") return {"timestamp=1, actual_q=2-7, actual_qd=8-13, actual_current=14-19", "ur10e_real"};
  if (target == "force_transfer") return {readFile(kData / "thesis" / "force_transfer_diagrams.csv")};
  if (target == "model") {
    return {
        "kind: joint_current\nload_torque: target_moment\neffects: [drive_gain, offset, coulomb, viscous]\n",
        "kind: gearbox_ftd\neffects: [load_friction]\n",
        "kind: joint_current\nload_torque: rigid_body\neffects:\n  - drive_gain\n  - {id: viscous, joints: [0, 1]}\n",
        // A discovered term as the diagnosis prints it, a payload in kg, friction with memory.
        "kind: joint_current\neffects:\n  - drive_gain\n  - {id: found_qd_abs_qd, expression: \"qd*abs(qd)\", joints: "
        "[0, 2]}\n"
        "  - {id: payload, mass_kg: 2.5, center_of_mass_z: 0.08}\n  - {id: dahl_friction, dahl_rate: 30}\n"};
  }
  // Not generated.yaml: every valid variant of it would generate its 50 problems (seconds each).
  if (target == "suite") return {readFile(kSuites / "thesis.yaml")};
  if (target == "number_list") return {"0.1,-0.2,0.3,1e-3,-4,5"};
  // A campaign log and a baseline of a tiny thesis campaign (RRTConnect and arc-auto, 2 runs).
  if (target == "ompl_log") return {readFile(kSeeds / "ompl_benchmark.log")};
  if (target == "baseline") return {readFile(kSeeds / "baseline.json")};
  return {};
}

// Tokens that break parsers in practice: number edge cases, YAML/XML/CSV syntax, bytes.
const std::vector<std::string> kTokens{"nan",
                                       "-inf",
                                       "1e400",
                                       "-0",
                                       "",
                                       "\"",
                                       "'",
                                       ":",
                                       "- ",
                                       "[",
                                       "]",
                                       "{",
                                       "}",
                                       "&a",
                                       "*a",
                                       "!!binary",
                                       "\t",
                                       std::string(1, '\0'),
                                       "\xff\xfe",
                                       ",,,",
                                       "\n\n",
                                       "<",
                                       ">",
                                       "</robot>",
                                       "package://x/y.stl",
                                       "99999999999999999999",
                                       "0x1p3",
                                       "~",
                                       "null",
                                       "true",
                                       "#",
                                       ";",
                                       "=",
                                       "-",
                                       "1-",
                                       "7-2"};

std::string mutate(std::string text, std::mt19937& random) {
  auto position = [&](std::size_t size) {
    return size == 0 ? 0 : std::uniform_int_distribution<std::size_t>(0, size - 1)(random);
  };
  const int operations = std::uniform_int_distribution<int>(1, 4)(random);
  for (int k = 0; k < operations; ++k) {
    switch (std::uniform_int_distribution<int>(0, 6)(random)) {
      case 0:  // flip a byte
        if (!text.empty()) text[position(text.size())] ^= static_cast<char>(1 << (random() % 8));
        break;
      case 1: {  // delete a range
        const auto start = position(text.size());
        text.erase(start, std::uniform_int_distribution<std::size_t>(1, 40)(random));
        break;
      }
      case 2:  // insert a token
        text.insert(position(text.size() + 1), kTokens[random() % kTokens.size()]);
        break;
      case 3:  // truncate
        text.resize(position(text.size() + 1));
        break;
      case 4: {  // replace a number-looking character run by a token
        const auto start = text.find_first_of("0123456789", position(text.size()));
        if (start != std::string::npos) {
          const auto end = text.find_first_not_of("0123456789.-e", start);
          text.replace(start, (end == std::string::npos ? text.size() : end) - start,
                       kTokens[random() % kTokens.size()]);
        }
        break;
      }
      case 5: {  // duplicate a line
        const auto start = text.rfind('\n', position(text.size()));
        const auto from = start == std::string::npos ? 0 : start + 1;
        const auto end = text.find('\n', from);
        const std::string line = text.substr(from, end == std::string::npos ? std::string::npos : end - from + 1);
        text.insert(from, line);
        break;
      }
      default: {  // swap two lines' worth of text
        const auto a = position(text.size()), b = position(text.size());
        if (a < b) std::swap(text[a], text[b]);
        break;
      }
    }
  }
  return text;
}

std::string printable(const std::string& input) {
  std::string shown;
  for (const unsigned char c : input.substr(0, 400)) {
    if (c == '\n' || (c >= 32 && c < 127))
      shown += static_cast<char>(c);
    else
      shown += "\\x" + std::string(1, "0123456789abcdef"[c >> 4]) + "0123456789abcdef"[c & 15];
  }
  return shown;
}

class ParserFuzz : public ::testing::TestWithParam<std::string> {};

TEST_P(ParserFuzz, MutatedInputsParseOrGiveAnArcplanError) {
  const auto& target = arcplan::fuzz::parserTarget(GetParam());
  const auto seeds = seedsFor(target.name);
  ASSERT_FALSE(seeds.empty());
  for (const auto& seed : seeds) {
    // The seeds themselves are valid input.
    EXPECT_TRUE(arcplan::fuzz::runParserTarget(target, seed)) << target.name << " rejects its seed";
  }
  std::mt19937 random(20261122);
  const int mutationsPerSeed = target.name == "urdf" ? 1000 : 2000;
  int rejected = 0, total = 0;
  for (const auto& seed : seeds) {
    for (int i = 0; i < mutationsPerSeed; ++i) {
      const std::string input = mutate(seed, random);
      try {
        rejected += arcplan::fuzz::runParserTarget(target, input) ? 0 : 1;
      } catch (const std::exception& e) {
        FAIL() << target.name << ": " << typeid(e).name() << " '" << e.what()
               << "' instead of arcplan::Error for input:\n"
               << printable(input);
      }
      ++total;
    }
  }
  // The mutations must reach the error paths, or the test proves nothing.
  EXPECT_GT(rejected, total / 20) << target.name;
}

INSTANTIATE_TEST_SUITE_P(Parsers, ParserFuzz,
                         ::testing::Values("urdf", "scene", "allowed_collisions", "joint_path", "rtde_log",
                                           "headerless_log", "log_folder", "column_map", "force_transfer", "model",
                                           "suite", "number_list", "ompl_log", "baseline", "ur_kinematics",
                                           "ur_joint_limits", "ur_physical_parameters", "ur_visual_parameters", "srdf",
                                           "moveit_scene", "moveit_request", "moveit_text_scene"));

}  // namespace
