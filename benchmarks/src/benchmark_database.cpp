// Reading a benchmark database: runs, problem families, per-pair settings and the experiments table.
#include "arcplan/benchmarks/benchmark_database.h"

#include <memory>
#include <set>

#include <sqlite3.h>

#include "arcplan/benchmarks/ranking.h"
#include "arcplan/common/error.h"
#include "arcplan/common/text_formatting.h"
#include "run_properties.h"

namespace arcplan::benchmarks {
namespace {

// A database opened read-only; statements finalize themselves.
class ReadOnlyDatabase {
public:
  using Statement = std::unique_ptr<sqlite3_stmt, int (*)(sqlite3_stmt*)>;

  explicit ReadOnlyDatabase(const std::filesystem::path& file) : file_(file), db_(nullptr, sqlite3_close) {
    if (!std::filesystem::is_regular_file(file)) throw Error("benchmark database " + file.string() + " not found");
    sqlite3* raw = nullptr;
    const int status = sqlite3_open_v2(file.string().c_str(), &raw, SQLITE_OPEN_READONLY, nullptr);
    db_.reset(raw);
    if (status != SQLITE_OK)
      throw Error("cannot open benchmark database " + file.string() + ": " + sqlite3_errmsg(raw));
  }
  Statement query(const std::string& sql) const {
    sqlite3_stmt* raw = nullptr;
    if (sqlite3_prepare_v2(db_.get(), sql.c_str(), -1, &raw, nullptr) != SQLITE_OK) {
      throw Error(file_.string() + ": not an OMPL benchmark database (" + sqlite3_errmsg(db_.get()) + ")");
    }
    return Statement(raw, sqlite3_finalize);
  }
  std::string lastError() const { return sqlite3_errmsg(db_.get()); }

  // Column name -> declared type ("REAL", "INTEGER", ...).
  std::map<std::string, std::string> columns(const std::string& table) const {
    std::map<std::string, std::string> columns;
    auto statement = query("PRAGMA table_info(" + table + ")");
    while (sqlite3_step(statement.get()) == SQLITE_ROW) columns[text(statement.get(), 1)] = text(statement.get(), 2);
    return columns;
  }

