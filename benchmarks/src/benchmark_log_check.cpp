// Whether an OMPL benchmark log is complete (benchmark_log_check.h).
#include "arcplan/benchmarks/benchmark_log_check.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <fstream>
#include <sstream>
#include <vector>

#include "arcplan/common/error.h"

namespace arcplan::benchmarks {
namespace {

struct LogDefect {
  std::string message;
};

// A log's lines in the order ompl_benchmark_statistics reads them; every check names its line.
class LogLines {
public:
  explicit LogLines(const std::string& text) {
    std::size_t start = 0;
    while (start < text.size()) {
      const auto end = text.find('\n', start);
      if (end == std::string::npos) {
        lines_.push_back(text.substr(start));
        lastLineCut_ = true;  // a complete log ends with a newline
        break;
      }
      lines_.push_back(text.substr(start, end - start));
      start = end + 1;
    }
  }

  bool atEnd() const { return next_ >= lines_.size(); }
  bool lastLineCut() const { return lastLineCut_; }
  std::size_t lineCount() const { return lines_.size(); }
  const std::string& peek() const { return lines_[next_]; }

  const std::string& take(const std::string& expected) {
    if (atEnd()) fail("the file ends where " + expected + " was expected");
    return lines_[next_++];
  }

  // A line "<whole number> <suffix>"; returns the number.
  unsigned long takeCount(const std::string& suffix) {
    const std::string& line = take("'N " + suffix + "'");
    const auto space = line.find(' ');
    if (space == std::string::npos || line.compare(space + 1, std::string::npos, suffix) != 0 || space == 0 ||
        !std::all_of(line.begin(), line.begin() + static_cast<std::ptrdiff_t>(space),
                     [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; })) {
      fail("expected 'N " + suffix + "', found '" + shortened(line) + "'");
    }
    unsigned long count = 0;
    const auto [end, error] = std::from_chars(line.data(), line.data() + space, count);
    if (error != std::errc() || end != line.data() + space) fail("the count in '" + shortened(line) + "' is too large");
    return count;
  }

  // A line "<value> <suffix>" (the seed, the limits, the total time).
  void takeValue(const std::string& suffix) {
    const std::string& line = take("'... " + suffix + "'");
    const auto space = line.find(' ');
    if (space == std::string::npos || space == 0 || line.compare(space + 1, std::string::npos, suffix) != 0) {
      fail("expected '<value> " + suffix + "', found '" + shortened(line) + "'");
    }
  }

  bool nextEndsWith(const std::string& suffix) const {
    return !atEnd() && peek().size() > suffix.size() &&
           peek().compare(peek().size() - suffix.size(), suffix.size(), suffix) == 0;
  }

  [[noreturn]] void fail(const std::string& message) const {
    throw LogDefect{"line " + std::to_string(std::min(next_, lines_.size())) + ": " + message};
  }

