#include "arcplan/benchmarks/campaign.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include <signal.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include "arcplan/benchmarks/generated_problems.h"
#include "arcplan/benchmarks/interrupt.h"
#include "arcplan/benchmarks/progress.h"
#include "arcplan/benchmarks/statistics_database.h"
#include "arcplan/common/atomic_file.h"
#include "arcplan/common/error.h"
#include "arcplan/common/plotting.h"
#include "arcplan/common/text_parsing.h"
#include "arcplan/planners/planning_problem.h"
#include "arcplan/robot/kinematics.h"
#include "job_runner.h"

namespace arcplan::benchmarks {
namespace {

// --- the campaign's settings, kept in the output directory -----------------------------------------

void createDirectory(const std::filesystem::path& directory) {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec) throw Error("cannot create directory " + directory.string() + ": " + ec.message());
}

nlohmann::json manifestOf(const Suite& suite) {
  nlohmann::json planners = nlohmann::json::array();
  for (const auto& planner : suite.planners) {
    planners.push_back({{"name", planner.label}, {"planner", planner.planner}, {"params", planner.parameters}});
  }
  nlohmann::json problems = nlohmann::json::array();
  for (const auto& problem : suite.problems) problems.push_back(problem.name);
  return {{"suite", suite.name},
          {"runs", suite.runs},
          {"time_limit_s", suite.timeLimit},
          {"vmax_mps", suite.vMax},
          {"generator_seed", suite.generator ? nlohmann::json(suite.generator->seed) : nlohmann::json(nullptr)},
          {"problems", problems},
          {"planners", planners}};
}

// A resumed or sharded campaign must run exactly the settings its directory was started with;
// mixing logs of different settings would make one ranking of incomparable runs.
void claimOutputDirectory(const std::filesystem::path& directory, const Suite& suite) {
  const auto file = directory / "campaign.json";
  const auto wanted = manifestOf(suite);
  if (std::filesystem::exists(file)) {
    nlohmann::json existing;
    try {
      std::ifstream in(file);
      existing = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
      throw Error(file.string() + ": not a campaign description (" + e.what() + "); use another --out");
    }
    if (existing != wanted) {
      std::string differences;
      for (const auto& [key, value] : wanted.items()) {
        if (!existing.contains(key) || existing[key] != value) differences += (differences.empty() ? "" : ", ") + key;
      }
      throw Error(directory.string() + " holds a campaign with other settings (" +
                  (differences.empty() ? std::string("unknown fields") : differences) +
                  " differ from campaign.json); resume with the same suite, --planners, --runs, --time and --vmax, "
                  "or choose another --out");
    }
    return;
  }
  writeFileAtomically(file, wanted.dump(2) + "\n");
}

std::string jobLabel(const Suite& suite, const Job& job) {
  return suite.problems[job.problem].name + " · " + suite.planners[job.planner].label;
}

std::filesystem::path pathsDirectory(const std::filesystem::path& out, const Suite& suite, const Problem& problem) {
  return out / "paths" / suite.name / problem.name;
}

bool isPlotProblem(const Suite& suite, const Problem& problem) {
  return std::find(suite.plotProblems.begin(), suite.plotProblems.end(), problem.name) != suite.plotProblems.end();
}

detail::JobFiles jobFiles(const std::filesystem::path& out, const Suite& suite, const Job& job) {
  detail::JobFiles files;
  files.log = jobLogPath(out, suite, job);
  const auto& problem = suite.problems[job.problem];
  if (isPlotProblem(suite, problem)) {
    files.medianRun = pathsDirectory(out, suite, problem) / (suite.planners[job.planner].label + ".csv");
  }
  return files;
}

// What the 3D plot needs besides the paths: obstacles and the TCP positions of start and goal.
void writePlotScene(const std::filesystem::path& file, const Problem& problem, double vMax) {
  const auto planning = planners::makePlanningProblem(std::make_shared<const collision::Scene>(problem.scene), problem.query);
  const auto& robot = planning.collisionModel->robot();
  const auto position = [&](const robot::Vector6& q) {
    const Eigen::Vector3d p = robot::tipPose(robot, q).translation();
    return nlohmann::json{p.x(), p.y(), p.z()};
  };
  nlohmann::json obstacles = nlohmann::json::array();
  for (const auto& obstacle : problem.scene.obstacles) {
    static const std::map<collision::Obstacle::Shape, const char*> shapes{{collision::Obstacle::Shape::Sphere, "sphere"},
                                                                          {collision::Obstacle::Shape::Box, "box"},
                                                                          {collision::Obstacle::Shape::Cylinder, "cylinder"},
                                                                          {collision::Obstacle::Shape::Mesh, "mesh"}};
    const Eigen::Matrix3d r = obstacle.pose.linear();
    const Eigen::Vector3d t = obstacle.pose.translation();
    obstacles.push_back({{"name", obstacle.name},
                         {"shape", shapes.at(obstacle.shape)},
                         {"radius", obstacle.radius},
                         {"length", obstacle.length},
                         {"size", {obstacle.size.x(), obstacle.size.y(), obstacle.size.z()}},
                         {"position", {t.x(), t.y(), t.z()}},
                         {"rotation", {{r(0, 0), r(0, 1), r(0, 2)}, {r(1, 0), r(1, 1), r(1, 2)}, {r(2, 0), r(2, 1), r(2, 2)}}}});
  }
  const nlohmann::json scene{{"problem", problem.name},
                             {"obstacles", obstacles},
                             {"start", position(planning.start)},
                             {"goal", position(planning.goal)},
                             {"vmax_mps", vMax}};
  writeFileAtomically(file, scene.dump(1) + "\n");
}

// --- running jobs ------------------------------------------------------------------------------------

struct RunState {
  std::size_t completed = 0;
  std::vector<std::string> failures;
  bool interrupted = false;
};

void runJobsInProcess(const Suite& suite, const std::vector<Job>& jobs, const std::filesystem::path& out,
                      ProgressDisplay& display, RunState& state) {
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    if (interruptRequested()) {
      state.interrupted = true;
      return;
    }
    const Job& job = jobs[i];
    try {
      const auto outcome = detail::runJob(suite, suite.problems[job.problem], suite.planners[job.planner],
                                          jobFiles(out, suite, job), [&](unsigned run, bool solved) {
                                            display.report({ProgressEvent::Kind::RunFinished, i, run, solved, 0});
                                          });
      display.report({ProgressEvent::Kind::JobFinished, i, 0, false, outcome.solved});
      ++state.completed;
    } catch (const detail::JobInterrupted&) {
      state.interrupted = true;
      return;
    } catch (const Error& e) {
      display.report({ProgressEvent::Kind::JobFailed, i, 0, false, 0});
      state.failures.push_back(jobLabel(suite, job) + ": " + e.what());
    }
  }
}

