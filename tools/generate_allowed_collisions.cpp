// Generates data/ur10e/allowed_collisions.yaml: the adjacent link pairs of arcplan's UR10e plus the
// pairs that never come close in many random configurations (uniform inside the joint limits,
// seeded), the way MoveIt's setup assistant finds "Never" pairs, but stricter: a pair is only
// disabled if it never collided AND never came closer than --margin, so a rare near-collision keeps
// the pair checked. Each candidate pair is measured alone (every other pair allowed), so its own
// minimum distance is known.
#include <cstdint>
#include <iomanip>
#include <iostream>
#include <random>
#include <sstream>

#include <CLI/CLI.hpp>

#include "arcplan/collision/allowed_collisions.h"
#include "arcplan/collision/collision_model.h"
#include "arcplan/common/atomic_file.h"
#include "arcplan/common/error.h"

namespace {

using namespace arcplan;

// Uniform in [0, 1) from the top 53 bits, identical on every standard library (unlike
// std::uniform_real_distribution), so the file is reproducible anywhere.
double unitSample(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

struct PairStatistics {
  std::string first, second;
  long collisions = 0;
  double minimumDistance = INFINITY;
};

PairStatistics measurePair(const std::shared_ptr<const robot::RobotModel>& robot, const std::string& first,
                           const std::string& second, long samples, std::uint64_t seed) {
  collision::AllowedCollisionMatrix everyOtherPair;
  for (const auto& a : robot->links()) {
    for (const auto& b : robot->links()) {
      if (a.name < b.name && !((a.name == first && b.name == second) || (a.name == second && b.name == first))) {
        everyOtherPair.allow(a.name, b.name);
      }
    }
  }
  const collision::CollisionModel model(robot, collision::Scene{}, everyOtherPair);
  collision::CollisionData data(model);
  std::mt19937_64 rng(seed);
  Eigen::VectorXd q(robot->dof());
  PairStatistics statistics{first, second};
  for (long s = 0; s < samples; ++s) {
    for (int j = 0; j < robot->dof(); ++j) {
      const auto& limits = robot->joints()[j].limits;
      q[j] = limits.lower + (limits.upper - limits.lower) * unitSample(rng);
    }
    const double d = collision::distance(model, data, q).selfDistance;
    statistics.minimumDistance = std::min(statistics.minimumDistance, d);
    if (d <= 0.0) ++statistics.collisions;
  }
  return statistics;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Finds the UR10e link pairs that can never collide and writes data/ur10e/allowed_collisions.yaml"};
  long samples = 1000000;
  std::uint64_t seed = 1;
  double margin = 0.002;  // above the meshes' polygon error (0.5 mm) and STL rounding
  std::string output = collision::ur10eAllowedCollisionsPath().string();
  app.add_option("--samples", samples, "random configurations per link pair")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_option("--seed", seed, "seed of the configuration sampler (mt19937_64)")->capture_default_str();
  app.add_option("--margin", margin, "a pair closer than this in some sample stays checked [m]")->capture_default_str();
  app.add_option("--out", output, "output file")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    const auto robot = std::make_shared<const robot::RobotModel>(robot::ur10e());
    const collision::AllowedCollisionMatrix adjacent = collision::adjacentLinkPairs(*robot);
    std::vector<std::string> links;
    for (const auto& link : robot->links()) {
      if (!link.collisions.empty()) links.push_back(link.name);
    }
    std::ostringstream never, checked;
    never << std::setprecision(4);
    for (std::size_t a = 0; a < links.size(); ++a) {
      for (std::size_t b = a + 1; b < links.size(); ++b) {
        if (adjacent.isAllowed(links[a], links[b])) continue;
        const PairStatistics s = measurePair(robot, links[a], links[b], samples, seed);
        std::cout << links[a] << " - " << links[b] << ": " << s.collisions << " collisions, min distance "
                  << s.minimumDistance << " m\n";
        if (s.collisions == 0 && s.minimumDistance > margin) {
          never << "  - {links: [" << s.first << ", " << s.second
                << "], reason: never, min_distance: " << s.minimumDistance << "}\n";
        } else {
          checked << "#   " << s.first << " - " << s.second << ": " << s.collisions << " of " << samples
                  << " samples in collision\n";
        }
      }
    }
    std::ostringstream file;
    file << "# Allowed collisions of arcplan's UR10e (data/ur10e/ur10e.urdf with the generated link meshes).\n"
         << "# Written by: arcplan_generate_allowed_collisions --samples " << samples << " --seed " << seed
         << " --margin " << margin << "\n"
         << "# adjacent: the links share a joint. never: in " << samples << " random configurations (uniform in\n"
         << "# the joint limits, mt19937_64 seed " << seed << ") the pair never collided and never came closer than "
         << margin << " m\n# (min_distance: the closest it came). Regenerate after changing the URDF or the meshes.\n"
         << "# Pairs that stay checked:\n"
         << checked.str() << "robot: ur10e\n"
         << "generator: {samples: " << samples << ", seed: " << seed << ", margin: " << margin << "}\n"
         << "allowed_collisions:\n";
    for (const auto& [first, second] : adjacent.pairs()) {
      file << "  - {links: [" << first << ", " << second << "], reason: adjacent}\n";
    }
    file << never.str();
    writeFileAtomically(output, file.str());
    std::cout << "wrote " << output << "\n";
  } catch (const std::exception& e) {
    std::cerr << "arcplan_generate_allowed_collisions: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
