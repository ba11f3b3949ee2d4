#include "ccbuild/planner/lower_bound.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "ccbuild/common/input_error.hpp"
#include "geometry.hpp"
#include "lemon_matching.hpp"

namespace ccbuild::planner {
namespace {

using detail::Vec2;
constexpr double kUnitsPerMetre = 1e5;  // 10 micrometres

std::int64_t cost_units(const Vec2& a, const Vec2& b, Metric metric) {
  const double m = metric_distance_m(metric, a, b);
  return static_cast<std::int64_t>(std::floor(m * kUnitsPerMetre));  // round down: stays a bound
}

}  // namespace

MatchingBound min_weight_matching(const std::vector<Vec2>& terminals, Metric metric,
                                  bool wildcard) {
  MatchingBound result;
  const int n = static_cast<int>(terminals.size());
  const int nodes = n + (wildcard ? 1 : 0);
  CCBUILD_CHECK(nodes % 2 == 0, "a perfect matching needs an even number of nodes");
  if (nodes == 0) {
    result.proven_optimal = true;
    return result;
  }
  const int W = wildcard ? n : -1;

  // Candidate edges: nearest neighbours, plus a greedy perfect matching so that the
  // sparse graph always has one.
  std::vector<std::pair<int, int>> edges;
  detail::PointGrid grid(terminals);
  const int k = std::min(10, n - 1);
  std::vector<char> taken(n, 0);
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::vector<int> unpaired;
  for (int u : order) {
    if (k > 0) {
      for (int v : grid.nearest(u, k, [](int) { return false; }))
        edges.emplace_back(std::min(u, v), std::max(u, v));
    }
  }
  for (int u : order) {
    if (taken[u]) continue;
    taken[u] = 1;
    int partner = -1;
    if (n > 1) {
      const auto near = grid.nearest(u, std::min(n - 1, 24), [&](int v) { return taken[v] != 0; });
      if (!near.empty()) partner = near.front();
    }
    if (partner < 0) {
      for (int v = 0; v < n; ++v)
        if (!taken[v]) {
          partner = v;
          break;
        }
    }
    if (partner < 0) {
      unpaired.push_back(u);
      continue;
    }
    taken[partner] = 1;
    edges.emplace_back(std::min(u, partner), std::max(u, partner));
  }
  CCBUILD_CHECK(unpaired.size() <= 1 && (unpaired.empty() || wildcard),
                "greedy matching is perfect");

  std::vector<std::int64_t> y(nodes);
  std::vector<std::vector<int>> node_blossoms(nodes);
  std::vector<std::int64_t> blossom_value;
  std::vector<int> blossom_size;
  std::vector<int> mate(nodes, -1);
  std::int64_t kScale = 1;

  // Slack of the dual constraint of pair (u, v) on the complete graph; < 0 is violated.
  auto slack = [&](int u, int v) -> std::int64_t {
    const std::int64_t base = y[u] + y[v] + kScale * cost_units(terminals[u], terminals[v], metric);
    if (base >= 0) return base;  // blossom variables are >= 0 and can only help
    // The blossoms holding both: a merge of the two ascending lists. Nested blossoms
    // make them long and many pairs get here; searching one list in the other was a
    // third of a 5,000-wall plan's time.
    std::int64_t z = 0;
    const auto& a = node_blossoms[u];
    const auto& b = node_blossoms[v];
    for (std::size_t i = 0, j = 0; i < a.size() && j < b.size();) {
      if (a[i] < b[j]) {
        ++i;
      } else if (b[j] < a[i]) {
        ++j;
      } else {
        z += blossom_value[a[i]];
        ++i;
        ++j;
      }
    }
    return base + z;
  };

  std::vector<std::pair<std::int64_t, std::pair<int, int>>> violations;
  constexpr int kMaxRounds = 8;
  for (int round = 1; round <= kMaxRounds; ++round) {
    result.rounds = round;
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    std::vector<std::pair<int, int>> graph_edges = edges;
    std::vector<std::int64_t> weights;
    weights.reserve(edges.size() + n);
    for (const auto& [u, v] : edges)
      weights.push_back(-cost_units(terminals[u], terminals[v], metric));
    if (wildcard) {
      for (int u = 0; u < n; ++u) {
        graph_edges.emplace_back(u, W);
        weights.push_back(0);
      }
    }
    const detail::SparseMatching solved =
        detail::max_weight_perfect_matching(nodes, graph_edges, weights);
    CCBUILD_CHECK(solved.perfect, "the candidate graph holds a perfect matching");
    kScale = solved.dual_scale;
    y = solved.node_potential;
    mate = solved.mate;
    blossom_value = solved.blossom_value;
    blossom_size.assign(solved.blossom_nodes.size(), 0);
    for (auto& list : node_blossoms) list.clear();
    for (std::size_t b = 0; b < solved.blossom_nodes.size(); ++b) {
      blossom_size[b] = static_cast<int>(solved.blossom_nodes[b].size());
      for (int node : solved.blossom_nodes[b]) node_blossoms[node].push_back(static_cast<int>(b));
    }

    // Check every pair of terminals. A pair can only be violated when its cost is below
    // (-y_u - y_v) / scale, so scan pairs in x order and stop once dx alone is too far.
    violations.clear();
    std::int64_t max_neg_y = std::numeric_limits<std::int64_t>::min();
    for (int v = 0; v < n; ++v) max_neg_y = std::max(max_neg_y, -y[v]);
    std::vector<int> by_x(n);
    std::iota(by_x.begin(), by_x.end(), 0);
    std::sort(by_x.begin(), by_x.end(),
              [&](int a, int b) { return terminals[a].x() < terminals[b].x(); });
    for (int i = 0; i < n; ++i) {
      const int u = by_x[i];
      const double reach_units = static_cast<double>(-y[u] + max_neg_y) / kScale;
      for (int j = i + 1; j < n; ++j) {
        const int v = by_x[j];
        if ((terminals[v].x() - terminals[u].x()) * kUnitsPerMetre > reach_units + 1.0) break;
        // Both metrics are at least |dy| too: skip the strip's far points unpriced.
        if (std::abs(terminals[v].y() - terminals[u].y()) * kUnitsPerMetre > reach_units + 1.0)
          continue;
        const std::int64_t s = slack(u, v);
        if (s < 0) violations.push_back({s, {std::min(u, v), std::max(u, v)}});
      }
    }
    if (violations.empty()) {
      result.proven_optimal = true;
      break;
    }
    if (round == kMaxRounds) break;
    std::sort(violations.begin(), violations.end());
    const std::size_t add =
        std::min<std::size_t>(violations.size(), 20 * static_cast<std::size_t>(n) + 100);
    for (std::size_t i = 0; i < add; ++i) edges.push_back(violations[i].second);
  }

  // Still violated after the last round: raise potentials until every pair holds. Raising
  // y only loosens the constraints, so the repaired duals are feasible and the bound valid.
  for (const auto& [s, uv] : violations) {
    const std::int64_t deficit = -slack(uv.first, uv.second);
    if (deficit > 0) y[uv.first] += deficit;
  }
  std::int64_t dual = 0;
  for (int i = 0; i < nodes; ++i) dual += y[i];
  for (std::size_t b = 0; b < blossom_value.size(); ++b)
    dual += blossom_value[b] * (blossom_size[b] / 2);
  // Max-weight dual >= -(min cost) * scale, so -dual / scale bounds the cost from below.
  result.lower_bound_m = std::max(0.0, static_cast<double>(-dual) / kScale / kUnitsPerMetre);
  result.matching_cost_m = 0.0;
  for (int u = 0; u < nodes; ++u) {
    const int v = mate[u];
    if (u < v) {
      const int a = u == W ? -1 : u, b = v == W ? -1 : v;
      result.pairs.emplace_back(a < 0 ? b : a, a < 0 ? -1 : b);
      if (a >= 0 && b >= 0) {
        result.matching_cost_m += metric_distance_m(metric, terminals[a], terminals[b]);
      }
    }
  }
  return result;
}

std::string to_string(BoundKind kind) {
  return kind == BoundKind::kMatching ? "matching" : "connected";
}

std::optional<BoundKind> parse_bound(const std::string& text) {
  for (BoundKind kind : {BoundKind::kMatching, BoundKind::kConnected})
    if (text == to_string(kind)) return kind;
  return std::nullopt;
}

std::string to_string(BoundSource source) {
  return source == BoundSource::kConnected ? "connected" : "matching";
}

std::string to_string(BoundStop stop) {
  switch (stop) {
    case BoundStop::kNoViolatedCuts:
      return "no-violated-cuts";
    case BoundStop::kStalled:
      return "stalled";
    case BoundStop::kRoundLimit:
      return "round-limit";
    case BoundStop::kTimeLimit:
      return "time-limit";
    case BoundStop::kCancelled:
      return "cancelled";
    case BoundStop::kLpFailed:
      return "lp-failed";
  }
  return "?";
}

BoundSource LayerBound::source() const {
  return connected && connected->lower_bound_m > matching_m ? BoundSource::kConnected
                                                            : BoundSource::kMatching;
}

LayerBound airtime_lower_bound(const floors::Layer& layer, Metric metric, const PathSpec& path,
                               BoundKind kind, const StopCondition& stop,
                               const ConnectedBoundLimits& limits) {
  LayerBound bound;
  std::vector<int> degree(layer.points.size(), 0);
  for (const auto& s : layer.segments) {
    ++degree[s.start_point];
    ++degree[s.end_point];
  }
  std::vector<char> odd(layer.points.size(), 0);
  for (std::size_t p = 0; p < degree.size(); ++p) odd[p] = degree[p] % 2;
  bound.odd_points = static_cast<int>(std::count(odd.begin(), odd.end(), 1));

  int start_point = -2;
  if (!path.closed) {
    // The start flips parity: the walk leaves it once more than it comes back.
    for (std::size_t p = 0; p < layer.points.size(); ++p) {
      if ((layer.points[p] - path.start_m).norm() <= 1e-6) {
        start_point = static_cast<int>(p);
        break;
      }
    }
    if (start_point >= 0) odd[start_point] ^= 1;
  }
  std::vector<Vec2> terminals;
  for (std::size_t p = 0; p < odd.size(); ++p) {
    if (odd[p]) {
      bound.terminals.push_back(static_cast<int>(p));
      terminals.push_back(layer.points[p]);
    }
  }
  if (!path.closed && start_point == -2) {
    bound.terminals.push_back(-2);
    terminals.push_back(path.start_m);
  }
  // An open path ends anywhere: one free end matches any terminal at no cost.
  bound.matching = min_weight_matching(terminals, metric, !path.closed);
  bound.matching_m = bound.matching.lower_bound_m;
  bound.distance_m = bound.matching_m;
  for (const auto& [u, v] : bound.matching.pairs)
    if (u >= 0 && v >= 0) bound.rounding_m += 1.0 / kUnitsPerMetre;  // the free end's pairs cost 0
  // The connected bound's first LP solve cannot be interrupted; on a time budget it
  // surely cannot keep (a generous 1e-7 s per wall squared: 2.5 s at 5,000 walls, where
  // it takes about 1.3 s), the matching bound stands alone rather than overrun it.
  const double walls = static_cast<double>(layer.segments.size());
  if (kind == BoundKind::kConnected && stop.remaining_s() >= 1e-7 * walls * walls) {
    bound.connected = connected_airtime_bound(layer, metric, path, limits, stop);
    if (bound.connected->certified && bound.connected->lower_bound_m > bound.distance_m) {
      bound.distance_m = bound.connected->lower_bound_m;
      // certified_dual_value's margin, and as much again for the tour's own sum.
      bound.rounding_m = 2e-9 * (1.0 + bound.distance_m);
    }
  }
  return bound;
}

}  // namespace ccbuild::planner