// Messages from worker processes; small enough that each write() to the pipe is atomic (PIPE_BUF).
struct WorkerMessage {
  enum Kind : std::int32_t { RunFinished, JobFinished, JobFailed };
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
};
static_assert(std::atomic<std::size_t>::is_always_lock_free && std::atomic<bool>::is_always_lock_free,
              "process-shared atomics must be lock-free");

void send(int fd, const WorkerMessage& message) {
  while (::write(fd, &message, sizeof message) < 0 && errno == EINTR) {
  }
}

[[noreturn]] void workerMain(const Suite& suite, const std::vector<Job>& jobs, const std::filesystem::path& out,
                             SharedCounters& shared, int fd) {
  watchStopFlag(&shared.stop);
  int exitCode = 0;
  while (true) {
    if (interruptRequested()) {
      exitCode = kWorkerInterrupted;
      break;
    }
    const std::size_t i = shared.nextJob.fetch_add(1);
    if (i >= jobs.size()) break;
    const Job& job = jobs[i];
    try {
      const auto outcome = detail::runJob(suite, suite.problems[job.problem], suite.planners[job.planner],
                                          jobFiles(out, suite, job), [&](unsigned run, bool solved) {
                                            WorkerMessage message;
                                            message.job = static_cast<std::uint32_t>(i);
                                            message.run = run;
                                            message.solved = solved ? 1 : 0;
                                            send(fd, message);
                                          });
      WorkerMessage message;
      message.kind = WorkerMessage::JobFinished;
      message.job = static_cast<std::uint32_t>(i);
      message.solved = outcome.solved;
      send(fd, message);
    } catch (const detail::JobInterrupted&) {
      exitCode = kWorkerInterrupted;
      break;
    } catch (const std::exception& e) {
      WorkerMessage message;
      message.kind = WorkerMessage::JobFailed;
      message.job = static_cast<std::uint32_t>(i);
      std::strncpy(message.text, e.what(), sizeof message.text - 1);
      send(fd, message);
    }
  }
  ::close(fd);
  _exit(exitCode);  // no atexit handlers or stdio flushing of the parent's state
}

