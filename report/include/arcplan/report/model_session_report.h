#pragma once
// The model session report: the error after every step (session.json), measured vs predicted per
// channel and the residual against the signals (the latest *_series.csv of the fitted data and of
// the validation data), the worst windows (compare.json), the diagnosis ranking with its
// explanations (diagnose_ranking.json) and the model-file lines that add the suggested effects.
#include <filesystem>

#include <nlohmann/json.hpp>

namespace arcplan::report {

struct ModelReportOptions {
  std::size_t maxSamplesPerChannel = 1500;  // keeps a 60 s × 500 Hz log's report small
};

// Throws arcplan::Error when `session` has no session.json or a file in it cannot be read; parts
// that are absent (no diagnosis yet) are listed under "missing".
nlohmann::json modelSessionReportData(const std::filesystem::path& session, const ModelReportOptions& options = {});

}  // namespace arcplan::report
