// Events (events.h) on simulated UR10e logs: pushes added through Jᵀ in known windows are found
// with their times and force, clean logs have none, a lasting change is not an event, and the
// diagnosis leaves the pushes out and says so. The same on real UR5 logs: test_real_ur5.cpp.
#include <cmath>

#include <gtest/gtest.h>

#include "arcplan/model/compare.h"
#include "arcplan/model/diagnose.h"
#include "arcplan/model/events.h"
#include "arcplan/model/fitting.h"
#include "arcplan/model/simulate.h"
#include "model/model_test_support.h"
#include "model/push_simulation.h"

namespace {

using namespace arcplan::model;
using arcplan::testing::jointCurrentModel;
using arcplan::testing::Push;

// The simulated arm's current per N·m (A/(N·m)), stated so the pushes go through the same gains.
const Eigen::VectorXd kGains = (Eigen::VectorXd(6) << 0.085, 0.085, 0.1, 0.12, 0.12, 0.12).finished();
const std::string kGainEntry = "{id: drive_gain, parameters: {per_torque: [0.085, 0.085, 0.1, 0.12, 0.12, 0.12]}}";

// The truth: the model's effects with the stated gains (the others at typical UR10e values).
ModelSpec truthOf(const std::string& effects) { return jointCurrentModel(kGainEntry + ", " + effects); }

Log simulated(const ModelSpec& truth, unsigned seed) {
  ExcitationOptions excitation;
  excitation.duration = 20.0;
  excitation.rate = 250.0;
  excitation.seed = seed;
  Eigen::VectorXd center(6);
  center << 0.0, -M_PI / 2, M_PI / 4, -M_PI / 2, -M_PI / 2, 0.0;
  SimulationOptions simulation;
  simulation.noise = 0.05;
  simulation.seed = seed;
  return simulateLog(truth, excitationTrajectory(center, excitation), simulation);
}

const std::vector<Push> kPushes{
    {4.0, 4.8, {30.0, 0.0, 0.0}}, {9.0, 10.5, {0.0, -40.0, 20.0}}, {15.0, 15.4, {0.0, 0.0, -50.0}}};

std::vector<Event> eventsOf(const ModelSpec& spec, const Log& fit, const Log& held) {
  const Dataset data = makeJointDataset(fit, spec), validation = makeJointDataset(held, spec);
  return compareModel(fitModel(spec, data), data, &validation).events;
}

TEST(Events, SimulatedPushesAreFoundWithTheirTimesAndForce) {
  const ModelSpec spec = jointCurrentModel("drive_gain, offset, coulomb, viscous");
  const ModelSpec truth = truthOf("offset, coulomb, viscous");
  const Log fit = simulated(truth, 11);
  Log held = simulated(truth, 12);
  arcplan::testing::addPushes(held, arcplan::robot::ur10e(), kPushes, kGains);
  const auto events = eventsOf(spec, fit, held);
  ASSERT_EQ(events.size(), kPushes.size());
  for (std::size_t i = 0; i < kPushes.size(); ++i) {
    const auto& push = kPushes[i];
    const auto& event = events[i];
    // The ramps are 0.08–0.1 s: the residual leaves the band within them.
    EXPECT_NEAR(event.start, push.start, 0.12) << i;
    EXPECT_NEAR(event.end, push.end, 0.12) << i;
    EXPECT_FALSE(event.joints.empty());
    ASSERT_TRUE(event.wrench.has_value());
    EXPECT_LT((*event.wrench - push.force).norm(), 0.15 * push.force.norm())
        << i << ": " << event.wrench->transpose() << " vs " << push.force.transpose();
  }
}

TEST(Events, CleanLogsHaveNone) {
  const ModelSpec spec = jointCurrentModel("drive_gain, offset, coulomb, viscous");
  EXPECT_TRUE(eventsOf(spec, simulated(truthOf("offset, coulomb, viscous"), 11),
                       simulated(truthOf("offset, coulomb, viscous"), 12))
                  .empty());
  // Also where the model misses an effect: its residual is there all the time, not a moment.
  const ModelSpec truth = truthOf("offset, coulomb, viscous, load_friction");
  EXPECT_TRUE(eventsOf(spec, simulated(truth, 11), simulated(truth, 12)).empty());
}

TEST(Events, ALastingChangeIsNotAnEvent) {
  const ModelSpec spec = jointCurrentModel("drive_gain, offset, coulomb, viscous");
  Log held = simulated(spec, 12);
  // From 8 s on, joint 1 draws 1 A more (a payload picked up): the residual never comes back.
  auto& current = held.vectors.at("actual_current");
  for (Eigen::Index k = 0; k < held.time.size(); ++k) {
    if (held.time[k] >= 8.0) current(k, 1) += 1.0;
  }
  EXPECT_TRUE(eventsOf(spec, simulated(spec, 11), held).empty());
}

TEST(Events, TheDiagnosisLeavesPushesOutAndSaysSo) {
  const ModelSpec base = jointCurrentModel("drive_gain, offset, coulomb, viscous");
  const ModelSpec truth = truthOf("offset, coulomb, viscous, load_friction");
  const Log fit = simulated(truth, 11), clean = simulated(truth, 12);
  Log pushed = clean;
  arcplan::testing::addPushes(pushed, arcplan::robot::ur10e(), kPushes, kGains);
  const Dataset data = makeJointDataset(fit, base);
  const Dataset cleanHeld = makeJointDataset(clean, base), pushedHeld = makeJointDataset(pushed, base);
  DiagnoseOptions options;
  options.discover = false;
  const Diagnosis reference = diagnose(base, data, &cleanHeld, options);
  const Diagnosis withPushes = diagnose(base, data, &pushedHeld, options);
  EXPECT_TRUE(reference.validationEvents.empty());
  ASSERT_EQ(withPushes.validationEvents.size(), kPushes.size());
  EXPECT_NE(withPushes.summary.find("Left out"), std::string::npos) << withPushes.summary;
  EXPECT_NE(withPushes.heldout.find("event windows left out"), std::string::npos);
  ASSERT_FALSE(reference.ranking.empty());
  EXPECT_EQ(reference.ranking.front().effect, "load_friction");
  ASSERT_FALSE(withPushes.ranking.empty());
  EXPECT_EQ(withPushes.ranking.front().effect, "load_friction");
  EXPECT_NEAR(withPushes.ranking.front().heldoutReduction, reference.ranking.front().heldoutReduction, 0.02);
  // Kept in, the pushes change the held-out error the effects are judged against.
  options.leaveOutEvents = false;
  const Diagnosis keptIn = diagnose(base, data, &pushedHeld, options);
  EXPECT_TRUE(keptIn.validationEvents.empty());
  EXPECT_GT(keptIn.heldoutBase.overallNrmse, 1.1 * reference.heldoutBase.overallNrmse);
}

}  // namespace
