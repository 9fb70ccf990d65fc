// A user effect written in the model file (or proposed by the diagnosis' discovery): each
// expression is one regressor column, evaluated by muparser over the dataset's signals. Variables: the channel's own
// signals by name (q, qd, qdd, tau, temperature, time, ...), every joint's signal as name_j (q_0, tau_3, ...), and
// sgn(x, w) for the smoothed sign.
#include <cmath>
#include <deque>

#include <muParser.h>

#include "arcplan/common/error.h"
#include "arcplan/model/dataset.h"
#include "arcplan/model/effect.h"
#include "model_internal.h"

namespace arcplan::model {
namespace {

double smoothedSign(double x, double width) { return smoothSign(x, width); }

class ExpressionEffect : public Effect {
public:
  explicit ExpressionEffect(const EffectSpec& spec) : Effect(spec) {
    // Syntax is checked now (unknown variables are accepted until a dataset binds them).
    for (std::size_t i = 0; i < spec.expressions.size(); ++i) {
      mu::Parser parser;
      parser.DefineFun("sgn", smoothedSign);
      parser.SetVarFactory([](const char*, void* user) -> double* { return static_cast<double*>(user); }, &scratch_);
      try {
        parser.SetExpr(spec.expressions[i]);
        parser.Eval();
      } catch (const mu::Parser::exception_type& e) {
        throw Error("effect '" + spec.id + "': expression '" + spec.expressions[i] + "': " + e.GetMsg());
      }
    }
  }
  std::string meaning() const override {
    return spec().explanation.empty() ? "user effect: " + term() : spec().explanation;
  }
  std::string term() const override {
    std::string text;
    for (std::size_t i = 0; i < spec().expressions.size(); ++i) {
      text += (i ? " + " : "") + std::string("c") + std::to_string(i) + "·(" + spec().expressions[i] + ")";
    }
    return text;
  }
  std::string residualPattern() const override { return "follows " + term(); }
  bool appliesTo(ModelKind) const override { return true; }
  std::vector<std::string> requiredSignals() const override { return {}; }
  std::vector<std::string> parameterNames() const override {
    std::vector<std::string> names;
    for (std::size_t i = 0; i < spec().expressions.size(); ++i) names.push_back("c" + std::to_string(i));
    return names;
  }

  void regressor(const Dataset& data, int channel, double, Eigen::Ref<Eigen::MatrixXd> columns) const override {
    const int samples = static_cast<int>(data.samples(channel));
    for (std::size_t i = 0; i < spec().expressions.size(); ++i) {
      mu::Parser parser;
      parser.DefineFun("sgn", smoothedSign);
      // Bulk mode reads every variable as an array of `samples` values; a deque keeps them in place.
      std::deque<Eigen::VectorXd> bound;
      auto bind = [&](const std::string& name, const Eigen::VectorXd& values) {
        bound.push_back(values);
        parser.DefineVar(name, bound.back().data());
      };
      try {
        parser.SetExpr(spec().expressions[i]);
        std::vector<std::string> used;  // copied: defining variables changes the parser's map
        for (const auto& entry : parser.GetUsedVar()) used.push_back(entry.first);
        for (const auto& name : used) {
          if (data.hasSignal(name)) {
            bind(name, data.signal(name, channel));
            continue;
          }
          const auto underscore = name.rfind('_');
          const std::string base = underscore == std::string::npos ? "" : name.substr(0, underscore);
          const std::string index = underscore == std::string::npos ? "" : name.substr(underscore + 1);
          const bool numbered =
              !index.empty() && index.size() <= 3 && index.find_first_not_of("0123456789") == std::string::npos;
          if (numbered && data.hasSignal(base) && std::stoi(index) < data.channelCount() &&
              data.samples(std::stoi(index)) == data.samples(channel)) {
            bind(name, data.signal(base, std::stoi(index)));
            continue;
          }
          std::string available;
          for (const auto& n : data.signalNames()) available += (available.empty() ? "" : ", ") + n;
          throw Error(data.source() + ": effect '" + id() + "': expression '" + spec().expressions[i] +
                      "' needs signal '" + name + "', which this log does not provide (available: " + available +
                      ", or name_J for joint J)");
        }
        parser.Eval(columns.col(static_cast<Eigen::Index>(i)).data(), samples);
      } catch (const mu::Parser::exception_type& e) {
        throw Error("effect '" + id() + "': expression '" + spec().expressions[i] + "': " + e.GetMsg());
      }
    }
    if (!columns.allFinite()) {
      throw Error("effect '" + id() + "': an expression gives NaN or infinite values on " + data.channelName(channel));
    }
  }

private:
  double scratch_ = 1.0;
};

}  // namespace

std::unique_ptr<Effect> detail::makeExpressionEffect(const EffectSpec& spec) {
  return std::make_unique<ExpressionEffect>(spec);
}

}  // namespace arcplan::model
