#include "arcplan/model/measurements.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "arcplan/common/atomic_file.h"
#include "arcplan/common/error.h"
#include "arcplan/common/text_parsing.h"
#include "arcplan/model/log_folder.h"
#include "log_reading.h"

namespace arcplan::model {
namespace {

using detail::isBlank;
using detail::isKnownScalar;
using detail::isKnownVector;
using detail::joinNames;

// Where the values of one signal come from in a row.
struct ColumnSource {
  std::string signal;  // "timestamp", a vector or a scalar name
  int joint = -1;      // -1 for timestamp / scalars
  int column = 0;      // 0-based field index
};

// Header fields -> column sources; vector signals must be name_0..name_{N-1} with one N for all.
std::vector<ColumnSource> mapHeader(const std::vector<std::string_view>& header, const std::filesystem::path& file) {
  std::vector<ColumnSource> sources;
  std::map<std::string, std::vector<int>> vectorColumns;  // signal -> column per joint index
  bool hasTimestamp = false;
  for (std::size_t c = 0; c < header.size(); ++c) {
    const std::string name(trim(header[c]));
    if (name == "timestamp") {
      sources.push_back({name, -1, static_cast<int>(c)});
      hasTimestamp = true;
      continue;
    }
    if (isKnownScalar(name)) {
      sources.push_back({name, -1, static_cast<int>(c)});
      continue;
    }
    const auto underscore = name.rfind('_');
    if (underscore == std::string::npos || underscore + 1 == name.size()) continue;
    const std::string base = name.substr(0, underscore), index = name.substr(underscore + 1);
    if (!isKnownVector(base) || index.size() > 3 || !std::all_of(index.begin(), index.end(), ::isdigit)) continue;
    const int joint = std::stoi(index);
    auto& columns = vectorColumns[base];
    if (static_cast<int>(columns.size()) <= joint) columns.resize(joint + 1, -1);
    if (columns[joint] >= 0) throw Error(file.string() + ": header names column '" + name + "' twice");
    columns[joint] = static_cast<int>(c);
  }
  if (!hasTimestamp) throw Error(file.string() + ": the header has no 'timestamp' column");
  int joints = -1;
  std::string firstVector;
  for (const auto& [signal, columns] : vectorColumns) {
    for (std::size_t j = 0; j < columns.size(); ++j) {
      if (columns[j] < 0) {
        throw Error(file.string() + ": header has " + signal + "_" + std::to_string(columns.size() - 1) + " but no " +
                    signal + "_" + std::to_string(j));
      }
    }
    if (joints < 0) {
      joints = static_cast<int>(columns.size());
      firstVector = signal;
    } else if (static_cast<int>(columns.size()) != joints) {
      throw Error(file.string() + ": mismatched joint count: " + firstVector + " has " + std::to_string(joints) +
                  " joints but " + signal + " has " + std::to_string(columns.size()));
    }
    for (std::size_t j = 0; j < columns.size(); ++j) sources.push_back({signal, static_cast<int>(j), columns[j]});
  }
  return sources;
}

std::vector<ColumnSource> sourcesFromMap(const ColumnMap& map) {
  std::vector<ColumnSource> sources;
  for (const auto& entry : map.entries) {
    if (entry.signal == "timestamp" || isKnownScalar(entry.signal)) {
      sources.push_back({entry.signal, -1, entry.columns.front()});
    } else {
      for (std::size_t j = 0; j < entry.columns.size(); ++j) {
        sources.push_back({entry.signal, static_cast<int>(j), entry.columns[j]});
      }
    }
  }
  return sources;
}

void appendNumber(std::string& out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, result.ptr);
}

}  // namespace

std::string LogQuality::summary() const {
  std::ostringstream text;
  text << "kept " << keptRows << " of " << dataRows << " rows";
  std::size_t droppedTotal = 0;
  for (const auto& d : dropped) droppedTotal += d.count;
  if (droppedTotal > 0) {
    text << "; dropped " << droppedTotal << " (";
    for (std::size_t i = 0; i < dropped.size(); ++i) {
      text << (i ? "; " : "") << dropped[i].reason << ": " << dropped[i].count << ", line"
           << (dropped[i].firstLines.size() > 1 ? "s " : " ");
      for (std::size_t k = 0; k < dropped[i].firstLines.size(); ++k) text << (k ? "," : "") << dropped[i].firstLines[k];
      if (dropped[i].count > dropped[i].firstLines.size()) text << ",...";
    }
    text << ")";
  }
  return text.str();
}