// Each job stays in one process (OMPL's seed generator and output handler are process-global), so
// parallelism is processes: `workers` forks pull job indices from a shared counter.
void runJobsInWorkers(const Suite& suite, const std::vector<Job>& jobs, const std::filesystem::path& out,
                      unsigned workers, ProgressDisplay& display, RunState& state) {
  void* memory = ::mmap(nullptr, sizeof(SharedCounters), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  if (memory == MAP_FAILED) throw Error(std::string("cannot share memory with worker processes: ") + std::strerror(errno));
  auto* shared = new (memory) SharedCounters();
  int fds[2];
  if (::pipe(fds) != 0) throw Error(std::string("cannot create a pipe to worker processes: ") + std::strerror(errno));

  std::cout.flush();
  std::cerr.flush();
  std::vector<pid_t> children;
  for (unsigned w = 0; w < workers; ++w) {
    const pid_t pid = ::fork();
    if (pid == 0) {
      ::close(fds[0]);
      workerMain(suite, jobs, out, *shared, fds[1]);
    }
    if (pid < 0) {
      shared->stop = true;
      break;
    }
    children.push_back(pid);
  }
  ::close(fds[1]);

  WorkerMessage message;
  std::size_t filled = 0;
  while (true) {
    const ssize_t got = ::read(fds[0], reinterpret_cast<char*>(&message) + filled, sizeof message - filled);
    if (got < 0) {
      if (errno == EINTR) {
        if (interruptRequested()) shared->stop = true;  // workers finish their run, then stop
        continue;
      }
      break;
    }
    if (got == 0) break;  // every worker has closed its end
    if (interruptRequested()) shared->stop = true;
    filled += static_cast<std::size_t>(got);
    if (filled < sizeof message) continue;
    filled = 0;
    switch (message.kind) {
      case WorkerMessage::RunFinished:
        display.report({ProgressEvent::Kind::RunFinished, message.job, message.run, message.solved != 0, 0});
        break;
      case WorkerMessage::JobFinished:
        display.report({ProgressEvent::Kind::JobFinished, message.job, 0, false, message.solved});
        ++state.completed;
        break;
      case WorkerMessage::JobFailed:
        display.report({ProgressEvent::Kind::JobFailed, message.job, 0, false, 0});
        state.failures.push_back(jobLabel(suite, jobs[message.job]) + ": " + message.text);
        break;
    }
  }
  ::close(fds[0]);
  for (const pid_t child : children) {
    int status = 0;
    while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) continue;
    if ((WIFEXITED(status) && (WEXITSTATUS(status) == kWorkerInterrupted || WEXITSTATUS(status) == 130)) ||
        (WIFSIGNALED(status) && (WTERMSIG(status) == SIGINT || WTERMSIG(status) == SIGTERM))) {
      state.interrupted = true;
    } else {
      state.failures.push_back("worker process " + std::to_string(child) + " ended abnormally (" +
                               (WIFSIGNALED(status) ? "signal " + std::to_string(WTERMSIG(status))
                                                    : "exit " + std::to_string(WEXITSTATUS(status))) +
                               "); the job it was running has no log and runs again when the campaign is resumed");
    }
  }
  if (interruptRequested()) state.interrupted = true;
  shared->~SharedCounters();
  ::munmap(memory, sizeof(SharedCounters));
}

// --- reports -----------------------------------------------------------------------------------------

std::string fileSafe(const std::string& experiment) {
  std::string name = experiment;
  std::replace(name.begin(), name.end(), '/', '_');
  return name;
}

