#include "arcplan/model/log_folder.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "arcplan/common/error.h"
#include "arcplan/common/text_parsing.h"
#include "log_reading.h"

namespace arcplan::model {
namespace {

// The real-time interface's short names (UR's client logs, the UR5 runs of ur5_kufieta) -> RTDE.
const std::vector<std::pair<std::string, std::string>>& shortNames() {
  static const std::vector<std::pair<std::string, std::string>> names{
      {"q_actual", "actual_q"},       {"qd_actual", "actual_qd"},   {"q_target", "target_q"},
      {"qd_target", "target_qd"},     {"qdd_target", "target_qdd"}, {"i_actual", "actual_current"},
      {"i_target", "target_current"}, {"m_target", "target_moment"}};
  return names;
}

// Files of one run stop a few cycles apart; more than this at the ends is not one recording.
constexpr double kToleratedEndsSeconds = 1.0;
constexpr double kToleratedEndsFraction = 0.05;
// Samples of two files are the same cycle when their times differ by at most this share of a step.
constexpr double kMatchFraction = 0.25;
// Steps that differ by more than this share are two clocks.
constexpr double kStepTolerance = 0.01;
// A file missing more than this share of the reference's cycles runs on another clock.
constexpr double kUnmatchedFraction = 0.05;

std::string seconds(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.4g s", value);
  return buffer;
}

// One signal file as read: rows of [time, values...] with their line numbers.
struct SignalFile {
  std::string signal;
  std::filesystem::path file;
  bool vector = true;
  int width = 0;             // fields per row: time + values
  std::vector<double> rows;  // row-major, `width` per row
  std::vector<std::size_t> lines;
  std::size_t dataRows = 0;
  std::vector<DroppedRows> dropped;

