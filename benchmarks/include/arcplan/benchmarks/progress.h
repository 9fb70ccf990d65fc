#pragma once
// Campaign progress on the terminal: problem, planner, run k/N, elapsed time and ETA. On a terminal
// one status line is rewritten after every run; otherwise (CI logs, Slurm output files) one line is
// printed per finished job.
#include <chrono>
#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

namespace arcplan::benchmarks {

struct ProgressEvent {
  enum class Kind : int { RunFinished, JobFinished, JobFailed };
  Kind kind = Kind::RunFinished;
  std::size_t job = 0;      // index into the list of jobs being run
  unsigned run = 0;         // 1-based run number (RunFinished)
  bool solved = false;      // RunFinished: the run succeeded
  unsigned solvedRuns = 0;  // JobFinished: successful runs of the job
};

class ProgressDisplay {
public:
  // jobLabels[i] names job i ("obstacle · RRTConnect"); every job has runsPerJob runs.
  ProgressDisplay(std::ostream& out, bool interactive, std::vector<std::string> jobLabels, unsigned runsPerJob);

  void report(const ProgressEvent& event);
  // Ends the status line (interactive) so later output starts on a fresh line.
  void finish();

  std::size_t finishedJobs() const { return finishedJobs_; }

private:
  std::string timing() const;

  std::ostream& out_;
  bool interactive_;
  std::vector<std::string> jobLabels_;
  unsigned runsPerJob_;
  std::chrono::steady_clock::time_point start_;
  std::size_t finishedRuns_ = 0;
  std::size_t finishedJobs_ = 0;
  bool lineOpen_ = false;
};

// "1:02:03" / "4:05" for a duration in seconds.
std::string formatDuration(double seconds);

}  // namespace arcplan::benchmarks