int Log::jointCount() const { return vectors.empty() ? 0 : static_cast<int>(vectors.begin()->second.cols()); }

const Eigen::MatrixXd& Log::vector(const std::string& signal) const {
  const auto it = vectors.find(signal);
  if (it == vectors.end()) throw Error(missing(signal));
  return it->second;
}

std::string Log::missing(const std::string& signal) const {
  std::vector<std::string> present;
  if (std::filesystem::is_directory(source)) {
    for (const auto& [name, values] : vectors) present.push_back(name);
    return source.string() + ": no file of signal " + signal + " (" + joinNames(folderFileNames(signal)) +
           "); the folder has " + (present.empty() ? std::string("no joint signals") : joinNames(present));
  }
  for (const auto& [name, values] : vectors) present.push_back(name + "_*");
  return source.string() + ": the log has no " + signal +
         "_* columns (it has: " + (present.empty() ? std::string("no joint signals") : joinNames(present)) + ")";
}

const std::vector<std::string>& knownVectorSignals() {
  static const std::vector<std::string> names{
      "target_q", "target_qd", "target_qdd", "target_current", "target_moment", "actual_q", "actual_qd",
      "actual_current", "joint_temperatures",
      // Newer controllers also send the measured current converted to a joint torque (N·m).
      "actual_current_as_torque"};
  return names;
}

const std::vector<std::string>& knownScalarSignals() {
  static const std::vector<std::string> names{"speed_scaling", "runtime_state"};
  return names;
}

int ColumnMap::width() const {
  int width = 0;
  for (const auto& entry : entries) {
    for (int c : entry.columns) width = std::max(width, c + 1);
  }
  return width;
}

const std::vector<std::string>& columnMapPresets() {
  static const std::vector<std::string> presets{"ur10e_real"};
  return presets;
}

ColumnMap parseColumnMap(const std::string& text) {
  if (trim(text) == "ur10e_real") {
    return parseColumnMap(
        "timestamp=1, actual_q=2-7, actual_qd=8-13, actual_current=14-19, target_current=20-25, target_moment=26-31");
  }
  ColumnMap map;
  std::string normalized = text;
  std::replace(normalized.begin(), normalized.end(), ';', ',');
  std::replace(normalized.begin(), normalized.end(), '\n', ',');
  int joints = -1;
  std::string firstVector;
  for (const auto field : splitFields(normalized, ',')) {
    const auto entryText = trim(field);
    if (entryText.empty()) continue;
    const auto equals = entryText.find('=');
    if (equals == std::string_view::npos) {
      throw Error("column map entry '" + std::string(entryText) +
                  "': expected signal=column or signal=first-last (1-based), or a preset (" +
                  joinNames(columnMapPresets()) + ")");
    }
    const std::string signal(trim(entryText.substr(0, equals)));
    const std::string range(trim(entryText.substr(equals + 1)));
    const bool scalar = signal == "timestamp" || isKnownScalar(signal);
    if (!scalar && !isKnownVector(signal)) {
      throw Error("column map: unknown column '" + signal + "' (known: timestamp, " + joinNames(knownVectorSignals()) +
                  ", " + joinNames(knownScalarSignals()) + ")");
    }
    const auto dash = range.find('-');
    const auto first = parseDouble(range.substr(0, dash));
    const auto last = dash == std::string::npos ? first : parseDouble(range.substr(dash + 1));
    if (!first || !last || *first < 1 || *last < *first || *first != std::floor(*first) || *last != std::floor(*last) ||
        *last > 100000 || *last - *first >= 1000) {
      throw Error("column map entry '" + std::string(entryText) + "': expected 1-based columns like 2 or 2-7");
    }
    ColumnMap::Entry entry{signal, {}};
    for (int c = static_cast<int>(*first); c <= static_cast<int>(*last); ++c) entry.columns.push_back(c - 1);
    if (scalar && entry.columns.size() != 1) {
      throw Error("column map entry '" + std::string(entryText) + "': " + signal + " is a single column");
    }
    if (!scalar) {
      if (joints < 0) {
        joints = static_cast<int>(entry.columns.size());
        firstVector = signal;
      } else if (static_cast<int>(entry.columns.size()) != joints) {
        throw Error("column map: mismatched joint count: " + firstVector + " spans " + std::to_string(joints) +
                    " columns but " + signal + " spans " + std::to_string(entry.columns.size()));
      }
    }
    for (const auto& existing : map.entries) {
      if (existing.signal == signal) throw Error("column map names '" + signal + "' twice");
    }
    map.entries.push_back(std::move(entry));
  }
  const bool hasTime =
      std::any_of(map.entries.begin(), map.entries.end(), [](const auto& e) { return e.signal == "timestamp"; });
  if (!hasTime) throw Error("column map '" + text + "' has no timestamp column");
  return map;
}

