#pragma once
// One seed for the random draws of RRTConnect + OMPL's simplifier, shared by everything that must
// draw the same: a benchmark run's RRTConnect (benchmarks' job runner seeds its SimpleSetup with
// the run seed) and the arc planner's joint-space fallback (its `seed` parameter, which the campaign
// sets to the same run seed). Both then compute the same simplified path on the same problem, so the
// fallback, which keeps the fastest of that path and its conversions, is no slower to execute than
// RRTConnect + simplifier of the same run provided its RRTConnect finds the first path within its time
// (that plan's simplification runs to the end; docs/reproducibility.md, docs/planners.md list the exceptions).
#include <cstdint>
#include <memory>

#include <ompl/base/Planner.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateSampler.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/SimpleSetup.h>

namespace arcplan::planners {

// The local seeds one seed gives the state samplers (the n-th sampler allocated in a run gets
// `sampler + n`) and the simplifier.
struct SamplingSeeds {
  std::uint32_t sampler = 1;
  std::uint32_t simplifier = 1;
};
SamplingSeeds samplingSeeds(std::uint32_t seed);

// OMPL's uniform sampler of a real-vector state space (the joint box), drawing from a generator seeded
// with `seed` instead of OMPL's process-wide seed.
ompl::base::StateSamplerPtr makeSeededSampler(const ompl::base::StateSpace* space, std::uint32_t seed);

// OMPL's simplifier as SimpleSetup::setup makes it (the problem's goal and objective), drawing from a
// generator seeded with `seed`.
ompl::geometric::PathSimplifierPtr makeSeededSimplifier(const ompl::base::SpaceInformationPtr& si,
                                                        const ompl::base::ProblemDefinition& problem,
                                                        std::uint32_t seed);

// The state sampler allocator of a seeded run: the n-th sampler it allocates draws from local seed
// `samplerSeed + n` (RRTConnect's is the first; the simplifier allocates the next when it repairs a path).
ompl::base::StateSamplerAllocator seededSamplerAllocator(std::uint32_t samplerSeed);

// Makes `setup` (already set up) draw from `seed`: its state space allocates seeded samplers (counted
// from here) and its simplifier is replaced by a seeded one. Call before every run; the allocator stays
// on the state space, which the setup's SpaceInformation owns.
void seedSampling(ompl::geometric::SimpleSetup& setup, std::uint32_t seed);

// Seeds one run with run seed `seed` as a benchmark campaign does and `arcplan plan --seed` repeats:
// seedSampling, and the planner's `seed` parameter (the arc planner's fallback) set to `seed` unless
// the user or the suite gave one (`seedGiven`). Call after setup and before every run.
void seedRun(ompl::geometric::SimpleSetup& setup, ompl::base::Planner& planner, std::uint32_t seed, bool seedGiven);

}  // namespace arcplan::planners
