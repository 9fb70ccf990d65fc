#pragma once
// Folders of MoveIt problems (MotionBenchMaker's layout): sceneNNNN.yaml + requestNNNN.yaml pairs,
// directly in a folder or one family folder deep, and the check of their start and goal with the
// robot's exact collision meshes that decides which of them are planned (docs/benchmarks.md).
#include <filesystem>
#include <string>
#include <vector>

#include "arcplan/benchmarks/suite.h"
#include "arcplan/collision/moveit_scene.h"

namespace arcplan::benchmarks {

struct MoveItProblemFiles {
  std::string family;  // the family folder's name ("box_ur5"), or the folder's own name for a flat folder
  std::string name;    // "<family>-NNNN"
  std::filesystem::path scene, request;
};

// Every pair, sorted by family then number. Throws arcplan::Error for a missing folder, a scene
// without its request (or the reverse), or a folder with no pairs.
std::vector<MoveItProblemFiles> listMoveItProblems(const std::filesystem::path& folder);

// Whether one end of a query can be planned from/to: inside the joint limits and free of contact
// under the exact meshes (no clearance asked); for a pose, some IK solution is.
struct EndpointValidity {
  bool valid = true;
  std::string problem;  // why not: "in collision: wrist_3_link–Can1, ..." or the limit/IK message
  std::vector<std::pair<std::string, std::string>> contacts;  // pairs in contact (joint endpoints)
};
struct ProblemValidity {
  EndpointValidity start, goal;
  bool valid() const { return start.valid && goal.valid; }
};
ProblemValidity checkEndpoints(const collision::Scene& scene, const std::string& query = "");

// Suite entries `moveit_problems: {folder, urdf | ur_type [description] [kinematics], srdf}`: every
// problem loaded; the valid ones appended to suite.problems (kind = family), the others to
// suite.excludedProblems. Paths relative to the suite file, else under ARCPLAN_SHARED_DATA. Throws
// arcplan::Error naming the problem's file.
struct MoveItProblemSource {
  std::filesystem::path folder;
  collision::MoveItRobot robot;  // a URDF, or a UR type from UR's description
};
void addMoveItProblems(const MoveItProblemSource& source, Suite& suite);

// The per-family table of loaded / valid / invalid start / invalid goal with the pairs in contact
// (Markdown) of the suite's MoveIt problems, as bench prints it and docs/benchmarks.md shows it; ""
// for a suite without any.
std::string validityTable(const Suite& suite);

}  // namespace arcplan::benchmarks