// Runs a plot script into a temporary PNG that replaces `target` only when the script succeeded.
void plot(const std::string& script, std::vector<std::string> arguments, const std::filesystem::path& target,
          std::vector<std::string>& notes) {
  auto temporary = target;
  temporary.replace_extension(".tmp" + std::to_string(::getpid()) + ".png");
  arguments.insert(arguments.end(), {"--out", temporary.string()});
  const auto outcome = runPlotScript(script, arguments);
  std::error_code ec;
  if (!outcome.ok) {
    std::filesystem::remove(temporary, ec);
    notes.push_back(target.filename().string() + ": " + outcome.message);
    return;
  }
  std::filesystem::rename(temporary, target, ec);
  if (ec) notes.push_back("cannot move " + temporary.string() + " to " + target.string() + ": " + ec.message());
}

void makePlots(const std::filesystem::path& database, const Ranking& ranking, const ReportOptions& options,
               std::vector<std::string>& notes) {
  if (!findMatplotlibPython()) {
    notes.push_back("plots skipped: no Python with matplotlib (install python3-matplotlib or set ARCPLAN_PYTHON)");
    return;
  }
  const auto directory = options.outDirectory / "plots";
  createDirectory(directory);
  std::string order;
  for (const auto& standing : ranking.overall) order += (order.empty() ? "" : ",") + standing.planner;
  plot("plot_benchmark_boxplots.py", {"--db", database.string(), "--order", order}, directory / "boxplots_all.png", notes);
  for (const auto& problem : ranking.problems) {
    // Median-run data of this problem; merged shards each hold the planners they ran.
    std::vector<std::string> paths;
    for (const auto& root : options.pathDirectories) {
      const auto folder = (root / problem.problem).lexically_normal();
      if (std::filesystem::exists(folder / "scene.json") &&
          std::find(paths.begin(), paths.end(), folder.string()) == paths.end()) {
        paths.push_back(folder.string());
      }
    }
    // Per-problem figures for problems with plot data, and for every problem of small campaigns.
    if (paths.empty() && ranking.problemCount() > 4) continue;
    const auto name = fileSafe(problem.problem);
    plot("plot_benchmark_boxplots.py", {"--db", database.string(), "--problem", problem.problem, "--order", order},
         directory / ("boxplots_" + name + ".png"), notes);
    if (paths.empty()) continue;
    std::vector<std::string> pathArguments{"--order", order, "--paths"};
    pathArguments.insert(pathArguments.end(), paths.begin(), paths.end());
    auto speed = pathArguments, view = pathArguments;
    speed.insert(speed.end(), {"--title", "TCP speed of each planner's median run — " + problem.problem});
    view.insert(view.end(), {"--title", "TCP paths of the median runs — " + problem.problem});
    plot("plot_benchmark_speed_profiles.py", speed, directory / ("speed_" + name + ".png"), notes);
    plot("plot_benchmark_paths3d.py", view, directory / ("paths3d_" + name + ".png"), notes);
  }
}

}  // namespace

Shard parseShard(const std::string& text) {
  const auto slash = text.find('/');
  const auto fail = [&]() -> Shard {
    throw Error("--shard: '" + text + "' is not K/N with whole numbers 1 <= K <= N (e.g. 2/8 for the second of 8 shards)");
  };
  if (slash == std::string::npos) return fail();
  const auto index = parseDouble(text.substr(0, slash)), count = parseDouble(text.substr(slash + 1));
  if (!index || !count || *index != std::floor(*index) || *count != std::floor(*count) || *count < 1 || *index < 1 ||
      *index > *count || *count > 1e6) {
    return fail();
  }
  return {static_cast<int>(*index), static_cast<int>(*count)};
}

std::vector<Job> campaignJobs(const Suite& suite) {
  std::vector<Job> jobs;
  for (std::size_t p = 0; p < suite.problems.size(); ++p) {
    for (std::size_t q = 0; q < suite.planners.size(); ++q) jobs.push_back({p, q});
  }
  return jobs;
}

std::vector<Job> shardJobs(const std::vector<Job>& jobs, const Shard& shard) {
  std::vector<Job> share;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    if (static_cast<int>(i % static_cast<std::size_t>(shard.count)) + 1 == shard.index) share.push_back(jobs[i]);
  }
  return share;
}

std::string experimentName(const Suite& suite, const Problem& problem) { return suite.name + "/" + problem.name; }

