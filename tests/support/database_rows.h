#pragma once
// Reads an ompl_benchmark_statistics database (SQLite) in tests: every row of a query as text.
#include <filesystem>
#include <string>
#include <vector>

namespace arcplan::testing {

using DatabaseRows = std::vector<std::vector<std::string>>;

// Opens `database` read-only and returns every row of `sql`, values as text and SQL NULL as
// `nullText`. An unopenable database or a failing query is a test failure (and no rows).
DatabaseRows databaseRows(const std::filesystem::path& database, const std::string& sql,
                          const std::string& nullText = "NULL");

}  // namespace arcplan::testing
