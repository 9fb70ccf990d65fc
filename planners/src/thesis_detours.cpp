// The thesis mode of the arc planner: the straight line A→B with the thesis' three-arc detour of
// one given shape around each obstacle that blocks it (seed chapter 3.4; docs/planners.md).
#include <algorithm>
#include <sstream>

#include "arc_planning.h"

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
  if (!q || query.ik.branchOf(*q) != query.startBranch) return false;  // the walk will tell
  if (collision::isCollisionFree(query.model, data, *q)) return false;
  const collision::CollisionReport report = collision::collide(query.model, data, *q);
  return std::any_of(report.collisions.begin(), report.collisions.end(),
                     [&](const collision::NamePair& pair) { return pair.second == obstacle.name; });
}

// The search of one thesis-mode query: the line's detours in order along it, the obstacle each goes
// around, and the waypoints validated so far that the next path shares.
class ThesisDetours {
public:
  ThesisDetours(const ArcQuery& query, const ArcParameters& shape, double planeAngle)
      : query_(query), shape_(shape), planeAngle_(planeAngle), line_(query.a, query.b), prefix_(query.startOnly()) {}

  ArcOutcome solve() {
    addBlockingObstacles();
    for (;;) {  // walk the path; whatever else blocks it on the line gets a detour too
      const std::string problem = detoursProblem(query_.a, query_.b, detours_);
      if (!problem.empty()) return failed("arc path around " + obstacleList() + ": " + problem);
      const ArcPath path(query_.a, query_.b, detours_);
      const Walk walked = query_.validator.walk(path, prefix_, query_.goal);
      if (walked.ok()) return solved(path, walked.waypoints);
      if (query_.ptc()) return failed("time limit reached before a valid path was found");
      const std::string where = detours_.empty() ? "straight line" : "arc path";
      if (!walked.rejected) {
        return failed(std::string(toString(walked.waypoints.status)) + " on the " + where + ": " +
                      walked.waypoints.reason);
      }
      const std::string why = detourAfterRejection(path, walked, where);
      if (!why.empty()) return failed(why);
    }
  }

private:
  // One IK and one collision check per obstacle at its O: the obstacles known to block the line
  // before any walk.
  void addBlockingObstacles() {
    collision::CollisionData data(query_.model);
    struct Blocking {
      double position;
      const collision::Obstacle* obstacle;
    };
    std::vector<Blocking> blocking;
    for (const collision::Obstacle& obstacle : query_.obstacles) {
      const double u = positionOnLine(line_, obstacle);
      if (blocksTheLineAtO(query_, line_, obstacle, data, u)) blocking.push_back({u, &obstacle});
    }
    std::stable_sort(blocking.begin(), blocking.end(),
                     [](const Blocking& x, const Blocking& y) { return x.position < y.position; });
    for (const Blocking& blocked : blocking) {
      detours_.push_back({blocked.position, shape_, planeAngle_});
      obstacles_.push_back(blocked.obstacle->name);
    }
  }

  // A detour around the obstacle behind the rejected walk, and the walk's waypoints up to where that
  // detour leaves the line as the next prefix; or why no detour helps.
  std::string detourAfterRejection(const ArcPath& path, const Walk& walked, const std::string& where) {
    const double failedAt = walked.waypoints.failedAtArcLength;
    const Rejection rejection = query_.validator.explain(*walked.rejected);
    const std::string why = rejection.describe(query_.validator.margin());
    std::ostringstream context;
    context << why << " on the " << where << " at TCP arc length " << failedAt << " m";
    for (std::size_t i = 0; i < detours_.size(); ++i) {
      const auto [from, to] = path.detourSpan(i);
      if (failedAt > from && failedAt <= to + 1e-12) {
        std::ostringstream message;
        message << why << " on arc detour " << i + 1 << " around '" << obstacles_[std::min(i, obstacles_.size() - 1)]
                << "' at TCP arc length " << failedAt << " m";
        return message.str();
      }
    }
    const auto obstacle = std::find_if(query_.obstacles.begin(), query_.obstacles.end(),
                                       [&](const collision::Obstacle& o) { return rejection.involves(o.name); });
    if (obstacle == query_.obstacles.end()) return context.str() + ": no obstacle to go around (self-collision)";
    if (std::find(obstacles_.begin(), obstacles_.end(), obstacle->name) != obstacles_.end() ||
        detours_.size() >= kMaxDetours) {
      return context.str() + ": '" + obstacle->name + "' still blocks the path after a detour around it";
    }
    const std::size_t index = insertDetour({positionOnLine(line_, *obstacle), shape_, planeAngle_}, obstacle->name);
    const std::string problem = detoursProblem(query_.a, query_.b, detours_);
    if (!problem.empty()) return context.str() + ": " + problem;
    const double entry = ArcPath(query_.a, query_.b, detours_).detourSpan(index).first;
    if (entry >= failedAt) {
      std::ostringstream message;
      message << context.str() << ": the detour around '" << obstacle->name << "' leaves the line at " << entry
              << " m, after the collision; increase half_chord or the side radii";
      return message.str();
    }
    prefix_ = walked.waypoints;  // up to the entry the new path is the walked one
    while (prefix_.arcLengths.back() > entry) {
      prefix_.arcLengths.pop_back();
      prefix_.joints.pop_back();
    }
    return {};
  }

  // Inserts the detour in order along the line; returns its index.
  std::size_t insertDetour(const Detour& detour, const std::string& obstacle) {
    const auto place = std::upper_bound(detours_.begin(), detours_.end(), detour.position,
                                        [](double position, const Detour& d) { return position < d.position; });
    const auto index = place - detours_.begin();
    detours_.insert(place, detour);
    obstacles_.insert(obstacles_.begin() + index, obstacle);
    return static_cast<std::size_t>(index);
  }

  std::string obstacleList() const {
    std::string around;
    for (const std::string& name : obstacles_) around += (around.empty() ? "'" : ", '") + name + "'";
    return around;
  }

  ArcOutcome failed(std::string reason) const {
    ArcOutcome outcome = failure(std::move(reason));
    outcome.obstacles = obstacles_;
    return outcome;
  }

  ArcOutcome solved(const ArcPath& path, JointConversionResult waypoints) const {
    ArcOutcome outcome;
    outcome.kind = detours_.empty() ? ArcPlannerResult::Kind::StraightLine : ArcPlannerResult::Kind::Detour;
    outcome.path = std::move(waypoints);
    outcome.detours = detours_;
    outcome.obstacles = obstacles_;
    outcome.tcpPathLength = path.length();
    outcome.cartesianFraction = 1.0;
    return outcome;
  }

  const ArcQuery& query_;
  const ArcParameters shape_;
  const double planeAngle_;
  const ArcPath line_;
  std::vector<Detour> detours_;  // ascending along the line
  std::vector<std::string> obstacles_;
  JointConversionResult prefix_;  // validated waypoints the next path shares
};

}  // namespace

JointConversionResult ArcQuery::startOnly() const {
  JointConversionResult prefix;
  prefix.joints.push_back(start);
  prefix.arcLengths.push_back(0.0);
  return prefix;
}

ArcOutcome failure(std::string reason) {
  ArcOutcome outcome;
  outcome.reason = std::move(reason);
  return outcome;
}

ArcOutcome planThesisDetours(const ArcQuery& query, const ArcParameters& shape, double planeAngle) {
  const std::string shapeProblem = arcParametersProblem(shape);
  if (!shapeProblem.empty()) return failure(shapeProblem);
  return ThesisDetours(query, shape, planeAngle).solve();
}

}  // namespace arcplan::planners::detail
