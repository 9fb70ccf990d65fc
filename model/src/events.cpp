#include "arcplan/model/events.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <Eigen/QR>

#include "arcplan/model/diagnose.h"
#include "arcplan/robot/kinematics.h"

namespace arcplan::model {
namespace {

constexpr double kMadToSigma = 1.4826;      // robust scale of Gaussian noise from its median absolute deviation
constexpr double kWrenchHalfWindow = 0.04;  // s around the peak over which the tool force is fitted

double medianStep(const Eigen::VectorXd& time) {
  std::vector<double> steps(static_cast<std::size_t>(std::max<Eigen::Index>(time.size() - 1, 1)), 1.0);
  for (Eigen::Index k = 1; k < time.size(); ++k) steps[static_cast<std::size_t>(k - 1)] = time[k] - time[k - 1];
  std::nth_element(steps.begin(), steps.begin() + static_cast<long>(steps.size() / 2), steps.end());
  return steps[steps.size() / 2] > 0.0 ? steps[steps.size() / 2] : 1.0;
}

// Centred moving average over 2·half + 1 samples (fewer at the ends).
Eigen::VectorXd movingAverage(const Eigen::VectorXd& x, Eigen::Index half) {
  const Eigen::Index n = x.size();
  Eigen::VectorXd prefix(n + 1);
  prefix[0] = 0.0;
  for (Eigen::Index k = 0; k < n; ++k) prefix[k + 1] = prefix[k] + x[k];
  Eigen::VectorXd result(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Index a = std::max<Eigen::Index>(0, k - half), b = std::min(n - 1, k + half);
    result[k] = (prefix[b + 1] - prefix[a]) / static_cast<double>(b - a + 1);
  }
  return result;
}

double median(std::vector<double>& values) {
  const auto middle = values.begin() + static_cast<long>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// Median and robust scale of values[a..b].
std::pair<double, double> robustLevelAndScale(const Eigen::VectorXd& x, Eigen::Index a, Eigen::Index b,
                                              std::vector<double>& buffer) {
  buffer.assign(x.data() + a, x.data() + b + 1);
  const double level = median(buffer);
  for (auto& v : buffer) v = std::abs(v - level);
  return {level, kMadToSigma * median(buffer)};
}

struct Band {
  Eigen::VectorXd level, scale;
};

// Rolling median and robust scale over 2·half + 1 samples, evaluated every `hop` samples and
// interpolated linearly in between (an hour-long log would otherwise sort a window per sample).
Band rollingBand(const Eigen::VectorXd& x, Eigen::Index half, Eigen::Index hop) {
  const Eigen::Index n = x.size();
  std::vector<double> buffer;
  // Never narrower than the whole log's scale (events.h).
  const double floor = std::max(robustLevelAndScale(x, 0, n - 1, buffer).second, 1e-12);
  std::vector<Eigen::Index> grid;
  for (Eigen::Index g = 0; g < n - 1; g += hop) grid.push_back(g);
  grid.push_back(n - 1);
  std::vector<double> levels, scales;
  for (auto g : grid) {
    const auto [level, scale] =
        robustLevelAndScale(x, std::max<Eigen::Index>(0, g - half), std::min(n - 1, g + half), buffer);
    levels.push_back(level);
    scales.push_back(std::max(scale, floor));
  }
  Band band{Eigen::VectorXd(n), Eigen::VectorXd(n)};
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const std::size_t next = std::min(i + 1, grid.size() - 1);
    const Eigen::Index a = grid[i], b = grid[next];
    for (Eigen::Index k = a; k <= b; ++k) {
      const double w = b > a ? static_cast<double>(k - a) / static_cast<double>(b - a) : 0.0;
      band.level[k] = (1.0 - w) * levels[i] + w * levels[next];
      band.scale[k] = (1.0 - w) * scales[i] + w * scales[next];
    }
  }
  return band;
}

// Current per N·m of each channel (drive_gain, else rigid_body's gravity gain), NaN where it is not
// identified (standard error above half the value: a wrist whose load torque hardly varies); empty
// when a channel has neither effect or the model is not one of joint currents.
std::vector<double> torqueGains(const FittedModel& model) {
  if (model.spec.kind != ModelKind::JointCurrent) return {};
  std::vector<double> gains;
  for (int c = 0; c < model.channelCount(); ++c) {
    const EffectFit* source = nullptr;
    for (const char* id : {"rigid_body", "drive_gain"}) {
      for (const auto& fit : model.effects) {
        if (fit.effect->id() == id && fit.applied[c]) source = &fit;
      }
    }
    if (!source) return {};
    const double gain = source->values[c][0], error = source->standardErrors[c][0];
    const bool identified = std::abs(gain) > 1e-9 && std::abs(error) <= 0.5 * std::abs(gain);  // NaN: no
    gains.push_back(identified ? gain : std::nan(""));
  }
  return gains;
}

struct ToolForce {
  Eigen::Vector3d force;
  double explained = 0.0;  // share of the torques' squared norm
};

// The tool force whose Jᵀf best explains the excursions (as torques) over samples [a, b].
ToolForce toolForce(const robot::RobotModel& robot, const Dataset& data, const std::vector<Eigen::VectorXd>& excursion,
                    const std::vector<double>& gains, Eigen::Index a, Eigen::Index b) {
  const int joints = data.channelCount();
  std::vector<int> used;  // joints with an identified gain
  for (int j = 0; j < joints; ++j) {
    if (!std::isnan(gains[static_cast<std::size_t>(j)])) used.push_back(j);
  }
  const auto rows = static_cast<Eigen::Index>(used.size());
  robot::KinematicsData kinematics(robot);
  Eigen::MatrixXd stacked((b - a + 1) * rows, 3);
  Eigen::VectorXd torques((b - a + 1) * rows);
  Eigen::VectorXd q(joints);
  for (Eigen::Index k = a; k <= b; ++k) {
    for (int j = 0; j < joints; ++j) q[j] = data.signal("q", j)[k];
    robot::forwardKinematics(robot, q, kinematics);
    const robot::Jacobian jacobian = robot::jacobian(robot, kinematics);
    for (Eigen::Index r = 0; r < rows; ++r) {
      const int j = used[static_cast<std::size_t>(r)];
      stacked.row((k - a) * rows + r) = jacobian.block(0, j, 3, 1).transpose();
      torques[(k - a) * rows + r] = excursion[static_cast<std::size_t>(j)][k] / gains[static_cast<std::size_t>(j)];
    }
  }
  const Eigen::Vector3d force = stacked.colPivHouseholderQr().solve(torques);
  const double total = torques.squaredNorm();
  return {force, total > 0.0 ? 1.0 - (stacked * force - torques).squaredNorm() / total : 0.0};
}

}  // namespace

std::vector<Event> findEvents(const FittedModel& model, const Dataset& data,
                              const std::vector<Eigen::VectorXd>& residuals, const EventOptions& options) {
  std::vector<Event> events;
  if (!data.timeOrdered() || data.channelCount() == 0 || data.samples(0) < 10) return events;
  const auto& time = data.signal("time", 0);
  const Eigen::Index n = time.size();
  const double step = medianStep(time);
  const auto samplesOf = [&](double seconds) { return std::max<Eigen::Index>(1, std::lround(seconds / step)); };
  const Eigen::Index bandHalf = samplesOf(options.bandWindow / 2.0);
  const int channels = data.channelCount();
  std::vector<Eigen::VectorXd> excursion, scaled;  // residual - level (channel unit), and in scales
  for (int c = 0; c < channels; ++c) {
    const Eigen::VectorXd smooth = movingAverage(residuals[c], samplesOf(options.smoothing / 2.0));
    const Band band = rollingBand(smooth, bandHalf, std::max<Eigen::Index>(1, bandHalf / 4));
    excursion.push_back(smooth - band.level);
    scaled.push_back(excursion.back().cwiseQuotient(band.scale));
  }
  auto worst = [&](Eigen::Index k) {
    double value = 0.0;
    for (int c = 0; c < channels; ++c) value = std::max(value, std::abs(scaled[c][k]));
    return value;
  };
  const std::vector<double> gains = torqueGains(model);
  std::shared_ptr<const robot::RobotModel> robot;
  Eigen::Index k = 0;
  while (k < n) {
    if (worst(k) <= options.threshold) {
      ++k;
      continue;
    }
    // One excursion: outside samples closer than mergeGap, extended to where every channel is back.
    Eigen::Index a = k, b = k;
    for (Eigen::Index m = k + 1; m < n && time[m] - time[b] <= options.mergeGap; ++m) {
      if (worst(m) > options.threshold) b = m;
    }
    while (a > 0 && worst(a) > options.exitThreshold) --a;
    while (b < n - 1 && worst(b) > options.exitThreshold) ++b;
    k = b + 1;
    const double duration = time[b] - time[a];
    const bool comesBack = a > 0 && b < n - 1;
    if (!comesBack || duration < options.minDuration || duration > options.maxDuration) continue;
    Event event;
    event.start = time[a];
    event.end = time[b];
    event.first = a;
    event.last = b;
    Eigen::Index peakSample = a;
    for (int c = 0; c < channels; ++c) {
      Eigen::Index at = a;
      scaled[c].segment(a, b - a + 1).cwiseAbs().maxCoeff(&at);
      at += a;
      const double size = std::abs(scaled[c][at]);
      if (size <= options.threshold) continue;
      event.joints.push_back(c);
      event.peak.push_back(excursion[c][at]);
      if (size > event.peakScales) {
        event.peakScales = size;
        peakSample = at;
      }
    }
    if (std::count_if(gains.begin(), gains.end(), [](double g) { return !std::isnan(g); }) >= 3) {
      if (!robot) robot = modelRobot(model.spec);
      if (robot->dof() == channels) {
        const Eigen::Index half = samplesOf(kWrenchHalfWindow);
        const ToolForce tool =
            toolForce(*robot, data, excursion, gains, std::max(a, peakSample - half), std::min(b, peakSample + half));
        // Not contact: too weak at the tool, or a torque pattern no force at the tool makes.
        if (tool.force.norm() < options.minimumForce || tool.explained < options.minimumForceFit) continue;
        event.wrench = tool.force;
        event.wrenchFit = tool.explained;
      }
    }
    events.push_back(std::move(event));
  }
  return events;
}

Dataset withoutEvents(const Dataset& data, const std::vector<Event>& events, double margin) {
  std::vector<bool> keep(static_cast<std::size_t>(data.channelCount() > 0 ? data.samples(0) : 0), true);
  const auto& time = data.signal("time", 0);
  for (const auto& event : events) {
    for (Eigen::Index k = 0; k < time.size(); ++k) {
      if (time[k] >= event.start - margin && time[k] <= event.end + margin) keep[static_cast<std::size_t>(k)] = false;
    }
  }
  return selectSamples(data, keep);
}

EventFreeData leaveOutEvents(const FittedModel& model, const Dataset& data, const Dataset* validation) {
  auto eventsOf = [&](const Dataset& log) {
    const auto predictions = predictAll(model, log);
    std::vector<Eigen::VectorXd> residuals;
    for (int c = 0; c < log.channelCount(); ++c) residuals.push_back(log.measured(c) - predictions[c]);
    return findEvents(model, log, residuals);
  };
  EventFreeData result;
  result.allData = &data;
  result.allValidation = validation;
  if (!data.timeOrdered()) return result;
  result.dataEvents = eventsOf(data);
  if (!result.dataEvents.empty()) result.cleanData = withoutEvents(data, result.dataEvents);
  if (validation) result.validationEvents = eventsOf(*validation);
  if (!result.validationEvents.empty()) result.cleanValidation = withoutEvents(*validation, result.validationEvents);
  return result;
}

std::string describeEvents(const std::vector<Event>& events, const Dataset& data) {
  const auto& time = data.signal("time", 0);
  double total = 0.0;
  std::string list;
  char buffer[64];
  for (const auto& event : events) {
    total += event.end - event.start;
    std::snprintf(buffer, sizeof(buffer), "%.2f–%.2f s", event.start, event.end);
    list += (list.empty() ? "" : ", ") + std::string(buffer) + " (" + describeChannels(data, event.joints) + ")";
  }
  std::snprintf(buffer, sizeof(buffer), " (%.1f s of %.1f s)", total, time[time.size() - 1] - time[0]);
  return std::to_string(events.size()) + (events.size() == 1 ? " event" : " events") + buffer + ": " + list;
}

}  // namespace arcplan::model
