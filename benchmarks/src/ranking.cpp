#include "arcplan/benchmarks/ranking.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <memory>
#include <numeric>
#include <set>
#include <sstream>

#include <sqlite3.h>

#include "arcplan/common/atomic_file.h"
#include "arcplan/common/error.h"

namespace arcplan::benchmarks {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Execution times and mean ranks closer than this are a tie (they come from identical paths).
constexpr double kTieTolerance = 1e-9;

using RunValues = std::map<std::string, double>;

bool succeeded(const RunValues& run) {
  const auto found = run.find("execution_time_s");
  return found != run.end() && std::isfinite(found->second);
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

PlannerStanding standingFromRuns(const std::string& planner, const std::vector<const RunValues*>& runs) {
  PlannerStanding standing;
  standing.planner = planner;
  standing.runs = static_cast<int>(runs.size());
  std::vector<double> executionTimes;  // every run, failures as +inf
  for (const auto* run : runs) {
    if (succeeded(*run)) {
      ++standing.successes;
      executionTimes.push_back(run->at("execution_time_s"));
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
      if (!succeeded(*run)) continue;
      const auto found = run->find(metric.key);
      if (found != run->end() && std::isfinite(found->second)) values.push_back(found->second);
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
    const double la = medianOf(a, "tcp_path_length_m"), lb = medianOf(b, "tcp_path_length_m");
    if (la != lb) return la < lb;
    return a.planner < b.planner;
  });
  for (std::size_t i = 0; i < planners.size(); ++i) {
    planners[i].rank = (i > 0 && !better(planners[i - 1], planners[i])) ? planners[i - 1].rank : static_cast<int>(i) + 1;
  }
}

std::string formatNumber(double value, int precision = 4) {
  if (std::isnan(value)) return "–";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  std::ostringstream out;
  out << std::setprecision(precision) << value;
  return out.str();
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

// Markdown table; `overall` adds mean rank, problem count and first places.
std::string standingsTable(const std::vector<PlannerStanding>& standings, bool overall) {
  std::ostringstream out;
  out << "| rank | planner |" << (overall ? " mean rank | problems | 1st |" : "") << " success |"
      << " exec time median (s) | TCP length median [min, max] (m) | solve time median (s) |"
      << " peak TCP speed median (m/s) | time above limit max (s) | min clearance median (m) | joint speed ratio max |\n";
  out << "|---:|---|" << (overall ? "---:|---:|---:|" : "") << "---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& s : standings) {
    const auto& length = s.metrics.at("tcp_path_length_m");
    out << "| " << s.rank << " | " << s.planner << " |";
    if (overall) out << " " << formatNumber(s.meanRank, 3) << " | " << s.problems << " | " << s.firstPlaces << " |";
    out << " " << percent(s.successRate) << " (" << s.successes << "/" << s.runs << ") |"
        << " " << formatNumber(s.metrics.at("execution_time_s").median) << " |"
        << " " << formatNumber(length.median) << " [" << formatNumber(length.min) << ", " << formatNumber(length.max)
        << "] |"
        << " " << formatNumber(s.metrics.at("solve_time_s").median, 3) << " |"
        << " " << formatNumber(s.metrics.at("peak_tcp_speed_mps").median) << " |"
        << " " << formatNumber(s.metrics.at("time_above_limit_s").max, 3) << " |"
        << " " << formatNumber(s.metrics.at("min_clearance_m").median, 3) << " |"
        << " " << formatNumber(s.metrics.at("max_joint_speed_ratio").max, 3) << " |\n";
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
        out << " " << percent(found->successRate) << " · rank " << formatNumber(found->meanRank, 3) << " |";
      }
    }
    out << "\n";
  }
  return out.str();
}

// sqlite3 handles closed on scope exit.
struct DatabaseCloser {
  void operator()(sqlite3* db) const { sqlite3_close(db); }
};
struct StatementFinalizer {
  void operator()(sqlite3_stmt* statement) const { sqlite3_finalize(statement); }
};
using Database = std::unique_ptr<sqlite3, DatabaseCloser>;
using Statement = std::unique_ptr<sqlite3_stmt, StatementFinalizer>;

Statement prepare(sqlite3* db, const std::string& sql, const std::filesystem::path& file) {
  sqlite3_stmt* raw = nullptr;
  if (sqlite3_prepare_v2(db, sql.c_str(), -1, &raw, nullptr) != SQLITE_OK) {
    throw Error(file.string() + ": not an OMPL benchmark database (" + sqlite3_errmsg(db) + ")");
  }
  return Statement(raw);
}

std::set<std::string> tableColumns(sqlite3* db, const std::string& table, const std::filesystem::path& file) {
  std::set<std::string> columns;
  auto statement = prepare(db, "PRAGMA table_info(" + table + ")", file);
  while (sqlite3_step(statement.get()) == SQLITE_ROW) {
    columns.insert(reinterpret_cast<const char*>(sqlite3_column_text(statement.get(), 1)));
  }
  return columns;
}

std::string removePrefix(std::string name) {
  for (const std::string prefix : {"geometric_", "control_"}) {
    if (name.rfind(prefix, 0) == 0) return name.substr(prefix.size());
  }
  return name;
}

}  // namespace

