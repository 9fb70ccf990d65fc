// The thesis mode of the arc planner: the straight line A→B with the thesis' three-arc detour of
// one given shape around each obstacle that blocks it (seed chapter 3.4; docs/planners.md).
#include <algorithm>
#include <sstream>

#include "arc_planning.h"
#include "arcplan/common/error.h"

namespace arcplan::planners::detail {
namespace {

// At most this many detours are chained along one line.
constexpr std::size_t kMaxDetours = 8;

// Where the obstacle's circumscribed ball centre projects onto the line (the thesis' O), on [0, |AB|].
double positionOnLine(const ArcPath& line, const collision::Obstacle& obstacle) {
  return std::clamp((obstacle.boundingCenter() - line.start().translation()).dot(line.lineDirection()), 0.0,
                    line.straightLength());
}

bool blocksTheLineAtO(const ArcQuery& query, const ArcPath& line, const collision::Obstacle& obstacle,
                      collision::CollisionData& data, double u) {
  // One IK and one collision check at O instead of walking the line up to the first collision.
  const double fraction = line.straightLength() > 0.0 ? u / line.straightLength() : 0.0;
  const robot::Vector6 seed = query.start + fraction * (query.goal - query.start);
  const std::optional<robot::Vector6> q = query.ik.solveNearest(line.pose(u), seed);
  if (!q || query.ik.branchOf(*q) != query.ik.branchOf(query.start)) return false;  // the walk will tell
  if (collision::isCollisionFree(query.model, data, *q)) return false;
  const collision::CollisionReport report = collision::collide(query.model, data, *q);
  return std::any_of(report.collisions.begin(), report.collisions.end(),
                     [&](const collision::NamePair& pair) { return pair.second == obstacle.name; });
}

}  // namespace

JointWaypoints ArcQuery::startOnly() const {
  JointWaypoints prefix;
  prefix.joints.push_back(start);
  prefix.arcLengths.push_back(0.0);
  return prefix;
}

JointWaypoints planThesisDetours(const ArcQuery& query, const ArcParameters& shape, double planeAngle,
                                 ArcPlannerResult& result) {
  const std::string shapeProblem = arcParametersProblem(shape);
  if (!shapeProblem.empty()) {
    result.reason = shapeProblem;
    return {};
  }
  const ArcPath line(query.a, query.b);
  collision::CollisionData data(query.model);
  struct Blocking {
    double position;
    const collision::Obstacle* obstacle;
  };
  std::vector<Blocking> blocking;
  for (const collision::Obstacle& obstacle : query.obstacles) {
    const double u = positionOnLine(line, obstacle);
    if (blocksTheLineAtO(query, line, obstacle, data, u)) blocking.push_back({u, &obstacle});
  }
  std::stable_sort(blocking.begin(), blocking.end(),
                   [](const Blocking& x, const Blocking& y) { return x.position < y.position; });
  std::vector<Detour> detours;  // ascending along the line
  for (const Blocking& blocked : blocking) {
    detours.push_back({blocked.position, shape, planeAngle});
    result.obstacles.push_back(blocked.obstacle->name);
  }

  // Walk the path; whatever else blocks it on the line gets a detour too.
  JointWaypoints prefix = query.startOnly();  // validated waypoints the next path shares
  for (;;) {
    std::optional<ArcPath> path;
    try {
      path.emplace(query.a, query.b, detours);
    } catch (const Error& error) {  // the given shape does not fit: a failure to report, not a search step
      std::string around;
      for (const std::string& name : result.obstacles) around += (around.empty() ? "'" : ", '") + name + "'";
      result.reason = "arc path around " + around + ": " + error.what();
      return {};
    }
    const JointWaypoints walked = query.validator.walk(*path, prefix, query.goal);
    if (walked.ok()) {
      result.kind = detours.empty() ? ArcPlannerResult::Kind::StraightLine : ArcPlannerResult::Kind::Detour;
      result.detours = detours;
      result.tcpPathLength = path->length();
      return walked;
    }
    if (query.ptc()) {
      result.reason = "time limit reached before a valid path was found";
      return {};
    }
    const std::string where = detours.empty() ? "straight line" : "arc path";
    if (walked.status != ConversionStatus::Rejected) {
      result.reason = std::string(toString(walked.status)) + " on the " + where + ": " + walked.reason;
      return {};
    }
    const double failedAt = walked.failedAtArcLength;
    const Rejection rejection = query.validator.rejection();
    const std::string why = rejection.describe(query.validator.margin());
    std::ostringstream context;
    context << why << " on the " << where << " at TCP arc length " << failedAt << " m";
    for (std::size_t i = 0; i < detours.size(); ++i) {
      const auto [from, to] = path->detourSpan(i);
      if (failedAt > from && failedAt <= to + 1e-12) {
        std::ostringstream message;
        message << why << " on arc detour " << i + 1 << " around '"
                << result.obstacles[std::min(i, result.obstacles.size() - 1)] << "' at TCP arc length " << failedAt
                << " m";
        result.reason = message.str();
        return {};
      }
    }
    const auto obstacle = std::find_if(query.obstacles.begin(), query.obstacles.end(),
                                       [&](const collision::Obstacle& o) { return rejection.involves(o.name); });
    if (obstacle == query.obstacles.end()) {
      result.reason = context.str() + ": no obstacle to go around (self-collision)";
      return {};
    }
    if (std::find(result.obstacles.begin(), result.obstacles.end(), obstacle->name) != result.obstacles.end() ||
        detours.size() >= kMaxDetours) {
      result.reason = context.str() + ": '" + obstacle->name + "' still blocks the path after a detour around it";
      return {};
    }
    const Detour detour{positionOnLine(line, *obstacle), shape, planeAngle};
    const auto place = std::upper_bound(detours.begin(), detours.end(), detour.position,
                                        [](double position, const Detour& d) { return position < d.position; });
    const auto index = place - detours.begin();
    detours.insert(place, detour);
    result.obstacles.insert(result.obstacles.begin() + index, obstacle->name);
    double entry = 0.0;
    try {
      entry = ArcPath(query.a, query.b, detours).detourSpan(static_cast<std::size_t>(index)).first;
    } catch (const Error& error) {
      result.reason = context.str() + ": " + error.what();
      return {};
    }
    if (entry >= failedAt) {
      std::ostringstream message;
      message << ": the detour around '" << obstacle->name << "' leaves the line at " << entry
              << " m, after the collision; increase half_chord or the side radii";
      result.reason = context.str() + message.str();
      return {};
    }
    // Up to the entry the new path is the walked one.
    prefix = walked;
    while (prefix.arcLengths.back() > entry) {
      prefix.arcLengths.pop_back();
      prefix.joints.pop_back();
    }
  }
}

}  // namespace arcplan::planners::detail
