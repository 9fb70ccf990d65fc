#include "arcplan/report/benchmark_runs.h"

#include <memory>
#include <set>

#include <sqlite3.h>

#include "arcplan/benchmarks/ranking.h"
#include "arcplan/common/error.h"

namespace arcplan::report {
namespace {

// A database opened read-only; statements finalize themselves.
class ReadOnlyDatabase {
public:
  using Statement = std::unique_ptr<sqlite3_stmt, int (*)(sqlite3_stmt*)>;

  explicit ReadOnlyDatabase(const std::filesystem::path& file) : file_(file), db_(nullptr, sqlite3_close) {
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

private:
  std::filesystem::path file_;
  std::unique_ptr<sqlite3, int (*)(sqlite3*)> db_;
};

std::string columnText(sqlite3_stmt* statement, int column) {
  const auto* text = sqlite3_column_text(statement, column);
  return text == nullptr ? std::string() : std::string(reinterpret_cast<const char*>(text));
}

// Column name -> declared type of a table ("REAL", "INTEGER", ...).
std::map<std::string, std::string> tableColumns(const ReadOnlyDatabase& db, const std::string& table) {
  std::map<std::string, std::string> columns;
  auto statement = db.query("PRAGMA table_info(" + table + ")");
  while (sqlite3_step(statement.get()) == SQLITE_ROW)
    columns[columnText(statement.get(), 1)] = columnText(statement.get(), 2);
  return columns;
}

std::string withoutGeometricPrefix(const std::string& planner) {
  const std::string prefix = "geometric_";
  return planner.rfind(prefix, 0) == 0 ? planner.substr(prefix.size()) : planner;
}

// One SQL expression per attribute: arcplan's ranked metrics (first existing column of each), or
// every numeric column of a plain OMPL database.
std::vector<std::pair<RunAttribute, std::string>> attributeExpressions(
    const std::map<std::string, std::string>& columns, bool arcplanColumns) {
  std::vector<std::pair<RunAttribute, std::string>> expressions;
  if (arcplanColumns) {
    for (const auto& metric : benchmarks::rankedMetrics()) {
      std::string present;
      for (const auto& column : metric.columns) {
        if (columns.count(column) != 0) present += (present.empty() ? "" : ", ") + ("runs." + column);
      }
      if (!present.empty()) expressions.push_back({{metric.key, metric.label}, "COALESCE(" + present + ", NULL)"});
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
          row[name] = columnText(statement.get(), column);
      }
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace

BenchmarkRuns readBenchmarkRuns(const std::filesystem::path& file) {
  if (!std::filesystem::is_regular_file(file)) throw Error("benchmark database " + file.string() + " not found");
  const ReadOnlyDatabase db(file);
  const auto columns = tableColumns(db, "runs");
  for (const char* required : {"experimentid", "plannerid", "solved"}) {
    if (columns.count(required) == 0) {
      throw Error(file.string() + ": not an OMPL benchmark database (table runs has no column '" + required + "')");
    }
  }
  BenchmarkRuns result;
  result.arcplanColumns = columns.count("execution_time") != 0;
  const auto expressions = attributeExpressions(columns, result.arcplanColumns);
  std::string select = "SELECT experiments.name, plannerConfigs.name, runs.solved";
  for (const auto& [attribute, expression] : expressions) {
    result.attributes.push_back(attribute);
    select += ", " + expression;
  }
  select +=
      " FROM runs JOIN experiments ON runs.experimentid = experiments.id"
      " JOIN plannerConfigs ON runs.plannerid = plannerConfigs.id ORDER BY runs.id";
  auto statement = db.query(select);
  int step = 0;
  int count = 0;
  while ((step = sqlite3_step(statement.get())) == SQLITE_ROW) {
    auto& plannerRuns =
        result.runs[columnText(statement.get(), 0)][withoutGeometricPrefix(columnText(statement.get(), 1))];
    BenchmarkRun run;
    run.index = static_cast<int>(plannerRuns.size());
    run.solved = sqlite3_column_type(statement.get(), 2) != SQLITE_NULL && sqlite3_column_int(statement.get(), 2) == 1;
    for (std::size_t i = 0; i < expressions.size(); ++i) {
      const int column = 3 + static_cast<int>(i);
      if (sqlite3_column_type(statement.get(), column) != SQLITE_NULL) {
        run.values[expressions[i].first.key] = sqlite3_column_double(statement.get(), column);
      }
    }
    plannerRuns.push_back(std::move(run));
    ++count;
  }
  if (step != SQLITE_DONE) throw Error(file.string() + ": reading runs failed: " + db.lastError());
  if (count == 0) throw Error(file.string() + ": the database holds no benchmark runs");
  result.experiments = experimentRows(db);
  return result;
}

}  // namespace arcplan::report