std::pair<std::size_t, std::size_t> parseLineRange(const std::string& text, const std::string& what) {
  const auto dash = text.find('-');
  const auto first = parseDouble(text.substr(0, dash));
  std::optional<double> last = 0.0;
  if (dash != std::string::npos && !trim(text.substr(dash + 1)).empty()) last = parseDouble(text.substr(dash + 1));
  if (dash == std::string::npos || !first || !last || *first < 1 || *first > 1e12 || *last > 1e12 ||
      *first != std::floor(*first) || *last != std::floor(*last) || (*last != 0.0 && *last < *first)) {
    throw Error(what + ": expected a 1-based line range FIRST-LAST or FIRST-, got '" + text + "'");
  }
  return {static_cast<std::size_t>(*first), static_cast<std::size_t>(*last)};
}

Log readLog(const std::filesystem::path& file, const LogReadOptions& options) {
  if (std::filesystem::is_directory(file)) return readLogFolder(file, options);
  detail::LineReader reader(file);
  std::string firstLine;
  bool found = false;
  while (!found && reader.next(firstLine)) found = !isBlank(firstLine) && trim(firstLine).front() != '#';
  if (!found) throw Error(file.string() + " is empty: no header and no data rows");
  const std::size_t firstLineNumber = reader.lineNumber();

  const char separator = firstLine.find(',') != std::string_view::npos ? ',' : ' ';
  const auto firstFields = splitFields(firstLine, separator);
  const bool hasHeader = std::any_of(firstFields.begin(), firstFields.end(),
                                     [](std::string_view f) { return !parseDouble(f).has_value(); });

  std::vector<ColumnSource> sources;
  std::size_t expectedFields = 0;  // header logs: exactly the header width; headerless: at least the map width
  if (hasHeader) {
    sources = mapHeader(firstFields, file);
    expectedFields = firstFields.size();
  } else {
    if (!options.columns) {
      throw Error(file.string() +
                  " has no header row; give a column map (--columns), e.g. 'ur10e_real' or "
                  "'timestamp=1, actual_q=2-7, actual_qd=8-13, actual_current=14-19'");
    }
    sources = sourcesFromMap(*options.columns);
    expectedFields = static_cast<std::size_t>(options.columns->width());
    if (firstFields.size() < expectedFields) {
      throw Error(file.string() + ": the column map uses column " + std::to_string(expectedFields) +
                  " but the first row (line " + std::to_string(firstLineNumber) + ") has only " +
                  std::to_string(firstFields.size()) + " columns: unknown column");
    }
  }

  // Values are gathered per source column, then moved into the log's matrices.
  std::vector<std::vector<double>> values(sources.size());
  std::vector<std::size_t> keptLines;
  detail::DropCounter dropped;
  std::size_t dataRows = 0;
  int timestampSource = -1;
  for (std::size_t s = 0; s < sources.size(); ++s) {
    if (sources[s].signal == "timestamp") timestampSource = static_cast<int>(s);
  }
  double lastTime = -std::numeric_limits<double>::infinity();
  std::vector<double> row(sources.size());
  // A headerless log's first line is already its first data row.
  std::string line = hasHeader ? std::string() : firstLine;
  bool haveLine = !hasHeader;
  for (; haveLine || reader.next(line); haveLine = false) {
    const std::size_t lineNumber = reader.lineNumber();
    if (isBlank(line)) continue;
    if (options.firstLine > 0 && lineNumber < options.firstLine) continue;
    if (options.lastLine > 0 && lineNumber > options.lastLine) break;
    ++dataRows;
    const auto fields = splitFields(line, separator);
    if (hasHeader ? fields.size() != expectedFields : fields.size() < expectedFields) {
      dropped.add(fields.size() < expectedFields ? "short row" : "too many fields", lineNumber);
      continue;
    }
    const char* problem = nullptr;
    for (std::size_t s = 0; s < sources.size() && !problem; ++s) {
      problem = detail::valueProblem(fields[sources[s].column], options.corruptMagnitude, row[s]);
    }
    if (problem) {
      dropped.add(problem, lineNumber);
      continue;
    }
    if (row[timestampSource] <= lastTime) {
      dropped.add("duplicate or backward timestamp", lineNumber);
      continue;
    }
    lastTime = row[timestampSource];
    for (std::size_t s = 0; s < sources.size(); ++s) values[s].push_back(row[s]);
    keptLines.push_back(lineNumber);
  }

  Log log;
  log.source = file;
  log.quality.dataRows = dataRows;
  log.quality.keptRows = keptLines.size();
  log.quality.dropped = dropped.take();
  if (dataRows == 0) throw Error(file.string() + " has no data rows (empty log)");
  if (keptLines.empty()) throw Error(file.string() + ": no valid rows: " + log.quality.summary());
  const auto rows = static_cast<Eigen::Index>(keptLines.size());
  log.lines = std::move(keptLines);
  std::map<std::string, int> jointCounts;
  for (const auto& source : sources) {
    if (source.joint >= 0) jointCounts[source.signal] = std::max(jointCounts[source.signal], source.joint + 1);
  }
  for (const auto& [signal, joints] : jointCounts) log.vectors[signal] = Eigen::MatrixXd(rows, joints);
  for (std::size_t s = 0; s < sources.size(); ++s) {
    const Eigen::Map<const Eigen::VectorXd> column(values[s].data(), rows);
    if (sources[s].signal == "timestamp") {
      log.time = column;
    } else if (sources[s].joint < 0) {
      log.scalars[sources[s].signal] = column;
    } else {
      log.vectors[sources[s].signal].col(sources[s].joint) = column;
    }
    std::vector<double>().swap(values[s]);  // release each column once copied: big logs never hold two copies
  }
  return log;
}

