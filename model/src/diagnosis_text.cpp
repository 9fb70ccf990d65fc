// The diagnosis in words: what each suggestion means, the summary, and how much of the residual
// the catalogue explains of what can be explained at all.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "model_internal.h"

namespace arcplan::model::detail {
namespace {

std::string number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.4g", value);
  return buffer;
}

std::string perChannel(const EffectCandidate& candidate, const Dataset& data) {
  std::string text;
  for (std::size_t k = 0; k < candidate.joints.size(); ++k) {
    const int c = candidate.joints[k];
    text += (k ? ", " : "") + data.channelName(c) + " -" + percentText(candidate.channelReduction[c]);
  }
  return text;
}

// The channels a suggestion is left off because, refitted with it, their held-out error rises (by
// at least 1 %: smaller changes are noise), e.g. " It is left off joint 0 (+16.0 %), where refitted
// with it the held-out error rises."
std::string leftOffText(const EffectCandidate& candidate, const Dataset& data) {
  std::vector<int> raised;
  std::string amounts;
  for (std::size_t c = 0; c < candidate.channelReduction.size(); ++c) {
    const int channel = static_cast<int>(c);
    if (candidate.channelReduction[c] > -0.01 ||
        std::find(candidate.joints.begin(), candidate.joints.end(), channel) != candidate.joints.end()) {
      continue;
    }
    raised.push_back(channel);
    amounts += (amounts.empty() ? "+" : ", +") + percentText(-candidate.channelReduction[c]);
  }
  if (raised.empty()) return "";
  return " It is left off " + describeChannels(data, raised) + " (" + amounts +
         "), where refitted with it the held-out error rises.";
}

std::string quantitiesText(const std::vector<PhysicalQuantity>& quantities) {
  std::string text;
  for (const auto& quantity : quantities) {
    text += "; " + quantity.meaning + " ";
    const bool vector = quantity.values.size() > 1;
    std::string values, errors;
    for (std::size_t i = 0; i < quantity.values.size(); ++i) {
      values += (i ? ", " : "") + number(quantity.values[i]);
      errors += (i ? ", " : "") + number(quantity.standardErrors[i]);
    }
    text += vector ? "(" + values + ") ± (" + errors + ")" : values + " ± " + errors;
    text += " " + quantity.name.substr(quantity.name.rfind('_') + 1);  // the unit ends the name: mass_kg
  }
  return text;
}

}  // namespace

std::string percentText(double fraction) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.1f%%", 100.0 * fraction);
  return buffer;
}

std::string explainCandidate(const Effect& effect, const EffectCandidate& candidate, const Dataset& data) {
  std::string text = "The residual on " + describeChannels(data, candidate.joints) + " " + effect.residualPattern() +
                     ": " + effect.meaning() + ". Adding " + candidate.effect + " removes " +
                     percentText(candidate.heldoutReduction) + " of the held-out residual (" +
                     perChannel(candidate, data) + ")";
  if (!candidate.nonlinearName.empty()) {
    text += "; " + candidate.nonlinearName + " =";
    for (std::size_t k = 0; k < candidate.joints.size(); ++k) {
      text += (k ? ", " : " ") + number(candidate.nonlinear[candidate.joints[k]]);
    }
    text += " " + candidate.nonlinearUnit;
  }
  return text + quantitiesText(candidate.quantities) + "." + leftOffText(candidate, data);
}

std::string explainDiscovery(const EffectCandidate& candidate, const std::string& words, const std::string& picture,
                             const Dataset& data) {
  std::string follows = words;
  // "its own speed" reads as "each joint's own speed" when the term applies to several joints.
  const auto own = follows.find("its own");
  if (own != std::string::npos && candidate.joints.size() > 1) follows.replace(own, 7, "each joint's own");
  return "The residual on " + describeChannels(data, candidate.joints) + " follows " + follows + " (" +
         candidate.entry.expressions.front() + "), a term outside the catalogue" +
         (picture.empty() ? std::string() : "; it fits " + picture) + ". Adding it removes " +
         percentText(candidate.heldoutReduction) + " of the held-out residual (" + perChannel(candidate, data) + ")." +
         leftOffText(candidate, data) + " Model-file entry: " + candidate.modelEntry;
}

std::string diagnosisSummary(const Diagnosis& diagnosis, double minimumReduction) {
  std::string summary;
  const auto& ranking = diagnosis.ranking;
  if (!ranking.empty() && ranking.front().suggested) {
    summary = ranking.front().explanation;
    for (std::size_t k = 1; k < ranking.size() && k < 3 && ranking[k].suggested; ++k) {
      summary += "\nNext: " + ranking[k].explanation;
    }
  } else {
    summary = "No effect lowers the held-out error significantly (each must remove at least " +
              percentText(minimumReduction) + " of a channel's held-out residual and pass the information criterion)";
    if (!ranking.empty()) {
      summary += "; the closest, " + ranking.front().effect + ", would change it by " +
                 percentText(-ranking.front().heldoutReduction);
    }
    summary += ".";
    if (diagnosis.residualFollows.empty()) {
      summary += " The held-out residual correlates with none of the signals (|r| < 0.1): it looks like noise.";
    } else {
      summary += " The held-out residual still follows:";
      for (std::size_t k = 0; k < diagnosis.residualFollows.size() && k < 5; ++k) {
        const auto& follow = diagnosis.residualFollows[k];
        summary +=
            (k ? ", " : " ") + follow.signal + " on " + follow.channel + " (r = " + number(follow.correlation) + ")";
      }
      summary += ".";
    }
  }
  if (!std::isnan(diagnosis.explainable)) {
    summary += "\nThe catalogue explains " + percentText(diagnosis.catalogueExplains) +
               " of the held-out residual, of the " + percentText(diagnosis.explainable) +
               " that can be explained at all (the rest is at the noise floor, " +
               "estimated from the residual's second differences).";
  }
  return summary;
}

}  // namespace arcplan::model::detail
