#include "arcplan/model/compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numeric>

#include "arcplan/model/term_library.h"

namespace arcplan::model {
namespace {

constexpr std::size_t kReportedCorrelations = 50;  // the strongest; the library has ~270 terms per channel

double standardDeviation(const Eigen::VectorXd& values) {
  if (values.size() == 0) return 0.0;
  return std::sqrt((values.array() - values.mean()).square().mean());
}

// Scale that turns a channel's residual into a normalised one: the spread of what it predicts.
double channelScale(const Eigen::VectorXd& measured) {
  const double spread = standardDeviation(measured);
  return spread > 1e-12 ? spread : 1.0;
}

std::string formatNumber(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.3g", value);
  return buffer;
}

RegimeBin summarize(const std::string& label, const Eigen::VectorXd& residual,
                    const std::vector<Eigen::Index>& members) {
  RegimeBin bin;
  bin.label = label;
  bin.count = static_cast<Eigen::Index>(members.size());
  if (members.empty()) return bin;
  double sum = 0.0, squares = 0.0;
  for (auto i : members) {
    sum += residual[i];
    squares += residual[i] * residual[i];
  }
  bin.meanResidual = sum / static_cast<double>(members.size());
  bin.rmsResidual = std::sqrt(squares / static_cast<double>(members.size()));
  return bin;
}

// Quartile bins of key(i) over the candidate samples.
Regime quartileRegime(const std::string& name, const std::string& unit, const Eigen::VectorXd& residual,
                      const std::vector<Eigen::Index>& candidates, const std::function<double(Eigen::Index)>& key) {
  Regime regime{name, {}};
  if (candidates.size() < 8) return regime;
  std::vector<double> values;
  for (auto i : candidates) values.push_back(key(i));
  std::vector<double> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  std::vector<double> edges{sorted.front()};
  for (int q = 1; q < 4; ++q) edges.push_back(sorted[sorted.size() * static_cast<std::size_t>(q) / 4]);
  edges.push_back(sorted.back());
  for (int b = 0; b < 4; ++b) {
    if (b > 0 && edges[b] == edges[b + 1] && edges[b] == edges[b - 1]) continue;
    std::vector<Eigen::Index> members;
    for (std::size_t k = 0; k < candidates.size(); ++k) {
      const bool inside = values[k] >= edges[b] && (b == 3 ? values[k] <= edges[b + 1] : values[k] < edges[b + 1]);
      if (inside) members.push_back(candidates[k]);
    }
    if (members.empty()) continue;
    regime.bins.push_back(
        summarize(formatNumber(edges[b]) + " to " + formatNumber(edges[b + 1]) + " " + unit, residual, members));
  }
  return regime;
}

double pearson(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const Eigen::ArrayXd x = a.array() - a.mean(), y = b.array() - b.mean();
  const double denominator = std::sqrt((x * x).sum() * (y * y).sum());
  return denominator > 0.0 ? (x * y).sum() / denominator : 0.0;
}

}  // namespace

ErrorSummary errorSummary(const Dataset& data, const std::vector<Eigen::VectorXd>& predictions) {
  ErrorSummary summary;
  double sumSquares = 0.0;
  for (int c = 0; c < data.channelCount(); ++c) {
    const Eigen::VectorXd& measured = data.measured(c);
    const Eigen::VectorXd residual = measured - predictions[static_cast<std::size_t>(c)];
    ChannelError error;
    error.channel = data.channelName(c);
    error.samples = measured.size();
    error.rmse = std::sqrt(residual.squaredNorm() / static_cast<double>(measured.size()));
    error.nrmse = error.rmse / channelScale(measured);
    const double total = (measured.array() - measured.mean()).square().sum();
    error.r2 = total > 0.0 ? 1.0 - residual.squaredNorm() / total : 0.0;
    sumSquares += error.nrmse * error.nrmse;
    summary.channels.push_back(error);
  }
  summary.overallNrmse = data.channelCount() > 0 ? std::sqrt(sumSquares / data.channelCount()) : 0.0;
  return summary;
}

std::vector<WorstWindow> worstWindows(const Dataset& data, const std::vector<Eigen::VectorXd>& residuals,
                                      std::size_t count) {
  struct Candidate {
    double start, end, score;
    std::string channel;
    Eigen::Index first, last;
    int group;
  };
  std::vector<Candidate> candidates;
  if (data.timeOrdered()) {
    // All channels share the time base: windows of a 50th of the log (0.5–5 s), half overlapping.
    const auto& time = data.signal("time", 0);
    const Eigen::Index n = time.size();
    const double duration = time[n - 1] - time[0];
    const double length = std::clamp(duration / 50.0, 0.5, 5.0);
    Eigen::Index first = 0;
    while (first < n) {
      Eigen::Index last = first;
      while (last + 1 < n && time[last + 1] - time[first] < length) ++last;
      double squares = 0.0, worst = -1.0;
      std::string worstChannel;
      for (int c = 0; c < data.channelCount(); ++c) {
        const double scale = channelScale(data.measured(c));
        const double channelSquares = residuals[c].segment(first, last - first + 1).squaredNorm() / (scale * scale);
        squares += channelSquares;
        if (channelSquares > worst) {
          worst = channelSquares;
          worstChannel = data.channelName(c);
        }
      }
      const double score = std::sqrt(squares / static_cast<double>((last - first + 1) * data.channelCount()));
      candidates.push_back({time[first], time[last], score, worstChannel, first, last, 0});
      if (last + 1 >= n) break;
      Eigen::Index next = first;
      while (next < last && time[next] - time[first] < 0.5 * length) ++next;
      first = std::max(next, first + 1);
    }
  } else {
    // Without time (gearbox data): per channel, windows of 5 consecutive points in order of load.
    for (int c = 0; c < data.channelCount(); ++c) {
      const auto& tau = data.signal("tau", c);
      std::vector<Eigen::Index> order(static_cast<std::size_t>(tau.size()));
      std::iota(order.begin(), order.end(), 0);
      std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) { return tau[a] < tau[b]; });
      const double scale = channelScale(data.measured(c));
      const std::size_t width = std::min<std::size_t>(5, order.size());
      for (std::size_t k = 0; k + width <= order.size(); ++k) {
        double squares = 0.0;
        for (std::size_t m = k; m < k + width; ++m) squares += std::pow(residuals[c][order[m]] / scale, 2);
        candidates.push_back({tau[order[k]], tau[order[k + width - 1]], std::sqrt(squares / width), data.channelName(c),
                              static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(k + width - 1), c});
      }
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) { return a.score > b.score; });
  std::vector<Candidate> chosen;
  for (const auto& candidate : candidates) {
    const bool overlaps = std::any_of(chosen.begin(), chosen.end(), [&](const Candidate& c) {
      return c.group == candidate.group && candidate.first <= c.last && c.first <= candidate.last;
    });
    if (!overlaps) chosen.push_back(candidate);
    if (chosen.size() == count) break;
  }
  std::vector<WorstWindow> windows;
  for (const auto& c : chosen) windows.push_back({c.start, c.end, c.score, c.channel});
  return windows;
}