void writeLog(const Log& log, const std::filesystem::path& file, CsvStyle style) {
  const char separator = style == CsvStyle::UrRtde ? ',' : ' ';
  std::vector<std::string> vectorOrder;
  for (const auto& name : knownVectorSignals()) {
    if (log.vectors.count(name)) vectorOrder.push_back(name);
  }
  for (const auto& [name, values] : log.vectors) {
    if (std::find(vectorOrder.begin(), vectorOrder.end(), name) == vectorOrder.end()) vectorOrder.push_back(name);
  }
  AtomicOutputFile out(file);
  std::string text = "timestamp";
  for (const auto& name : vectorOrder) {
    for (Eigen::Index j = 0; j < log.vectors.at(name).cols(); ++j) text += separator + name + "_" + std::to_string(j);
  }
  for (const auto& [name, values] : log.scalars) text += separator + name;
  text += '\n';
  out.stream() << text;
  // Row by row: an hour at 500 Hz is gigabytes of text, never built whole.
  for (std::size_t r = 0; r < log.rows(); ++r) {
    text.clear();
    appendNumber(text, log.time[static_cast<Eigen::Index>(r)]);
    for (const auto& name : vectorOrder) {
      const auto& matrix = log.vectors.at(name);
      for (Eigen::Index j = 0; j < matrix.cols(); ++j) {
        text += separator;
        appendNumber(text, matrix(static_cast<Eigen::Index>(r), j));
      }
    }
    for (const auto& [name, values] : log.scalars) {
      text += separator;
      appendNumber(text, values[static_cast<Eigen::Index>(r)]);
    }
    text += '\n';
    out.stream() << text;
  }
  out.commit();
}

}  // namespace arcplan::model
