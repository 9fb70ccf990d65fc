#pragma once
// Run folders: one CSV per signal, the way UR's real-time interface is often logged (e.g. the UR5
// runs of shared/data/ur5_kufieta). Each file is `log_<signal>.csv` without a header: the time in s
// in column 1, then one column per joint (one value for a scalar signal), separated by commas
// (blanks around them allowed) or blanks. <signal> is an RTDE name (`log_actual_q.csv`,
// `log_target_moment.csv`, `log_actual_current_as_torque.csv`, ...) or the real-time interface's
// short name (`log_q_actual.csv`, `log_qd_actual.csv`, `log_q_target.csv`, `log_qd_target.csv`,
// `log_qdd_target.csv`, `log_i_actual.csv`, `log_i_target.csv`, `log_m_target.csv`). Files of
// other signals (TCP force, a force sensor on its own clock, start times) are skipped.
//
// The files are aligned on their time column. They must run on one clock (the same median step,
// samples within a quarter step of each other) and cover the same time: files written by one
// recorder stop a few cycles apart (the UR5 runs by up to 0.8 s), so up to max(1 s, 5 % of the run)
// at the ends is cut to the span every file covers and noted; more is an error. A time column that
// does not increase is an error naming the file and line. Rows that cannot be trusted (short,
// unparseable, NaN/inf, corrupted magnitudes) are dropped and reported as in an RTDE log.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "arcplan/model/measurements.h"

namespace arcplan::model {

// Reads the folder as one log on the time of its reference file (actual_q's when present, else the
// first signal of knownVectorSignals()); `Log::lines` are the reference file's lines.
// `options.firstLine/lastLine` keep the same lines of every file (one line per cycle in each);
// `options.columns` does not apply. Throws arcplan::Error naming the file and line.
Log readLogFolder(const std::filesystem::path& folder, const LogReadOptions& options = {});

// The signal a file name holds ("log_i_actual.csv" -> "actual_current"); nullopt for other files.
std::optional<std::string> folderSignal(const std::string& fileName);

// The file names that would hold `signal` in a run folder, the RTDE name first.
std::vector<std::string> folderFileNames(const std::string& signal);

}  // namespace arcplan::model
