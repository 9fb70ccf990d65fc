#include "worker_pool.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <iostream>
#include <new>

#include <signal.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include "arcplan/benchmarks/interrupt.h"
#include "arcplan/common/error.h"

namespace arcplan::benchmarks::detail {
namespace {

PoolResult runInProcess(std::size_t jobCount, const JobFunction& job,
                        const std::function<std::string(std::size_t)>& label, ProgressDisplay& display) {
  PoolResult result;
  for (std::size_t i = 0; i < jobCount; ++i) {
    if (interruptRequested()) {
      result.interrupted = true;
      return result;
    }
    try {
      const auto outcome = job(i, [&](unsigned run, bool solved) {
        display.report({ProgressEvent::Kind::RunFinished, i, run, solved, 0});
      });
      display.report({ProgressEvent::Kind::JobFinished, i, 0, false, outcome.solved});
      ++result.completed;
    } catch (const JobInterrupted&) {
      result.interrupted = true;
      return result;
    } catch (const OutputWriteError& e) {
      display.report({ProgressEvent::Kind::JobFailed, i, 0, false, 0});
      result.failures.push_back(label(i) + ": " + e.what());
      result.outputFailure = e.what();
      return result;
    } catch (const Error& e) {
      display.report({ProgressEvent::Kind::JobFailed, i, 0, false, 0});
      result.failures.push_back(label(i) + ": " + e.what());
    }
  }
  return result;
}

// Messages from worker processes; small enough that each write() to the pipe is atomic (PIPE_BUF).
struct WorkerMessage {
  enum Kind : std::int32_t { RunFinished, JobFinished, JobFailed, OutputFailed };
  std::int32_t kind = RunFinished;
  std::uint32_t job = 0;
  std::uint32_t run = 0;
  std::uint32_t solved = 0;
  char text[496] = {};
};
static_assert(sizeof(WorkerMessage) <= PIPE_BUF, "worker messages must be written atomically");

constexpr int kWorkerInterrupted = 2;  // exit code of a worker that stopped on request

// Shared between the campaign process and its workers (an anonymous shared mapping).
struct SharedCounters {
  std::atomic<std::size_t> nextJob{0};
  std::atomic<bool> stop{false};
  std::atomic<bool> outputFailed{false};
};
static_assert(std::atomic<std::size_t>::is_always_lock_free && std::atomic<bool>::is_always_lock_free,
              "process-shared atomics must be lock-free");

void send(int fd, const WorkerMessage& message) {
  while (::write(fd, &message, sizeof message) < 0 && errno == EINTR) {
  }
}

WorkerMessage messageAbout(WorkerMessage::Kind kind, std::size_t job) {
  WorkerMessage message;
  message.kind = kind;
  message.job = static_cast<std::uint32_t>(job);
  return message;
}

[[noreturn]] void workerMain(std::size_t jobCount, const JobFunction& job, SharedCounters& shared, int fd) {
  watchStopFlag(&shared.stop);
  int exitCode = 0;
  while (true) {
    if (interruptRequested()) {
      exitCode = kWorkerInterrupted;
      break;
    }
    if (shared.outputFailed) break;
    const std::size_t i = shared.nextJob.fetch_add(1);
    if (i >= jobCount) break;
    try {
      const auto outcome = job(i, [&](unsigned run, bool solved) {
        auto message = messageAbout(WorkerMessage::RunFinished, i);
        message.run = run;
        message.solved = solved ? 1 : 0;
        send(fd, message);
      });
      auto message = messageAbout(WorkerMessage::JobFinished, i);
      message.solved = outcome.solved;
      send(fd, message);
    } catch (const JobInterrupted&) {
      exitCode = kWorkerInterrupted;
      break;
    } catch (const OutputWriteError& e) {
      shared.outputFailed = true;  // no other worker takes a new job
      auto message = messageAbout(WorkerMessage::OutputFailed, i);
      std::strncpy(message.text, e.what(), sizeof message.text - 1);
      send(fd, message);
      break;
    } catch (const std::exception& e) {
      auto message = messageAbout(WorkerMessage::JobFailed, i);
      std::strncpy(message.text, e.what(), sizeof message.text - 1);
      send(fd, message);
    }
  }
  ::close(fd);
  _exit(exitCode);  // no atexit handlers or stdio flushing of the parent's state
}

// Reads worker messages until every worker has closed its end of the pipe.
void collectMessages(int fd, SharedCounters& shared, const std::function<std::string(std::size_t)>& label,
                     ProgressDisplay& display, PoolResult& result) {
  WorkerMessage message;
  std::size_t filled = 0;
  while (true) {
    const ssize_t got = ::read(fd, reinterpret_cast<char*>(&message) + filled, sizeof message - filled);
    if (got < 0) {
      if (errno == EINTR) {
        if (interruptRequested()) shared.stop = true;  // workers finish their run, then stop
        continue;
      }
      break;
    }
    if (got == 0) break;
    if (interruptRequested()) shared.stop = true;
    filled += static_cast<std::size_t>(got);
    if (filled < sizeof message) continue;
    filled = 0;
    switch (message.kind) {
      case WorkerMessage::RunFinished:
        display.report({ProgressEvent::Kind::RunFinished, message.job, message.run, message.solved != 0, 0});
        break;
      case WorkerMessage::JobFinished:
        display.report({ProgressEvent::Kind::JobFinished, message.job, 0, false, message.solved});
        ++result.completed;
        break;
      case WorkerMessage::JobFailed:
      case WorkerMessage::OutputFailed:
        display.report({ProgressEvent::Kind::JobFailed, message.job, 0, false, 0});
        result.failures.push_back(label(message.job) + ": " + message.text);
        if (message.kind == WorkerMessage::OutputFailed) result.outputFailure = message.text;
        break;
    }
  }
}

// A worker that ended on a signal or with an unexpected exit code lost the job it was running.
void waitForWorkers(const std::vector<pid_t>& children, PoolResult& result) {
  for (const pid_t child : children) {
    int status = 0;
    while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) continue;
    if ((WIFEXITED(status) && (WEXITSTATUS(status) == kWorkerInterrupted || WEXITSTATUS(status) == 130)) ||
        (WIFSIGNALED(status) && (WTERMSIG(status) == SIGINT || WTERMSIG(status) == SIGTERM))) {
      result.interrupted = true;
    } else {
      result.failures.push_back("worker process " + std::to_string(child) + " ended abnormally (" +
                                (WIFSIGNALED(status) ? "signal " + std::to_string(WTERMSIG(status))
                                                     : "exit " + std::to_string(WEXITSTATUS(status))) +
                                "); the job it was running has no log and runs again when the campaign is resumed");
    }
  }
}

PoolResult runInWorkers(std::size_t jobCount, unsigned workers, const JobFunction& job,
                        const std::function<std::string(std::size_t)>& label, ProgressDisplay& display) {
  void* memory = ::mmap(nullptr, sizeof(SharedCounters), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  if (memory == MAP_FAILED)
    throw Error(std::string("cannot share memory with worker processes: ") + std::strerror(errno));
  auto* shared = new (memory) SharedCounters();
  int fds[2];
  if (::pipe(fds) != 0) throw Error(std::string("cannot create a pipe to worker processes: ") + std::strerror(errno));

  std::cout.flush();
  std::cerr.flush();
  std::vector<pid_t> children;
  const pid_t parent = ::getpid();
  for (unsigned w = 0; w < workers; ++w) {
    const pid_t pid = ::fork();
    if (pid == 0) {
      // A worker outliving a killed campaign would go on writing into an output directory that a
      // resumed campaign owns: the kernel kills it with its parent (checked after, in case the
      // parent died before the request).
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (::getppid() != parent) _exit(kWorkerInterrupted);
      ::close(fds[0]);
      workerMain(jobCount, job, *shared, fds[1]);
    }
    if (pid < 0) {
      shared->stop = true;
      break;
    }
    children.push_back(pid);
  }
  ::close(fds[1]);

  PoolResult result;
  collectMessages(fds[0], *shared, label, display, result);
  ::close(fds[0]);
  waitForWorkers(children, result);
  if (interruptRequested()) result.interrupted = true;
  shared->~SharedCounters();
  ::munmap(memory, sizeof(SharedCounters));
  return result;
}

}  // namespace

PoolResult runJobs(std::size_t jobCount, unsigned workers, const JobFunction& job,
                   const std::function<std::string(std::size_t)>& label, ProgressDisplay& display) {
  if (workers <= 1) return runInProcess(jobCount, job, label, display);
  return runInWorkers(jobCount, workers, job, label, display);
}

}  // namespace arcplan::benchmarks::detail
