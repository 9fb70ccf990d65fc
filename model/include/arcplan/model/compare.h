#pragma once
// How well a fitted model predicts a dataset, and where it fails.
//
// Per channel: RMSE, normalised RMSE (RMSE / standard deviation of the measured values) and R²;
// overall NRMSE = root mean square of the channels' NRMSE. Where it fails: the time windows with
// the largest normalised residual, and the residual binned by regime (direction of motion,
// motoring vs regenerating, speed, load, temperature, joint angle), and events (events.h).
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "arcplan/model/dataset.h"
#include "arcplan/model/events.h"
#include "arcplan/model/fitting.h"

namespace arcplan::model {

struct ChannelError {
  std::string channel;
  double rmse = 0.0;
  double nrmse = 0.0;
  double r2 = 0.0;
  Eigen::Index samples = 0;
};

struct ErrorSummary {
  std::vector<ChannelError> channels;
  double overallNrmse = 0.0;
};

ErrorSummary errorSummary(const Dataset& data, const std::vector<Eigen::VectorXd>& predictions);

struct WorstWindow {
  double start = 0.0, end = 0.0;  // s (row indices for data without time)
  double nrmse = 0.0;             // RMS over channels of the residual / channel std, in the window
  std::string worstChannel;
};

struct RegimeBin {
  std::string label;
  Eigen::Index count = 0;
  double meanResidual = 0.0;
  double rmsResidual = 0.0;
};

struct Regime {
  std::string name;  // direction, power_flow, speed, load, temperature, joint_angle
  std::vector<RegimeBin> bins;
};

struct ChannelRegimes {
  std::string channel;
  std::vector<Regime> regimes;
};

// Pearson correlation of a channel's residual with one signal (or a function of it).
struct ResidualCorrelation {
  std::string channel;
  std::string signal;  // a term of term_library.h as an expression: "abs(qd)", "qd_1", "qd_0*qd_2"
  double correlation = 0.0;
};

struct Comparison {
  ErrorSummary data;
  std::optional<ErrorSummary> validation;
  std::string failuresOn;  // "validation" or "data": where windows and regimes were computed
  std::vector<WorstWindow> worstWindows;
  std::vector<Event> events;  // moments the residual leaves its noise band and comes back (events.h)
  std::vector<ChannelRegimes> regimes;
  std::vector<ResidualCorrelation> strongestCorrelations;  // |r| >= 0.1, the 50 strongest first
};

std::vector<WorstWindow> worstWindows(const Dataset& data, const std::vector<Eigen::VectorXd>& residuals,
                                      std::size_t count = 5);
std::vector<ChannelRegimes> residualRegimes(const Dataset& data, const std::vector<Eigen::VectorXd>& residuals);
std::vector<ResidualCorrelation> residualCorrelations(const Dataset& data,
                                                      const std::vector<Eigen::VectorXd>& residuals,
                                                      double minimum = 0.1);

// The model predicts `data` (and `validation`); failures are analysed on the validation data when
// given, else on `data`.
Comparison compareModel(const FittedModel& model, const Dataset& data, const Dataset* validation);

}  // namespace arcplan::model
