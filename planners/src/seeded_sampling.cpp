#include "arcplan/planners/seeded_sampling.h"

#include <string>

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/util/RandomNumbers.h>

#include <atomic>

namespace arcplan::planners {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

class SeededJointSampler : public ob::RealVectorStateSampler {
public:
  SeededJointSampler(const ob::StateSpace* space, std::uint32_t seed) : RealVectorStateSampler(space) {
    rng_.setLocalSeed(seed);
  }
};

class SeededSimplifier : public og::PathSimplifier {
public:
  SeededSimplifier(const ob::SpaceInformationPtr& si, const ob::ProblemDefinition& problem, std::uint32_t seed)
      : PathSimplifier(si, problem.getGoal(), problem.getOptimizationObjective()) {
    rng_.setLocalSeed(seed);
  }
};

// OMPL rejects a local seed of 0; keep the seeds in 31 bits like the campaign's.
std::uint32_t nonZero(std::uint64_t value) { return static_cast<std::uint32_t>(value % 2147483646ULL) + 1U; }

}  // namespace

SamplingSeeds samplingSeeds(std::uint32_t seed) {
  // Two streams that differ however close two seeds are (a multiplicative hash of the seed).
  const std::uint64_t mixed = static_cast<std::uint64_t>(seed) * 0x9E3779B97F4A7C15ULL;
  return {seed, static_cast<std::uint32_t>(mixed >> 32)};
}

ob::StateSamplerPtr makeSeededSampler(const ob::StateSpace* space, std::uint32_t seed) {
  return std::make_shared<SeededJointSampler>(space, nonZero(seed));
}

og::PathSimplifierPtr makeSeededSimplifier(const ob::SpaceInformationPtr& si, const ob::ProblemDefinition& problem,
                                           std::uint32_t seed) {
  return std::make_shared<SeededSimplifier>(si, problem, nonZero(seed));
}

ob::StateSamplerAllocator seededSamplerAllocator(std::uint32_t samplerSeed) {
  auto allocated = std::make_shared<std::atomic<std::uint32_t>>(0);
  return [samplerSeed, allocated](const ob::StateSpace* space) {
    return makeSeededSampler(space, samplerSeed + allocated->fetch_add(1));
  };
}

void seedSampling(og::SimpleSetup& setup, std::uint32_t seed) {
  const SamplingSeeds seeds = samplingSeeds(seed);
  setup.getStateSpace()->setStateSamplerAllocator(seededSamplerAllocator(seeds.sampler));
  setup.getPathSimplifier() =
      makeSeededSimplifier(setup.getSpaceInformation(), *setup.getProblemDefinition(), seeds.simplifier);
}

void seedRun(og::SimpleSetup& setup, ob::Planner& planner, std::uint32_t seed, bool seedGiven) {
  seedSampling(setup, seed);
  if (!seedGiven && planner.params().hasParam("seed")) planner.params().setParam("seed", std::to_string(seed));
}

}  // namespace arcplan::planners
