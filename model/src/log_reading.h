#pragma once
// What the two log readers share (measurements.cpp: one CSV, log_folder.cpp: one CSV per signal):
// reading line by line, the rules for a value that cannot be trusted, and counting dropped rows.
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "arcplan/model/measurements.h"

namespace arcplan::model::detail {

// Reads a log line by line: a one-hour 500 Hz log is gigabytes of text, so it is never held whole.
class LineReader {
public:
  explicit LineReader(const std::filesystem::path& file);
  // The next line without its '\n'; false at the end of the file.
  bool next(std::string& line);
  std::size_t lineNumber() const { return lineNumber_; }  // 1-based number of the line last read

private:
  std::ifstream in_;
  std::size_t lineNumber_ = 0;
};

// Why a field is not a trustworthy value (nullptr: it is one, stored in `value`): unparseable,
// NaN/inf, or a corrupted magnitude (the real UR10e logs hold rows with values around 1e280).
const char* valueProblem(std::string_view field, double corruptMagnitude, double& value);

class DropCounter {
public:
  void add(const std::string& reason, std::size_t line);
  std::vector<DroppedRows> take() { return std::move(dropped_); }

private:
  std::vector<DroppedRows> dropped_;
};

bool isKnownVector(const std::string& name);
bool isKnownScalar(const std::string& name);
std::string joinNames(const std::vector<std::string>& names);  // "a, b, c"
bool isBlank(std::string_view line);

}  // namespace arcplan::model::detail
