#pragma once
// The VAMP half of the side-by-side benchmark (perf/peer_vamp_mbm.cpp): VAMP's UR5 (a fixed
// compiled sphere model of the MBM UR5 + Robotiq 85), its environment, RRT-Connect and simplifier.
//
// VAMP is built with -march=native and its own Eigen settings, so this interface carries no Eigen
// and no VAMP type: vamp_side.cpp is compiled alone into a library whose symbols are hidden except
// these (an Eigen type crossing between code built with and without AVX would change its alignment).
#include <array>
#include <cstddef>
#include <string>
#include <vector>

// Only what this header declares is visible outside the library.
#define ARCPLAN_PEER_VAMP_API __attribute__((visibility("default")))

namespace arcplan::peer_vamp {

using Joints = std::array<double, 6>;
using Point = std::array<double, 3>;

// Obstacles in VAMP's terms, in the URDF root frame (the MoveIt world frame of the MBM problems).
struct VampCuboid {
  Point center{};
  std::array<Point, 3> axes{};  // the box's local x, y, z axes (unit vectors)
  Point halfExtents{};
};
struct VampCapsule {  // a segment swept by a ball: what VAMP checks for a cylinder
  Point end1{}, end2{};
  double radius = 0.0;
};
struct VampSphere {
  Point center{};
  double radius = 0.0;
};
struct VampScene {
  std::vector<VampCuboid> cuboids;
  std::vector<VampCapsule> capsules;
  std::vector<VampSphere> spheres;
};

// The settings of VAMP's own MBM evaluation (scripts/evaluate_mbm.py with its defaults): RRTCSettings
// defaults except range 1.5 (ROBOT_RRT_RANGES["ur5"]) and max_iterations = max_samples = 10^6
// (DEFAULT_ITERATIONS); SimplifySettings defaults; a Halton sampler reset before every problem.
struct VampSettings {
  double range = 1.5;
  std::size_t maxIterations = 1000000;
};

struct VampRun {
  bool startValid = false;  // under VAMP's spheres; its script skips a problem with an invalid end
  bool goalValid = false;
  bool solved = false;
  std::vector<Joints> path;      // simplified, as VAMP returns it (float32 values)
  std::size_t rawWaypoints = 0;  // of the RRT-Connect path before simplification
  std::size_t iterations = 0;
  double planningUs = 0.0;        // VAMP's own timer of RRTC::solve (starts after its buffers)
  double simplificationUs = 0.0;  // VAMP's own timer of simplify
  double wallUs = 0.0;            // steady_clock around both calls, as arcplan's planners are timed
  double initialCost = 0.0;       // joint-space length of the raw path [rad]
  double simplifiedCost = 0.0;
};

// Plans start -> goal in `scene`. The environment is built before the clock starts (like the
// collision model on arcplan's side). Nothing is planned when start or goal is invalid.
ARCPLAN_PEER_VAMP_API VampRun runVamp(const VampScene& scene, const Joints& start, const Joints& goal,
                                      const VampSettings& settings);

// VAMP's state check of one configuration (all lanes of one SIMD block the same state).
ARCPLAN_PEER_VAMP_API bool vampStateValid(const VampScene& scene, const Joints& q);

// VAMP's forward kinematics of the end-effector link (robotiq_85_base_link) in the URDF root frame,
// as a row-major 4x4 matrix: to compare VAMP's compiled robot with the URDF arcplan loads.
ARCPLAN_PEER_VAMP_API std::array<double, 16> vampEndEffectorPose(const Joints& q);

// What VAMP's compiled robot is and how it was built, for the JSON: name, end effector, sphere
// count, joint names, SIMD width (rake) and edge resolution.
struct VampRobotInfo {
  std::string name, endEffector;
  std::size_t spheres = 0, rake = 0, resolution = 0;
  std::vector<std::string> jointNames;
};
ARCPLAN_PEER_VAMP_API VampRobotInfo vampRobotInfo();

}  // namespace arcplan::peer_vamp
