#include "arcplan/model/term_library.h"

#include <cmath>
#include <cstdio>

namespace arcplan::model {
namespace {

using Transform = CandidateTerm::Transform;

std::string variable(const std::string& signal, int joint) {
  return joint < 0 ? signal : signal + "_" + std::to_string(joint);
}

std::string noun(const std::string& signal) {
  if (signal == "q") return "angle";
  if (signal == "qd") return "speed";
  if (signal == "qdd") return "acceleration";
  if (signal == "tau") return "load torque";
  return signal;
}

std::string owner(const std::string& signal, int joint) {
  if (signal == "time") return "time";
  return (joint < 0 ? std::string("its own ") : "joint " + std::to_string(joint) + "'s ") + noun(signal);
}

// The physical picture a single-signal term fits ("" where the catalogue already names it or a
// signal alone suggests none).
std::string pictureOf(Transform transform, const std::string& signal, int joint, int harmonic) {
  const bool own = joint < 0;
  const std::string other = own ? "" : "joint " + std::to_string(joint);
  if (signal == "q") {
    if (transform == Transform::Identity) return "a spring or cable pulling in proportion to the angle";
    if (harmonic > 1) return "a torque repeating with the angle (an eccentric or cogging part)";
    return own ? "gravity of a mass the joint tilts, or a cable whose pull follows its angle"
               : "gravity of a body " + other + " tilts, or a cable or hose whose pull follows " + other + "'s angle";
  }
  if (signal == "qd" || signal == "qdd") {
    if (transform == Transform::SignedSquare || transform == Transform::Square) {
      return "drag growing with the speed squared (churning lubricant) or a centrifugal torque";
    }
    if (own) return signal == "qdd" ? "inertia the model lacks (rotor, tool)" : "";
    return "motion coupling from " + other + " (a hose or cable it drags, or inertia the model does not couple)";
  }
  if (signal == "tau") {
    if (transform == Transform::SignedSquare || transform == Transform::Square) {
      return "current growing faster than the load (motor saturation, a load-dependent efficiency)";
    }
    return own ? "" : "load of " + other + " reaching this joint (a shared structure or cable)";
  }
  if (signal == "temperature") return "thermal drift of the sensor or of the friction";
  if (signal == "time") return "a slow drift (warm-up, sensor drift)";
  return "";
}

std::string productPicture(const std::string& a, const std::string& b) {
  if (a == "qd" && b == "qd") return "a Coriolis or centrifugal coupling between joints";
  if (a == "tau" || b == "tau") return "losses that grow with load and motion together";
  return "an inertial coupling between joints";
}

CandidateTerm single(Transform transform, const std::string& signal, int joint, double smoothing, int harmonic = 1) {
  CandidateTerm term;
  term.transform = transform;
  term.signal = signal;
  term.joint = joint;
  term.harmonic = harmonic;
  term.picture = pictureOf(transform, signal, joint, harmonic);
  const std::string x = variable(signal, joint), who = owner(signal, joint);
  const std::string k = harmonic == 1 ? "" : std::to_string(harmonic) + "*";
  char width[32];
  std::snprintf(width, sizeof(width), "%g", smoothing);
  switch (transform) {
    case Transform::Identity:
      term.expression = x, term.words = who;
      break;
    case Transform::Magnitude:
      term.expression = "abs(" + x + ")", term.words = "the magnitude of " + who;
      break;
    case Transform::Sign:
      term.expression = "sgn(" + x + ", " + width + ")", term.words = "the direction of " + who;
      break;
    case Transform::SignedSquare:
      term.expression = x + "*abs(" + x + ")", term.words = "the square of " + who + ", with its sign";
      break;
    case Transform::Square:
      term.expression = x + "^2", term.words = "the square of " + who;
      break;
    case Transform::Sine:
      term.expression = "sin(" + k + x + ")", term.words = "sin(" + k + who + ")";
      break;
    case Transform::Cosine:
      term.expression = "cos(" + k + x + ")", term.words = "cos(" + k + who + ")";
      break;
    case Transform::Product:
      break;
  }
  return term;
}

// sin or cos of Σ sign·q_joint over neighbouring joints, every joint named.
CandidateTerm angleCombination(Transform transform, const std::vector<std::pair<int, int>>& parts) {
  CandidateTerm term;
  term.transform = transform;
  term.signal = "q";
  term.joint = parts.front().first;
  term.angleSum = parts;
  std::string sum, words;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const auto [joint, sign] = parts[i];
    const std::string op = i == 0 ? "" : (sign > 0 ? "+" : "-");
    sum += op + variable("q", joint);
    words += (i == 0 ? "" : " " + op + " ") + owner("q", joint);
  }
  const std::string function = transform == Transform::Sine ? "sin" : "cos";
  term.expression = function + "(" + sum + ")";
  term.words = function + "(" + words + ")";
  const std::string span = std::to_string(parts.front().first) + "–" + std::to_string(parts.back().first);
  term.picture = parts.back().second > 0
                     ? "gravity of a body carried across joints " + span +
                           ": its lever arm follows the sum of their angles (a hanging cable, a mass beyond joint " +
                           std::to_string(parts.back().first) + ")"
                     : "a coupling through the angle between joints " + span + " (a cable or linkage spanning both)";
  return term;
}

// `base` times sgn(qd) of the channel's own joint: a friction level that `base` modulates.
CandidateTerm directional(CandidateTerm base, double smoothing, const std::string& picture) {
  char width[32];
  std::snprintf(width, sizeof(width), "%g", smoothing);
  base.directional = true;
  base.expression = "sgn(qd, " + std::string(width) + ")*" + base.expression;
  base.words = "its own friction level scaled by " + base.words;
  base.picture = picture;
  return base;
}

// The angle terms of several joints and the modulated friction levels (term_library.h).
void addPhysicalTerms(const Dataset& data, double smoothing, std::vector<CandidateTerm>& terms) {
  const int joints = data.channelCount();
  if (data.timeOrdered() && data.hasSignal("q")) {
    for (int first = 0; first < joints; ++first) {
      std::vector<std::pair<int, int>> run{{first, 1}};
      for (int last = first + 1; last < joints; ++last) {
        run.emplace_back(last, 1);
        for (auto t : {Transform::Sine, Transform::Cosine}) terms.push_back(angleCombination(t, run));
      }
      if (first + 1 < joints) {
        for (auto t : {Transform::Sine, Transform::Cosine}) {
          terms.push_back(angleCombination(t, {{first, 1}, {first + 1, -1}}));
        }
      }
    }
  }
  if (!data.hasSignal("qd")) return;
  if (data.hasSignal("q")) {
    const std::string picture =
        "friction whose level changes with where the joint stands (an eccentric bearing or gear, a seal, the "
        "weight pressing the bearing)";
    for (int k = 1; k <= 2; ++k) {
      for (auto t : {Transform::Sine, Transform::Cosine}) {
        terms.push_back(directional(single(t, "q", -1, smoothing, k), smoothing, picture));
      }
    }
  }
  if (data.hasSignal("tau")) {
    terms.push_back(directional(single(Transform::Magnitude, "tau", -1, smoothing), smoothing,
                                "friction growing with the transmitted load (gear teeth and bearings pressed by it)"));
    terms.push_back(directional(single(Transform::Square, "tau", -1, smoothing), smoothing,
                                "friction growing with the square of the transmitted load"));
  }
}

}  // namespace

