// Logs built from values in memory (measurements.h, makeLog): the checks a file reader makes per row, as errors.
#include <cmath>
#include <string>

#include "arcplan/common/error.h"
#include "arcplan/model/measurements.h"
#include "log_reading.h"

namespace arcplan::model {
namespace {

// The first value of `values` that is NaN/inf or of corrupted magnitude, as "row R, column C is nan".
std::string badValue(const Eigen::MatrixXd& values, double corruptMagnitude) {
  for (Eigen::Index r = 0; r < values.rows(); ++r) {
    for (Eigen::Index c = 0; c < values.cols(); ++c) {
      const double x = values(r, c);
      if (std::isfinite(x) && std::abs(x) <= corruptMagnitude) continue;
      const std::string where = "row " + std::to_string(r) + (values.cols() > 1 ? ", column " + std::to_string(c) : "");
      return where + " is " +
             (std::isfinite(x) ? "corrupted (|x| > " + std::to_string(corruptMagnitude) + ")"
                               : std::string(std::isnan(x) ? "NaN" : "infinite"));
    }
  }
  return {};
}

void checkTime(const std::string& source, const Eigen::VectorXd& time, double corruptMagnitude) {
  if (time.size() == 0) throw Error(source + ": time: no rows (empty log)");
  if (const auto bad = badValue(time, corruptMagnitude); !bad.empty()) throw Error(source + ": time: " + bad);
  for (Eigen::Index r = 1; r < time.size(); ++r) {
    if (!(time[r] > time[r - 1])) {
      throw Error(source + ": time: row " + std::to_string(r) + " (" + std::to_string(time[r]) +
                  " s) does not follow row " + std::to_string(r - 1) + " (" + std::to_string(time[r - 1]) +
                  " s): the time must increase");
    }
  }
}

}  // namespace

Log makeLog(const std::string& source, Eigen::VectorXd time, std::map<std::string, Eigen::MatrixXd> signals,
            double corruptMagnitude) {
  checkTime(source, time, corruptMagnitude);
  Log log;
  log.source = source;
  std::string firstVector;
  for (auto& [name, values] : signals) {
    const bool vector = detail::isKnownVector(name);
    if (!vector && !detail::isKnownScalar(name)) {
      throw Error(source + ": unknown signal '" + name + "' (known: " + detail::joinNames(knownVectorSignals()) + ", " +
                  detail::joinNames(knownScalarSignals()) + ")");
    }
    if (values.rows() != time.size()) {
      throw Error(source + ": " + name + ": " + std::to_string(values.rows()) + " rows, but the time has " +
                  std::to_string(time.size()));
    }
    if (const auto bad = badValue(values, corruptMagnitude); !bad.empty())
      throw Error(source + ": " + name + ": " + bad);
    if (!vector) {
      if (values.cols() != 1) {
        throw Error(source + ": " + name + ": a scalar signal has one column, got " + std::to_string(values.cols()));
      }
      log.scalars[name] = values.col(0);
      continue;
    }
    if (values.cols() == 0) throw Error(source + ": " + name + ": no columns; expected one per joint");
    if (firstVector.empty()) {
      firstVector = name;
    } else if (values.cols() != log.vectors.at(firstVector).cols()) {
      throw Error(source + ": mismatched joint count: " + firstVector + " has " +
                  std::to_string(log.vectors.at(firstVector).cols()) + " columns but " + name + " has " +
                  std::to_string(values.cols()));
    }
    log.vectors[name] = std::move(values);
  }
  if (log.vectors.empty()) {
    throw Error(source + ": no joint signal (one of " + detail::joinNames(knownVectorSignals()) + ")");
  }
  log.time = std::move(time);
  log.quality.dataRows = log.quality.keptRows = log.rows();
  return log;
}

}  // namespace arcplan::model
