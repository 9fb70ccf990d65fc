#include "parser_targets.h"

#include <fstream>
#include <set>
#include <stdexcept>
#include <unistd.h>

#include "arcplan/benchmarks/baseline.h"
#include "arcplan/benchmarks/benchmark_log_check.h"
#include "arcplan/benchmarks/suite.h"
#include "arcplan/collision/allowed_collisions.h"
#include "arcplan/collision/moveit_scene.h"
#include "arcplan/collision/scene.h"
#include "arcplan/common/error.h"
#include "arcplan/common/text_parsing.h"
#include "arcplan/model/force_transfer.h"
#include "arcplan/model/log_folder.h"
#include "arcplan/model/measurements.h"
#include "arcplan/model/model_spec.h"
#include "arcplan/robot/robot_model.h"
#include "arcplan/robot/srdf.h"
#include "ur_description_files.h"
#include "arcplan/trajectory/joint_path.h"

namespace arcplan::fuzz {
namespace {

// File-based parsers get the input as a file; one per process, rewritten for every input.
std::filesystem::path inputFile(const std::string& suffix) {
  const std::filesystem::path base =
      std::filesystem::exists("/dev/shm") ? "/dev/shm" : std::filesystem::temp_directory_path();
  return base / ("arcplan_fuzz_" + std::to_string(::getpid()) + suffix);
}

std::filesystem::path writeInput(const std::string& input, const std::string& suffix) {
  // The files (one per suffix) go when the process ends.
  static struct InputFiles {
    std::set<std::filesystem::path> written;
    ~InputFiles() {
      std::error_code ignored;
      for (const auto& file : written) std::filesystem::remove(file, ignored);
    }
  } inputFiles;
  const auto file = inputFile(suffix);
  std::ofstream(file, std::ios::binary | std::ios::trunc) << input;
  inputFiles.written.insert(file);
  return file;
}

// Named as arcplan's own URDF so relative mesh paths in a mutated UR10e description still resolve.
void parseUrdf(const std::string& input) { robot::parseRobotModel(input, robot::ur10eUrdfPath()); }
// Universal Robots' description files (robot/src/ur_description_files.h); the visual parameters name
// meshes in arcplan's data folder.
void parseUrKinematics(const std::string& input) { robot::detail::readUrKinematics(writeInput(input, ".yaml")); }
void parseUrJointLimits(const std::string& input) { robot::detail::readUrJointLimits(writeInput(input, ".yaml")); }
void parseUrPhysicalParameters(const std::string& input) {
  robot::detail::readUrPhysicalParameters(writeInput(input, ".yaml"));
}
void parseUrVisualParameters(const std::string& input) {
  robot::detail::readUrVisualParameters(writeInput(input, ".yaml"), robot::ur10eUrdfPath().parent_path());
}
void parseSrdf(const std::string& input) { robot::parseSrdfDisabledCollisions(input, "fuzz.srdf"); }
void parseScene(const std::string& input) { collision::loadScene(writeInput(input, ".yaml")); }
// MoveIt messages read against arcplan's UR10e; a request is read with an empty scene beside it.
void parseMoveItScene(const std::string& input) {
  collision::loadMoveItScene(writeInput(input, ".yaml"), {robot::ur10eUrdfPath(), {}});
}
void parseMoveItRequest(const std::string& input) {
  const auto scene = writeInput("name: fuzz\n", "_scene.yaml");
  collision::loadMoveItProblem(scene, writeInput(input, ".yaml"), {robot::ur10eUrdfPath(), {}});
}
void parseMoveItTextScene(const std::string& input) {
  collision::loadMoveItTextScene(writeInput(input, ".scene"), {robot::ur10eUrdfPath(), {}});
}
void parseAllowedCollisions(const std::string& input) { collision::loadAllowedCollisions(writeInput(input, ".yaml")); }
void parseJointPath(const std::string& input) { trajectory::readJointPathCsv(writeInput(input, ".csv")); }
void parseRtdeLog(const std::string& input) { model::readLog(writeInput(input, ".csv")); }
void parseHeaderlessLog(const std::string& input) {
  model::LogReadOptions options;
  options.columns = model::parseColumnMap("ur10e_real");
  model::readLog(writeInput(input, ".csv"), options);
}
// A run folder in one input: a line "=== NAME" starts file NAME (a plain file name); the files are
// written to a fresh folder for every input.
void parseLogFolder(const std::string& input) {
  static struct Folder {
    std::filesystem::path path = inputFile("_folder");
    ~Folder() {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  } folder;
  std::filesystem::remove_all(folder.path);
  std::filesystem::create_directory(folder.path);
  std::ofstream file;
  std::size_t start = 0;
  while (start < input.size()) {
    const auto end = std::min(input.find('\n', start), input.size());
    const std::string line = input.substr(start, end - start);
    start = end + 1;
    if (line.rfind("=== ", 0) == 0) {
      const std::string name = line.substr(4);
      const bool plain = !name.empty() && name.size() < 100 && name != "." && name != ".." &&
                         name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_.-") == std::string::npos;
      if (!plain) throw Error("fuzz input: '" + name + "' is not a plain file name");
      file.close();
      file.open(folder.path / name, std::ios::binary | std::ios::trunc);
    } else if (file.is_open()) {
      file << line << '\n';
    }
  }
  file.close();
  model::readLogFolder(folder.path);
}
void parseColumnMap(const std::string& input) { model::parseColumnMap(input); }
void parseForceTransfer(const std::string& input) { model::readForceTransferData(writeInput(input, ".csv")); }
void parseModel(const std::string& input) { model::parseModelYaml(input, "fuzz_model.yaml"); }
void parseSuite(const std::string& input) { benchmarks::loadSuite(writeInput(input, ".yaml")); }
void parseNumbers(const std::string& input) { parseNumberList(input, "--joints"); }
// The completeness check of campaign logs says what is wrong instead of throwing; a defect counts as rejected.
void parseOmplLog(const std::string& input) {
  if (const auto defect = benchmarks::benchmarkLogProblem(writeInput(input, ".log"))) throw Error(*defect);
}
void parseBaseline(const std::string& input) {
  const auto file = writeInput(input, ".json");
  benchmarks::baselineResults(benchmarks::readBaseline(file), file.string());
}

}  // namespace

const std::vector<ParserTarget>& parserTargets() {
  static const std::vector<ParserTarget> targets{
      {"urdf", ".urdf", parseUrdf},
      {"scene", ".yaml", parseScene},
      {"allowed_collisions", ".yaml", parseAllowedCollisions},
      {"moveit_scene", ".yaml", parseMoveItScene},
      {"moveit_request", ".yaml", parseMoveItRequest},
      {"moveit_text_scene", ".scene", parseMoveItTextScene},
      {"ur_kinematics", ".yaml", parseUrKinematics},
      {"ur_joint_limits", ".yaml", parseUrJointLimits},
      {"ur_physical_parameters", ".yaml", parseUrPhysicalParameters},
      {"ur_visual_parameters", ".yaml", parseUrVisualParameters},
      {"srdf", ".srdf", parseSrdf},
      {"joint_path", ".csv", parseJointPath},
      {"rtde_log", ".csv", parseRtdeLog},
      {"headerless_log", ".csv", parseHeaderlessLog},
      {"log_folder", "", parseLogFolder},
      {"column_map", "", parseColumnMap},
      {"force_transfer", ".csv", parseForceTransfer},
      {"model", ".yaml", parseModel},
      {"suite", ".yaml", parseSuite},
      {"number_list", "", parseNumbers},
      {"ompl_log", ".log", parseOmplLog},
      {"baseline", ".json", parseBaseline},
  };
  return targets;
}

const ParserTarget& parserTarget(const std::string& name) {
  for (const auto& target : parserTargets()) {
    if (target.name == name) return target;
  }
  throw std::out_of_range("unknown fuzz target " + name);
}

bool runParserTarget(const ParserTarget& target, std::string_view input) {
  try {
    target.parse(std::string(input));
    return true;
  } catch (const Error&) {
    return false;
  }
}

}  // namespace arcplan::fuzz
