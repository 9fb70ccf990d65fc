// The model loop's promise: what diagnose proposes, fit carries out, and it lowers the held-out
// error on every joint it touches. Checked here: friction states with memory start afresh at every
// run (joined runs, gaps left by events) against states simulated by hand run by run; a step keeps
// the searched parameters of the effects already in the model; and a term that helps one joint and
// hurts another is proposed only where it helps, with the held-out errors of a least-squares fit
// done here with Eigen's QR (not the library's normal equations).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include <Eigen/QR>
#include <gtest/gtest.h>

#include "arcplan/model/diagnose.h"
#include "arcplan/model/fitting.h"
#include "arcplan/model/workflow.h"
#include "model/model_test_support.h"

namespace {

using namespace arcplan::model;
using arcplan::testing::jointCurrentModel;
using arcplan::testing::pathDataset;
using arcplan::testing::regressorColumns;

// Dahl's state along one run from z = 0: dz/du = s·ρ·(1 − z·s) over the path length u of each
// step (direction s), integrated with 200 Runge–Kutta steps per sample.
std::vector<double> dahlByHand(const Eigen::VectorXd& q, double rate) {
  std::vector<double> states{0.0};
  double z = 0.0;
  for (Eigen::Index k = 1; k < q.size(); ++k) {
    const double dq = q[k] - q[k - 1], s = dq > 0 ? 1.0 : (dq < 0 ? -1.0 : 0.0), h = std::abs(dq) / 200;
    auto slope = [&](double value) { return s * rate * (1.0 - value * s); };
    for (int i = 0; i < 200 && s != 0.0; ++i) {
      const double k1 = slope(z), k2 = slope(z + 0.5 * h * k1), k3 = slope(z + 0.5 * h * k2), k4 = slope(z + h * k3);
      z += h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
    states.push_back(z);
  }
  return states;
}

// The first element of maxwell_slip (breakaway 1e-4 rad) along one run from rest: δ ← clamp(δ + Δq).
std::vector<double> firstElementByHand(const Eigen::VectorXd& q) {
  std::vector<double> z{0.0};
  double deflection = 0.0;
  for (Eigen::Index k = 1; k < q.size(); ++k) {
    deflection = std::clamp(deflection + q[k] - q[k - 1], -1e-4, 1e-4);
    z.push_back(deflection / 1e-4);
  }
  return z;
}

TEST(MemoryStates, StartAfreshAtEveryRunAndAfterEveryGap) {
  // Run 1 climbs 10 mrad and rests; run 2 starts 0.5 rad higher and goes down 3 mrad.
  std::vector<double> up, down;
  for (int k = 0; k < 50; ++k) up.push_back(2e-4 * k);
  for (int k = 0; k < 30; ++k) down.push_back(0.5 - 1e-4 * k);
  const Dataset first = pathDataset(up, 120), second = pathDataset(down, 80);
  const Dataset joined = joinRuns({first, second});
  ASSERT_EQ(joined.runStarts(), (std::vector<Eigen::Index>{0, 120}));
  const double rate = 500.0;
  std::vector<double> expected = dahlByHand(first.signal("q", 0), rate);
  for (double z : dahlByHand(second.signal("q", 0), rate)) expected.push_back(z);
  const Eigen::MatrixXd dahl = regressorColumns("dahl_friction", joined, 0, rate);
  for (int k = 0; k < 200; ++k) ASSERT_NEAR(dahl(k, 0), expected[k], 1e-9) << "sample " << k;
  // Carried across the boundary, the 0.49 rad jump would have set the state to +1, not 0, and run
  // 2's 2.9 mrad descent would end at -1 + 2·exp(-500·0.0029) = -0.53 instead of -1 + exp(..) = -0.77.
  EXPECT_EQ(dahl(120, 0), 0.0);
  EXPECT_NEAR(dahl(199, 0), expected[199], 1e-9);
  EXPECT_NEAR(expected[199], -1.0 + std::exp(-500.0 * 0.0029), 1e-6);

  std::vector<double> element = firstElementByHand(first.signal("q", 0));
  for (double z : firstElementByHand(second.signal("q", 0))) element.push_back(z);
  const Eigen::MatrixXd maxwell = regressorColumns("maxwell_slip", joined);
  for (int k = 0; k < 200; ++k) ASSERT_NEAR(maxwell(k, 0), element[k], 1e-12) << "sample " << k;

  // Samples 30–59 left out (an event): a run starts where the kept samples resume.
  std::vector<bool> keep(200, true);
  for (int k = 30; k < 60; ++k) keep[k] = false;
  const Dataset gapped = selectSamples(joined, keep);
  ASSERT_EQ(gapped.runStarts(), (std::vector<Eigen::Index>{0, 30, 90}));
  const Eigen::VectorXd& q = gapped.signal("q", 0);
  std::vector<double> pieces;
  for (auto [begin, end] : {std::pair<int, int>{0, 30}, {30, 90}, {90, 170}}) {
    for (double z : dahlByHand(q.segment(begin, end - begin), rate)) pieces.push_back(z);
  }
  const Eigen::MatrixXd afterGap = regressorColumns("dahl_friction", gapped, 0, rate);
  for (int k = 0; k < 170; ++k) ASSERT_NEAR(afterGap(k, 0), pieces[k], 1e-9) << "sample " << k;
}

TEST(ModelLoop, AStepKeepsTheSearchedParametersOfTheEffectsAlreadyInTheModel) {
  const auto pair = arcplan::testing::simulatePair(
      jointCurrentModel("drive_gain, offset, coulomb, viscous, position_ripple"), jointCurrentModel(), 0.05);
  const FittedModel before =
      fitModel(jointCurrentModel("drive_gain, offset, coulomb, viscous, position_ripple"), pair.data);
  EffectSpec dahl;
  dahl.id = "dahl_friction";
  const FittedModel after = extendModel(before, {dahl}, pair.data);
  ASSERT_EQ(after.effects.size(), 5u + 1u);
  for (int c = 0; c < 6; ++c) {
    EXPECT_EQ(after.effects[4].nonlinear[c], before.effects[4].nonlinear[c]) << "joint " << c;
    EXPECT_FALSE(std::isnan(after.effects[5].nonlinear[c])) << "joint " << c;  // the addition's own rate: searched
  }
}

// Current = 0.1·tau + 0.05 + 0.5·sgn(qd) + 0.2·qd (+ 0.05·qdd on joints 0 and 1) + noise 0.02 A.
// Joint 1 has the inertia term in both logs; joint 0 has it in the fit log only, reversed in the
// validation log: rotor_inertia fitted on the fit log helps joint 1 and hurts joint 0 held out.
Dataset inertiaLog(double joint0Inertia, double phase, unsigned seed) {
  auto motion = arcplan::testing::makeMotionLog(3000, 100.0, phase);
  const Dataset prepared = makeJointDataset(motion.log, jointCurrentModel());
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, 0.02);
  auto& current = motion.log.vectors["actual_current"];
  for (int j = 0; j < 6; ++j) {
    const double inertia = j == 0 ? joint0Inertia : (j == 1 ? 0.05 : 0.0);
    for (int k = 0; k < 3000; ++k) {
      const double qd = prepared.signal("qd", j)[k];
      current(k, j) = 0.1 * prepared.signal("tau", j)[k] + 0.05 + 0.5 * std::tanh(qd / 0.01) + 0.2 * qd +
                      inertia * prepared.signal("qdd", j)[k] + noise(random);
    }
  }
  return makeJointDataset(motion.log, jointCurrentModel());
}

// Held-out RMSE of joint j with the base columns (and qdd), fitted by QR on `fit`.
double heldOutRmse(const Dataset& fit, const Dataset& held, int j, bool withInertia) {
  auto design = [&](const Dataset& d) {
    const Eigen::Index n = d.samples(j);
    Eigen::MatrixXd x(n, withInertia ? 5 : 4);
    x.col(0) = d.signal("tau", j);
    x.col(1).setOnes();
    x.col(2) = (d.signal("qd", j) / 0.01).array().tanh().matrix();
    x.col(3) = d.signal("qd", j);
    if (withInertia) x.col(4) = d.signal("qdd", j);
    return x;
  };
  const Eigen::VectorXd beta = design(fit).colPivHouseholderQr().solve(fit.measured(j));
  return std::sqrt((held.measured(j) - design(held) * beta).squaredNorm() / static_cast<double>(held.samples(j)));
}

TEST(ModelLoop, AStepThatHelpsOneJointAndHurtsAnotherIsProposedOnlyWhereItHelps) {
  const Dataset fit = inertiaLog(0.05, 0.0, 1), held = inertiaLog(-0.05, 7.0, 2);
  const double without0 = heldOutRmse(fit, held, 0, false), with0 = heldOutRmse(fit, held, 0, true);
  const double without1 = heldOutRmse(fit, held, 1, false), with1 = heldOutRmse(fit, held, 1, true);
  ASSERT_GT(with0, 1.1 * without0);  // the case is what it should be: joint 0 hurt, joint 1 helped
  ASSERT_LT(with1, 0.9 * without1);

  const ModelSpec base = jointCurrentModel("drive_gain, offset, coulomb, viscous");
  DiagnoseOptions options;
  options.discover = false;
  options.candidates = {"rotor_inertia"};
  const Diagnosis diagnosis = diagnose(base, fit, &held, options);
  ASSERT_FALSE(diagnosis.ranking.empty());
  const auto& proposal = diagnosis.ranking.front();
  ASSERT_TRUE(proposal.suggested);
  EXPECT_EQ(proposal.joints, std::vector<int>{1});
  EXPECT_NEAR(proposal.channelReduction[1], 1.0 - with1 / without1, 1e-3);
  EXPECT_NEAR(proposal.channelReduction[0], 1.0 - with0 / without0, 1e-3);
  char raised[32];
  std::snprintf(raised, sizeof(raised), "+%.1f%%", 100.0 * (with0 / without0 - 1.0));
  EXPECT_NE(proposal.explanation.find("left off joint 0 (" + std::string(raised) + ")"), std::string::npos)
      << proposal.explanation;

  const FitStep step = addEffectsAndFit(base, {proposal.entry}, fit, &held);
  EXPECT_TRUE(step.validationEvents.empty());
  EXPECT_NEAR(step.beforeValidation->channels[1].rmse, without1, 1e-6);
  EXPECT_NEAR(step.afterValidation->channels[1].rmse, with1, 1e-6);
  EXPECT_NEAR(step.afterValidation->channels[0].rmse, without0, 1e-6);  // left off: unchanged
  double before = 0.0, after = 0.0;
  for (int j = 0; j < 6; ++j) {
    before += std::pow(step.beforeValidation->channels[j].rmse, 2);
    after += std::pow(step.afterValidation->channels[j].rmse, 2);
  }
  EXPECT_LT(after, before);
}

}  // namespace