std::vector<CandidateTerm> candidateTerms(const Dataset& data, int channel) {
  std::vector<CandidateTerm> terms;
  const double smoothing = data.settings().velocitySmoothing;
  // Channels of data without time (gearbox directions) do not share samples: own signals only.
  std::vector<int> joints;
  for (int j = 0; j < data.channelCount(); ++j) {
    if (data.timeOrdered() || j == channel) joints.push_back(j);
  }
  auto own = [&](int j) { return j == channel ? -1 : j; };
  for (int j : joints) {
    const int who = own(j);
    if (data.hasSignal("q")) {
      terms.push_back(single(Transform::Identity, "q", who, smoothing));
      for (int k = 1; k <= 3; ++k) {
        terms.push_back(single(Transform::Sine, "q", who, smoothing, k));
        terms.push_back(single(Transform::Cosine, "q", who, smoothing, k));
      }
    }
    if (data.hasSignal("qd")) {
      for (auto t :
           {Transform::Identity, Transform::Magnitude, Transform::Sign, Transform::SignedSquare, Transform::Square}) {
        terms.push_back(single(t, "qd", who, smoothing));
      }
    }
    if (data.hasSignal("qdd")) {
      for (auto t : {Transform::Identity, Transform::Magnitude, Transform::SignedSquare}) {
        terms.push_back(single(t, "qdd", who, smoothing));
      }
    }
    if (data.hasSignal("tau")) {
      for (auto t : {Transform::Identity, Transform::Magnitude, Transform::SignedSquare, Transform::Square}) {
        terms.push_back(single(t, "tau", who, smoothing));
      }
    }
    if (data.hasSignal("temperature")) terms.push_back(single(Transform::Identity, "temperature", who, smoothing));
  }
  if (data.timeOrdered()) terms.push_back(single(Transform::Identity, "time", -1, smoothing));
  // Products of two motion or load signals, each pair once.
  std::vector<std::pair<std::string, int>> factors;
  for (const std::string signal : {"qd", "qdd", "tau"}) {
    if (!data.hasSignal(signal)) continue;
    for (int j : joints) factors.emplace_back(signal, own(j));
  }
  for (std::size_t a = 0; a < factors.size(); ++a) {
    for (std::size_t b = a + 1; b < factors.size(); ++b) {
      CandidateTerm term;
      term.transform = Transform::Product;
      term.signal = factors[a].first;
      term.joint = factors[a].second;
      term.otherSignal = factors[b].first;
      term.otherJoint = factors[b].second;
      term.expression = variable(term.signal, term.joint) + "*" + variable(term.otherSignal, term.otherJoint);
      term.words =
          "the product of " + owner(term.signal, term.joint) + " and " + owner(term.otherSignal, term.otherJoint);
      term.picture = productPicture(term.signal, term.otherSignal);
      terms.push_back(std::move(term));
    }
  }
  addPhysicalTerms(data, smoothing, terms);
  return terms;
}