  std::size_t count() const { return lines.size(); }
  double time(std::size_t row) const { return rows[row * static_cast<std::size_t>(width)]; }
  double value(std::size_t row, int column) const { return rows[row * static_cast<std::size_t>(width) + column + 1]; }
  std::string name() const { return file.filename().string(); }
  std::string at(std::size_t line) const { return file.string() + ":" + std::to_string(line); }
  double medianStep() const {
    std::vector<double> steps;
    for (std::size_t r = 1; r < count(); ++r) steps.push_back(time(r) - time(r - 1));
    std::nth_element(steps.begin(), steps.begin() + static_cast<long>(steps.size() / 2), steps.end());
    return steps[steps.size() / 2];
  }
};

SignalFile readSignalFile(const std::string& signal, const std::filesystem::path& file, const LogReadOptions& options) {
  SignalFile result;
  result.signal = signal;
  result.file = file;
  result.vector = !detail::isKnownScalar(signal);
  detail::LineReader reader(file);
  detail::DropCounter dropped;
  std::string line;
  char separator = 0;
  double lastTime = -std::numeric_limits<double>::infinity();
  std::size_t lastLine = 0;
  std::vector<double> row;
  while (reader.next(line)) {
    const std::size_t number = reader.lineNumber();
    if (detail::isBlank(line) || trim(line).front() == '#') continue;
    if (options.firstLine > 0 && number < options.firstLine) continue;
    if (options.lastLine > 0 && number > options.lastLine) break;
    if (separator == 0) separator = line.find(',') != std::string::npos ? ',' : ' ';
    const auto fields = splitFields(line, separator);
    if (result.width == 0) {
      result.width = static_cast<int>(fields.size());
      if (result.width < 2 || (!result.vector && result.width != 2) || result.width > 1001) {
        throw Error(result.at(number) + ": expected the time and " +
                    (result.vector ? std::string("one value per joint") : std::string("one value")) + ", got " +
                    std::to_string(fields.size()) + " field(s)");
      }
      row.resize(fields.size());
    }
    ++result.dataRows;
    if (static_cast<int>(fields.size()) != result.width) {
      dropped.add(static_cast<int>(fields.size()) < result.width ? "short row" : "too many fields", number);
      continue;
    }
    const char* problem = nullptr;
    for (std::size_t f = 0; f < fields.size() && !problem; ++f) {
      problem = detail::valueProblem(fields[f], options.corruptMagnitude, row[f]);
    }
    if (problem) {
      dropped.add(problem, number);
      continue;
    }
    if (row[0] <= lastTime) {
      throw Error(result.at(number) + ": time " + seconds(row[0]) + " is not after " + seconds(lastTime) + " of line " +
                  std::to_string(lastLine) + ": the time column must increase");
    }
    lastTime = row[0];
    lastLine = number;
    result.rows.insert(result.rows.end(), row.begin(), row.end());
    result.lines.push_back(number);
  }
  if (result.dataRows == 0) throw Error(file.string() + " has no data rows (empty file)");
  if (result.count() < 2) throw Error(file.string() + ": fewer than 2 valid rows, no time step");
  result.dropped = dropped.take();
  return result;
}

// The signal files of a folder, in the order of knownVectorSignals() then knownScalarSignals().
std::vector<SignalFile> readSignalFiles(const std::filesystem::path& folder, const LogReadOptions& options) {
  std::vector<std::pair<std::string, std::filesystem::path>> found;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    const auto signal = folderSignal(entry.path().filename().string());
    if (!signal) continue;
    for (const auto& [other, file] : found) {
      if (other == *signal) {
        throw Error(folder.string() + ": " + file.filename().string() + " and " + entry.path().filename().string() +
                    " both hold " + *signal);
      }
    }
    found.emplace_back(*signal, entry.path());
  }
  if (found.empty()) {
    throw Error(folder.string() +
                ": no signal files (log_<signal>.csv with an RTDE name such as log_actual_q.csv, or a "
                "real-time interface name such as log_q_actual.csv)");
  }
  std::vector<std::string> order = knownVectorSignals();
  order.insert(order.end(), knownScalarSignals().begin(), knownScalarSignals().end());
  std::vector<SignalFile> files;
  for (const auto& signal : order) {
    for (const auto& [name, file] : found) {
      if (name == signal) files.push_back(readSignalFile(name, file, options));
    }
  }
  const SignalFile* firstVector = nullptr;
  for (const auto& file : files) {
    if (!file.vector) continue;
    if (!firstVector) {
      firstVector = &file;
    } else if (file.width != firstVector->width) {
      throw Error(folder.string() + ": mismatched joint count: " + firstVector->name() + " has " +
                  std::to_string(firstVector->width - 1) + " joints but " + file.name() + " has " +
                  std::to_string(file.width - 1));
    }
  }
  return files;
}

std::size_t referenceIndex(const std::vector<SignalFile>& files) {
  for (std::size_t f = 0; f < files.size(); ++f) {
    if (files[f].signal == "actual_q") return f;
  }
  return 0;
}

// One clock: the same median step, and every file covering the same time up to the tolerated ends.
// Returns the span every file covers.
std::pair<double, double> checkClocks(const std::filesystem::path& folder, const std::vector<SignalFile>& files,
                                      const SignalFile& reference, double step) {
  for (const auto& file : files) {
    const double own = file.medianStep();
    if (std::abs(own - step) > kStepTolerance * step) {
      throw Error(folder.string() + ": " + reference.name() + " and " + file.name() +
                  " run on different clocks: a sample every " + seconds(step) + " in " + reference.name() +
                  " (median step), every " + seconds(own) + " in " + file.name());
    }
  }
  double start = -std::numeric_limits<double>::infinity(), end = std::numeric_limits<double>::infinity();
  for (const auto& file : files) {
    start = std::max(start, file.time(0));
    end = std::min(end, file.time(file.count() - 1));
  }
  const auto shortest = std::min_element(files.begin(), files.end(), [](const auto& a, const auto& b) {
    return a.time(a.count() - 1) - a.time(0) < b.time(b.count() - 1) - b.time(0);
  });
  const auto longest = std::max_element(files.begin(), files.end(), [](const auto& a, const auto& b) {
    return a.time(a.count() - 1) - a.time(0) < b.time(b.count() - 1) - b.time(0);
  });
  const double tolerated = std::max(kToleratedEndsSeconds, kToleratedEndsFraction * std::max(0.0, end - start));
  for (const auto& file : files) {
    const double beyond = (start - file.time(0)) + (file.time(file.count() - 1) - end);
    if (end <= start || beyond > tolerated) {
      auto span = [](const SignalFile& f) {
        return seconds(f.time(0)) + " to " + seconds(f.time(f.count() - 1)) + " (lines " +
               std::to_string(f.lines.front()) + "-" + std::to_string(f.lines.back()) + ")";
      };
      throw Error(folder.string() + ": files of different lengths: " + shortest->name() + " covers " + span(*shortest) +
                  ", " + longest->name() + " covers " + span(*longest) +
                  "; the files of one run must cover the same time (up to " + seconds(tolerated) + " at the ends)");
    }
  }
  return {start, end};
}

}  // namespace

std::optional<std::string> folderSignal(const std::string& fileName) {
  const std::string prefix = "log_", suffix = ".csv";
  if (fileName.size() <= prefix.size() + suffix.size() || fileName.compare(0, prefix.size(), prefix) != 0 ||
      fileName.compare(fileName.size() - suffix.size(), suffix.size(), suffix) != 0) {
    return std::nullopt;
  }
  const std::string name = fileName.substr(prefix.size(), fileName.size() - prefix.size() - suffix.size());
  if (detail::isKnownVector(name) || detail::isKnownScalar(name)) return name;
  for (const auto& [shortName, signal] : shortNames()) {
    if (name == shortName) return signal;
  }
  return std::nullopt;
}

