#include "arcplan/benchmarks/progress.h"

#include <cmath>
#include <cstdio>

namespace arcplan::benchmarks {

std::string formatDuration(double seconds) {
  const long total = std::lround(std::max(0.0, seconds));
  char text[32];
  if (total >= 3600) {
    std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", total / 3600, (total / 60) % 60, total % 60);
  } else {
    std::snprintf(text, sizeof text, "%ld:%02ld", total / 60, total % 60);
  }
  return text;
}

ProgressDisplay::ProgressDisplay(std::ostream& out, bool interactive, std::vector<std::string> jobLabels,
                                 unsigned runsPerJob)
    : out_(out),
      interactive_(interactive),
      jobLabels_(std::move(jobLabels)),
      runsPerJob_(runsPerJob),
      start_(std::chrono::steady_clock::now()) {}

std::string ProgressDisplay::timing() const {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const std::size_t totalRuns = jobLabels_.size() * runsPerJob_;
  std::string text = "elapsed " + formatDuration(elapsed) + " · ETA ";
  if (finishedRuns_ == 0 || totalRuns == 0) return text + "--";
  const double remaining = elapsed * static_cast<double>(totalRuns - std::min(totalRuns, finishedRuns_)) /
                           static_cast<double>(finishedRuns_);
  return text + formatDuration(remaining);
}

void ProgressDisplay::report(const ProgressEvent& event) {
  const std::string jobCount =
      std::to_string(finishedJobs_ + (event.kind == ProgressEvent::Kind::RunFinished ? 1 : 0)) + "/" +
      std::to_string(jobLabels_.size());
  const std::string& label = event.job < jobLabels_.size() ? jobLabels_[event.job] : std::string("?");
  switch (event.kind) {
    case ProgressEvent::Kind::RunFinished:
      ++finishedRuns_;
      if (interactive_) {
        out_ << "\r\033[K[job " << jobCount << "] " << label << " · run " << event.run << "/" << runsPerJob_ << " · "
             << timing() << std::flush;
        lineOpen_ = true;
      }
      break;
    case ProgressEvent::Kind::JobFinished:
    case ProgressEvent::Kind::JobFailed: {
      ++finishedJobs_;
      // Runs of a failed or abandoned job no longer count as outstanding.
      const std::size_t expected = finishedJobs_ * runsPerJob_;
      if (finishedRuns_ < expected) finishedRuns_ = expected;
      // A failure stays visible on a terminal too: it gets its own line above the status line.
      if (!interactive_ || event.kind == ProgressEvent::Kind::JobFailed) {
        if (interactive_) out_ << "\r\033[K";
        out_ << "[" << finishedJobs_ << "/" << jobLabels_.size() << "] " << label << ": ";
        if (event.kind == ProgressEvent::Kind::JobFinished) {
          out_ << event.solvedRuns << "/" << runsPerJob_ << " runs solved";
        } else {
          out_ << "failed";
        }
        out_ << " · " << timing() << "\n" << std::flush;
      }
      break;
    }
  }
}

void ProgressDisplay::finish() {
  if (interactive_ && lineOpen_) out_ << "\r\033[K" << std::flush;
  lineOpen_ = false;
}

}  // namespace arcplan::benchmarks
