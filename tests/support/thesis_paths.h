#pragma once
// The thesis query's two joint-space solutions (the UR10e of data/scenes/thesis_obstacle.yaml, start A and goal B) and
// dense paths between them, for the collision tests and the micro-benchmarks (perf/). No GoogleTest here: perf
// includes it too.
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Core>

namespace arcplan::testing {

inline const Eigen::VectorXd kThesisSolutionA =
    (Eigen::VectorXd(6) << -1.098, -1.510, 2.351, -2.411, -1.571, -1.098).finished();
inline const Eigen::VectorXd kThesisSolutionB =
    (Eigen::VectorXd(6) << 0.399, -1.624, 2.012, -1.958, -1.571, 0.399).finished();

// A path of `steps` small joint steps (the arc planner's waypoints are ~1 cm of TCP apart) from A to B through the
// particle's neighbourhood, bent sideways by a smooth random offset (sin(πs) times a normal draw per joint, σ 0.25 rad)
// so that some pass it at a few centimetres, some within 1 cm and some through it. `Random` is a standard engine the
// caller seeded.
template <typename Random>
std::vector<Eigen::VectorXd> bentLine(Random& random, int steps) {
  std::normal_distribution<double> offset(0.0, 0.25);
  Eigen::VectorXd bend(6);
  for (auto& v : bend) v = offset(random);
  std::vector<Eigen::VectorXd> path;
  for (int k = 0; k <= steps; ++k) {
    const double s = static_cast<double>(k) / steps;
    path.push_back(kThesisSolutionA + s * (kThesisSolutionB - kThesisSolutionA) + std::sin(M_PI * s) * bend);
  }
  return path;
}

}  // namespace arcplan::testing