std::filesystem::path jobLogPath(const std::filesystem::path& out, const Suite& suite, const Job& job) {
  return out / "logs" / suite.name / suite.problems[job.problem].name / (suite.planners[job.planner].label + ".log");
}

CampaignResult runCampaign(const Suite& suite, const CampaignOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (options.outDirectory.empty()) throw Error("--out: an output directory is required");
  detail::checkPlannerConfigurations(suite);  // bad planners or parameters: nothing is written
  createDirectory(options.outDirectory);
  claimOutputDirectory(options.outDirectory, suite);

  CampaignResult result;
  const auto all = campaignJobs(suite);
  const auto share = shardJobs(all, options.shard);
  std::vector<Job> pending;
  for (const auto& job : share) {
    if (!std::filesystem::exists(jobLogPath(options.outDirectory, suite, job))) pending.push_back(job);
  }
  result.jobsInShard = share.size();
  result.jobsSkipped = share.size() - pending.size();
  result.jobsInCampaign = all.size();

  for (const auto& problem : suite.problems) {
    if (suite.generator) {
      const auto file = options.outDirectory / "scenes" / (problem.name + ".yaml");
      if (problem.kind != "scene file" && !std::filesystem::exists(file)) writeFileAtomically(file, sceneToYaml(problem.scene));
    }
    if (isPlotProblem(suite, problem)) {
      const auto file = pathsDirectory(options.outDirectory, suite, problem) / "scene.json";
      if (!std::filesystem::exists(file)) writePlotScene(file, problem, suite.vMax);
    }
  }

  std::vector<std::string> labels;
  for (const auto& job : pending) labels.push_back(jobLabel(suite, job));
  std::ostream discard(nullptr);  // no buffer: swallows everything
  ProgressDisplay shown(options.showProgress ? std::cerr : discard, options.showProgress && ::isatty(STDERR_FILENO) != 0,
                        labels, suite.runs);

  RunState state;
  {
    const InterruptHandlers handlers;
    const unsigned workers = std::max(1u, std::min<unsigned>(options.workers, static_cast<unsigned>(pending.size())));
    if (workers <= 1) {
      runJobsInProcess(suite, pending, options.outDirectory, shown, state);
    } else {
      runJobsInWorkers(suite, pending, options.outDirectory, workers, shown, state);
    }
    shown.finish();
    if (interruptRequested()) state.interrupted = true;
  }
  clearInterruptRequest();
  result.jobsRun = state.completed;
  result.interrupted = state.interrupted;
  result.notes = state.failures;
  for (const auto& job : all) {
    if (std::filesystem::exists(jobLogPath(options.outDirectory, suite, job))) ++result.jobsDoneInCampaign;
  }

  if (!state.failures.empty()) {
    std::string message = std::to_string(state.failures.size()) + " job(s) failed:";
    for (const auto& failure : state.failures) message += "\n  " + failure;
    throw Error(message);
  }
  if (!result.interrupted && result.jobsDoneInCampaign == result.jobsInCampaign) {
    const auto database = options.outDirectory / "benchmark.db";
    buildBenchmarkDatabase(findLogs({options.outDirectory / "logs" / suite.name}), database);
    ReportOptions report;
    report.outDirectory = options.outDirectory;
    report.pathDirectories = {options.outDirectory / "paths"};
    report.plots = options.plots;
    result.ranking = reportFromDatabase(database, report, result.notes);
  } else if (!result.interrupted) {
    result.notes.push_back(std::to_string(result.jobsDoneInCampaign) + " of " + std::to_string(result.jobsInCampaign) +
                           " jobs of the campaign are done in " + options.outDirectory.string() +
                           "; the database and ranking are made when the last shard finishes in this directory, or "
                           "merge the shards' logs with `arcplan bench rank --logs DIR... --db F`");
  }
  result.wallTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

Ranking reportFromDatabase(const std::filesystem::path& database, const ReportOptions& options,
                           std::vector<std::string>& notes) {
  auto ranking = rankDatabase(database);
  createDirectory(options.outDirectory);
  writeRanking(ranking, options.outDirectory);
  if (options.plots) makePlots(database, ranking, options, notes);
  return ranking;
}

}  // namespace arcplan::benchmarks
