#pragma once
// The vocabulary of single-nozzle tool paths: a sequence of wall pieces, each traversed
// in a direction, and how the path starts and ends.

#include <Eigen/Core>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace ccbuild::planner {

/// How an air move travels: straight ("D" in the papers) or one axis at a time ("R",
/// x first, then y; distance |dx| + |dy|).
enum class Metric { kEuclidean, kRectilinear };
/// What the optimiser minimises: airtime distance only (as in the papers' examples), or
/// the full time model (travel, rotation with the stopper, accel delays, lifts).
enum class Objective { kDistance, kTime };

/// The length of an air move between `a` and `b` in `metric`, m: straight-line, or
/// |dx| + |dy|. The one definition every cost, bound and check uses.
inline double metric_distance_m(Metric metric, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a;
  return metric == Metric::kEuclidean ? d.norm() : std::abs(d.x()) + std::abs(d.y());
}

std::string to_string(Metric metric);
std::string to_string(Objective objective);
std::optional<Metric> parse_metric(const std::string& text);
std::optional<Objective> parse_objective(const std::string& text);

/// One wall piece deposited: `segment` indexes floors::Layer::segments; `reversed`
/// means from the piece's end point to its start point.
struct Step {
  int segment = 0;
  bool reversed = false;
  bool operator==(const Step&) const = default;
};

using Sequence = std::vector<Step>;

/// Where a path starts and whether it returns. A closed tour (the default) ends with
/// the move from the last wall back to the first one's start. An open path starts at
/// `start_m` and ends where its last wall ends; `first` optionally fixes its first step.
struct PathSpec {
  bool closed = true;
  Eigen::Vector2d start_m = Eigen::Vector2d::Zero();  ///< open paths only
  std::optional<Step> first;                          ///< open paths only

  static PathSpec closed_tour() { return {}; }
  static PathSpec open_from(const Eigen::Vector2d& start_m,
                            std::optional<Step> first = std::nullopt) {
    return PathSpec{false, start_m, first};
  }
};

}  // namespace ccbuild::planner