const std::vector<RankedMetric>& rankedMetrics() {
  static const std::vector<RankedMetric> metrics{
      {"execution_time_s", "execution time (s)", {"execution_time"}},
      {"tcp_path_length_m", "TCP path length (m)", {"tcp_path_length"}},
      {"joint_path_length_rad", "joint path length (rad)", {"simplified_solution_length", "solution_length"}},
      {"solve_time_s", "solve time (s)", {"solve_time"}},
      {"mean_tcp_speed_mps", "mean TCP speed (m/s)", {"mean_tcp_speed"}},
      {"peak_tcp_speed_mps", "peak TCP speed (m/s)", {"peak_tcp_speed"}},
      {"time_above_limit_s", "time above limit (s)", {"time_above_limit"}},
      {"min_clearance_m", "min clearance (m)", {"min_clearance"}},
      {"max_joint_speed_ratio", "max joint speed ratio", {"max_joint_speed_ratio"}},
  };
  return metrics;
}

namespace {

// Mean rank, pooled runs and first places of every planner over `problems`, best first.
std::vector<PlannerStanding> aggregate(const std::vector<const ProblemRanking*>& problems,
                                       const std::map<std::string, std::map<std::string, std::vector<RunValues>>>& runs) {
  std::map<std::string, std::vector<int>> ranksOf;
  std::map<std::string, std::vector<const RunValues*>> runsOf;
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
    standings[i].rank = (i > 0 && !better(standings[i - 1], standings[i])) ? standings[i - 1].rank : static_cast<int>(i) + 1;
  }
  return standings;
}

}  // namespace

Ranking rankRuns(const std::map<std::string, std::map<std::string, std::vector<RunValues>>>& runs,
                 const std::map<std::string, std::string>& families) {
  Ranking ranking;
  for (const auto& [problem, planners] : runs) {
    ProblemRanking entry;
    entry.problem = problem;
    for (const auto& [planner, plannerRuns] : planners) {
      std::vector<const RunValues*> pointers;
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
  if (!std::filesystem::is_regular_file(file)) throw Error("benchmark database " + file.string() + " not found");
  sqlite3* raw = nullptr;
  if (sqlite3_open_v2(file.string().c_str(), &raw, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    Database closer(raw);
    throw Error("cannot open benchmark database " + file.string() + ": " + sqlite3_errmsg(raw));
  }
  Database db(raw);
  const auto columns = tableColumns(db.get(), "runs", file);
  for (const char* required : {"experimentid", "plannerid", "solved"}) {
    if (columns.count(required) == 0) {
      throw Error(file.string() + ": not an OMPL benchmark database (table runs has no column '" + required +
                  "'; build it with ompl_benchmark_statistics)");
    }
  }
  // Metric expressions: the first existing column of each metric, NULL when no log had it.
  std::string select = "SELECT experiments.name, plannerConfigs.name, runs.solved";
  for (const auto& metric : rankedMetrics()) {
    std::vector<std::string> present;
    for (const auto& column : metric.columns) {
      if (columns.count(column) != 0) present.push_back("runs." + column);
    }
    if (present.empty()) {
      select += ", NULL";
    } else if (present.size() == 1) {
      select += ", " + present.front();
    } else {
      select += ", COALESCE(" + present.front();
      for (std::size_t i = 1; i < present.size(); ++i) select += ", " + present[i];
      select += ")";
    }
  }
  select += " FROM runs JOIN experiments ON runs.experimentid = experiments.id"
            " JOIN plannerConfigs ON runs.plannerid = plannerConfigs.id";
  auto statement = prepare(db.get(), select, file);

  std::map<std::string, std::map<std::string, std::vector<RunValues>>> runs;
  int step = 0;
  int count = 0;
  while ((step = sqlite3_step(statement.get())) == SQLITE_ROW) {
    const auto text = [&](int column) {
      const auto* value = sqlite3_column_text(statement.get(), column);
      return value == nullptr ? std::string() : std::string(reinterpret_cast<const char*>(value));
    };
    RunValues run;
    const bool solved = sqlite3_column_type(statement.get(), 2) != SQLITE_NULL && sqlite3_column_int(statement.get(), 2) == 1;
    if (solved) {
      int column = 3;
      for (const auto& metric : rankedMetrics()) {
        if (sqlite3_column_type(statement.get(), column) != SQLITE_NULL) {
          run[metric.key] = sqlite3_column_double(statement.get(), column);
        }
        ++column;
      }
    }
    runs[text(0)][removePrefix(text(1))].push_back(std::move(run));
    ++count;
  }
  if (step != SQLITE_DONE) throw Error(file.string() + ": reading runs failed: " + sqlite3_errmsg(db.get()));
  if (count == 0) throw Error(file.string() + ": the database holds no benchmark runs");
  // Problem families are an arcplan experiment parameter; logs from elsewhere simply have none.
  std::map<std::string, std::string> families;
  if (tableColumns(db.get(), "experiments", file).count("problemkind") != 0) {
    auto kinds = prepare(db.get(), "SELECT name, problemkind FROM experiments WHERE problemkind IS NOT NULL", file);
    while (sqlite3_step(kinds.get()) == SQLITE_ROW) {
      families[reinterpret_cast<const char*>(sqlite3_column_text(kinds.get(), 0))] =
          reinterpret_cast<const char*>(sqlite3_column_text(kinds.get(), 1));
    }
  }
  auto ranking = rankRuns(runs, families);
  ranking.database = file;
  return ranking;
}

std::string rankingMarkdown(const Ranking& ranking) {
  std::ostringstream out;
  out << "# Planner ranking\n\n";
  out << "Database: `" << ranking.database.string() << "` — " << ranking.problemCount() << " problem"
      << (ranking.problemCount() == 1 ? "" : "s") << ", " << ranking.overall.size() << " planner configurations.\n\n";
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
  out << "Overall ranking (" << ranking.problemCount() << " problem" << (ranking.problemCount() == 1 ? "" : "s")
      << ", mean of per-problem ranks):\n\n"
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
