#pragma once
// What the campaign fault and determinism tests share: a tiny generated suite with an iteration
// budget, `arcplan bench` started as a child process (to kill it or limit its file size), and the
// runs of a benchmark database without the columns that measure time.
#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace arcplan::testing {

// A suite file of 2 generated problems (a line problem and a pillar) and the given planners, with
// `runs` runs of at most 20 s (a safety cap never reached) and an iteration budget.
std::filesystem::path writeTinySuite(const std::filesystem::path& directory, const std::vector<std::string>& planners,
                                     unsigned runs, unsigned budget);

// `arcplan bench --suite SUITE --no-plots --quiet --out OUT` plus `extra`.
std::vector<std::string> benchArguments(const std::filesystem::path& suite, const std::filesystem::path& out,
                                        const std::vector<std::string>& extra = {});

// `arcplan` running in a child process; stdout and stderr go to files next to nothing the campaign writes.
class ArcplanProcess {
public:
  // fileSizeLimit: RLIMIT_FSIZE of the child (bytes), as `prlimit --fsize` would set it.
  explicit ArcplanProcess(const std::vector<std::string>& arguments, std::optional<long> fileSizeLimit = std::nullopt);
  ArcplanProcess(const ArcplanProcess&) = delete;
  ArcplanProcess& operator=(const ArcplanProcess&) = delete;
  ~ArcplanProcess();  // kills and collects a child still running

  pid_t pid() const { return pid_; }
  bool running();                       // not yet exited (collects it when it has)
  int wait();                           // exit code, or 128 + signal
  std::string err() const;              // its stderr so far
  std::vector<pid_t> children() const;  // its child processes now (the worker processes)

private:
  pid_t pid_ = -1;
  std::optional<int> exitCode_;
  std::filesystem::path errFile_;
};

// Whether process `pid` is gone (or a zombie nobody collected yet).
bool processGone(pid_t pid);
// A pid that no process has now (a child that has exited and been collected).
pid_t deadPid();

// Every run of the database as text, ordered by experiment, planner and run, with the experiment and
// planner names and every run column except those that measure time or memory (time, memory,
// simplification_time, solve_time) and the row ids.
std::vector<std::string> deterministicRuns(const std::filesystem::path& database);

}  // namespace arcplan::testing
