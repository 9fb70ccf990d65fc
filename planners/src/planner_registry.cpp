#include "arcplan/planners/planner_registry.h"

#include <ompl/geometric/planners/est/BiEST.h>
#include <ompl/geometric/planners/est/EST.h>
#include <ompl/geometric/planners/est/ProjEST.h>
#include <ompl/geometric/planners/fmt/BFMT.h>
#include <ompl/geometric/planners/fmt/FMT.h>
#include <ompl/geometric/planners/informedtrees/ABITstar.h>
#include <ompl/geometric/planners/informedtrees/AITstar.h>
#include <ompl/geometric/planners/informedtrees/BITstar.h>
#include <ompl/geometric/planners/kpiece/BKPIECE1.h>
#include <ompl/geometric/planners/kpiece/KPIECE1.h>
#include <ompl/geometric/planners/kpiece/LBKPIECE1.h>
#include <ompl/geometric/planners/pdst/PDST.h>
#include <ompl/geometric/planners/prm/LazyPRM.h>
#include <ompl/geometric/planners/prm/LazyPRMstar.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/prm/PRMstar.h>
#include <ompl/geometric/planners/rrt/BiTRRT.h>
#include <ompl/geometric/planners/rrt/InformedRRTstar.h>
#include <ompl/geometric/planners/rrt/LBTRRT.h>
#include <ompl/geometric/planners/rrt/LazyRRT.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTXstatic.h>
#include <ompl/geometric/planners/rrt/RRTsharp.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/geometric/planners/rrt/SORRTstar.h>
#include <ompl/geometric/planners/rrt/TRRT.h>
#include <ompl/geometric/planners/sbl/SBL.h>
#include <ompl/geometric/planners/stride/STRIDE.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdlib>
#include <functional>
#include <map>
#include <optional>
#include <sstream>

#include "arcplan/common/error.h"
#include "arcplan/planners/arc_planner.h"
#include "planner_properties.h"

namespace og = ompl::geometric;
namespace ob = ompl::base;

namespace arcplan::planners {
namespace {

// The time of a registered OMPL planner's last solve(), taken around that call alone, as the arc planner takes its
// own (lastSolveTime). A caller's clock around Planner::solve(fn, checkInterval) — OMPL's Benchmark asks solve(ptc,
// 0.1), SimpleSetup::solve(t) a hundredth of t from 1 s on — also counts the wait for the thread that evaluates the
// termination condition: it sleeps in 1 ms steps and is joined after the solve, so a 50 µs RRTConnect solve was
// recorded as 1.1–1.2 ms in most runs of a campaign on an idle machine (docs/benchmarks.md, "Solve time").
class SolveClock {
public:
  virtual ~SolveClock() = default;
  double lastSolveTime() const { return lastSolveTime_; }

protected:
  double lastSolveTime_ = 0.0;
};

template <typename PlannerType>
class SolveTimed final : public PlannerType, public SolveClock {
public:
  explicit SolveTimed(const ob::SpaceInformationPtr& si) : PlannerType(si) {}

  using PlannerType::solve;
  ob::PlannerStatus solve(const ob::PlannerTerminationCondition& ptc) override {
    const auto start = std::chrono::steady_clock::now();
    const ob::PlannerStatus status = PlannerType::solve(ptc);
    lastSolveTime_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return status;
  }

