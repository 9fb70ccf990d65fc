#include "job_runner.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <iomanip>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <vector>

#include <Eigen/Core>
#include <fcl/config.h>
#include <ompl/config.h>
#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include "arcplan/benchmarks/campaign.h"
#include "arcplan/benchmarks/interrupt.h"
#include "arcplan/benchmarks/median_run.h"
#include "arcplan/benchmarks/solution_measurement.h"
#include "arcplan/benchmarks/solution_policy.h"
#include "arcplan/collision/collision_model.h"
#include "arcplan/collision/endpoint_clearance.h"
#include "arcplan/collision/joint_states.h"
#include "arcplan/collision/ompl_validity.h"
#include "arcplan/common/atomic_file.h"
#include "arcplan/common/error.h"
#include "arcplan/common/text_formatting.h"
#include "arcplan/planners/planner_registry.h"
#include "arcplan/planners/planning_problem.h"
#include "arcplan/planners/seeded_sampling.h"
#include "arcplan/trajectory/metric_descriptors.h"
#include "arcplan/trajectory/path_measurement.h"
#include "run_properties.h"

namespace arcplan::benchmarks::detail {
namespace {

namespace ob = ompl::base;

// Samples kept of the median run for the speed-profile and 3D plots.
constexpr std::size_t kProfileSamples = 600;

// Run properties and experiment parameters are text in the log; 10 significant digits.
std::string number(double value) { return formatNumber(value, 10); }

std::string versionText(int major, int minor, int patch) {
  return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(patch);
}

// ompl::tools::Benchmark writing what OMPL 1.5.2 leaves out: its config.h defines OMPL_VERSION as "",
// so the first log line reads "OMPL version " (ompl_benchmark_statistics then stores the version as
// "OMPL version"); and the "random seed" line, which OMPL fills with the process's first seed, gets
// the seed this job actually reseeded with.
class CampaignBenchmark : public ompl::tools::Benchmark {
public:
  using Benchmark::Benchmark;

  void setRecordedSeed(std::uint32_t seed) { exp_.seed = seed; }

  bool saveResultsToStream(std::ostream& out) const override {
    std::ostringstream log;
    if (!Benchmark::saveResultsToStream(log)) return false;
    std::string text = log.str();
    const std::string emptyVersion = "OMPL version \n";
    if (text.rfind(emptyVersion, 0) == 0) {
      text.replace(0, emptyVersion.size(),
                   "OMPL version " + versionText(OMPL_MAJOR_VERSION, OMPL_MINOR_VERSION, OMPL_PATCH_VERSION) + "\n");
    }
    out << text;
    return static_cast<bool>(out);
  }
};

// A planner that stops after a fixed number of iterations, counted as OMPL's
// IterationTerminationCondition counts them: every time the planner asks its termination condition
// whether to stop. ompl::tools::Benchmark only passes a time (and memory) condition to solve(), so
// the benchmarked planner is this wrapper, which hands its planner that condition OR the budget. For a
// single-threaded planner with seeded random numbers, the run then no longer depends on how fast the
// machine is; the time limit stays as a safety cap, and a run it ends is recorded as such.
class IterationBudgetPlanner : public ob::Planner {
public:
  IterationBudgetPlanner(ob::PlannerPtr planner, unsigned budget)
      : ob::Planner(planner->getSpaceInformation(), planner->getName()), planner_(std::move(planner)), budget_(budget) {
    // What ompl::tools::Benchmark reads without a virtual call: the wrapped planner's own.
    specs_ = planner_->getSpecs();
    params_ = planner_->params();
    for (const auto& [name, property] : planner_->getPlannerProgressProperties())
      addPlannerProgressProperty(name, property);
  }

  ob::PlannerStatus solve(const ob::PlannerTerminationCondition& limit) override {
    iterations_ = 0;
    capReached_ = false;
    // PRM evaluates its condition from two threads: the counter is atomic.
    const ob::PlannerTerminationCondition condition([this, &limit] {
      if (limit()) {
        capReached_ = true;
        return true;
      }
      return iterations_.fetch_add(1) >= budget_;
    });
    return planner_->solve(condition);
  }

  // Iterations the last run used (the evaluation that ended it included) and whether the safety cap
  // (time or memory), not the budget, ended it.
  unsigned long long iterationsUsed() const { return iterations_.load(); }
  bool capReached() const { return capReached_.load(); }

