#pragma once
// Where the model fails for a moment: short windows in which the residual leaves its own local
// noise band on one or more joints at once and comes back, as when a person pushes the arm or it
// touches something. A missing physical effect leaves its trace all along the log; an event is a
// moment, and the diagnosis leaves it out instead of fitting an effect to it.
//
// Per channel the residual is smoothed over `smoothing` seconds (a push lasts longer, a noise spike
// does not); its band is the rolling median ± the rolling robust scale (1.4826·MAD) over
// `bandWindow` seconds, both robust to the event itself as long as it fills less than half the
// window, and never narrower than the channel's robust scale over the whole log (a joint at rest has
// a tiny local scale, and its first move is not an event). A sample is outside when
// |residual − level| > `threshold` scales on some channel; the outside samples of all channels form
// one excursion while they are closer than `mergeGap`; it extends to where every channel is back
// within `exitThreshold` scales. An excursion is an event when it lasts `minDuration`..`maxDuration`
// and comes back before the log ends (longer ones are a change of condition, not a moment).
//
// Where the model knows the arm (joint currents with a drive gain or rigid_body on every joint, the
// robot's joint count, at least 3 joints whose current per N·m is identified), an event must also
// look like contact: the force at the tool whose Jᵀf best explains the excursions (as torques, on the
// identified joints) is at least `minimumForce` and explains at least `minimumForceFit` of them. On the real UR5 logs
// the model's own errors leave the band too, mostly as a few tenths of a N·m on one wrist, which no force at the tool
// explains. Time-ordered data only.
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "arcplan/model/dataset.h"
#include "arcplan/model/fitting.h"

namespace arcplan::model {

// Defaults measured on the real UR5 logs (docs/model-results.md): pushes of 20–60 N for 0.3–2 s
// through Jᵀ found 93 % of the time, 0.5 false events per minute on the undisturbed runs.
struct EventOptions {
  double smoothing = 0.1;         // s, moving average of the residual before it is compared with its band
  double bandWindow = 8.0;        // s, rolling window of the band's level and scale
  double threshold = 5.0;         // robust scales a channel must leave its band by
  double exitThreshold = 2.0;     // robust scales within which every channel must be back at an event's ends
  double minDuration = 0.25;      // s; shorter excursions are noise
  double maxDuration = 5.0;       // s; longer ones are not a moment
  double mergeGap = 0.3;          // s; excursions closer than this are one
  double minimumForce = 12.0;     // N at the tool, where the arm is known
  double minimumForceFit = 0.65;  // share of the excursion torques the tool force must explain
};

struct Event {
  double start = 0.0, end = 0.0;     // s, on the log's time axis
  Eigen::Index first = 0, last = 0;  // sample range
  std::vector<int> joints;           // channels that left their band
  std::vector<double> peak;          // per joint of `joints`: the residual of largest excursion (channel unit)
  double peakScales = 0.0;           // the largest excursion, in robust scales of its channel
  // The force at the tool (N, base frame) whose joint torques Jᵀf best explain the residual torques
  // (least squares over the samples within ±0.04 s of the peak), when the model knows the arm
  // (joint currents with a drive gain or rigid_body on every joint, and the robot's joint count).
  std::optional<Eigen::Vector3d> wrench;
  double wrenchFit = 0.0;  // share of the excursion torques Jᵀf explains (with `wrench`)
};

std::vector<Event> findEvents(const FittedModel& model, const Dataset& data,
                              const std::vector<Eigen::VectorXd>& residuals, const EventOptions& options = {});

// The dataset without the samples of the events and `margin` seconds around them (an event's ends
// are where the residual is back within exitThreshold scales, not where the push began; the
// diagnosis scores effects without them).
Dataset withoutEvents(const Dataset& data, const std::vector<Event>& events, double margin = 0.3);

// The samples the model loop fits and scores on, one rule for diagnose and fit: each log without
// the events of `model`'s residual on it (the model as it is before a step), so a step is fitted
// and held out on the same samples the diagnosis scored it on.
struct EventFreeData {
  const Dataset* allData = nullptr;  // the logs given (not owned)
  const Dataset* allValidation = nullptr;
  std::optional<Dataset> cleanData, cleanValidation;  // only where events were left out
  std::vector<Event> dataEvents, validationEvents;
  const Dataset& data() const { return cleanData ? *cleanData : *allData; }
  const Dataset* validation() const { return cleanValidation ? &*cleanValidation : allValidation; }
};
EventFreeData leaveOutEvents(const FittedModel& model, const Dataset& data, const Dataset* validation);

// "3 events (2.4 s of 82.1 s) left out: 12.3–13.1 s (joints 0–2), ..."
std::string describeEvents(const std::vector<Event>& events, const Dataset& data);

}  // namespace arcplan::model
