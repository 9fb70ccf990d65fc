// Discovery beyond the catalogue: logs simulated with hidden terms that no catalogue effect
// describes (cross-joint, nonlinear speed and load terms, products, gravity carried across joints,
// friction levels that follow the position or the load), written as truth expressions. The
// diagnosis must propose the true expression first with at least 0.8x the held-out gain of the
// truth itself, the proposed model-file entry must bring the affected joints within 1.3x of the
// noise, and a clean log must get no proposal at all. Also: every library term's expression reproduces its values, and
// `compare` sees residuals that follow another joint's signals.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "arcplan/model/compare.h"
#include "arcplan/model/diagnose.h"
#include "arcplan/model/effect.h"
#include "arcplan/model/term_library.h"
#include "arcplan/model/workflow.h"
#include "model/model_test_support.h"

namespace {

using namespace arcplan::model;
using arcplan::testing::jointCurrentModel;

const std::string kBase = "drive_gain, offset, coulomb, viscous";
constexpr double kNoise = 0.05;  // A

struct HiddenTerm {
  // A constructor rather than an aggregate: the last two fields are optional in the table below.
  HiddenTerm(std::string name, std::string expression, std::vector<int> joints, std::string coefficients,
             std::string picture = "", std::string baseExtra = "")
      : name(std::move(name)),
        expression(std::move(expression)),
        joints(std::move(joints)),
        coefficients(std::move(coefficients)),
        picture(std::move(picture)),
        baseExtra(std::move(baseExtra)) {}
  std::string name;
  std::string expression;  // the truth, as a user expression (own joint bare, others name_j)
  std::vector<int> joints;
  std::string coefficients;  // one per joint (0 where not applied)
  std::string picture;       // part of the physical picture the explanation must name ("": any)
  std::string baseExtra;     // effects the base model has beyond kBase ("": none)
};

// Pooled held-out gain of a fit step (the share of the held-out residual RMS it removes), as the
// diagnosis pools it: over every channel, weighted by its samples.
double pooledGain(const FitStep& step) {
  double before = 0.0, after = 0.0;
  for (std::size_t c = 0; c < step.afterValidation->channels.size(); ++c) {
    const auto n = static_cast<double>(step.afterValidation->channels[c].samples);
    before += n * std::pow(step.beforeValidation->channels[c].rmse, 2);
    after += n * std::pow(step.afterValidation->channels[c].rmse, 2);
  }
  return 1.0 - std::sqrt(after / before);
}

void PrintTo(const HiddenTerm& h, std::ostream* out) { *out << h.name << ": " << h.expression; }

class OutsideTheCatalogue : public ::testing::TestWithParam<HiddenTerm> {};

TEST_P(OutsideTheCatalogue, DiscoveryProposesTheTermAndItReachesTheNoise) {
  const auto& hidden = GetParam();
  std::string joints;
  for (int j : hidden.joints) joints += (joints.empty() ? "" : ", ") + std::to_string(j);
  const std::string baseEffects = kBase + (hidden.baseExtra.empty() ? "" : ", " + hidden.baseExtra);
  const ModelSpec base = jointCurrentModel(baseEffects);
  const std::string truthEntry = "{id: hidden, expression: \"" + hidden.expression + "\", joints: [" + joints + "]";
  const ModelSpec truth =
      jointCurrentModel(baseEffects + ", " + truthEntry + ", parameters: {c0: [" + hidden.coefficients + "]}}");
  const auto [data, validation] = arcplan::testing::simulatePair(truth, base, kNoise);

  // The catalogue against discovery (effects other tests of this executable register are left out).
  DiagnoseOptions options;
  options.candidates = catalogueEffects();
  const Diagnosis diagnosis = diagnose(base, data, &validation, options);
  ASSERT_FALSE(diagnosis.ranking.empty());
  const auto& top = diagnosis.ranking.front();
  ASSERT_TRUE(top.suggested) << diagnosis.summary;
  EXPECT_TRUE(top.discovered) << diagnosis.summary;
  ASSERT_EQ(top.entry.expressions.size(), 1u) << diagnosis.summary;
  EXPECT_EQ(top.entry.expressions.front(), hidden.expression) << diagnosis.summary;
  if (!hidden.picture.empty()) {
    EXPECT_NE(top.explanation.find(hidden.picture), std::string::npos) << top.explanation;
  }
  // At least 0.8x of what the true term itself removes from the held-out residual (fitted alone on
  // the training log, scored on the validation log).
  const FitStep truthStep = addEffectsAndFit(base, {jointCurrentModel(truthEntry + "}").effects[0]}, data, &validation);
  RecordProperty("truth_gain", std::to_string(pooledGain(truthStep)));
  EXPECT_GE(top.heldoutReduction, 0.8 * pooledGain(truthStep)) << diagnosis.summary;
  for (int j : hidden.joints) {
    EXPECT_NE(std::find(top.joints.begin(), top.joints.end(), j), top.joints.end()) << "joint " << j;
  }
  // The ready-to-paste entry parses as a model-file effect and names the expression.
  EXPECT_NE(top.modelEntry.find("expression: \"" + hidden.expression + "\""), std::string::npos) << top.modelEntry;
  const ModelSpec pasted = jointCurrentModel(baseEffects + ", " + top.modelEntry);
  EXPECT_EQ(pasted.effects.back().expressions, top.entry.expressions);

  const FitStep step = addEffectsAndFit(base, {pasted.effects.back()}, data, &validation);
  ASSERT_TRUE(step.afterValidation);
  RecordProperty("first", top.effect + " " + std::to_string(top.heldoutReduction));
  for (int j : hidden.joints) {
    RecordProperty("joint_" + std::to_string(j), std::to_string(step.beforeValidation->channels[j].rmse) + " -> " +
                                                     std::to_string(step.afterValidation->channels[j].rmse));
    EXPECT_LE(step.afterValidation->channels[j].rmse, 1.3 * kNoise) << "joint " << j;
    EXPECT_LT(step.afterValidation->channels[j].rmse, step.beforeValidation->channels[j].rmse) << "joint " << j;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Hidden, OutsideTheCatalogue,
    ::testing::Values(
        // A hose on the elbow pulled by the shoulder's motion.
        HiddenTerm{"shoulder_speed_on_elbow", "qd_1", {2}, "0, 0, 0.3, 0, 0, 0"},
        // Drag growing with the speed squared on every joint.
        HiddenTerm{"quadratic_drag", "qd*abs(qd)", {0, 1, 2, 3, 4, 5}, "1.0, 1.0, 0.8, 0.5, 0.5, 0.5"},
        // A product of two other joints' speeds on the shoulder (an unmodelled Coriolis-like term).
        HiddenTerm{"speed_product", "qd_0*qd_2", {1}, "0, 0.5, 0, 0, 0, 0"},
        // Motor saturation: current growing faster than the torque on the loaded joints.
        HiddenTerm{"torque_saturation", "tau*abs(tau)", {1, 2}, "0, 4e-5, 2e-4, 0, 0, 0"},
        // A cable on the base whose pull depends on the shoulder's angle.
        HiddenTerm{"shoulder_angle_on_base", "cos(q_1)", {0}, "0.2, 0, 0, 0, 0, 0"},
        // A weight carried across shoulder and elbow (a hanging cable): its lever arm on the shoulder
        // follows q1 + q2.
        HiddenTerm{
            "weight_across_shoulder_and_elbow", "cos(q_1+q_2)", {1}, "0, 0.4, 0, 0, 0, 0", "carried across joints 1–2"},
        // The same on the elbow, over elbow and first wrist, as a sine.
        HiddenTerm{"weight_across_elbow_and_wrist", "sin(q_2+q_3)", {2}, "0, 0, 0.12, 0, 0, 0", "joints 2–3"},
        // Friction whose level follows the joint's own angle (an eccentric bearing), on the loaded joints.
        HiddenTerm{"friction_following_the_angle",
                   "sgn(qd, 0.01)*cos(q)",
                   {1, 2},
                   "0, 0.15, 0.15, 0, 0, 0",
                   "changes with where the joint stands"},
        HiddenTerm{"base_friction_following_the_angle", "sgn(qd, 0.01)*sin(q)", {0}, "0.1, 0, 0, 0, 0, 0", ""},
        // Load-dependent friction on the first wrist of a model whose load_friction covers only
        // shoulder and elbow (so the catalogue effect is not a candidate again).
        HiddenTerm{"wrist_friction_following_the_load",
                   "sgn(qd, 0.01)*abs(tau)",
                   {3},
                   "0, 0, 0, 0.05, 0, 0",
                   "pressed by it",
                   "{id: load_friction, joints: [1, 2]}"}),
    [](const auto& info) { return info.param.name; });

TEST(Discovery, ProposesNothingOnCleanLogs) {
  const ModelSpec base = jointCurrentModel(kBase);
  for (unsigned seed : {21u, 31u}) {
    const auto [data, validation] = arcplan::testing::simulatePair(base, base, kNoise, seed);
    for (const Dataset* held : {static_cast<const Dataset*>(&validation), static_cast<const Dataset*>(nullptr)}) {
      const Diagnosis diagnosis = diagnose(base, data, held);
      for (const auto& candidate : diagnosis.ranking) {
        EXPECT_FALSE(candidate.suggested)
            << "seed " << seed << ": " << candidate.effect << " " << candidate.explanation;
      }
      // Nothing is left to explain: the residual is the simulated noise.
      EXPECT_LT(diagnosis.explainable, 0.05) << diagnosis.summary;
      for (double floor : diagnosis.noiseFloor) EXPECT_NEAR(floor, kNoise, 0.1 * kNoise);
    }
  }
}

TEST(Discovery, ExplainableShareSeesTheHiddenTermAndTheCatalogueMissingIt) {
  // qd_1 on joint 2 at 0.3 A·s/rad: most of joint 2's held-out residual is explainable, and no
  // catalogue effect explains much of it.
  const ModelSpec base = jointCurrentModel(kBase);
  const ModelSpec truth =
      jointCurrentModel(kBase + ", {id: hose, expression: qd_1, joints: [2], parameters: {c0: [0, 0, 0.3, 0, 0, 0]}}");
  const auto [data, validation] = arcplan::testing::simulatePair(truth, base, kNoise);
  const Diagnosis diagnosis = diagnose(base, data, &validation);
  // Expected share from the numbers themselves: pooled RMS of the held-out residual vs the noise.
  double squares = 0.0, samples = 0.0;
  for (const auto& channel : diagnosis.heldoutBase.channels) {
    squares += channel.rmse * channel.rmse * static_cast<double>(channel.samples);
    samples += static_cast<double>(channel.samples);
  }
  const double expected = 1.0 - kNoise / std::sqrt(squares / samples);
  EXPECT_NEAR(diagnosis.explainable, expected, 0.05) << diagnosis.summary;
  EXPECT_LT(diagnosis.catalogueExplains, 0.5 * diagnosis.explainable) << diagnosis.summary;
  EXPECT_NE(diagnosis.summary.find("of the held-out residual, of the"), std::string::npos) << diagnosis.summary;
}

TEST(TermLibrary, EveryExpressionReproducesTheTermsValues) {
  auto motion = arcplan::testing::makeMotionLog(400, 100.0);
  const ModelSpec spec = jointCurrentModel();
  const Dataset data = makeJointDataset(motion.log, spec);
  const int channel = 2;
  const auto terms = candidateTerms(data, channel);
  // 6 joints x (7 angle + 5 speed + 3 acceleration + 4 torque + 1 temperature terms) + time +
  // every pair of the 18 speed, acceleration and torque signals + sin and cos of the sum over each
  // of the 15 runs of >= 2 neighbouring joints and of the 5 neighbours' differences + sgn(qd) times
  // sin, cos of q and 2q + sgn(qd) times |tau| and tau².
  EXPECT_EQ(terms.size(), 6u * 20u + 1u + 18u * 17u / 2u + 2u * (15u + 5u) + 4u + 2u);
  for (const std::string expected : {"cos(q_1+q_2)", "sin(q_0+q_1+q_2+q_3+q_4+q_5)", "cos(q_4-q_5)",
                                     "sgn(qd, 0.01)*sin(2*q)", "sgn(qd, 0.01)*abs(tau)", "sgn(qd, 0.01)*tau^2"}) {
    EXPECT_TRUE(std::any_of(terms.begin(), terms.end(), [&](const auto& t) { return t.expression == expected; }))
        << expected;
  }
  for (const auto& term : terms) {
    EffectSpec spec;
    spec.id = "term";
    spec.expressions = {term.expression};
    const Eigen::MatrixXd column = arcplan::testing::regressorColumns(spec, data, channel);
    ASSERT_EQ(column.cols(), 1);
    EXPECT_LT((column.col(0) - evaluateTerm(term, data, channel)).cwiseAbs().maxCoeff(), 1e-9) << term.expression;
  }
}

TEST(Compare, ResidualCorrelationsLookAtEveryJoint) {
  auto motion = arcplan::testing::makeMotionLog(2000, 100.0);
  const ModelSpec spec = jointCurrentModel();
  const Dataset data = makeJointDataset(motion.log, spec);
  std::vector<Eigen::VectorXd> residuals(6, Eigen::VectorXd::Zero(2000));
  residuals[2] = 0.3 * data.signal("qd", 1);  // the elbow's residual follows the shoulder's speed
  const auto correlations = residualCorrelations(data, residuals);
  ASSERT_FALSE(correlations.empty());
  EXPECT_EQ(correlations.front().channel, "actual_current_2");
  EXPECT_EQ(correlations.front().signal, "qd_1");
  EXPECT_NEAR(correlations.front().correlation, 1.0, 1e-9);
}

}  // namespace
