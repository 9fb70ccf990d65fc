#pragma once
// Robot logs as arcplan reads and writes them: RTDE CSV (UR's record.py, space-separated, or
// ur_rtde, comma-separated; a header row with vectors expanded as name_0..name_5), headerless
// logs read through an explicit column map, and run folders of one CSV per signal (log_folder.h). Rows that cannot be
// trusted (short, unparseable, NaN/inf, corrupted magnitudes, duplicated or backward timestamps) are dropped and
// reported with their line numbers, never used.
#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace arcplan::model {

// One reason rows were dropped, with how many and where (1-based line numbers in the file).
struct DroppedRows {
  std::string reason;
  std::size_t count = 0;
  std::vector<std::size_t> firstLines;  // at most kReportedLines of them
  static constexpr std::size_t kReportedLines = 5;
};

struct LogQuality {
  std::size_t dataRows = 0;  // rows after the header
  std::size_t keptRows = 0;
  std::vector<DroppedRows> dropped;
  std::vector<std::string> notes;  // e.g. which signals were derived and how
  // "kept 29998 of 30000 rows; dropped 2 (duplicate timestamp: 1, lines 17; ...)"
  std::string summary() const;
};

// A measured log: time plus named signals. Vector signals (one value per joint) are stored as
// rows x joints matrices under their RTDE name without the index ("actual_q").
struct Log {
  std::filesystem::path source;
  Eigen::VectorXd time;
  std::map<std::string, Eigen::MatrixXd> vectors;
  std::map<std::string, Eigen::VectorXd> scalars;
  std::vector<std::size_t> lines;  // source line of every kept row
  LogQuality quality;

  std::size_t rows() const { return static_cast<std::size_t>(time.size()); }
  int jointCount() const;  // columns of the vector signals (all equal, checked on reading)
  bool has(const std::string& signal) const { return vectors.count(signal) > 0; }
  // Throws arcplan::Error naming the file and the signal when absent.
  const Eigen::MatrixXd& vector(const std::string& signal) const;
  // Why `signal` is absent, naming the file (or, for a run folder, the file names it would have).
  std::string missing(const std::string& signal) const;
};

// The RTDE joint signals arcplan understands (docs/model.md, "Inputs"), and its scalar ones. Other header
// columns (TCP pose, robot mode, ...) are skipped.
const std::vector<std::string>& knownVectorSignals();
const std::vector<std::string>& knownScalarSignals();

// Where each signal sits in a headerless row. Columns are 0-based here; the text form is 1-based
// like the README of the real logs: "timestamp=1, actual_q=2-7, actual_qd=8-13, ...".
struct ColumnMap {
  struct Entry {
    std::string signal;
    std::vector<int> columns;  // one per joint for vectors, one for scalars / timestamp
  };
  std::vector<Entry> entries;
  int width() const;  // 1 + the largest column used
};

// Parses the text form, or a preset name: "ur10e_real" is the layout of the real UR10e logs in
// shared/data/ur10e_real (31 columns: time, q, qd, actual current, target current, target moment).
// Throws arcplan::Error for unknown signals, bad ranges, or a vector whose range is not one
// column per joint.
ColumnMap parseColumnMap(const std::string& text);
const std::vector<std::string>& columnMapPresets();

struct LogReadOptions {
  std::optional<ColumnMap> columns;  // required for headerless logs, ignored with a header
  // Keep only these 1-based file lines (inclusive); 0 = open end. Use it to cut the rest phases
  // at the start and end of a log.
  std::size_t firstLine = 0;
  std::size_t lastLine = 0;
  // A value larger than this in magnitude marks the row as corrupted (the real logs contain rows
  // with values around 1e280; no physical signal in a robot log comes near 1e12).
  double corruptMagnitude = 1e12;
};

// Reads an RTDE CSV or a headerless log, or a run folder of one CSV per signal (log_folder.h).
// Throws arcplan::Error when the file is missing or empty, when a column the map names does not
// exist, when vector signals disagree on the joint count, or when no valid row is left.
Log readLog(const std::filesystem::path& file, const LogReadOptions& options = {});

// A log from values already in memory (NumPy arrays from Python, another program's buffers): `time` in s,
// strictly increasing; every signal one row per time, under its RTDE name (knownVectorSignals: rows x joints, one
// joint count for all; knownScalarSignals: one column). Nothing is dropped, unlike in a file: a signal arcplan does
// not know, a row count or joint count that does not match, a NaN/inf or a corrupted magnitude, or a time that does
// not increase throws arcplan::Error naming `source`, the signal and the row (0-based). `Log::lines` stays empty.
Log makeLog(const std::string& source, Eigen::VectorXd time, std::map<std::string, Eigen::MatrixXd> signals,
            double corruptMagnitude = 1e12);

// "355-5090" -> lines 355..5090; "355-" open end. Throws arcplan::Error naming `what`.
std::pair<std::size_t, std::size_t> parseLineRange(const std::string& text, const std::string& what);

enum class CsvStyle { UrRtde, RecordPy };  // comma-separated, space-separated

// Writes the log as RTDE CSV with a header (timestamp, vectors as name_0..name_N, scalars),
// atomically.
void writeLog(const Log& log, const std::filesystem::path& file, CsvStyle style = CsvStyle::UrRtde);

}  // namespace arcplan::model
