#include "arcplan/benchmarks/interrupt.h"

#include <atomic>
#include <csignal>

#include <unistd.h>

namespace arcplan::benchmarks {
namespace {

std::atomic<int> signalCount{0};
std::atomic<const std::atomic<bool>*> watchedStopFlag{nullptr};
struct sigaction previousInterrupt {};
struct sigaction previousTerminate {};

extern "C" void onSignal(int) {
  if (signalCount.fetch_add(1) >= 1) _exit(130);  // second signal: leave now (async-signal-safe)
}

}  // namespace

InterruptHandlers::InterruptHandlers() {
  struct sigaction action {};
  action.sa_handler = onSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;  // no SA_RESTART: a blocking read in the campaign parent returns EINTR
  sigaction(SIGINT, &action, &previousInterrupt);
  sigaction(SIGTERM, &action, &previousTerminate);
}

InterruptHandlers::~InterruptHandlers() {
  sigaction(SIGINT, &previousInterrupt, nullptr);
  sigaction(SIGTERM, &previousTerminate, nullptr);
}

bool interruptRequested() {
  const auto* stop = watchedStopFlag.load();
  return signalCount.load() > 0 || (stop != nullptr && stop->load());
}

void watchStopFlag(const std::atomic<bool>* stopFlag) { watchedStopFlag.store(stopFlag); }
void requestInterrupt() { signalCount.fetch_add(1); }
void clearInterruptRequest() { signalCount.store(0); }

}  // namespace arcplan::benchmarks