  void getPlannerData(ob::PlannerData& data) const override {
    PlannerType::getPlannerData(data);
    detail::recordSolveTime(data, lastSolveTime_);
  }
};

template <typename PlannerType>
ob::PlannerAllocator omplAllocator() {
  return [](const ob::SpaceInformationPtr& si) { return std::make_shared<SolveTimed<PlannerType>>(si); };
}

using AllocatorFactory = std::function<ob::PlannerAllocator()>;

// Registration order is the order `plannerNames` lists.
const std::vector<std::pair<std::string, AllocatorFactory>>& omplPlanners() {
  static const std::vector<std::pair<std::string, AllocatorFactory>> planners = {
      {"RRTConnect", omplAllocator<og::RRTConnect>},
      {"RRT", omplAllocator<og::RRT>},
      {"RRTstar", omplAllocator<og::RRTstar>},
      {"InformedRRTstar", omplAllocator<og::InformedRRTstar>},
      {"SORRTstar", omplAllocator<og::SORRTstar>},
      {"RRTsharp", omplAllocator<og::RRTsharp>},
      {"RRTXstatic", omplAllocator<og::RRTXstatic>},
      {"LazyRRT", omplAllocator<og::LazyRRT>},
      {"BiTRRT", omplAllocator<og::BiTRRT>},
      {"TRRT", omplAllocator<og::TRRT>},
      {"LBTRRT", omplAllocator<og::LBTRRT>},
      {"PRM", omplAllocator<og::PRM>},
      {"PRMstar", omplAllocator<og::PRMstar>},
      {"LazyPRM", omplAllocator<og::LazyPRM>},
      {"LazyPRMstar", omplAllocator<og::LazyPRMstar>},
      {"KPIECE1", omplAllocator<og::KPIECE1>},
      {"BKPIECE1", omplAllocator<og::BKPIECE1>},
      {"LBKPIECE1", omplAllocator<og::LBKPIECE1>},
      {"EST", omplAllocator<og::EST>},
      {"BiEST", omplAllocator<og::BiEST>},
      {"ProjEST", omplAllocator<og::ProjEST>},
      {"SBL", omplAllocator<og::SBL>},
      {"STRIDE", omplAllocator<og::STRIDE>},
      {"PDST", omplAllocator<og::PDST>},
      {"FMT", omplAllocator<og::FMT>},
      {"BFMT", omplAllocator<og::BFMT>},
      {"BITstar", omplAllocator<og::BITstar>},
      {"ABITstar", omplAllocator<og::ABITstar>},
      {"AITstar", omplAllocator<og::AITstar>},
  };
  return planners;
}

constexpr const char* kArcName = "arc";

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

// The numeric bounds of an OMPL range suggestion ("low:high" or "low:step:high"); none for other
// suggestions (a list of choices such as "0,1", or nothing).
std::optional<std::pair<double, double>> numericRange(const std::string& suggestion) {
  std::vector<double> numbers;
  std::size_t begin = 0;
  while (begin <= suggestion.size()) {
    const std::size_t end = std::min(suggestion.find(':', begin), suggestion.size());
    const std::string part = suggestion.substr(begin, end - begin);
    char* stop = nullptr;
    const double value = std::strtod(part.c_str(), &stop);
    if (part.empty() || stop != part.c_str() + part.size()) return std::nullopt;
    numbers.push_back(value);
    begin = end + 1;
  }
  if (numbers.size() < 2 || numbers.size() > 3) return std::nullopt;
  return std::make_pair(numbers.front(), numbers.back());
}

std::string joined(const std::vector<std::string>& items) {
  std::string text;
  for (const auto& item : items) text += (text.empty() ? "" : ", ") + item;
  return text;
}

}  // namespace

const std::vector<std::string>& plannerNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> list{kArcName};
    for (const auto& [name, factory] : omplPlanners()) list.push_back(name);
    return list;
  }();
  return names;
}

std::string canonicalPlannerName(const std::string& name) {
  for (const std::string& known : plannerNames()) {
    if (lowercase(known) == lowercase(name)) return known;
  }
  throw Error("unknown planner '" + name + "'; known planners: " + joined(plannerNames()));
}

bool isArcPlanner(const std::string& name) { return canonicalPlannerName(name) == kArcName; }

