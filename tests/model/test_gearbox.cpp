// The thesis' Harmonic Drive force-transfer data (tables 2.2–2.4): from the classical linear
// force-transfer model, the diagnosis must propose the load-dependent term, and adding it must
// lower the RMSE by the factor a plain polynomial fit (written here) gives: at least 1.9x on every
// gearbox and direction.
#include <cmath>
#include <map>

#include <Eigen/QR>
#include <gtest/gtest.h>

#include "arcplan/model/diagnose.h"
#include "arcplan/model/force_transfer.h"
#include "arcplan/model/workflow.h"

namespace {

using namespace arcplan::model;

const std::filesystem::path kThesisData =
    std::filesystem::path(ARCPLAN_TEST_DATA_DIR) / "thesis/force_transfer_diagrams.csv";

ModelSpec linearForceTransferModel() {
  // Each direction is a line: transfer coefficient (slope) and threshold (intercept).
  return parseModelYaml("kind: gearbox_ftd\neffects: [drive_gain, offset]\n", "linear_ftd.yaml");
}

// RMSE of a polynomial least-squares fit of input torque on output torque, degree 1 or 2.
double polynomialRmse(const std::vector<ForceTransferPoint>& points, int degree) {
  Eigen::MatrixXd x(static_cast<Eigen::Index>(points.size()), degree + 1);
  Eigen::VectorXd y(static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int d = 0; d <= degree; ++d) x(static_cast<Eigen::Index>(i), d) = std::pow(points[i].outputTorque, d);
    y[static_cast<Eigen::Index>(i)] = points[i].inputTorque;
  }
  const Eigen::VectorXd coefficients = x.colPivHouseholderQr().solve(y);
  return std::sqrt((y - x * coefficients).squaredNorm() / static_cast<double>(points.size()));
}

TEST(GearboxData, ReadsTheThreeHarmonicDrivesOfTheThesis) {
  const auto points = readForceTransferData(kThesisData);
  EXPECT_EQ(points.size(), 160u);
  std::map<std::string, int> perGearbox;
  for (const auto& p : points) ++perGearbox[p.gearbox];
  EXPECT_EQ(perGearbox["HFUC-20-2UH-100"], 60);  // 3 series x 10 loads x 2 directions
  EXPECT_EQ(perGearbox["HFUS-20-2SO-100"], 80);  // 4 series
  EXPECT_EQ(perGearbox["HDUR-32-IH-120"], 20);
  // Table 2.4: DIRECT input at the largest load.
  const auto last = std::find_if(points.rbegin(), points.rend(), [](const auto& p) { return p.direct; });
  EXPECT_DOUBLE_EQ(last->inputTorque, 7.284);
  EXPECT_DOUBLE_EQ(last->outputTorque, 517.932);
}

TEST(GearboxData, DiagnosisProposesTheLoadDependentTermAndItLowersTheRmseAsAPolynomialFitDoes) {
  const auto points = readForceTransferData(kThesisData);
  const auto spec = linearForceTransferModel();
  const Dataset data = makeGearboxDataset(points, spec, kThesisData.string());
  ASSERT_EQ(data.channelCount(), 6);

  const auto diagnosis = diagnose(spec, data, nullptr);
  ASSERT_FALSE(diagnosis.ranking.empty());
  const auto& top = diagnosis.ranking.front();
  EXPECT_EQ(top.effect, "load_friction");
  EXPECT_TRUE(top.suggested);
  EXPECT_EQ(top.joints, (std::vector<int>{0, 1, 2, 3, 4, 5}));  // every gearbox and direction
  EXPECT_NE(top.explanation.find("grows with |load torque|"), std::string::npos) << top.explanation;
  EXPECT_NE(diagnosis.heldout.find("cross-validation"), std::string::npos);

  const auto step = addEffectsAndFit(spec, {parseEffectArgument("load_friction")}, data, nullptr);
  for (int c = 0; c < data.channelCount(); ++c) {
    std::vector<ForceTransferPoint> channelPoints;
    for (const auto& p : points) {
      if (p.gearbox + (p.direct ? "/direct" : "/indirect") == data.channelName(c)) channelPoints.push_back(p);
    }
    const double expected = polynomialRmse(channelPoints, 1) / polynomialRmse(channelPoints, 2);
    const double before = step.beforeData.channels[c].rmse, after = step.afterData.channels[c].rmse;
    EXPECT_NEAR(before, polynomialRmse(channelPoints, 1), 1e-9) << data.channelName(c);
    EXPECT_NEAR(before / after, expected, 1e-6 * expected) << data.channelName(c);
    EXPECT_GE(before / after, 1.9) << data.channelName(c);
  }
}

}  // namespace
