#pragma once
// Ctrl-C during a campaign: the first SIGINT (or SIGTERM) asks the campaign to stop after the run in
// progress — completed job logs stay, the interrupted job writes nothing; a second one ends the
// process at once (still without a half-written file: logs are only ever renamed into place).
#include <atomic>

namespace arcplan::benchmarks {

// Installs the handlers for its lifetime and restores the previous ones afterwards.
class InterruptHandlers {
public:
  InterruptHandlers();
  ~InterruptHandlers();
  InterruptHandlers(const InterruptHandlers&) = delete;
  InterruptHandlers& operator=(const InterruptHandlers&) = delete;
};

// True after a signal, or once `stopFlag` (see below) is set.
bool interruptRequested();
// A flag another process sets to stop this one (campaign workers watch their parent's flag in shared
// memory); nullptr removes it.
void watchStopFlag(const std::atomic<bool>* stopFlag);
// For tests and for worker processes that are told to stop by their parent.
void requestInterrupt();
void clearInterruptRequest();

}  // namespace arcplan::benchmarks
