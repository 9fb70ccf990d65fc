#include "arcplan/report/benchmark_runs.h"

#include <memory>
#include <set>

#include <sqlite3.h>

#include "arcplan/benchmarks/ranking.h"
#include "arcplan/common/error.h"

namespace arcplan::report {
namespace {

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

std::string columnText(sqlite3_stmt* statement, int column) {
  const auto* text = sqlite3_column_text(statement, column);
  return text == nullptr ? std::string() : std::string(reinterpret_cast<const char*>(text));
}

// Column name -> declared type of a table ("REAL", "INTEGER", ...).
std::map<std::string, std::string> tableColumns(sqlite3* db, const std::string& table, const std::filesystem::path& file) {
  std::map<std::string, std::string> columns;
  auto statement = prepare(db, "PRAGMA table_info(" + table + ")", file);
  while (sqlite3_step(statement.get()) == SQLITE_ROW) columns[columnText(statement.get(), 1)] = columnText(statement.get(), 2);
  return columns;
}

std::string withoutGeometricPrefix(const std::string& planner) {
  const std::string prefix = "geometric_";
  return planner.rfind(prefix, 0) == 0 ? planner.substr(prefix.size()) : planner;
}

// One SQL expression per attribute: arcplan's ranked metrics (first existing column of each), or
// every numeric column of a plain OMPL database.
std::vector<std::pair<RunAttribute, std::string>> attributeExpressions(const std::map<std::string, std::string>& columns,
                                                                       bool arcplanColumns) {
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

nlohmann::json experimentRows(sqlite3* db, const std::filesystem::path& file) {
  nlohmann::json rows = nlohmann::json::array();
  auto statement = prepare(db, "SELECT * FROM experiments ORDER BY id", file);
  const int count = sqlite3_column_count(statement.get());
  while (sqlite3_step(statement.get()) == SQLITE_ROW) {
    nlohmann::json row = nlohmann::json::object();
    for (int column = 0; column < count; ++column) {
      const std::string name = sqlite3_column_name(statement.get(), column);
      switch (sqlite3_column_type(statement.get(), column)) {
        case SQLITE_NULL: break;
        case SQLITE_INTEGER: row[name] = sqlite3_column_int64(statement.get(), column); break;
        case SQLITE_FLOAT: row[name] = sqlite3_column_double(statement.get(), column); break;
        default: row[name] = columnText(statement.get(), column);
      }
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace

BenchmarkRuns readBenchmarkRuns(const std::filesystem::path& file) {
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
  select += " FROM runs JOIN experiments ON runs.experimentid = experiments.id"
            " JOIN plannerConfigs ON runs.plannerid = plannerConfigs.id ORDER BY runs.id";
  auto statement = prepare(db.get(), select, file);
  int step = 0;
  int count = 0;
  while ((step = sqlite3_step(statement.get())) == SQLITE_ROW) {
    auto& plannerRuns = result.runs[columnText(statement.get(), 0)][withoutGeometricPrefix(columnText(statement.get(), 1))];
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
  if (step != SQLITE_DONE) throw Error(file.string() + ": reading runs failed: " + sqlite3_errmsg(db.get()));
  if (count == 0) throw Error(file.string() + ": the database holds no benchmark runs");
  result.experiments = experimentRows(db.get(), file);
  return result;
}

}  // namespace arcplan::report
