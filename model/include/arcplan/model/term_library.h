#pragma once
// Candidate terms beyond the catalogue: a library generated from every joint's signals and their
// transforms, used by the diagnosis to discover a term nobody catalogued and by `compare` to say
// which signals the residual follows. The library holds the terms a rigid-body and friction
// regressor is made of. For the channel of joint c, over every joint j:
//   q_j:            q, sin(k·q), cos(k·q) for k = 1..3
//   qd_j:           qd, |qd|, sgn(qd), qd·|qd|, qd²
//   qdd_j:          qdd, |qdd|, qdd·|qdd|
//   tau_j:          tau, |tau|, tau·|tau|, tau²
//   temperature_j:  temperature (when the log has it)
//   time
//   products of two of {qd_j, qdd_j, tau_j} over all joints (qd_0·qd_2, qd·tau, ...)
// and, the terms of gravity carried across joints and of friction whose level changes (logs):
//   sin, cos of the sum of every run of neighbouring joints' angles (q_1+q_2, q_1+q_2+q_3, ...)
//     and of the difference of two neighbours (q_1-q_2): a body whose weight's lever arm follows
//     several joints, on any channel
//   sgn(qd)·sin(k·q), sgn(qd)·cos(k·q) for k = 1, 2: the channel's friction level modulated by
//     its own angle
//   sgn(qd)·|tau|, sgn(qd)·tau²: its friction level modulated by its own load
// Each term carries its muparser expression as the model file's expression effect reads it (the
// channel's own signals by bare name, other joints as name_j; sums of angles always name every
// joint), so a discovered term pastes into a model file unchanged, its meaning in words, and the
// physical picture it fits.
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "arcplan/model/dataset.h"

namespace arcplan::model {

struct CandidateTerm {
  enum class Transform { Identity, Magnitude, Sign, SignedSquare, Square, Sine, Cosine, Product };
  Transform transform = Transform::Identity;
  std::string signal;       // dataset signal name: q, qd, qdd, tau, temperature, time
  int joint = -1;           // -1: the channel's own joint
  int harmonic = 1;         // k of sin/cos(k·q)
  std::string otherSignal;  // second factor of a product
  int otherJoint = -1;
  // Sine / Cosine of a combination of joints' angles: Σ sign·q_joint (joint >= 0); empty: of `signal`.
  std::vector<std::pair<int, int>> angleSum;
  bool directional = false;  // times sgn(qd) of the channel's own joint: a friction level
  std::string expression;    // "qd_1", "qd*abs(qd)", "sin(2*q_3)", "qd_0*qd_2", "cos(q_1+q_2)", "sgn(qd, 0.01)*cos(q)"
  std::string words;         // "joint 1's speed", "the square of its own speed, with its sign"
  std::string picture;       // the physical picture it fits ("" when it is only a signal)
};

// The library for one channel. Data without time (gearbox directions, whose channels do not share
// samples) gets the channel's own signals only, and no time term.
std::vector<CandidateTerm> candidateTerms(const Dataset& data, int channel);

// The term's values on `channel`, computed directly (the expression gives the same numbers).
Eigen::VectorXd evaluateTerm(const CandidateTerm& term, const Dataset& data, int channel);

}  // namespace arcplan::model
