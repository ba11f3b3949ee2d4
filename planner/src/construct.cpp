// The initial tour for the chained local search: an Euler walk over walls plus the
// cheapest set of air moves that makes one exist (the matching of odd points, which is
// also the lower bound), with disconnected parts joined by doubled shortest links.

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "cc_tsp.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/planner/lower_bound.hpp"
#include "union_find.hpp"

namespace ccbuild::planner::detail {
namespace {

struct Edge {
  int a = 0, b = 0;
  int segment = -1;  // -1: an air move
};

/// How far a varied walk moves each odd point before matching, metres. On ten 1,000-wall
/// floor plans 0.1 m gained the restarts most: 0.095% against 0.028% for 0.03 m and 0.037%
/// for 0.3 m (bench/README.md); it is a tenth of a door.
constexpr double kVariationShift_m = 0.1;

}  // namespace

Sequence euler_construction(const CostModel& model, const std::vector<int>& segments, bool open,
                            const Vec2& start, std::optional<Vec2> start_heading,
                            std::mt19937_64* variation) {
  if (segments.empty()) return {};
  const auto& layer = model.layer();
  std::vector<Vec2> location(layer.points.begin(), layer.points.end());
  int start_location = -1;
  if (open) {
    for (std::size_t p = 0; p < location.size(); ++p)
      if ((location[p] - start).norm() <= 1e-6) start_location = static_cast<int>(p);
    if (start_location < 0) {
      start_location = static_cast<int>(location.size());
      location.push_back(start);
    }
  }
  const int locations = static_cast<int>(location.size());

  std::vector<Edge> edges;
  std::vector<int> degree(locations, 0);
  std::vector<char> used_location(locations, 0);
  for (int s : segments) {
    const auto& seg = layer.segments[s];
    edges.push_back({seg.start_point, seg.end_point, s});
    ++degree[seg.start_point];
    ++degree[seg.end_point];
    used_location[seg.start_point] = used_location[seg.end_point] = 1;
  }
  if (open) used_location[start_location] = 1;

  // T-join: odd points (the start flips parity on an open path), matched cheaply.
  std::vector<int> terminals;
  std::vector<Vec2> terminal_points;
  for (int p = 0; p < locations; ++p) {
    const bool odd = (degree[p] % 2 == 1) != (open && p == start_location);
    if (odd) {
      terminals.push_back(p);
      terminal_points.push_back(location[p]);
      if (variation) {
        std::uniform_real_distribution<double> shift(-kVariationShift_m, kVariationShift_m);
        terminal_points.back() += Vec2(shift(*variation), shift(*variation));
      }
    }
  }
  const MatchingBound matching = min_weight_matching(terminal_points, model.metric(), open);
  for (const auto& [i, j] : matching.pairs) {
    if (i >= 0 && j >= 0) edges.push_back({terminals[i], terminals[j], -1});
  }

  // Join disconnected parts with their shortest links, each travelled there and back.
  UnionFind parts(locations);
  for (const auto& e : edges) parts.unite(e.a, e.b);
  std::vector<int> active;
  for (int p = 0; p < locations; ++p)
    if (used_location[p]) active.push_back(p);
  auto count_parts = [&] {
    std::vector<char> root(locations, 0);
    int n = 0;
    for (int p : active) n += !root[parts.find(p)]++ ? 1 : 0;
    return n;
  };
  if (count_parts() > 1) {
    std::vector<Vec2> points;
    for (int p : active) points.push_back(location[p]);
    PointGrid grid(points);
    std::vector<std::tuple<double, int, int>> links;
    const int k = std::min(static_cast<int>(active.size()) - 1, 8);
    for (int i = 0; i < static_cast<int>(active.size()); ++i) {
      const int root = parts.find(active[i]);
      for (int j : grid.nearest(i, k, [&](int q) { return parts.find(active[q]) == root; }))
        links.emplace_back(model.distance_m(points[i], points[j]), active[i], active[j]);
    }
    std::sort(links.begin(), links.end());
    UnionFind joined = parts;
    for (const auto& [d, a, b] : links) {
      if (joined.unite(a, b)) {
        edges.push_back({a, b, -1});
        edges.push_back({b, a, -1});
      }
    }
    // Neighbour lists can miss a far-off part; join what is left to the nearest point.
    for (int p : active) {
      if (joined.find(p) == joined.find(active[0])) continue;
      int best = -1;
      double best_d = 0.0;
      for (int q : active) {
        if (joined.find(q) != joined.find(active[0])) continue;
        const double d = model.distance_m(location[p], location[q]);
        if (best < 0 || d < best_d) {
          best = q;
          best_d = d;
        }
      }
      joined.unite(p, best);
      edges.push_back({p, best, -1});
      edges.push_back({best, p, -1});
    }
  }

  // Hierholzer's walk. At each point prefer walls to air moves, and among walls the
  // one that turns least from the current heading.
  std::vector<std::vector<int>> incident(locations);
  for (int e = 0; e < static_cast<int>(edges.size()); ++e) {
    incident[edges[e].a].push_back(e);
    incident[edges[e].b].push_back(e);
  }
  std::vector<char> used(edges.size(), 0);
  struct Frame {
    int location;
    int edge;      // edge used to arrive, -1 at the start
    bool forward;  // arrived travelling a -> b
  };
  auto heading_of = [&](const Frame& f) -> std::optional<Vec2> {
    if (f.edge < 0) return start_heading;
    const Edge& e = edges[f.edge];
    Vec2 d = location[f.forward ? e.b : e.a] - location[f.forward ? e.a : e.b];
    if (d.norm() <= 1e-12) return std::nullopt;
    return d.normalized();
  };
  const int first = open ? start_location : layer.segments[segments.front()].start_point;
  std::vector<Frame> stack{{first, -1, true}};
  std::vector<Frame> walk;
  walk.reserve(edges.size());
  while (!stack.empty()) {
    const Frame top = stack.back();
    const int v = top.location;
    const auto heading = heading_of(top);
    int chosen = -1;
    double chosen_score = 0.0;
    for (int e : incident[v]) {
      if (used[e]) continue;
      const Edge& edge = edges[e];
      const int w = edge.a == v ? edge.b : edge.a;
      double score = edge.segment >= 0 ? 0.0 : 10.0;  // walls first
      if (variation) {
        score += std::uniform_real_distribution<double>(0.0, 1.0)(*variation);
      } else if (heading && edge.segment >= 0) {
        const Vec2 d = (location[w] - location[v]).normalized();
        score += std::acos(std::clamp(heading->dot(d), -1.0, 1.0));
      }
      if (chosen < 0 || score < chosen_score - 1e-12) {
        chosen = e;
        chosen_score = score;
      }
    }
    if (chosen < 0) {
      stack.pop_back();
      if (top.edge >= 0) walk.push_back(top);
      continue;
    }
    used[chosen] = 1;
    const Edge& edge = edges[chosen];
    const bool forward = edge.a == v;
    stack.push_back({forward ? edge.b : edge.a, chosen, forward});
  }
  std::reverse(walk.begin(), walk.end());
  CCBUILD_CHECK(walk.size() == edges.size(), "the Euler walk uses every edge");

  Sequence sequence;
  sequence.reserve(segments.size());
  for (const Frame& f : walk) {
    const Edge& e = edges[f.edge];
    if (e.segment < 0) continue;
    // The wall's own direction is start_point -> end_point, stored as a -> b.
    sequence.push_back({e.segment, !f.forward});
  }
  return sequence;
}

}  // namespace ccbuild::planner::detail
