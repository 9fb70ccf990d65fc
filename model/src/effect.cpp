#include "arcplan/model/effect.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>

#include <Eigen/Cholesky>

#include "arcplan/common/error.h"
#include "arcplan/model/dataset.h"
#include "model_internal.h"

namespace arcplan::model {

namespace {

struct Registry {
  Registry() {
    for (const auto& entry : detail::catalogueTable()) factories[entry.id] = entry.factory;
  }
  std::mutex mutex;
  std::map<std::string, EffectFactory> factories;
};

Registry& registry() {
  static Registry instance;
  return instance;
}

// Residual sum of squares left after fitting `columns`, beyond the span of `basis`, to `residual`
// (orthogonal to that span).
double remainingSquares(Eigen::MatrixXd columns, const Eigen::VectorXd& residual, const Eigen::MatrixXd& basis) {
  if (basis.cols() > 0 && basis.rows() == columns.rows()) columns -= basis * (basis.transpose() * columns);
  const Eigen::MatrixXd gram = columns.transpose() * columns;
  const Eigen::VectorXd moment = columns.transpose() * residual;
  const Eigen::LDLT<Eigen::MatrixXd> solver(gram +
                                            1e-12 * gram.trace() * Eigen::MatrixXd::Identity(gram.rows(), gram.cols()));
  return residual.squaredNorm() - moment.dot(solver.solve(moment));
}

}  // namespace

double smoothSign(double x, double width) { return std::tanh(x / width); }

std::optional<double> Effect::option(const std::string& name) const {
  const auto it = spec_.options.find(name);
  if (it == spec_.options.end()) return std::nullopt;
  return it->second;
}

double Effect::searchNonlinear(const Dataset& data, int channel, const Eigen::VectorXd& residual,
                               const Eigen::MatrixXd& basis) const {
  const auto parameter = nonlinearParameter();
  if (!parameter) return 0.0;
  if (const auto fixed = option(parameter->name)) return *fixed;
  const auto& grid = parameter->grid;
  Eigen::MatrixXd columns(data.samples(channel), static_cast<Eigen::Index>(parameterNames().size()));
  auto cost = [&](double value) {
    regressor(data, channel, value, columns);
    return remainingSquares(columns, residual, basis);
  };
  std::size_t best = 0;
  double bestCost = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const double c = cost(grid[i]);
    if (c < bestCost) {
      bestCost = c;
      best = i;
    }
  }
  if (parameter->integer || grid.size() < 3) return grid[best];
  // Golden-section refinement between the neighbours of the best grid point.
  double low = grid[best == 0 ? 0 : best - 1], high = grid[std::min(best + 1, grid.size() - 1)];
  const double ratio = (std::sqrt(5.0) - 1.0) / 2.0;
  double a = high - ratio * (high - low), b = low + ratio * (high - low);
  double costA = cost(a), costB = cost(b);
  for (int iteration = 0; iteration < 25; ++iteration) {
    if (costA < costB) {
      high = b;
      b = a;
      costB = costA;
      a = high - ratio * (high - low);
      costA = cost(a);
    } else {
      low = a;
      a = b;
      costA = costB;
      b = low + ratio * (high - low);
      costB = cost(b);
    }
  }
  const double refined = 0.5 * (low + high);
  return cost(refined) <= bestCost ? refined : grid[best];
}

std::vector<PhysicalQuantity> Effect::physicalQuantities(const Eigen::VectorXd&, const Eigen::MatrixXd&) const {
  return {};
}

std::vector<double> Effect::typicalParameters(ModelKind, int) const {
  return std::vector<double>(parameterNames().size(), 0.0);
}

double Effect::typicalNonlinear(int) const {
  const auto parameter = nonlinearParameter();
  return parameter && !parameter->grid.empty() ? parameter->grid[parameter->grid.size() / 2] : 0.0;
}

void registerEffect(const std::string& id, EffectFactory factory) {
  auto& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  if (id.empty()) throw Error("registerEffect: empty effect id");
  if (r.factories.count(id)) throw Error("registerEffect: effect '" + id + "' is already registered");
  r.factories[id] = std::move(factory);
}

bool isRegisteredEffect(const std::string& id) {
  auto& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  return r.factories.count(id) > 0;
}

std::vector<std::string> registeredEffects() {
  auto& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  std::vector<std::string> ids = catalogueEffects();
  for (const auto& [id, factory] : r.factories) {
    if (std::find(ids.begin(), ids.end(), id) == ids.end()) ids.push_back(id);
  }
  return ids;
}

const std::vector<std::string>& catalogueEffects() {
  static const std::vector<std::string> ids = [] {
    std::vector<std::string> list;
    for (const auto& entry : detail::catalogueTable()) list.push_back(entry.id);
    return list;
  }();
  return ids;
}

std::unique_ptr<Effect> createEffect(const EffectSpec& spec) {
  if (!spec.expressions.empty()) {
    if (isRegisteredEffect(spec.id)) {
      throw Error("effect '" + spec.id + "': an expression effect cannot reuse the name of a registered effect");
    }
    return detail::makeExpressionEffect(spec);
  }
  EffectFactory factory;
  {
    auto& r = registry();
    std::lock_guard<std::mutex> lock(r.mutex);
    const auto it = r.factories.find(spec.id);
    if (it != r.factories.end()) factory = it->second;
  }
  if (!factory) {
    std::string known;
    for (const auto& id : registeredEffects()) known += (known.empty() ? "" : ", ") + id;
    throw Error("unknown effect '" + spec.id + "' (known: " + known +
                "; or give an expression: {id: NAME, expression: \"...\"})");
  }
  auto effect = factory(spec);
  const auto allowed = effect->optionNames();
  const auto parameter = effect->nonlinearParameter();
  for (const auto& [name, value] : spec.options) {
    const bool known =
        std::find(allowed.begin(), allowed.end(), name) != allowed.end() || (parameter && parameter->name == name);
    if (!known) {
      std::string names;
      for (const auto& n : allowed) names += (names.empty() ? "" : ", ") + n;
      if (parameter) names += (names.empty() ? "" : ", ") + parameter->name;
      throw Error("effect '" + spec.id + "': unknown option '" + name +
                  "' (options: " + (names.empty() ? std::string("none") : names) + ")");
    }
  }
  return effect;
}

}  // namespace arcplan::model
