#pragma once
// A valid lower bound on the airtime distance of any tool path of a layer.
//
// Air moves and walls together form a closed walk (or, for an open path, a walk from the
// start point) through every wall. In that multigraph every point has even degree (for an
// open path: all but the start and the end), so the air moves contain a T-join of the
// points where an odd number of wall ends meet (plus the start point, and one free end,
// for open paths). Dropping the requirement that the walk be connected, the cheapest such
// air-move set is a minimum-weight perfect matching of those points under the metric
// (which satisfies the triangle inequality). Its value is therefore a lower bound.
//
// The matching is solved with LEMON on a sparse candidate graph (nearest neighbours plus
// a greedy perfect matching); the dual solution LEMON returns is then checked against
// every pair of points of the complete graph and the solve repeated with the violated
// pairs added. The bound reported is the dual objective, repaired if needed, so it is a
// proof, not an estimate. Costs are rounded down to 10 micrometres.

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "ccbuild/floors/slice.hpp"
#include "ccbuild/planner/tool_path.hpp"

namespace ccbuild::planner {

struct MatchingBound {
  double lower_bound_m = 0.0;    ///< dual value: a valid lower bound on the matching
  double matching_cost_m = 0.0;  ///< cost of the matching found (equal when proven optimal)
  bool proven_optimal = false;   ///< duals feasible on the complete graph without repair
  /// Matched terminal indices; -1 stands for the free end (wildcard) when there is one.
  std::vector<std::pair<int, int>> pairs;
  int rounds = 0;  ///< sparse solves until the duals held on the complete graph
};

/// Minimum-weight perfect matching of `terminals` under `metric` on the complete graph.
/// With `wildcard`, one extra node matches any terminal at cost 0 (terminal count + 1
/// must then be even; without it, the count must be even).
MatchingBound min_weight_matching(const std::vector<Eigen::Vector2d>& terminals, Metric metric,
                                  bool wildcard);

struct LayerBound {
  double distance_m = 0.0;  ///< lower bound on the airtime distance of `path` on the layer
  int odd_points = 0;       ///< points where an odd number of wall ends meet
  /// Terminal points used (layer point indices; -2 for an open path's start when it is
  /// not a layer point) and their matching, for constructing a tour from it.
  std::vector<int> terminals;
  MatchingBound matching;
};

/// The matching bound above, for a closed tour or an open path from path.start_m (a
/// fixed first wall only raises the true optimum, so the bound stays valid).
LayerBound airtime_lower_bound(const floors::Layer& layer, Metric metric, const PathSpec& path);

}  // namespace ccbuild::planner
