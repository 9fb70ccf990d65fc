#pragma once
// One campaign job: one planner configuration on one problem, `runs` runs through
// ompl::tools::Benchmark, the metrics of every run (docs/metrics.md) stored as run properties, and the
// OMPL log written atomically. Internal to arcplan::benchmarks (campaign.cpp drives it).
#include <cstdint>
#include <exception>
#include <filesystem>
#include <functional>

#include "arcplan/benchmarks/suite.h"
#include "arcplan/common/error.h"

namespace arcplan::benchmarks::detail {

struct JobFiles {
  std::filesystem::path log;
  std::filesystem::path medianRun;  // CSV of the median run's TCP speed and path; empty: not wanted
};

struct JobOutcome {
  unsigned runs = 0;
  unsigned solved = 0;  // runs with an exact solution whose metrics could be computed
};

// Thrown between runs when an interrupt was requested; the job has written nothing. Deliberately not
// a std::runtime_error: OMPL's Benchmark catches those from its events and would carry on.
struct JobInterrupted : std::exception {
  const char* what() const noexcept override { return "benchmark job interrupted"; }
};

// A job's log or median-run file could not be written (disk full, file size limit, ...): the job has
// no log, and the jobs after it would fail the same way, so the campaign stops (worker_pool.h).
struct OutputWriteError : Error {
  using Error::Error;
};

// OMPL's seed generator is reseeded with this before the job's planner and SimpleSetup exist, and
// with runSeed before every run, so a job repeats exactly whatever ran before it in the process. One
// per problem, not per planner: run k of every planner of a problem has the same run seed, from which
// its samplers and simplifier draw (planners/seeded_sampling.h) — the arc planner's fallback computes
// the path RRTConnect + simplifier computes in the same run.
std::uint32_t jobSeed(const Suite& suite, const Problem& problem);
std::uint32_t runSeed(std::uint32_t jobSeed, unsigned run);

// Allocates every planner configuration once on the suite's first problem so that unknown planners
// and parameters are reported before anything runs. Throws arcplan::Error naming the suite and planner.
void checkPlannerConfigurations(const Suite& suite);

// Throws JobInterrupted (see above), OutputWriteError or arcplan::Error (the problem cannot be set up).
JobOutcome runJob(const Suite& suite, const Problem& problem, const PlannerConfiguration& planner,
                  const JobFiles& files, const std::function<void(unsigned run, bool solved)>& onRunFinished);

}  // namespace arcplan::benchmarks::detail
