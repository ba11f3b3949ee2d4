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
//
// The matching ignores that the walk is connected, so on layers of many separate pieces
// (short walls between openings) it can sit several per cent below the optimum. The
// connected bound below adds connectivity in an LP; the layer's bound is the better of
// the two.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "ccbuild/floors/slice.hpp"
#include "ccbuild/planner/termination.hpp"
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

/// Work limits of the connected bound. They are counts, not seconds, so that the bound
/// (and every answer that depends on it) is the same on any machine.
struct ConnectedBoundLimits {
  /// Cutting-plane rounds. The last rounds cost the most and add the least: on 1,000-wall
  /// floor plans 50 rounds reach all but ~0.1% of what 300 do, in about half the time.
  int max_rounds = 50;
  int pricing_interval = 10;    ///< rounds between checks on the complete graph
  int max_pricing_rounds = 20;  ///< column additions per check
  /// Stop when `pricing_interval` rounds raised the LP by less than this fraction.
  double stall_fraction = 2e-4;
  int neighbours = 5;            ///< initial candidate pairs per point
  int max_cuts_per_round = 400;  ///< from each exact separation
  /// Exact parity separation (a Gomory-Hu tree of all points) only up to this many
  /// points; above it, parity cuts come from the support graph's parts alone.
  int max_parity_tree_nodes = 4000;
  /// Keep the dual solution behind the bound (ConnectedBound::certificate).
  bool keep_certificate = false;
};

/// Why the connected bound's cutting planes stopped.
enum class BoundStop {
  kNoViolatedCuts,  ///< the LP solution violates no cut found: the bound is final
  kStalled,         ///< rounds stopped raising the bound (ConnectedBoundLimits::stall_fraction)
  kRoundLimit,      ///< ConnectedBoundLimits::max_rounds
  kTimeLimit,
  kCancelled,
  kLpFailed,  ///< GLPK failed; the bound falls back to what was certified before
};
/// "no-violated-cuts", "stalled", "round-limit", "time-limit", "cancelled", "lp-failed".
std::string to_string(BoundStop stop);

/// One set of the connected bound's dual solution. Its width is the dual of the row
/// x(delta(points)) >= rhs: every air move between a point inside and a point outside
/// pays it. Nested and overlapping sets add up ("moats" around the points).
struct BoundMoat {
  std::vector<int> points;  ///< sorted node ids (ConnectedBoundCertificate)
  double rhs = 1.0;         ///< 1: an odd number of walls leave the set; 2: none, it is whole parts
  double width_m = 0.0;     ///< the dual value, >= 0 unless `exact`
  /// The open path's free end alone, whose row is an equality (exactly one air move
  /// there): its width may be negative.
  bool exact = false;
};

/// The dual solution behind ConnectedBound::lower_bound_m, complete enough to re-check
/// the bound without ccbuild (docs/json.md, tests/tools/check_bound.py): for every pair of
/// points, the widths of the moats holding exactly one of them sum to at most their
/// distance, and the bound is the sum of rhs * width over the moats.
struct ConnectedBoundCertificate {
  /// Node ids 0 .. points_m.size() - 1: the layer's points, then (open path) the start
  /// when it is not one of them. An open path has one more node, the free end, with id
  /// points_m.size(): joined to the start like a wall, at distance 0 from every point.
  std::vector<Eigen::Vector2d> points_m;
  int start = -1;                ///< the open path's start node; -1: a closed tour
  std::vector<BoundMoat> moats;  ///< those of non-zero width
};

struct ConnectedBound {
  double lower_bound_m = 0.0;  ///< certified: a dual solution feasible on the complete graph
  double lp_value_m = 0.0;     ///< the last LP's value on its candidate pairs
  bool certified = false;
  int rounds = 0;  ///< cutting-plane rounds run (each a separation; the last may find none)
  int cuts = 0;    ///< cuts added beyond the initial ones
  int columns = 0;
  int rows = 0;
  BoundStop stopped_by = BoundStop::kNoViolatedCuts;
  /// With ConnectedBoundLimits::keep_certificate, the dual solution whose value (less a
  /// margin of about 1e-9 of it for floating-point sums) is lower_bound_m.
  std::optional<ConnectedBoundCertificate> certificate;
};

/// The connected bound: air moves and walls together are connected and every point has
/// even degree, which the matching bound only half uses. The LP relaxation
///   min sum d(u, v) x_uv  over all pairs of points, x >= 0, with
///   x(delta(S)) >= 1  for every set S of points that an odd number of walls leave,
///   x(delta(S)) >= 2  for every union S of whole wall-connected parts (not all of them),
/// (for an open path, a free end joined to the start like a wall, with exactly one air
/// move) is solved with LEMON's LP (GLPK) by cutting planes on a sparse candidate graph;
/// the cuts are found from the LP solution (parts of its support, and the minimum cut
/// between wall-connected parts). After every round its dual solution is checked on every
/// pair of points of the complete graph and scaled until feasible there, so the value
/// reported is a proof whatever cuts were found. Units: metres. Throws nothing for valid
/// layers; `certified` is false only when the LP solver failed.
ConnectedBound connected_airtime_bound(const floors::Layer& layer, Metric metric,
                                       const PathSpec& path,
                                       const ConnectedBoundLimits& limits = {},
                                       const StopCondition& stop = StopCondition());

enum class BoundKind {
  kMatching,   ///< the matching bound alone (fast; ignores connectivity)
  kConnected,  ///< the better of the matching and the connected bound
};
std::string to_string(BoundKind kind);
/// "matching" or "connected"; nullopt for anything else.
std::optional<BoundKind> parse_bound(const std::string& text);

/// Which bound a reported value is.
enum class BoundSource { kMatching, kConnected };
/// "matching" or "connected".
std::string to_string(BoundSource source);

struct LayerBound {
  double distance_m = 0.0;  ///< lower bound on the airtime distance of `path` on the layer
  double matching_m = 0.0;  ///< the matching bound
  std::optional<ConnectedBound> connected;  ///< when asked for
  int odd_points = 0;                       ///< points where an odd number of wall ends meet
  /// How far below its exact value `distance_m` may lie from rounding alone, m: the
  /// matching bound floors each matched pair's cost to 10 micrometres, the connected
  /// bound keeps a margin of about 1e-9 of its value for floating-point sums. A tour no
  /// longer than distance_m + rounding_m is optimal to within rounding_m.
  double rounding_m = 0.0;
  /// An airtime distance no longer than this is optimal to within rounding_m, m.
  double proof_m() const { return distance_m + rounding_m; }
  /// Terminal points used (layer point indices; -2 for an open path's start when it is
  /// not a layer point) and their matching, for constructing a tour from it.
  std::vector<int> terminals;
  MatchingBound matching;
  /// Which bound `distance_m` is.
  BoundSource source() const;
};

/// The lower bound on the airtime distance of `path` (closed tour, or open path from
/// path.start_m; a fixed first wall only raises the true optimum, so the bound stays
/// valid). Metres. The connected bound stops early, still valid, when `stop` says so.
LayerBound airtime_lower_bound(const floors::Layer& layer, Metric metric, const PathSpec& path,
                               BoundKind kind = BoundKind::kConnected,
                               const StopCondition& stop = StopCondition(),
                               const ConnectedBoundLimits& limits = {});

}  // namespace ccbuild::planner
