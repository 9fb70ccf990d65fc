// Reading the runs of a benchmark database (the SQLite file ompl_benchmark_statistics builds from
// OMPL logs) into the per-run values rankRuns ranks.
#include <memory>
#include <set>

#include <sqlite3.h>

#include "arcplan/benchmarks/ranking.h"
#include "arcplan/common/error.h"
#include "arcplan/common/text_formatting.h"
#include "run_properties.h"

namespace arcplan::benchmarks {
namespace {

using RunValues = std::map<std::string, double>;

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

// OMPL names planners "geometric_RRTConnect"; the ranking shows the configuration label.
std::string removePrefix(std::string name) {
  for (const std::string prefix : {"geometric_", "control_"}) {
    if (name.rfind(prefix, 0) == 0) return name.substr(prefix.size());
  }
  return name;
}

Database openReadOnly(const std::filesystem::path& file) {
  if (!std::filesystem::is_regular_file(file)) throw Error("benchmark database " + file.string() + " not found");
  sqlite3* raw = nullptr;
  if (sqlite3_open_v2(file.string().c_str(), &raw, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    Database closer(raw);
    throw Error("cannot open benchmark database " + file.string() + ": " + sqlite3_errmsg(raw));
  }
  return Database(raw);
}

// SELECT of (experiment, planner, solved, one value per metric): each metric reads the first of its
// columns that the database has (COALESCE over several), NULL when no log had any of them.
std::string runsQuery(const std::set<std::string>& columns) {
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
      select += ", COALESCE(" + joinText(present, ", ") + ")";
    }
  }
  return select +
         " FROM runs JOIN experiments ON runs.experimentid = experiments.id"
         " JOIN plannerConfigs ON runs.plannerid = plannerConfigs.id";
}

// Problem families are an arcplan experiment parameter; logs from elsewhere simply have none.
std::map<std::string, std::string> problemFamilies(sqlite3* db, const std::filesystem::path& file) {
  std::map<std::string, std::string> families;
  const std::string column = databaseColumn(kProblemKindParameter);
  if (tableColumns(db, "experiments", file).count(column) == 0) return families;
  auto kinds = prepare(db, "SELECT name, " + column + " FROM experiments WHERE " + column + " IS NOT NULL", file);
  while (sqlite3_step(kinds.get()) == SQLITE_ROW) {
    families[reinterpret_cast<const char*>(sqlite3_column_text(kinds.get(), 0))] =
        reinterpret_cast<const char*>(sqlite3_column_text(kinds.get(), 1));
  }
  return families;
}

// Settings columns of the experiments table (a job's log each) and how bench compare names them;
// a database from elsewhere may lack some.
struct SettingColumn {
  const char* column;
  const char* name;
};
constexpr SettingColumn kSettingColumns[] = {
    {"runcount", "runs"},
    {"timelimit", "time limit (s)"},
    {"vmax", "vmax (m/s)"},
    {"clearance", "clearance (m)"},
    {"iterationbudget", "iteration budget"},
    {"jobseed", "job seed"},
    {"generatorseed", "generator seed"},
    {"problemorigin", "problem origin"},
    {"queryname", "query"},
    {"arcplanversion", "arcplan version"},
    {"omplversion", "OMPL version"},
    {"fclversion", "FCL version"},
    {"eigenversion", "Eigen version"},
    {"hostname", "host"},
};

// "key = value\n;key = value\n;" as OMPL writes a planner's parameters.
void addPlannerParameters(const std::string& text, std::map<std::string, std::string>& settings) {
  std::size_t begin = 0;
  while (begin < text.size()) {
    auto end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(begin, end - begin);
    begin = end + 1;
    if (!line.empty() && line.front() == ';') line.erase(0, 1);
    const auto equals = line.find(" = ");
    if (equals == std::string::npos) continue;
    const std::string name = line.substr(0, equals);
    if (name.rfind("projection.", 0) == 0) continue;
    settings["parameter " + name] = line.substr(equals + 3);
  }
}

void recordSetting(std::map<std::string, std::string>& settings, const std::string& name, const std::string& value) {
  auto [entry, inserted] = settings.emplace(name, value);
  if (inserted || entry->second == value) return;
  // Several jobs of one pair (merged shards) with different values: keep each value once.
  if (("| " + entry->second + " |").find("| " + value + " |") != std::string::npos) return;
  entry->second += " | " + value;
}

using SettingsByPair = std::map<std::string, std::map<std::string, std::map<std::string, std::string>>>;

SettingsByPair pairSettings(sqlite3* db, const std::filesystem::path& file) {
  const auto experimentColumns = tableColumns(db, "experiments", file);
  const bool plannerSettings = tableColumns(db, "plannerConfigs", file).count("settings") != 0;
  std::vector<const SettingColumn*> present;
  std::string select = "SELECT DISTINCT experiments.name, plannerConfigs.name";
  select += plannerSettings ? ", plannerConfigs.settings" : ", NULL";
  for (const auto& setting : kSettingColumns) {
    if (experimentColumns.count(setting.column) == 0) continue;
    present.push_back(&setting);
    select += std::string(", experiments.") + setting.column;
  }
  select +=
      " FROM runs JOIN experiments ON runs.experimentid = experiments.id"
      " JOIN plannerConfigs ON runs.plannerid = plannerConfigs.id";
  auto statement = prepare(db, select, file);
  SettingsByPair settings;
  while (sqlite3_step(statement.get()) == SQLITE_ROW) {
    const auto text = [&](int column) {
      const auto* value = sqlite3_column_text(statement.get(), column);
      return value == nullptr ? std::string() : std::string(reinterpret_cast<const char*>(value));
    };
    auto& pair = settings[text(0)][removePrefix(text(1))];
    std::map<std::string, std::string> parameters;
    addPlannerParameters(text(2), parameters);
    for (const auto& [name, value] : parameters) recordSetting(pair, name, value);
    for (std::size_t i = 0; i < present.size(); ++i) {
      if (sqlite3_column_type(statement.get(), static_cast<int>(i) + 3) == SQLITE_NULL) continue;
      recordSetting(pair, present[i]->name, text(static_cast<int>(i) + 3));
    }
  }
  return settings;
}

}  // namespace