  static std::string text(sqlite3_stmt* statement, int column) {
    const auto* value = sqlite3_column_text(statement, column);
    return value == nullptr ? std::string() : std::string(reinterpret_cast<const char*>(value));
  }

private:
  std::filesystem::path file_;
  std::unique_ptr<sqlite3, int (*)(sqlite3*)> db_;
};

const char* const kRunsJoin =
    " FROM runs JOIN experiments ON runs.experimentid = experiments.id"
    " JOIN plannerConfigs ON runs.plannerid = plannerConfigs.id";

// OMPL names planners "geometric_RRTConnect"; campaigns know them by their configuration label.
PlannerLabel plannerLabel(const std::string& name) {
  for (const std::string prefix : {"geometric_", "control_"}) {
    if (name.rfind(prefix, 0) == 0) return name.substr(prefix.size());
  }
  return name;
}

// One SQL expression per attribute: the metric table's metrics (the first existing column of each),
// or every numeric column of a plain OMPL database.
std::vector<std::pair<RunAttribute, std::string>> attributeExpressions(
    const std::map<std::string, std::string>& columns, bool arcplanColumns) {
  std::vector<std::pair<RunAttribute, std::string>> expressions;
  if (arcplanColumns) {
    for (const auto& metric : rankedMetrics()) {
      std::vector<std::string> present;
      for (const auto& column : metric.columns) {
        if (columns.count(column) != 0) present.push_back("runs." + column);
      }
      if (!present.empty()) {
        expressions.push_back({{metric.key, metric.label}, "COALESCE(" + joinText(present, ", ") + ", NULL)"});
      }
    }
    return expressions;
  }
  static const std::set<std::string> identifiers{"id", "experimentid", "plannerid", "solved"};
  for (const auto& [column, type] : columns) {
    if (identifiers.count(column) != 0) continue;
    if (type == "REAL" || type == "INTEGER" || type == "BOOLEAN") {
      std::string label = column;
      for (auto& c : label) c = c == '_' ? ' ' : c;
      expressions.push_back({{column, label}, "runs." + column});
    }
  }
  return expressions;
}

void readRuns(const ReadOnlyDatabase& db, const std::map<std::string, std::string>& columns,
              BenchmarkDatabase& database) {
  const auto expressions = attributeExpressions(columns, database.arcplanColumns);
  std::string select = "SELECT experiments.name, plannerConfigs.name, runs.solved";
  for (const auto& [attribute, expression] : expressions) {
    database.attributes.push_back(attribute);
    select += ", " + expression;
  }
  auto statement = db.query(select + kRunsJoin + " ORDER BY runs.id");
  int step = 0;
  int count = 0;
  while ((step = sqlite3_step(statement.get())) == SQLITE_ROW) {
    RunRecord run;
    run.solved = sqlite3_column_type(statement.get(), 2) != SQLITE_NULL && sqlite3_column_int(statement.get(), 2) == 1;
    for (std::size_t i = 0; i < expressions.size(); ++i) {
      const int column = 3 + static_cast<int>(i);
      if (sqlite3_column_type(statement.get(), column) != SQLITE_NULL) {
        run.values[expressions[i].first.key] = sqlite3_column_double(statement.get(), column);
      }
    }
    const auto problem = ReadOnlyDatabase::text(statement.get(), 0);
    database.runs[problem][plannerLabel(ReadOnlyDatabase::text(statement.get(), 1))].push_back(std::move(run));
    ++count;
  }
  if (step != SQLITE_DONE) throw Error(database.file.string() + ": reading runs failed: " + db.lastError());
  if (count == 0) throw Error(database.file.string() + ": the database holds no benchmark runs");
}

// Problem families are an arcplan experiment parameter; logs from elsewhere simply have none.
std::map<ProblemName, std::string> problemFamilies(const ReadOnlyDatabase& db,
                                                   const std::map<std::string, std::string>& experimentColumns) {
  std::map<ProblemName, std::string> families;
  const std::string column = databaseColumn(kProblemKindParameter);
  if (experimentColumns.count(column) == 0) return families;
  auto kinds = db.query("SELECT name, " + column + " FROM experiments WHERE " + column + " IS NOT NULL");
  while (sqlite3_step(kinds.get()) == SQLITE_ROW) {
    families[ReadOnlyDatabase::text(kinds.get(), 0)] = ReadOnlyDatabase::text(kinds.get(), 1);
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

void recordSetting(PairSettings& settings, const std::string& name, const std::string& value) {
  auto [entry, inserted] = settings.emplace(name, value);
  if (inserted || entry->second == value) return;
  // Several jobs of one pair (merged shards) with different values: keep each value once.
  if (("| " + entry->second + " |").find("| " + value + " |") != std::string::npos) return;
  entry->second += " | " + value;
}

// "key = value\n;key = value\n;" as OMPL writes a planner's parameters.
void addPlannerParameters(const std::string& text, PairSettings& settings) {
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
    recordSetting(settings, "parameter " + name, line.substr(equals + 3));
  }
}

PerPair<PairSettings> pairSettings(const ReadOnlyDatabase& db,
                                   const std::map<std::string, std::string>& experimentColumns) {
  const bool plannerSettings = db.columns("plannerConfigs").count("settings") != 0;
  std::vector<const SettingColumn*> present;
  std::string select = "SELECT DISTINCT experiments.name, plannerConfigs.name";
  select += plannerSettings ? ", plannerConfigs.settings" : ", NULL";
  for (const auto& setting : kSettingColumns) {
    if (experimentColumns.count(setting.column) == 0) continue;
    present.push_back(&setting);
    select += std::string(", experiments.") + setting.column;
  }
  auto statement = db.query(select + kRunsJoin);
  PerPair<PairSettings> settings;
  while (sqlite3_step(statement.get()) == SQLITE_ROW) {
    const auto text = [&](int column) { return ReadOnlyDatabase::text(statement.get(), column); };
    auto& pair = settings[text(0)][plannerLabel(text(1))];
    addPlannerParameters(text(2), pair);
    for (std::size_t i = 0; i < present.size(); ++i) {
      if (sqlite3_column_type(statement.get(), static_cast<int>(i) + 3) == SQLITE_NULL) continue;
      recordSetting(pair, present[i]->name, text(static_cast<int>(i) + 3));
    }
  }
  return settings;
}

nlohmann::json experimentRows(const ReadOnlyDatabase& db) {
  nlohmann::json rows = nlohmann::json::array();
  auto statement = db.query("SELECT * FROM experiments ORDER BY id");
  const int count = sqlite3_column_count(statement.get());
  while (sqlite3_step(statement.get()) == SQLITE_ROW) {
    nlohmann::json row = nlohmann::json::object();
    for (int column = 0; column < count; ++column) {
      const std::string name = sqlite3_column_name(statement.get(), column);
      switch (sqlite3_column_type(statement.get(), column)) {
        case SQLITE_NULL:
          break;
        case SQLITE_INTEGER:
          row[name] = sqlite3_column_int64(statement.get(), column);
          break;
        case SQLITE_FLOAT:
          row[name] = sqlite3_column_double(statement.get(), column);
          break;
        default:
          row[name] = ReadOnlyDatabase::text(statement.get(), column);
      }
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace

std::filesystem::path campaignDatabase(const std::filesystem::path& folderOrDatabase) {
  if (!std::filesystem::is_directory(folderOrDatabase)) return folderOrDatabase;
  const auto database = folderOrDatabase / "benchmark.db";
  if (!std::filesystem::is_regular_file(database)) {
    throw Error(folderOrDatabase.string() +
                ": not a finished campaign folder (no benchmark.db; `arcplan bench` writes it once every job of the "
                "campaign is done)");
  }
  return database;
}

BenchmarkDatabase readBenchmarkDatabase(const std::filesystem::path& file) {
  const ReadOnlyDatabase db(file);
  BenchmarkDatabase database;
  database.file = file;
  const auto columns = db.columns("runs");
  for (const char* required : {"experimentid", "plannerid", "solved"}) {
    if (columns.count(required) == 0) {
      throw Error(file.string() + ": not an OMPL benchmark database (table runs has no column '" + required +
                  "'; build it with ompl_benchmark_statistics)");
    }
  }
  const auto& executionTime = trajectory::metricDescriptor(&trajectory::TrajectoryMetrics::executionTime);
  database.arcplanColumns = columns.count(executionTime.columns.front()) != 0;
  readRuns(db, columns, database);
  const auto experimentColumns = db.columns("experiments");
  database.families = problemFamilies(db, experimentColumns);
  database.settings = pairSettings(db, experimentColumns);
  database.experiments = experimentRows(db);
  return database;
}

}  // namespace arcplan::benchmarks
