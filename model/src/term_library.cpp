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

CandidateTerm single(Transform transform, const std::string& signal, int joint, double smoothing, int harmonic = 1) {
  CandidateTerm term;
  term.transform = transform;
  term.signal = signal;
  term.joint = joint;
  term.harmonic = harmonic;
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
      terms.push_back(std::move(term));
    }
  }
  return terms;
}

Eigen::VectorXd evaluateTerm(const CandidateTerm& term, const Dataset& data, int channel) {
  const Eigen::ArrayXd x = data.signal(term.signal, term.joint < 0 ? channel : term.joint).array();
  const double k = term.harmonic;
  switch (term.transform) {
    case Transform::Identity:
      return x.matrix();
    case Transform::Magnitude:
      return x.abs().matrix();
    case Transform::Sign:
      return (x / data.settings().velocitySmoothing).tanh().matrix();
    case Transform::SignedSquare:
      return (x * x.abs()).matrix();
    case Transform::Square:
      return x.square().matrix();
    case Transform::Sine:
      return (k * x).sin().matrix();
    case Transform::Cosine:
      return (k * x).cos().matrix();
    case Transform::Product:
      return (x * data.signal(term.otherSignal, term.otherJoint < 0 ? channel : term.otherJoint).array()).matrix();
  }
  return x.matrix();
}

}  // namespace arcplan::model