  void setProblemDefinition(const ob::ProblemDefinitionPtr& problem) override {
    ob::Planner::setProblemDefinition(problem);
    planner_->setProblemDefinition(problem);
  }
  void setup() override {
    planner_->setup();
    setup_ = true;
  }
  void clear() override { planner_->clear(); }
  void clearQuery() override { planner_->clearQuery(); }
  void checkValidity() override { planner_->checkValidity(); }
  void getPlannerData(ob::PlannerData& data) const override { planner_->getPlannerData(data); }
  void printProperties(std::ostream& out) const override { planner_->printProperties(out); }
  void printSettings(std::ostream& out) const override { planner_->printSettings(out); }

private:
  ob::PlannerPtr planner_;
  unsigned long long budget_;
  std::atomic<unsigned long long> iterations_{0};
  std::atomic<bool> capReached_{false};
};

// A failed write of a job's output names the file and the system's reason (disk full, file too large).
void writeJobOutput(const std::filesystem::path& file, const std::function<void(AtomicOutputFile&)>& write) {
  try {
    AtomicOutputFile out(file);
    write(out);
    out.commit();
  } catch (const Error& e) {
    throw OutputWriteError(e.what());
  }
}

// FNV-1a: a stable hash of the job's names (std::hash may differ between standard libraries).
std::uint64_t stableHash(const std::string& text) {
  std::uint64_t hash = 14695981039346656037ULL;
  for (unsigned char c : text) {
    hash ^= c;
    hash *= 1099511628211ULL;
  }
  return hash;
}

// OMPL seeds must be > 0; keep them in 31 bits so every SQL and log reader treats them as plain integers.
std::uint32_t toSeed(std::uint64_t value) { return static_cast<std::uint32_t>(value % 2147483646ULL) + 1U; }

// OMPL prints an error when the seed generator is reseeded after its first use; here that is the point.
void reseedQuietly(std::uint32_t seed) {
  const auto level = ompl::msg::getLogLevel();
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  ompl::RNG::setSeed(seed);
  ompl::msg::setLogLevel(level);
}

// The trajectory metrics as run properties, under their names from the metric table; a metric
// that was not measured (no obstacle to measure the clearance to) is left out.
void recordMetrics(const trajectory::TrajectoryMetrics& metrics, ompl::tools::Benchmark::RunProperties& run) {
  for (const auto& metric : trajectory::metricDescriptors()) {
    if (metric.member == nullptr || metric.omplProperty.empty()) continue;  // the planner's or OMPL's own
    const double value = metrics.*metric.member;
    if (std::isfinite(value)) run[metric.omplProperty] = number(value);
  }
}

struct RecordedRun {
  unsigned run = 0;
  double executionTime = 0.0;
  double tcpPathLength = 0.0;
  MedianRun samples;  // with the joints: the HTML report moves the arm along them
};

RecordedRun recordProfile(unsigned run, const trajectory::TimedTrajectory& trajectory) {
  RecordedRun recorded;
  recorded.run = run;
  recorded.executionTime = trajectory.duration();
  recorded.tcpPathLength = trajectory.tcpPathLength;
  MedianRun& samples = recorded.samples;
  const std::size_t n = trajectory.time.size();
  const std::size_t stride = std::max<std::size_t>(1, n / kProfileSamples);
  const auto keep = [&](std::size_t i) {
    samples.time.push_back(trajectory.time[i]);
    samples.tcpSpeed.push_back(trajectory.tcpSpeed[i]);
    samples.tcp.push_back(trajectory.tcpPosition[i]);
    samples.joints.push_back(trajectory.position[i]);
  };
  for (std::size_t i = 0; i < n; i += stride) keep(i);
  if (n > 0 && (n - 1) % stride != 0) keep(n - 1);
  return recorded;
}

// The run with the median execution time among the successful ones (the lower one of an even count).
void writeMedianRunFile(const std::filesystem::path& file, const std::string& planner, std::vector<RecordedRun> runs) {
  if (runs.empty()) return;
  std::sort(runs.begin(), runs.end(), [](const RecordedRun& a, const RecordedRun& b) {
    return a.executionTime < b.executionTime || (a.executionTime == b.executionTime && a.run < b.run);
  });
  RecordedRun& median = runs[(runs.size() - 1) / 2];
  median.samples.notes = {{"planner", planner},
                          {"run", std::to_string(median.run)},
                          {"execution time (s)", formatNumber(median.executionTime, 9)},
                          {"tcp path length (m)", formatNumber(median.tcpPathLength, 9)},
                          {"successful runs", std::to_string(runs.size())}};
  writeJobOutput(file, [&](AtomicOutputFile& out) { writeMedianRun(out.stream(), median.samples); });
}

// Every planner's validity checker and motion validator keep the suite's clearance.
planners::PlanningProblem setUpProblem(const Suite& suite, const Problem& problem) {
  planners::PlanningProblemOptions options;
  options.clearance = suite.clearance;
  return planners::makePlanningProblem(std::make_shared<const collision::Scene>(problem.scene), problem.query, options);
}

std::vector<std::pair<std::string, std::string>> parameterList(const PlannerConfiguration& planner) {
  return {planner.parameters.begin(), planner.parameters.end()};
}

// Restores OMPL's output handler and log level however the job ends (Benchmark switches the handler
// off while it runs and does not switch it back when an event throws).
class OmplOutputScope {
public:
  OmplOutputScope() : handler_(ompl::msg::getOutputHandler()), level_(ompl::msg::getLogLevel()) {
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  }
  ~OmplOutputScope() {
    ompl::msg::useOutputHandler(handler_);
    ompl::msg::setLogLevel(level_);
  }

private:
  ompl::msg::OutputHandler* handler_;
  ompl::msg::LogLevel level_;
};

}  // namespace

std::uint32_t jobSeed(const Suite& suite, const Problem& problem) {
  return toSeed(stableHash(suite.name + "/" + problem.name));
}

std::uint32_t runSeed(std::uint32_t job, unsigned run) {
  // The run number first: FNV-1a mixes a byte only through the bytes after it.
  return toSeed(stableHash(std::to_string(run) + "#" + std::to_string(job)));
}

void checkPlannerConfigurations(const Suite& suite) {
  const OmplOutputScope output;
  const auto problem = setUpProblem(suite, suite.problems.front());
  for (const auto& configuration : suite.planners) {
    try {
      const auto name = planners::canonicalPlannerName(configuration.planner);
      planners::makePlanner(name, problem.setup->getSpaceInformation(), problem.plannerContext(),
                            parameterList(configuration));
    } catch (const Error& e) {
      throw Error(suite.sourceFile.string() + ": planner '" + configuration.label + "': " + e.what());
    }
  }
}

JobOutcome runJob(const Suite& suite, const Problem& problem, const PlannerConfiguration& configuration,
                  const JobFiles& files, const std::function<void(unsigned run, bool solved)>& onRunFinished) {
  const OmplOutputScope output;
  const std::uint32_t seed = jobSeed(suite, problem);
  reseedQuietly(seed);  // before the SimpleSetup and the planner create their random generators

  const auto planning = setUpProblem(suite, problem);
  ompl::geometric::SimpleSetup& setup = *planning.setup;
  const std::string plannerName = planners::canonicalPlannerName(configuration.planner);
  ob::PlannerPtr planner = planners::makePlanner(plannerName, setup.getSpaceInformation(), planning.plannerContext(),
                                                 parameterList(configuration));
  planner->setName(configuration.label);
  // A budgeted campaign is meant to repeat exactly (docs/reproducibility.md); a wall-clock search
  // deadline (the arc planner's `deadline`) would make its answers depend on the machine's load, so
  // under a budget it is off unless the suite sets it. The logs record the value used.
  if (suite.iterationBudget && !configuration.parameters.count("deadline") && planner->params().hasParam("deadline")) {
    planner->params().setParam("deadline", "0");
  }
  // The suite's clearance for every planner, the arc planner's own included (unless the suite sets it).
  keepProblemClearance(*planner, suite.clearance, configuration.parameters.count("clearance") > 0);
  std::shared_ptr<IterationBudgetPlanner> budgeted;
  if (suite.iterationBudget) {
    budgeted = std::make_shared<IterationBudgetPlanner>(planner, *suite.iterationBudget);
    planner = budgeted;
  }

  CampaignBenchmark benchmark(setup, experimentName(suite, problem));
  benchmark.addExperimentParameter("suite", "TEXT", suite.name);
  benchmark.addExperimentParameter("problem", "TEXT", problem.name);
  benchmark.addExperimentParameter(kProblemKindParameter.name, kProblemKindParameter.type, problem.kind);
  benchmark.addExperimentParameter("problem origin", "TEXT", problem.origin);
  benchmark.addExperimentParameter("query name", "TEXT", problem.query);
  benchmark.addExperimentParameter("vmax", "REAL", number(suite.vMax));
  benchmark.addExperimentParameter("clearance", "REAL", number(suite.clearance));
  // What a start or goal closer than `clearance` relaxes it to near itself (endpoint_clearance.h).
  const auto* validity =
      dynamic_cast<const collision::CollisionStateValidityChecker*>(setup.getStateValidityChecker().get());
  const collision::EndpointClearance& required = validity->requiredClearance();  // makePlanningProblem's
  benchmark.addExperimentParameter("endpoint clearance", "REAL", number(required.smallestStateClearance()));
  benchmark.addExperimentParameter("approach zone", "REAL", number(collision::kApproachZoneLength));
  benchmark.addExperimentParameter("job seed", "INTEGER", std::to_string(seed));
  if (suite.iterationBudget) {
    benchmark.addExperimentParameter("iteration budget", "INTEGER", std::to_string(*suite.iterationBudget));
  }
  if (suite.generator)
    benchmark.addExperimentParameter("generator seed", "INTEGER", std::to_string(suite.generator->seed));
  benchmark.addExperimentParameter("ompl version", "TEXT",
                                   versionText(OMPL_MAJOR_VERSION, OMPL_MINOR_VERSION, OMPL_PATCH_VERSION));
  benchmark.addExperimentParameter("fcl version", "TEXT", FCL_VERSION);
  benchmark.addExperimentParameter("eigen version", "TEXT",
                                   versionText(EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION));
  benchmark.addExperimentParameter("arcplan version", "TEXT", ARCPLAN_VERSION);
  benchmark.addPlanner(planner);

  trajectory::TimeScalingOptions scaling;
  scaling.maxTcpSpeed = suite.vMax;

  JobOutcome outcome;
  unsigned currentRun = 0;
  std::uint32_t currentSeed = 0;
  std::vector<RecordedRun> recorded;

  benchmark.setPreRunEvent([&](const ob::PlannerPtr& running) {
    if (interruptRequested()) throw JobInterrupted();
    ++currentRun;
    currentSeed = runSeed(seed, currentRun);
    ompl::RNG::setSeed(currentSeed);  // OMPL's output is off inside benchmark()
    // Samplers, simplifier and the arc planner's `seed` (unless the suite sets it) follow the run seed too.
    planners::seedRun(setup, *running, currentSeed, configuration.parameters.count("seed") > 0);
  });
  benchmark.setPostRunEvent([&](const ob::PlannerPtr&, ompl::tools::Benchmark::RunProperties& run) {
    run["run seed INTEGER"] = std::to_string(currentSeed);
    if (budgeted) {
      run["iterations INTEGER"] = std::to_string(budgeted->iterationsUsed());
      run["time cap reached BOOLEAN"] = budgeted->capReached() ? "1" : "0";
    }
    // Every registered planner reports its own solve time (planners::lastSolveTime), copied by OMPL from its planner
    // data; OMPL's "time" also counts the wait for its termination-condition thread (docs/benchmarks.md).
    bool success = false;
    if (setup.haveExactSolutionPath()) {
      try {
        const trajectory::JointPath path = collision::waypointsOf(setup.getSolutionPath());
        const MeasuredSolution measured = measureSolution(planning, path, scaling);  // as `plan` measures
        recordMetrics(measured.measurement.metrics, run);
        // A path that comes closer than the suite's clearance (in an approach zone: the zone's) is not a
        // success, whatever validated it: OMPL's "solved" is withdrawn, which is what the ranking and
        // ompl_benchmark_statistics count.
        const bool keptClearance = measured.keptClearance();
        run["clearance kept BOOLEAN"] = keptClearance ? "1" : "0";
        if (!keptClearance) run["solved BOOLEAN"] = "0";
        success = keptClearance;
        if (success && !files.medianRun.empty())
          recorded.push_back(recordProfile(currentRun, *measured.measurement.timed));
      } catch (const Error&) {
        // A path that cannot be time-scaled is a failed run: it has no execution time.
      }
    }
    run["time scaled BOOLEAN"] = success ? "1" : "0";
    outcome.runs += 1;
    outcome.solved += success ? 1 : 0;
    if (onRunFinished) onRunFinished(currentRun, success);
  });

  ompl::tools::Benchmark::Request request(suite.timeLimit, 4096.0, suite.runs);
  request.displayProgress = false;
  request.saveConsoleOutput = false;
  // As `arcplan plan` does, but inside OMPL's Benchmark, which keeps the simplifier's path even when it fails
  // the motion validator: the clearance judgement in the post-run event then counts the run as not solved.
  request.simplify = simplifiesSolution(plannerName);
  benchmark.benchmark(request);
  benchmark.setRecordedSeed(seed);

  // The plot data first: a job counts as done once its log exists.
  if (!files.medianRun.empty()) writeMedianRunFile(files.medianRun, configuration.label, std::move(recorded));
  writeJobOutput(files.log, [&](AtomicOutputFile& log) {
    if (!benchmark.saveResultsToStream(log.stream())) {
      throw Error("writing " + files.log.string() + " failed: " + std::strerror(errno));
    }
  });
  return outcome;
}

}  // namespace arcplan::benchmarks::detail