ob::PlannerAllocator plannerAllocator(const std::string& name, const PlannerContext& context) {
  const std::string canonical = canonicalPlannerName(name);
  if (canonical == kArcName) {
    if (!context.collisionModel) throw Error("the arc planner needs the problem's collision model");
    return [context](const ob::SpaceInformationPtr& si) {
      return std::make_shared<ArcPlanner>(si, context.collisionModel, context.obstacles);
    };
  }
  for (const auto& [registered, factory] : omplPlanners()) {
    if (registered == canonical) return factory();
  }
  throw Error("planner '" + canonical + "' has no allocator");  // unreachable: every name has one
}

double lastSolveTime(const ob::Planner& planner) {
  if (const auto* arc = dynamic_cast<const ArcPlanner*>(&planner)) return arc->lastResult().solveTime;
  if (const auto* timed = dynamic_cast<const SolveClock*>(&planner)) return timed->lastSolveTime();
  throw Error("planner '" + planner.getName() +
              "' was not made by the planner registry: it has no solve time of its own");
}

ob::PlannerPtr makePlanner(const std::string& name, const ob::SpaceInformationPtr& si, const PlannerContext& context,
                           const std::vector<std::pair<std::string, std::string>>& parameters) {
  ob::PlannerPtr planner = plannerAllocator(name, context)(si);
  setPlannerParameters(*planner, parameters);
  return planner;
}

void setPlannerParameters(ob::Planner& planner, const std::vector<std::pair<std::string, std::string>>& parameters) {
  for (const auto& [key, value] : parameters) {
    if (!planner.params().hasParam(key)) {
      std::map<std::string, std::string> current;
      planner.params().getParams(current);
      std::vector<std::string> valid;
      for (const auto& [parameter, setting] : current) valid.push_back(parameter + "=" + setting);
      throw Error("planner " + planner.getName() + " has no parameter '" + key +
                  "'; its parameters: " + (valid.empty() ? std::string("(none)") : joined(valid)));
    }
    const std::string rejected =
        "planner " + planner.getName() + ": parameter '" + key + "' does not accept '" + value + "'";
    // OMPL's setters take any number; the declared range is the contract the planner documents.
    const std::string suggestion = planner.params()[key].getRangeSuggestion();
    if (const auto range = numericRange(suggestion)) {
      char* stop = nullptr;
      const double number = std::strtod(value.c_str(), &stop);
      if (stop != value.c_str() + value.size() || !(number >= range->first && number <= range->second)) {
        std::ostringstream message;
        message << rejected << ": expected a number in [" << range->first << ", " << range->second
                << "] (declared range " << suggestion << ")";
        throw Error(message.str());
      }
    }
    bool accepted = false;
    try {
      accepted = planner.params().setParam(key, value);
    } catch (const Error& error) {
      throw Error(rejected + ": " + error.what());
    } catch (const std::exception& error) {  // OMPL's own number parsing throws std::runtime_error
      throw Error(rejected + ": " + error.what());
    }
    if (!accepted) {
      throw Error(rejected + (suggestion.empty() ? "" : " (suggested range " + suggestion + ")"));
    }
  }
}

std::vector<std::pair<std::string, std::vector<DeclaredParameter>>> declaredParameters(
    const ob::SpaceInformationPtr& si, const PlannerContext& context) {
  std::vector<std::pair<std::string, std::vector<DeclaredParameter>>> result;
  for (const std::string& name : plannerNames()) {
    const ob::PlannerPtr planner = plannerAllocator(name, context)(si);
    std::vector<DeclaredParameter> parameters;
    for (const auto& [key, parameter] : planner->params().getParams()) {
      parameters.push_back({key, parameter->getValue(), parameter->getRangeSuggestion()});
    }
    result.emplace_back(name, std::move(parameters));
  }
  return result;
}

std::pair<std::string, std::string> parseParameterAssignment(const std::string& text) {
  const auto equals = text.find('=');
  if (equals == std::string::npos || equals == 0 || equals + 1 == text.size()) {
    throw Error("--param expects NAME=VALUE (e.g. range=0.2), got '" + text + "'");
  }
  return {text.substr(0, equals), text.substr(equals + 1)};
}

}  // namespace arcplan::planners
