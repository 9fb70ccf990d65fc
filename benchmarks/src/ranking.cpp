// The ranking rule: planners ordered per problem, overall and per problem family (ranking.h).
#include "arcplan/benchmarks/ranking.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "arcplan/benchmarks/benchmark_database.h"

namespace arcplan::benchmarks {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Execution times and mean ranks closer than this are a tie (they come from identical paths).
constexpr double kTieTolerance = 1e-9;

const std::string& key(double trajectory::TrajectoryMetrics::*member) {
  return trajectory::metricDescriptor(member).key;
}

double medianOfSorted(const std::vector<double>& sorted) {
  const std::size_t n = sorted.size();
  if (n == 0) return std::numeric_limits<double>::quiet_NaN();
  if (n % 2 == 1) return sorted[n / 2];
  const double low = sorted[n / 2 - 1], high = sorted[n / 2];
  return std::isinf(high) ? high : 0.5 * (low + high);
}

MetricSummary summarize(std::vector<double> values) {
  MetricSummary summary;
  summary.count = static_cast<int>(values.size());
  if (values.empty()) {
    summary.median = summary.mean = summary.min = summary.max = std::numeric_limits<double>::quiet_NaN();
    return summary;
  }
  std::sort(values.begin(), values.end());
  summary.median = medianOfSorted(values);
  summary.mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
  summary.min = values.front();
  summary.max = values.back();
  return summary;
}

PlannerStanding standingFromRuns(const std::string& planner, const std::vector<const RunRecord*>& runs) {
  PlannerStanding standing;
  standing.planner = planner;
  standing.runs = static_cast<int>(runs.size());
  std::vector<double> executionTimes;  // every run, failures as +inf
  for (const auto* run : runs) {
    if (run->succeeded()) {
      ++standing.successes;
      executionTimes.push_back(*run->value(key(&trajectory::TrajectoryMetrics::executionTime)));
    } else {
      executionTimes.push_back(kInfinity);
    }
  }
  standing.successRate = standing.runs > 0 ? static_cast<double>(standing.successes) / standing.runs : 0.0;
  std::sort(executionTimes.begin(), executionTimes.end());
  standing.medianExecutionTime = standing.runs > 0 ? medianOfSorted(executionTimes) : kInfinity;
  for (const auto& metric : rankedMetrics()) {
    std::vector<double> values;
    for (const auto* run : runs) {
      if (!run->succeeded()) continue;
      if (const auto value = run->value(metric.key)) values.push_back(*value);
    }
    standing.metrics[metric.key] = summarize(std::move(values));
  }
  return standing;
}

bool nearlyEqual(double a, double b) {
  if (std::isinf(a) || std::isinf(b)) return a == b;
  return std::abs(a - b) <= kTieTolerance * std::max({1.0, std::abs(a), std::abs(b)});
}

// Display order inside a tie: shorter TCP path, then name, so output is deterministic.
double medianOf(const PlannerStanding& s, const std::string& key) {
  const auto& summary = s.metrics.at(key);
  return summary.count > 0 ? summary.median : kInfinity;
}

void rankProblem(std::vector<PlannerStanding>& planners) {
  const auto better = [](const PlannerStanding& a, const PlannerStanding& b) {
    if (!nearlyEqual(a.successRate, b.successRate)) return a.successRate > b.successRate;
    return !nearlyEqual(a.medianExecutionTime, b.medianExecutionTime) && a.medianExecutionTime < b.medianExecutionTime;
  };
  std::sort(planners.begin(), planners.end(), [&](const PlannerStanding& a, const PlannerStanding& b) {
    if (better(a, b)) return true;
    if (better(b, a)) return false;
    const std::string& length = key(&trajectory::TrajectoryMetrics::tcpPathLength);
    const double la = medianOf(a, length), lb = medianOf(b, length);
    if (la != lb) return la < lb;
    return a.planner < b.planner;
  });
  for (std::size_t i = 0; i < planners.size(); ++i) {
    planners[i].rank =
        (i > 0 && !better(planners[i - 1], planners[i])) ? planners[i - 1].rank : static_cast<int>(i) + 1;
  }
}

// Mean rank, pooled runs and first places of every planner over `problems`, best first.
std::vector<PlannerStanding> aggregate(const std::vector<const ProblemRanking*>& problems, const CampaignRuns& runs) {
  std::map<PlannerLabel, std::vector<int>> ranksOf;
  std::map<PlannerLabel, std::vector<const RunRecord*>> runsOf;
  for (const auto* problem : problems) {
    for (const auto& standing : problem->planners) {
      ranksOf[standing.planner].push_back(standing.rank);
      for (const auto& run : runs.at(problem->problem).at(standing.planner)) runsOf[standing.planner].push_back(&run);
    }
  }
  std::vector<PlannerStanding> standings;
  for (const auto& [planner, pooled] : runsOf) {
    auto standing = standingFromRuns(planner, pooled);
    const auto& ranks = ranksOf.at(planner);
    standing.problems = static_cast<int>(ranks.size());
    standing.meanRank = std::accumulate(ranks.begin(), ranks.end(), 0.0) / static_cast<double>(ranks.size());
    standing.firstPlaces = static_cast<int>(std::count(ranks.begin(), ranks.end(), 1));
    standings.push_back(std::move(standing));
  }
  const auto better = [](const PlannerStanding& a, const PlannerStanding& b) {
    if (!nearlyEqual(a.meanRank, b.meanRank)) return a.meanRank < b.meanRank;
    return !nearlyEqual(a.successRate, b.successRate) && a.successRate > b.successRate;
  };
  std::sort(standings.begin(), standings.end(), [&](const PlannerStanding& a, const PlannerStanding& b) {
    if (better(a, b)) return true;
    if (better(b, a)) return false;
    return a.planner < b.planner;
  });
  for (std::size_t i = 0; i < standings.size(); ++i) {
    standings[i].rank =
        (i > 0 && !better(standings[i - 1], standings[i])) ? standings[i - 1].rank : static_cast<int>(i) + 1;
  }
  return standings;
}

}  // namespace

const std::vector<RankedMetric>& rankedMetrics() { return trajectory::metricDescriptors(); }

Ranking rankRuns(const CampaignRuns& runs, const std::map<ProblemName, std::string>& families) {
  Ranking ranking;
  for (const auto& [problem, planners] : runs) {
    ProblemRanking entry;
    entry.problem = problem;
    for (const auto& [planner, plannerRuns] : planners) {
      std::vector<const RunRecord*> pointers;
      for (const auto& run : plannerRuns) pointers.push_back(&run);
      entry.planners.push_back(standingFromRuns(planner, pointers));
    }
    rankProblem(entry.planners);
    ranking.problems.push_back(std::move(entry));
  }
  std::vector<const ProblemRanking*> all;
  std::map<std::string, std::vector<const ProblemRanking*>> byFamily;
  for (const auto& problem : ranking.problems) {
    all.push_back(&problem);
    if (const auto found = families.find(problem.problem); found != families.end() && !found->second.empty()) {
      byFamily[found->second].push_back(&problem);
    }
  }
  ranking.overall = aggregate(all, runs);
  if (byFamily.size() > 1) {
    for (const auto& [family, members] : byFamily) {
      ranking.families.push_back({family, static_cast<int>(members.size()), aggregate(members, runs)});
    }
  }
  return ranking;
}

Ranking rankDatabase(const std::filesystem::path& file) {
  const auto database = readBenchmarkDatabase(file);
  auto ranking = rankRuns(database.runs, database.families);
  ranking.database = file;
  return ranking;
}

}  // namespace arcplan::benchmarks