Eigen::VectorXd evaluateTerm(const CandidateTerm& term, const Dataset& data, int channel) {
  auto values = [&]() -> Eigen::ArrayXd {
    if (!term.angleSum.empty()) {
      Eigen::ArrayXd angle = Eigen::ArrayXd::Zero(data.samples(channel));
      for (const auto& [joint, sign] : term.angleSum) angle += sign * data.signal("q", joint).array();
      if (term.transform == Transform::Sine) return angle.sin();
      return angle.cos();
    }
    const Eigen::ArrayXd x = data.signal(term.signal, term.joint < 0 ? channel : term.joint).array();
    const double k = term.harmonic;
    switch (term.transform) {
      case Transform::Identity:
        return x;
      case Transform::Magnitude:
        return x.abs();
      case Transform::Sign:
        return (x / data.settings().velocitySmoothing).tanh();
      case Transform::SignedSquare:
        return x * x.abs();
      case Transform::Square:
        return x.square();
      case Transform::Sine:
        return (k * x).sin();
      case Transform::Cosine:
        return (k * x).cos();
      case Transform::Product:
        return x * data.signal(term.otherSignal, term.otherJoint < 0 ? channel : term.otherJoint).array();
    }
    return x;
  };
  Eigen::ArrayXd result = values();
  if (term.directional) result *= (data.signal("qd", channel).array() / data.settings().velocitySmoothing).tanh();
  return result.matrix();
}

}  // namespace arcplan::model
