// Discovery beyond the catalogue (diagnose.h): screen every library term on the training residual,
// score the best few per channel on held-out data, and turn the ones that pass into candidates
// with a ready-to-paste model-file entry.
#include <algorithm>
#include <cctype>
#include <map>

#include "arcplan/model/term_library.h"
#include "model_internal.h"

namespace arcplan::model::detail {
namespace {

// How many discovered terms the ranking shows (the best ones; the loop finds the next after a fit).
constexpr std::size_t kShownTerms = 3;

std::string idFor(const std::string& expression) {
  std::string id = "found_";
  for (char ch : expression) {
    const bool keep = std::isalnum(static_cast<unsigned char>(ch)) != 0;
    if (keep) {
      id += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    } else if (id.back() != '_') {
      id += '_';
    }
  }
  while (id.back() == '_') id.pop_back();
  return id;
}

std::string entryText(const EffectSpec& entry) {
  std::string joints;
  for (int j : entry.joints) joints += (joints.empty() ? "" : ", ") + std::to_string(j);
  return "{id: " + entry.id + ", expression: \"" + entry.expressions.front() + "\", joints: [" + joints + "]}";
}

// Training-data share of the residual each term explains beyond the model's own columns:
// (xᵀr)² / |x⊥|², x⊥ = x minus its projection on the columns (r is already orthogonal to them).
std::vector<std::pair<double, CandidateTerm>> screen(const Dataset& data, int channel, const Eigen::MatrixXd& basis,
                                                     const Eigen::VectorXd& residual) {
  Eigen::VectorXd orthogonal = residual;
  if (basis.cols() > 0) orthogonal -= basis * (basis.transpose() * residual);
  std::vector<std::pair<double, CandidateTerm>> scored;
  for (auto& term : candidateTerms(data, channel)) {
    const Eigen::VectorXd x = evaluateTerm(term, data, channel);
    const double norm = x.squaredNorm();
    const double projected = basis.cols() > 0 ? (basis.transpose() * x).squaredNorm() : 0.0;
    const double remaining = norm - projected;
    if (!(remaining > 1e-9 * norm)) continue;  // the model's columns already span it
    const double along = x.dot(orthogonal);
    scored.emplace_back(along * along / remaining, std::move(term));
  }
  return scored;
}

}  // namespace

std::vector<EffectCandidate> discoverTerms(const Dataset& data, const Dataset* validation,
                                           const HeldOutBaseline& baseline, const DiagnoseOptions& options) {
  std::vector<EffectCandidate> found;
  if (!data.timeOrdered() || data.kind() == ModelKind::GearboxFtd) return found;
  const int channels = data.channelCount();
  std::map<std::string, CandidateTerm> shortlist;  // by expression: deterministic order, no repeats
  for (int c = 0; c < channels; ++c) {
    auto scored = screen(data, c, baseline.trainBasis[c], baseline.trainResidual[c]);
    const auto keep =
        std::min<std::size_t>(scored.size(), static_cast<std::size_t>(std::max(1, options.screenedPerChannel)));
    std::partial_sort(scored.begin(), scored.begin() + static_cast<std::ptrdiff_t>(keep), scored.end(),
                      [](const auto& a, const auto& b) { return a.first > b.first; });
    for (std::size_t k = 0; k < keep; ++k) shortlist.emplace(scored[k].second.expression, scored[k].second);
  }
  std::vector<std::pair<std::string, std::string>> pictures;  // words and picture of each of `found`
  for (const auto& [expression, term] : shortlist) {
    std::vector<double> squares(static_cast<std::size_t>(channels));
    std::vector<int> ranks(static_cast<std::size_t>(channels));
    for (int c = 0; c < channels; ++c) {
      const Eigen::MatrixXd train = evaluateTerm(term, data, c);
      const Eigen::MatrixXd held = validation ? Eigen::MatrixXd(evaluateTerm(term, *validation, c)) : Eigen::MatrixXd();
      std::tie(squares[c], ranks[c]) = baseline.scorers[c].score(train, held);
    }
    EffectCandidate candidate;
    candidate.discovered = true;
    candidate.effect = idFor(expression);
    candidate.entry.id = candidate.effect;
    candidate.entry.expressions = {expression};
    candidate.nonlinear.assign(static_cast<std::size_t>(channels), std::numeric_limits<double>::quiet_NaN());
    judgeCandidate(candidate, squares, ranks, false, baseline, options.minimumReduction);
    if (!candidate.suggested) continue;
    candidate.entry.explanation = term.picture.empty() ? term.words : term.words + ": " + term.picture;
    found.push_back(std::move(candidate));
    pictures.emplace_back(term.words, term.picture);
  }
  // The best first; each checked by its step (checkStep) until kShownTerms pass.
  std::vector<std::size_t> order(found.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  auto better = [&](std::size_t a, std::size_t b) { return found[a].heldoutReduction > found[b].heldoutReduction; };
  std::stable_sort(order.begin(), order.end(), better);
  std::vector<EffectCandidate> shown;
  for (std::size_t k = 0; k < order.size() && shown.size() < kShownTerms; ++k) {
    EffectCandidate& candidate = found[order[k]];
    if (baseline.checkStep) baseline.checkStep(candidate);
    if (!candidate.suggested) continue;
    candidate.modelEntry = entryText(candidate.entry);
    const auto& [words, picture] = pictures[order[k]];
    candidate.explanation = explainDiscovery(candidate, words, picture, data);
    shown.push_back(std::move(candidate));
  }
  std::stable_sort(shown.begin(), shown.end(),
                   [](const auto& a, const auto& b) { return a.heldoutReduction > b.heldoutReduction; });
  return shown;
}

}  // namespace arcplan::model::detail