std::vector<ChannelRegimes> residualRegimes(const Dataset& data, const std::vector<Eigen::VectorXd>& residuals) {
  std::vector<ChannelRegimes> result;
  const bool gearbox = data.kind() == ModelKind::GearboxFtd;
  const double rest = gearbox ? 0.0 : 5.0 * data.settings().velocitySmoothing;
  for (int c = 0; c < data.channelCount(); ++c) {
    ChannelRegimes channel{data.channelName(c), {}};
    const Eigen::VectorXd& residual = residuals[c];
    const Eigen::Index n = residual.size();
    const auto& qd = data.signal("qd", c);
    std::vector<Eigen::Index> positive, negative, resting, moving;
    for (Eigen::Index i = 0; i < n; ++i) {
      if (qd[i] > rest) {
        positive.push_back(i);
      } else if (qd[i] < -rest) {
        negative.push_back(i);
      } else {
        resting.push_back(i);
      }
      if (std::abs(qd[i]) > rest) moving.push_back(i);
    }
    Regime direction{"direction", {}};
    for (const auto& [label, members] :
         {std::pair{gearbox ? "direct" : "qd > 0", positive}, std::pair{gearbox ? "indirect" : "qd < 0", negative},
          std::pair{"at rest", resting}}) {
      if (!members.empty()) direction.bins.push_back(summarize(label, residual, members));
    }
    channel.regimes.push_back(direction);
    const bool hasLoad = data.hasSignal("tau");
    if (hasLoad) {
      const auto& tau = data.signal("tau", c);
      std::vector<Eigen::Index> motoring, regenerating;
      for (auto i : moving) (tau[i] * qd[i] > 0.0 ? motoring : regenerating).push_back(i);
      Regime power{"power_flow", {}};
      if (!motoring.empty()) power.bins.push_back(summarize("motoring (tau·qd > 0)", residual, motoring));
      if (!regenerating.empty()) power.bins.push_back(summarize("regenerating (tau·qd < 0)", residual, regenerating));
      channel.regimes.push_back(power);
    }
    std::vector<Eigen::Index> all(static_cast<std::size_t>(n));
    std::iota(all.begin(), all.end(), 0);
    if (!gearbox) {
      channel.regimes.push_back(
          quartileRegime("speed", "rad/s", residual, moving, [&](Eigen::Index i) { return std::abs(qd[i]); }));
    }
    if (hasLoad) {
      const auto& tau = data.signal("tau", c);
      channel.regimes.push_back(
          quartileRegime("load", "N·m", residual, all, [&](Eigen::Index i) { return std::abs(tau[i]); }));
    }
    if (data.hasSignal("temperature")) {
      const auto& temperature = data.signal("temperature", c);
      channel.regimes.push_back(
          quartileRegime("temperature", "°C", residual, all, [&](Eigen::Index i) { return temperature[i]; }));
    }
    if (data.hasSignal("q")) {
      const auto& q = data.signal("q", c);
      channel.regimes.push_back(
          quartileRegime("joint_angle", "rad", residual, all, [&](Eigen::Index i) { return q[i]; }));
    }
    result.push_back(std::move(channel));
  }
  return result;
}

