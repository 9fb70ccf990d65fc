// Error metrics and where-it-fails analysis, against numbers computed here.
#include <cmath>
#include <fstream>
#include <map>
#include <random>

#include <gtest/gtest.h>

#include "arcplan/model/compare.h"
#include "arcplan/model/fitting.h"
#include "arcplan/model/plots.h"
#include "model/model_test_support.h"
#include "support/command.h"

namespace {

using namespace arcplan::model;
using arcplan::testing::jointCurrentModel;

Dataset syntheticDataset(int samples, double rate) {
  auto motion = arcplan::testing::makeMotionLog(samples, rate);
  std::mt19937 random(4);
  std::normal_distribution<double> noise(0.0, 1.0);
  auto& current = motion.log.vectors["actual_current"];
  for (Eigen::Index k = 0; k < current.rows(); ++k) {
    for (int j = 0; j < 6; ++j) current(k, j) = std::sin(0.3 * k + j) + 0.1 * noise(random);
  }
  return makeJointDataset(motion.log, jointCurrentModel());
}

TEST(Compare, ErrorMetricsMatchTheirDefinitions) {
  const Dataset data = syntheticDataset(1000, 100.0);
  std::vector<Eigen::VectorXd> predictions;
  for (int c = 0; c < 6; ++c) predictions.push_back(data.measured(c) * 0.9 + Eigen::VectorXd::Constant(1000, 0.05 * c));
  const auto summary = errorSummary(data, predictions);
  double sumNrmseSquares = 0.0;
  for (int c = 0; c < 6; ++c) {
    const Eigen::VectorXd& y = data.measured(c);
    double squares = 0.0, total = 0.0;
    const double mean = y.sum() / 1000.0;
    for (int k = 0; k < 1000; ++k) {
      squares += std::pow(y[k] - predictions[c][k], 2);
      total += std::pow(y[k] - mean, 2);
    }
    const double rmse = std::sqrt(squares / 1000.0), std = std::sqrt(total / 1000.0);
    EXPECT_NEAR(summary.channels[c].rmse, rmse, 1e-12);
    EXPECT_NEAR(summary.channels[c].nrmse, rmse / std, 1e-12);
    EXPECT_NEAR(summary.channels[c].r2, 1.0 - squares / total, 1e-12);
    sumNrmseSquares += std::pow(rmse / std, 2);
  }
  EXPECT_NEAR(summary.overallNrmse, std::sqrt(sumNrmseSquares / 6.0), 1e-12);
}

TEST(Compare, WorstWindowIsWhereTheModelFails) {
  const Dataset data = syntheticDataset(3000, 100.0);  // 30 s
  std::vector<Eigen::VectorXd> residuals;
  std::mt19937 random(9);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (int c = 0; c < 6; ++c) {
    Eigen::VectorXd r(3000);
    for (int k = 0; k < 3000; ++k) r[k] = noise(random);
    residuals.push_back(r);
  }
  for (int k = 2100; k < 2150; ++k) residuals[3][k] = 2.0;  // t = 21.0 .. 21.5 s on joint 3
  const auto windows = worstWindows(data, residuals, 3);
  ASSERT_EQ(windows.size(), 3u);
  EXPECT_EQ(windows[0].worstChannel, "actual_current_3");
  EXPECT_LE(windows[0].start, 21.25);
  EXPECT_GE(windows[0].end, 21.25);
  EXPECT_GT(windows[0].nrmse, 5.0 * windows[2].nrmse);
}

TEST(Compare, RegimesSeparateDirectionAndPowerFlow) {
  const Dataset data = syntheticDataset(2000, 100.0);
  std::vector<Eigen::VectorXd> residuals;
  for (int c = 0; c < 6; ++c) {
    const auto& qd = data.signal("qd", c);
    const auto& tau = data.signal("tau", c);
    Eigen::VectorXd r(2000);
    // +0.3 when moving forward, -0.3 backward; +1 extra when regenerating.
    for (int k = 0; k < 2000; ++k) r[k] = (qd[k] > 0 ? 0.3 : -0.3) + (tau[k] * qd[k] < 0 ? 1.0 : 0.0);
    residuals.push_back(r);
  }
  const auto regimes = residualRegimes(data, residuals);
  ASSERT_EQ(regimes.size(), 6u);
  const auto& joint = regimes[2];
  ASSERT_EQ(joint.regimes[0].name, "direction");
  ASSERT_EQ(joint.regimes[1].name, "power_flow");
  // Expected bin means, counted here.
  const auto& qd = data.signal("qd", 2);
  const auto& tau = data.signal("tau", 2);
  double motoring = 0.0, regenerating = 0.0;
  int motoringCount = 0, regeneratingCount = 0;
  for (int k = 0; k < 2000; ++k) {
    if (std::abs(qd[k]) <= 0.05) continue;
    if (tau[k] * qd[k] > 0) {
      motoring += residuals[2][k];
      ++motoringCount;
    } else {
      regenerating += residuals[2][k];
      ++regeneratingCount;
    }
  }
  const auto& power = joint.regimes[1].bins;
  ASSERT_EQ(power.size(), 2u);
  EXPECT_EQ(power[0].count, motoringCount);
  EXPECT_NEAR(power[0].meanResidual, motoring / motoringCount, 1e-12);
  EXPECT_NEAR(power[1].meanResidual, regenerating / regeneratingCount, 1e-12);
  for (const auto& bin : joint.regimes[0].bins) {
    if (bin.label == "qd < 0") {
      EXPECT_GT(bin.meanResidual, -0.3);  // regenerating phases add +1
    }
  }
  std::vector<std::string> names;
  for (const auto& regime : joint.regimes) names.push_back(regime.name);
  EXPECT_EQ(names,
            (std::vector<std::string>{"direction", "power_flow", "speed", "load", "temperature", "joint_angle"}));
}

TEST(Compare, ResidualCorrelationsNameTheSignalTheResidualFollows) {
  const Dataset data = syntheticDataset(2000, 100.0);
  std::vector<Eigen::VectorXd> residuals;
  for (int c = 0; c < 6; ++c) residuals.push_back(Eigen::VectorXd::Zero(2000));
  residuals[4] = 0.2 * data.signal("qd", 4).cwiseAbs();
  const auto correlations = residualCorrelations(data, residuals);
  ASSERT_FALSE(correlations.empty());
  EXPECT_EQ(correlations.front().channel, "actual_current_4");
  EXPECT_EQ(correlations.front().signal, "abs(qd)");
  EXPECT_NEAR(correlations.front().correlation, 1.0, 1e-9);
}

TEST(Compare, SeriesOfALongLogIsWrittenAsEveryKthSample) {
  // 20 001 samples are more than a plot can show (20 000 per channel): every 2nd sample is written,
  // ceil(20001 / 2) = 10 001 rows per channel, each with its own sample index 0, 2, ..., 20 000.
  const Dataset data = syntheticDataset(20001, 500.0);
  const auto model = fitModel(jointCurrentModel(), data);
  const auto directory = arcplan::testing::freshTempDirectory("compare_long_series");
  plotComparison(model, data, directory, "compare_data");
  std::ifstream series(directory / "compare_data_series.csv");
  std::string line;
  ASSERT_TRUE(std::getline(series, line));
  std::map<std::string, std::vector<long>> indices;
  while (std::getline(series, line)) {
    const auto comma = line.find(',');
    indices[line.substr(0, comma)].push_back(std::stol(line.substr(comma + 1)));
  }
  ASSERT_EQ(indices.size(), 6u);
  for (const auto& [channel, written] : indices) {
    ASSERT_EQ(written.size(), 10001u) << channel;
    for (std::size_t row = 0; row < written.size(); ++row)
      ASSERT_EQ(written[row], static_cast<long>(2 * row)) << channel;
  }
}

}  // namespace
