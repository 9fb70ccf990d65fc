#pragma once
// Runs a campaign's jobs one after another in this process, or in parallel in forked worker
// processes. Each job stays in one process because OMPL's seed generator and output handler are
// process-global; workers pull job indices from a counter in shared memory and report runs, results
// and failures to the parent over a pipe, which feeds the progress display. Internal to
// arcplan::benchmarks (campaign.cpp drives it).
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "arcplan/benchmarks/progress.h"
#include "job_runner.h"

namespace arcplan::benchmarks::detail {

// Runs job `index`, calling onRunFinished after every run; throws JobInterrupted or std::exception.
using JobFunction =
    std::function<JobOutcome(std::size_t index, const std::function<void(unsigned run, bool solved)>& onRunFinished)>;

struct PoolResult {
  std::size_t completed = 0;
  std::vector<std::string> failures;  // "<job label>: <why>"
  bool interrupted = false;
  std::string outputFailure;  // set when a job could not write its output: the pool stopped early
};

// Runs jobs 0..jobCount-1 with at most `workers` processes (1: in this process). Stops between runs
// when an interrupt is requested, and hands out no further job once one failed to write its output
// (OutputWriteError: a full disk fails every job). `label(i)` names job i in failure messages. Workers
// die with the campaign process (PR_SET_PDEATHSIG), so a killed campaign leaves none running.
PoolResult runJobs(std::size_t jobCount, unsigned workers, const JobFunction& job,
                   const std::function<std::string(std::size_t)>& label, ProgressDisplay& display);

}  // namespace arcplan::benchmarks::detail
