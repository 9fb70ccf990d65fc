// The ranking as Markdown (ranking.md, and the tables `arcplan bench` prints), JSON and CSV.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "arcplan/benchmarks/ranking.h"
#include "arcplan/common/atomic_file.h"
#include "arcplan/common/text_formatting.h"

namespace arcplan::benchmarks {
namespace {

// Numbers in tables: "–" where there is none (no successful run).
std::string tableNumber(double value, int significantDigits = 4) {
  return std::isnan(value) ? "–" : formatNumber(value, significantDigits);
}

std::string percent(double rate) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(0) << 100.0 * rate << " %";
  return out.str();
}

nlohmann::json numberOrNull(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json standingJson(const PlannerStanding& standing, bool overall) {
  nlohmann::json entry{{"name", standing.planner},
                       {"rank", standing.rank},
                       {"success_rate", standing.successRate},
                       {"runs", standing.runs},
                       {"solved", standing.successes},
                       {"median_execution_time_all_runs_s", numberOrNull(standing.medianExecutionTime)}};
  if (overall) {
    entry["mean_rank"] = standing.meanRank;
    entry["problems"] = standing.problems;
    entry["first_places"] = standing.firstPlaces;
  }
  for (const auto& metric : rankedMetrics()) {
    const auto& summary = standing.metrics.at(metric.key);
    entry[metric.key] = summary.count == 0 ? nlohmann::json(nullptr)
                                           : nlohmann::json{{"median", summary.median},
                                                            {"mean", summary.mean},
                                                            {"min", summary.min},
                                                            {"max", summary.max},
                                                            {"count", summary.count}};
  }
  return entry;
}

// Markdown table; `overall` adds mean rank, problem count and first places. The metric columns are
// a chosen few statistics (the median where typical values matter, the max where the worst does).
std::string standingsTable(const std::vector<PlannerStanding>& standings, bool overall) {
  std::ostringstream out;
  out << "| rank | planner |" << (overall ? " mean rank | problems | 1st |" : "") << " success |"
      << " exec time median (s) | TCP length median [min, max] (m) | solve time median (s) |"
      << " peak TCP speed median (m/s) | time above limit max (s) | min clearance median (m) | joint speed ratio max "
         "|\n";
  out << "|---:|---|" << (overall ? "---:|---:|---:|" : "") << "---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& s : standings) {
    using M = trajectory::TrajectoryMetrics;
    const auto summary = [&](double M::*member) -> const MetricSummary& {
      return s.metrics.at(trajectory::metricDescriptor(member).key);
    };
    const auto& length = summary(&M::tcpPathLength);
    out << "| " << s.rank << " | " << s.planner << " |";
    if (overall) out << " " << tableNumber(s.meanRank, 3) << " | " << s.problems << " | " << s.firstPlaces << " |";
    out << " " << percent(s.successRate) << " (" << s.successes << "/" << s.runs << ") |"
        << " " << tableNumber(summary(&M::executionTime).median) << " |"
        << " " << tableNumber(length.median) << " [" << tableNumber(length.min) << ", " << tableNumber(length.max)
        << "] |"
        << " " << tableNumber(s.metrics.at(trajectory::solveTimeDescriptor().key).median, 3) << " |"
        << " " << tableNumber(summary(&M::peakTcpSpeed).median) << " |"
        << " " << tableNumber(summary(&M::timeAboveLimit).max, 3) << " |"
        << " " << tableNumber(summary(&M::minClearance).median, 3) << " |"
        << " " << tableNumber(summary(&M::maxJointSpeedRatio).max, 3) << " |\n";
  }
  return out.str();
}

// Planners x families: success rate and mean rank within each family.
std::string familyMatrix(const Ranking& ranking) {
  std::ostringstream out;
  out << "| planner |";
  for (const auto& family : ranking.families) out << " " << family.family << " (" << family.problems << ") |";
  out << "\n|---|";
  for (std::size_t i = 0; i < ranking.families.size(); ++i) out << "---:|";
  out << "\n";
  for (const auto& overall : ranking.overall) {
    out << "| " << overall.planner << " |";
    for (const auto& family : ranking.families) {
      const auto found = std::find_if(family.planners.begin(), family.planners.end(),
                                      [&](const PlannerStanding& s) { return s.planner == overall.planner; });
      if (found == family.planners.end()) {
        out << " – |";
      } else {
        out << " " << percent(found->successRate) << " · rank " << tableNumber(found->meanRank, 3) << " |";
      }
    }
    out << "\n";
  }
  return out.str();
}

std::string plural(int count, const std::string& noun) {
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

}  // namespace

std::string rankingMarkdown(const Ranking& ranking) {
  std::ostringstream out;
  out << "# Planner ranking\n\n";
  out << "Database: `" << ranking.database.string() << "` — " << plural(ranking.problemCount(), "problem") << ", "
      << ranking.overall.size() << " planner configurations.\n\n";
  out << "## How planners are ranked\n\n"
      << "A run **succeeds** when the planner returns an exact solution and the path could be simplified (sampling "
         "planners, as `arcplan plan` does), densified and time-scaled with PCHIP under the TCP speed limit; every "
         "metric below is measured on that scaled path.\n\n"
      << "On each problem the planners are ordered by\n\n"
      << "1. **success rate**, higher first;\n"
      << "2. **median execution time over all runs**, shorter first, where a failed run counts as +inf. The median is "
         "therefore finite only when more than half of the runs succeed: a planner that solves 2 of 100 runs never "
         "wins on the median of its 2 successes.\n\n"
      << "Planners equal in both keys (e.g. deterministic planners returning the same path) share a rank (1, 2, 2, 4, "
         "...); planners that never succeed share the last rank. Within a tie, rows are listed by median TCP path "
         "length, then name.\n\n"
      << "The **overall rank** orders planners by their **mean rank** over the problems they ran on (each problem "
         "weighs the same); equal mean ranks are split by the pooled success rate, and remain a tie if that is equal "
         "too. The overall metric columns pool the successful runs of all problems. `problems` shows on how many "
         "problems a planner ran, `1st` on how many it ranked first.\n\n"
      << "Metric columns are statistics over the successful runs only (– when there is none).\n\n";
  out << "## Overall\n\n" << standingsTable(ranking.overall, true) << "\n";
  if (!ranking.families.empty()) {
    out << "## By problem family\n\n"
        << "Success rate and mean rank of each planner over the problems of one family (number of problems in "
           "brackets); the full tables follow.\n\n"
        << familyMatrix(ranking) << "\n";
    for (const auto& family : ranking.families) {
      out << "### " << family.family << " (" << family.problems << " problems)\n\n"
          << standingsTable(family.planners, true) << "\n";
    }
  }
  out << "## Per problem\n\n";
  for (const auto& problem : ranking.problems) {
    out << "### " << problem.problem << "\n\n" << standingsTable(problem.planners, false) << "\n";
  }
  return out.str();
}

nlohmann::json rankingJson(const Ranking& ranking) {
  nlohmann::json document;
  document["database"] = ranking.database.string();
  document["ranking_rule"] =
      "per problem: success rate (desc), then median execution time over all runs with failures as +inf (asc); "
      "ties share a rank; overall: mean per-problem rank (asc), then pooled success rate (desc)";
  document["planners"] = nlohmann::json::array();
  for (const auto& standing : ranking.overall) document["planners"].push_back(standingJson(standing, true));
  document["families"] = nlohmann::json::array();
  for (const auto& family : ranking.families) {
    nlohmann::json entry{{"name", family.family}, {"problems", family.problems}, {"planners", nlohmann::json::array()}};
    for (const auto& standing : family.planners) entry["planners"].push_back(standingJson(standing, true));
    document["families"].push_back(std::move(entry));
  }
  document["problems"] = nlohmann::json::array();
  for (const auto& problem : ranking.problems) {
    nlohmann::json entry{{"name", problem.problem}, {"planners", nlohmann::json::array()}};
    for (const auto& standing : problem.planners) entry["planners"].push_back(standingJson(standing, false));
    document["problems"].push_back(std::move(entry));
  }
  return document;
}

std::string rankingCsv(const Ranking& ranking) {
  std::ostringstream out;
  out << std::setprecision(10);
  out << "problem,planner,rank,mean_rank,success_rate,runs,solved,median_execution_time_all_runs_s";
  for (const auto& metric : rankedMetrics()) {
    for (const char* statistic : {"median", "mean", "min", "max"}) out << "," << metric.key << "_" << statistic;
  }
  out << "\n";
  const auto row = [&](const std::string& problem, const PlannerStanding& s, bool overall) {
    out << problem << "," << s.planner << "," << s.rank << ",";
    if (overall) out << s.meanRank;
    out << "," << s.successRate << "," << s.runs << "," << s.successes << ",";
    if (std::isfinite(s.medianExecutionTime)) out << s.medianExecutionTime;
    for (const auto& metric : rankedMetrics()) {
      const auto& summary = s.metrics.at(metric.key);
      for (double value : {summary.median, summary.mean, summary.min, summary.max}) {
        out << ",";
        if (summary.count > 0) out << value;
      }
    }
    out << "\n";
  };
  for (const auto& standing : ranking.overall) row("overall", standing, true);
  for (const auto& problem : ranking.problems) {
    for (const auto& standing : problem.planners) row(problem.problem, standing, false);
  }
  return out.str();
}

std::string rankingTerminalTable(const Ranking& ranking, int maxProblemTables) {
  std::ostringstream out;
  out << "Overall ranking (" << plural(ranking.problemCount(), "problem") << ", mean of per-problem ranks):\n\n"
      << standingsTable(ranking.overall, true);
  if (!ranking.families.empty()) {
    out << "\nBy problem family (success rate · mean rank within the family):\n\n" << familyMatrix(ranking);
  }
  if (ranking.problemCount() <= maxProblemTables) {
    for (const auto& problem : ranking.problems) {
      out << "\nProblem " << problem.problem << ":\n\n" << standingsTable(problem.planners, false);
    }
  }
  return out.str();
}

void writeRanking(const Ranking& ranking, const std::filesystem::path& directory) {
  writeFileAtomically(directory / "ranking.md", rankingMarkdown(ranking));
  writeFileAtomically(directory / "ranking.json", rankingJson(ranking).dump(2) + "\n");
  writeFileAtomically(directory / "ranking.csv", rankingCsv(ranking));
}

}  // namespace arcplan::benchmarks
