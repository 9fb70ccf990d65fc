#pragma once
// A physical effect: a named term of the model whose regressor columns, per channel (joint), are
// computed from the log's signals. Most effects are linear in their parameters (fitted by least
// squares per joint); some have one nonlinear parameter that is searched (a delay, a spatial
// frequency, a Stribeck velocity).
//
// Users add effects without touching the core, either as a C++ class registered by name:
//
//   class Drag : public arcplan::model::Effect { ... };
//   arcplan::model::registerEffect("drag", [](const EffectSpec& s) { return std::make_unique<Drag>(s); });
//
// or as an expression over the log's signals in the model file (see model_spec.h).
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "arcplan/model/model_spec.h"

namespace arcplan::model {

class Dataset;

struct NonlinearParameter {
  std::string name;          // key in the model file ("stribeck_velocity")
  std::string unit;          // for reports ("rad/s")
  std::vector<double> grid;  // candidates tried by the default search; refined between neighbours
  bool integer = false;      // integer-valued (no refinement between grid points)
};

// A parameter of the arm in physical units (a payload's mass in kg), from an effect fitted jointly
// across channels, with its standard errors.
struct PhysicalQuantity {
  std::string name;  // "mass_kg", "center_of_mass_m"
  std::string meaning;
  std::vector<double> values, standardErrors;
};

class Effect {
public:
  explicit Effect(EffectSpec spec) : spec_(std::move(spec)) {}
  virtual ~Effect() = default;

  const EffectSpec& spec() const { return spec_; }
  const std::string& id() const { return spec_.id; }

  // Physical meaning in one sentence, and the term as a formula (for docs, reports and --help).
  virtual std::string meaning() const = 0;
  virtual std::string term() const = 0;
  // How the residual of a model lacking this effect looks, completing "the residual on joints 1-2 ...".
  virtual std::string residualPattern() const = 0;
  virtual bool appliesTo(ModelKind kind) const = 0;
  // Dataset signals the regressor reads (see dataset.h for the names).
  virtual std::vector<std::string> requiredSignals() const = 0;
  // Names of the linear parameters, one regressor column each.
  virtual std::vector<std::string> parameterNames() const = 0;
  virtual std::optional<NonlinearParameter> nonlinearParameter() const { return std::nullopt; }
  // Extra numeric options the model file may set for this effect (besides the nonlinear parameter).
  virtual std::vector<std::string> optionNames() const { return {}; }

  // Regressor columns (samples x parameterNames().size()) of `channel`; `nonlinear` is the value of
  // the nonlinear parameter (ignored by linear effects).
  virtual void regressor(const Dataset& data, int channel, double nonlinear,
                         Eigen::Ref<Eigen::MatrixXd> columns) const = 0;

  // Chooses the nonlinear parameter that best explains `residual` (samples of `channel`): the
  // default tries every grid value, fits the columns by least squares and refines around the best
  // with a golden-section search. `basis` (orthonormal columns, possibly none) spans the model's
  // other columns, which `residual` is already orthogonal to: the effect's columns are measured
  // by what they add beyond them (variable projection), so a term the others partly explain is
  // not misplaced. Effects with a faster exact search override it.
  virtual double searchNonlinear(const Dataset& data, int channel, const Eigen::VectorXd& residual,
                                 const Eigen::MatrixXd& basis = Eigen::MatrixXd()) const;

  // Effects whose parameters are physical quantities of the whole arm (a payload) have ONE set of
  // parameters for all channels, fitted jointly: channel c's prediction is gain_c·columns_c·θ, with
  // gain_c the channel's drive gain (current per N·m) from the same fit. Per-channel values stored
  // for such an effect are gain_c·θ.
  virtual bool sharedAcrossChannels() const { return false; }
  // θ and its covariance in physical units (for reports); empty for ordinary effects.
  virtual std::vector<PhysicalQuantity> physicalQuantities(const Eigen::VectorXd& shared,
                                                           const Eigen::MatrixXd& covariance) const;

  // Typical parameter values on a UR10e, used by `arcplan model simulate` when the model file gives
  // none (per channel, in the units of the channel's prediction).
  virtual std::vector<double> typicalParameters(ModelKind kind, int channel) const;
  virtual double typicalNonlinear(int channel) const;

  // The value of an option or the fixed nonlinear parameter from the model file, if set.
  std::optional<double> option(const std::string& name) const;

private:
  EffectSpec spec_;
};

using EffectFactory = std::function<std::unique_ptr<Effect>(const EffectSpec&)>;

// Adds an effect under `id` (throws arcplan::Error if the id is taken). The built-in catalogue is
// registered on first use of the registry.
void registerEffect(const std::string& id, EffectFactory factory);
bool isRegisteredEffect(const std::string& id);
std::vector<std::string> registeredEffects();
// The built-in catalogue (docs/model.md, "Effect catalogue"), in its order.
const std::vector<std::string>& catalogueEffects();

// The effect for a spec: a registered id, or a user expression effect when spec.expressions is
// set. Throws arcplan::Error naming the unknown id and listing the known ones.
std::unique_ptr<Effect> createEffect(const EffectSpec& spec);

// Smoothed sign used by every friction term: tanh(x / width).
double smoothSign(double x, double width);

}  // namespace arcplan::model
