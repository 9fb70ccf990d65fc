#include "summary.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <set>
#include <sstream>

namespace arcplan::peer_vamp {
namespace {

nlohmann::json number(const std::optional<double>& value) { return value ? nlohmann::json(*value) : nullptr; }

struct Totals {
  std::size_t problems = 0, validInputs = 0, solved = 0, validExact = 0;
  std::vector<double> total, planning, simplification, wall, cost, certification;
};

Totals totals(const std::vector<Outcome>& outcomes, const std::string& family = "") {
  Totals t;
  for (const Outcome& o : outcomes) {
    if (!family.empty() && o.family != family) continue;
    ++t.problems;
    t.validInputs += o.inputsValid;
    if (!o.solved) continue;
    ++t.solved;
    t.validExact += o.validExact;
    if (o.validExact) t.certification.push_back(o.certificationUs);
    t.total.push_back(o.totalUs);
    t.planning.push_back(o.planningUs);
    t.simplification.push_back(o.simplificationUs);
    if (o.wallUs) t.wall.push_back(*o.wallUs);
    t.cost.push_back(o.pathCost);
  }
  return t;
}

nlohmann::json totalsJson(const Totals& t) {
  nlohmann::json json = {{"problems", t.problems},
                         {"valid_inputs", t.validInputs},
                         {"solved", t.solved},
                         {"total_us_median", number(percentile(t.total, 0.5))},
                         {"total_us_p95", number(percentile(t.total, 0.95))},
                         {"planning_us_median", number(percentile(t.planning, 0.5))},
                         {"simplification_us_median", number(percentile(t.simplification, 0.5))},
                         {"paths_valid_exact", t.validExact},
                         {"path_cost_rad_median", number(percentile(t.cost, 0.5))},
                         {"certification_us_median", number(percentile(t.certification, 0.5))},
                         {"certification_us_p95", number(percentile(t.certification, 0.95))}};
  if (!t.wall.empty()) {
    json["wall_us_median"] = number(percentile(t.wall, 0.5));
    json["wall_us_p95"] = number(percentile(t.wall, 0.95));
  }
  return json;
}

nlohmann::json outcomeJson(const Outcome& o) {
  nlohmann::json json = {
      {"family", o.family}, {"problem", o.problem}, {"inputs_valid", o.inputsValid}, {"solved", o.solved}};
  if (!o.solved) {
    json["reason"] = o.reason;
    return json;
  }
  json.update({{"total_us", o.totalUs},
               {"planning_us", o.planningUs},
               {"simplification_us", o.simplificationUs},
               {"path_cost_rad", o.pathCost},
               {"waypoints", o.waypoints},
               {"path_valid_exact", o.validExact},
               {"path_start", o.pathStart},
               {"path_end", o.pathEnd},
               {"start_error_rad", o.startError},
               {"goal_error_rad", o.goalError}});
  if (o.wallUs) json["wall_us"] = *o.wallUs;
  if (!o.mode.empty()) json["mode"] = o.mode;
  if (o.validExact) json["certification_us"] = o.certificationUs;
  if (!o.validExact) json["exact_failure"] = o.exactFailure;
  return json;
}

std::string cell(const std::optional<double>& value, int decimals) {
  if (!value) return "–";
  std::ostringstream text;
  text << std::fixed << std::setprecision(decimals) << *value;
  return text.str();
}

void table(std::ostringstream& out, const std::map<std::string, std::vector<Outcome>>& byPlanner,
           const std::vector<std::string>& order, const std::string& family) {
  out << "| planner | solved / valid inputs / problems | total median [µs] | total 95th [µs] | "
         "paths valid under exact meshes | certifying a valid path, median / 95th [µs] |\n|---|---|---|---|---|---|\n";
  for (const std::string& planner : order) {
    const Totals t = totals(byPlanner.at(planner), family);
    out << "| " << planner << " | " << t.solved << " / " << t.validInputs << " / " << t.problems << " | "
        << cell(percentile(t.total, 0.5), 0) << " | " << cell(percentile(t.total, 0.95), 0) << " | " << t.validExact
        << " / " << t.solved << " | " << cell(percentile(t.certification, 0.5), 0) << " / "
        << cell(percentile(t.certification, 0.95), 0) << " |\n";
  }
}

}  // namespace

std::optional<double> percentile(std::vector<double> values, double p) {
  if (values.empty()) return std::nullopt;
  std::sort(values.begin(), values.end());
  const double position = p * static_cast<double>(values.size() - 1);
  const auto below = static_cast<std::size_t>(std::floor(position));
  const std::size_t above = std::min(below + 1, values.size() - 1);
  return values[below] + (position - static_cast<double>(below)) * (values[above] - values[below]);
}

nlohmann::json plannerJson(const std::vector<Outcome>& outcomes) {
  nlohmann::json json = totalsJson(totals(outcomes));
  std::set<std::string> families;
  for (const Outcome& o : outcomes) families.insert(o.family);
  json["families"] = nlohmann::json::object();
  for (const std::string& family : families) json["families"][family] = totalsJson(totals(outcomes, family));
  json["per_problem"] = nlohmann::json::array();
  for (const Outcome& o : outcomes) json["per_problem"].push_back(outcomeJson(o));
  return json;
}

std::string markdownTables(const std::map<std::string, std::vector<Outcome>>& byPlanner,
                           const std::vector<std::string>& plannerOrder) {
  std::ostringstream out;
  out << "All problems\n\n";
  table(out, byPlanner, plannerOrder, "");
  std::set<std::string> families;
  for (const Outcome& o : byPlanner.at(plannerOrder.front())) families.insert(o.family);
  for (const std::string& family : families) {
    out << "\n" << family << "\n\n";
    table(out, byPlanner, plannerOrder, family);
  }
  return out.str();
}

}  // namespace arcplan::peer_vamp