RecordedRuns readRecordedRuns(const std::filesystem::path& file) {
  const Database db = openReadOnly(file);
  const auto columns = tableColumns(db.get(), "runs", file);
  for (const char* required : {"experimentid", "plannerid", "solved"}) {
    if (columns.count(required) == 0) {
      throw Error(file.string() + ": not an OMPL benchmark database (table runs has no column '" + required +
                  "'; build it with ompl_benchmark_statistics)");
    }
  }
  auto statement = prepare(db.get(), runsQuery(columns), file);

  RecordedRuns recorded;
  auto& runs = recorded.runs;
  int step = 0;
  int count = 0;
  while ((step = sqlite3_step(statement.get())) == SQLITE_ROW) {
    const auto text = [&](int column) {
      const auto* value = sqlite3_column_text(statement.get(), column);
      return value == nullptr ? std::string() : std::string(reinterpret_cast<const char*>(value));
    };
    RunValues run;
    const bool solved =
        sqlite3_column_type(statement.get(), 2) != SQLITE_NULL && sqlite3_column_int(statement.get(), 2) == 1;
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
  recorded.families = problemFamilies(db.get(), file);
  recorded.settings = pairSettings(db.get(), file);
  return recorded;
}

Ranking rankDatabase(const std::filesystem::path& file) {
  const auto recorded = readRecordedRuns(file);
  auto ranking = rankRuns(recorded.runs, recorded.families);
  ranking.database = file;
  return ranking;
}

}  // namespace arcplan::benchmarks