std::vector<ResidualCorrelation> residualCorrelations(const Dataset& data,
                                                      const std::vector<Eigen::VectorXd>& residuals, double minimum) {
  // Every joint's signals and their transforms (term_library.h), not only the channel's own.
  std::vector<ResidualCorrelation> result;
  for (int c = 0; c < data.channelCount(); ++c) {
    for (const auto& term : candidateTerms(data, c)) {
      const double r = pearson(residuals[c], evaluateTerm(term, data, c));
      if (std::abs(r) >= minimum) result.push_back({data.channelName(c), term.expression, r});
    }
  }
  std::stable_sort(result.begin(), result.end(),
                   [](const auto& a, const auto& b) { return std::abs(a.correlation) > std::abs(b.correlation); });
  if (result.size() > kReportedCorrelations) result.resize(kReportedCorrelations);
  return result;
}

Comparison compareModel(const FittedModel& model, const Dataset& data, const Dataset* validation) {
  Comparison comparison;
  const auto predictions = predictAll(model, data);
  comparison.data = errorSummary(data, predictions);
  const Dataset* failures = &data;
  std::vector<Eigen::VectorXd> failurePredictions = predictions;
  if (validation) {
    failurePredictions = predictAll(model, *validation);
    comparison.validation = errorSummary(*validation, failurePredictions);
    failures = validation;
  }
  comparison.failuresOn = validation ? "validation" : "data";
  std::vector<Eigen::VectorXd> residuals;
  for (int c = 0; c < failures->channelCount(); ++c) residuals.push_back(failures->measured(c) - failurePredictions[c]);
  comparison.worstWindows = worstWindows(*failures, residuals);
  comparison.events = findEvents(model, *failures, residuals);
  comparison.regimes = residualRegimes(*failures, residuals);
  comparison.strongestCorrelations = residualCorrelations(*failures, residuals);
  return comparison;
}

}  // namespace arcplan::model