  static std::string shortened(const std::string& line) { return line.size() > 60 ? line.substr(0, 60) + "..." : line; }

private:
  std::vector<std::string> lines_;
  std::size_t next_ = 0;
  bool lastLineCut_ = false;
};

void takePrefixed(LogLines& lines, const std::string& prefix, std::string* rest = nullptr) {
  const std::string& line = lines.take("'" + prefix + "...'");
  if (line.rfind(prefix, 0) != 0) lines.fail("expected '" + prefix + "...', found '" + LogLines::shortened(line) + "'");
  if (rest != nullptr) *rest = line.substr(prefix.size());
}

// "<<<|" ... "|>>>": the setup and CPU blocks.
void takeBlock(LogLines& lines) {
  takePrefixed(lines, "<<<|");
  while (true) {
    if (lines.take("the end of a '<<<|' block ('|>>>')").rfind("|>>>", 0) == 0) return;
  }
}

// One planner: its settings, the property names, one line per run, optional progress data, ".".
void checkPlanner(LogLines& lines, const LogExpectation& expected) {
  const std::string& name = lines.take("a planner name");
  if (!expected.planner.empty() && name != "geometric_" + expected.planner) {
    lines.fail("planner '" + name + "', expected 'geometric_" + expected.planner + "'");
  }
  const auto settings = lines.takeCount("common properties");
  for (unsigned long i = 0; i < settings; ++i) {
    if (lines.take("a planner setting").find(" = ") == std::string::npos)
      lines.fail("expected a setting 'name = value'");
  }
  const auto properties = lines.takeCount("properties for each run");
  for (unsigned long i = 0; i < properties; ++i) {
    if (lines.take("a run property name").find(' ') == std::string::npos) lines.fail("expected a property 'name TYPE'");
  }
  const auto runs = lines.takeCount("runs");
  if (expected.runs != 0 && runs != expected.runs) {
    lines.fail(std::to_string(runs) + " runs, expected " + std::to_string(expected.runs));
  }
  for (unsigned long run = 0; run < runs; ++run) {
    if (lines.atEnd()) {
      lines.fail(std::to_string(run) + " of " + std::to_string(runs) + " runs, then the file ends");
    }
    const std::string& values = lines.take("a run");
    std::size_t separators = 0;
    for (auto at = values.find("; "); at != std::string::npos; at = values.find("; ", at + 2)) ++separators;
    if (separators != properties || values.size() < 2 || values.compare(values.size() - 2, 2, "; ") != 0) {
      lines.fail("run " + std::to_string(run + 1) + " of " + std::to_string(runs) + " has " +
                 std::to_string(separators) + " of " + std::to_string(properties) + " values (cut short or garbled)");
    }
  }
  if (!lines.atEnd() && lines.peek() != ".") {
    const auto progress = lines.takeCount("progress properties for each run");
    for (unsigned long i = 0; i < progress; ++i) lines.take("a progress property name");
    const auto series = lines.takeCount("runs");
    for (unsigned long i = 0; i < series; ++i) lines.take("a run's progress data");
  }
  if (lines.take("'.' (the end of the planner)") != ".") lines.fail("expected '.' (the end of the planner)");
}

void checkLog(LogLines& lines, const LogExpectation& expected) {
  if (lines.lineCount() == 0) lines.fail("the file is empty");
  if (lines.peek().find(" version") != std::string::npos && lines.peek().rfind("Experiment ", 0) != 0) lines.take("");
  std::string experiment;
  takePrefixed(lines, "Experiment ", &experiment);
  if (!expected.experiment.empty() && experiment != expected.experiment) {
    lines.fail("experiment '" + experiment + "', expected '" + expected.experiment + "'");
  }
  if (lines.nextEndsWith(" experiment properties")) {
    const auto count = lines.takeCount("experiment properties");
    for (unsigned long i = 0; i < count; ++i) {
      if (lines.take("an experiment property").find(" = ") == std::string::npos)
        lines.fail("expected 'name TYPE = value'");
    }
  }
  takePrefixed(lines, "Running on ");
  takePrefixed(lines, "Starting at ");
  takeBlock(lines);
  if (!lines.atEnd() && lines.peek().rfind("<<<|", 0) == 0) takeBlock(lines);
  lines.takeValue("is the random seed");
  lines.takeValue("seconds per run");
  lines.takeValue("MB per run");
  if (lines.nextEndsWith(" runs per planner")) {
    const auto runs = lines.takeCount("runs per planner");
    if (expected.runs != 0 && runs != expected.runs) {
      lines.fail(std::to_string(runs) + " runs per planner, expected " + std::to_string(expected.runs));
    }
  }
  lines.takeValue("seconds spent to collect the data");
  if (lines.nextEndsWith(" enum type") || lines.nextEndsWith(" enum types")) {
    const auto enums = lines.takeCount(lines.nextEndsWith(" enum type") ? "enum type" : "enum types");
    for (unsigned long i = 0; i < enums; ++i) {
      if (lines.take("an enum").find('|') == std::string::npos) lines.fail("expected an enum 'name|value|...'");
    }
  }
  const auto planners = lines.takeCount("planners");
  if (planners == 0) lines.fail("the log has no planner");
  if (!expected.planner.empty() && planners != 1) lines.fail(std::to_string(planners) + " planners, expected 1");
  for (unsigned long i = 0; i < planners; ++i) checkPlanner(lines, expected);
  if (lines.lastLineCut()) lines.fail("the last line has no newline (the file was cut short)");
  while (!lines.atEnd()) {
    if (!lines.take("").empty()) lines.fail("text after the end of the log");
  }
}

}  // namespace

std::optional<std::string> benchmarkLogProblem(const std::filesystem::path& log, const LogExpectation& expected) {
  std::ifstream in(log, std::ios::binary);
  if (!in) return "cannot be read";
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return "cannot be read";
  const std::string content = text.str();
  if (content.find('\0') != std::string::npos) return "contains NUL bytes (a block the file system never wrote)";
  LogLines lines(content);
  try {
    checkLog(lines, expected);
  } catch (const LogDefect& defect) {
    return defect.message;
  }
  return std::nullopt;
}

}  // namespace arcplan::benchmarks