std::vector<std::string> folderFileNames(const std::string& signal) {
  std::vector<std::string> names{"log_" + signal + ".csv"};
  for (const auto& [shortName, rtde] : shortNames()) {
    if (rtde == signal) names.push_back("log_" + shortName + ".csv");
  }
  return names;
}

Log readLogFolder(const std::filesystem::path& folder, const LogReadOptions& options) {
  if (!std::filesystem::is_directory(folder)) throw Error("log folder " + folder.string() + " is not a directory");
  const std::vector<SignalFile> files = readSignalFiles(folder, options);
  const SignalFile& reference = files[referenceIndex(files)];
  const double step = reference.medianStep();
  const auto [start, end] = checkClocks(folder, files, reference, step);
  const double tolerance = kMatchFraction * step;

  // Walk the reference's rows; every other file must have a sample of the same cycle.
  std::vector<std::size_t> cursor(files.size(), 0), unmatched(files.size(), 0), firstUnmatched(files.size(), 0);
  std::vector<std::vector<std::size_t>> matches(files.size());
  std::vector<std::size_t> keptRows;
  detail::DropCounter dropped;
  std::size_t consideredRows = 0;
  for (std::size_t r = 0; r < reference.count(); ++r) {
    const std::size_t line = reference.lines[r];
    const double t = reference.time(r);
    if (t < start - tolerance || t > end + tolerance) {
      dropped.add("outside the time every file covers", line);
      continue;
    }
    ++consideredRows;
    std::string missing;
    for (std::size_t f = 0; f < files.size(); ++f) {
      auto& p = cursor[f];
      while (p < files[f].count() && files[f].time(p) < t - tolerance) ++p;
      if (p < files[f].count() && std::abs(files[f].time(p) - t) <= tolerance) continue;
      if (unmatched[f]++ == 0) firstUnmatched[f] = line;
      if (missing.empty()) missing = files[f].name();
    }
    if (!missing.empty()) {
      dropped.add("no valid sample of " + missing + " at this time", line);
      continue;
    }
    keptRows.push_back(r);
    for (std::size_t f = 0; f < files.size(); ++f) matches[f].push_back(cursor[f]);
  }
  for (std::size_t f = 0; f < files.size(); ++f) {
    if (unmatched[f] > std::max<std::size_t>(2, static_cast<std::size_t>(kUnmatchedFraction * consideredRows))) {
      throw Error(reference.at(firstUnmatched[f]) + ": " + files[f].name() + " has no sample within " +
                  seconds(tolerance) + " of this row's time, nor of " + std::to_string(unmatched[f] - 1) +
                  " other rows: the files run on different clocks");
    }
  }

  Log log;
  log.source = folder;
  log.quality.dataRows = reference.dataRows;  // = its bad rows + rows outside the span + unmatched + kept
  log.quality.keptRows = keptRows.size();
  log.quality.dropped = reference.dropped;
  for (auto& d : dropped.take()) log.quality.dropped.push_back(std::move(d));
  if (keptRows.empty()) throw Error(folder.string() + ": no valid rows: " + log.quality.summary());
  const auto rows = static_cast<Eigen::Index>(keptRows.size());
  log.time.resize(rows);
  for (Eigen::Index k = 0; k < rows; ++k) {
    log.time[k] = reference.time(keptRows[static_cast<std::size_t>(k)]);
    log.lines.push_back(reference.lines[keptRows[static_cast<std::size_t>(k)]]);
  }
  for (std::size_t f = 0; f < files.size(); ++f) {
    const auto& file = files[f];
    if (file.vector) {
      Eigen::MatrixXd values(rows, file.width - 1);
      for (Eigen::Index k = 0; k < rows; ++k) {
        for (int j = 0; j + 1 < file.width; ++j) values(k, j) = file.value(matches[f][static_cast<std::size_t>(k)], j);
      }
      log.vectors[file.signal] = std::move(values);
    } else {
      Eigen::VectorXd values(rows);
      for (Eigen::Index k = 0; k < rows; ++k) values[k] = file.value(matches[f][static_cast<std::size_t>(k)], 0);
      log.scalars[file.signal] = std::move(values);
    }
    if (&file != &reference && !file.dropped.empty()) {
      LogQuality own;
      own.dataRows = file.dataRows;
      own.keptRows = file.count();
      own.dropped = file.dropped;
      log.quality.notes.push_back(file.name() + ": " + own.summary());
    }
  }
  std::vector<std::string> names;
  for (const auto& file : files) names.push_back(file.name());
  log.quality.notes.push_back("one file per signal (" + detail::joinNames(names) + "), aligned on the time of " +
                              reference.name() + " (a sample every " + seconds(step) + "), " + seconds(start) + " to " +
                              seconds(end) + ": the time every file covers");
  return log;
}

}  // namespace arcplan::model
