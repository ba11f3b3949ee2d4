#include "schedule_deposits.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"

namespace ccbuild::schedule::detail {

void label_pieces(std::vector<planner::Waypoint>& path, const floors::Layer& layer) {
  std::unordered_map<std::int64_t, std::vector<int>> by_wall;
  for (int s = 0; s < static_cast<int>(layer.segments.size()); ++s)
    by_wall[layer.segments[s].wall_id].push_back(s);
  auto on = [&](int s, const Eigen::Vector2d& p) {
    const auto& seg = layer.segments[s];
    const Eigen::Vector2d a = layer.start_m(seg), d = layer.end_m(seg) - a;
    const double u = std::clamp((p - a).dot(d) / std::max(d.squaredNorm(), 1e-18), 0.0, 1.0);
    return (a + u * d - p).norm() <= kOnSpan_m;
  };
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    if (!path[k].extruding) continue;
    const Eigen::Vector2d mid = 0.5 * (path[k].position_m + path[k + 1].position_m);
    int found = -1;
    if (auto it = by_wall.find(path[k].wall); it != by_wall.end())
      for (int s : it->second)
        if (on(s, mid)) found = s;
    for (int s = 0; found < 0 && s < static_cast<int>(layer.segments.size()); ++s)
      if (on(s, mid)) found = s;
    CCBUILD_CHECK(found >= 0,
                  printf_string("a deposited span of wall %lld from (%.4f, %.4f) to "
                                "(%.4f, %.4f) lies on no wall piece of its layer",
                                static_cast<long long>(path[k].wall), path[k].position_m.x(),
                                path[k].position_m.y(), path[k + 1].position_m.x(),
                                path[k + 1].position_m.y()));
    path[k].wall = layer.segments[found].wall_id;
    path[k].piece = layer.segments[found].piece + 1;
  }
}

DepositIndex index_of(const std::vector<std::vector<planner::Waypoint>>& nozzles) {
  DepositIndex index;
  for (const auto& path : nozzles)
    for (std::size_t k = 0; k + 1 < path.size(); ++k)
      if (path[k].extruding)
        index.spans[path[k].wall].push_back(
            {path[k].position_m, path[k + 1].position_m, path[k].t_s, path[k + 1].t_s});
  return index;
}

namespace {

/// A span of a plan along a piece: where it starts and ends along the piece (m from the
/// piece's start) and when.
struct Along {
  double ua = 0.0, ub = 0.0, ta = 0.0, tb = 0.0;
  double lo() const { return std::min(ua, ub); }
  double hi() const { return std::max(ua, ub); }
  /// When it passes `u` (m along the piece).
  double time_at(double u) const {
    if (std::abs(ub - ua) < 1e-12) return ta;
    return ta + std::clamp((u - ua) / (ub - ua), 0.0, 1.0) * (tb - ta);
  }
};

/// The spans of `index` on `wall` that lie along the piece from `a` in direction `e`
/// (unit) over `length_m`: both their ends within kOnSpan_m of its line, and more than a
/// point of it covered (not a collinear neighbour's, nor a crossing leg of the wall).
std::vector<Along> along_piece(const DepositIndex& index, std::int64_t wall,
                               const Eigen::Vector2d& a, const Eigen::Vector2d& e,
                               double length_m) {
  std::vector<Along> out;
  const auto it = index.spans.find(wall);
  if (it == index.spans.end()) return out;
  const Eigen::Vector2d n(-e.y(), e.x());
  for (const Span& s : it->second) {
    if (std::abs((s.a - a).dot(n)) > kOnSpan_m || std::abs((s.b - a).dot(n)) > kOnSpan_m) continue;
    const Along g{(s.a - a).dot(e), (s.b - a).dot(e), s.ta, s.tb};
    if (g.lo() > length_m - kOnSpan_m || g.hi() < kOnSpan_m) continue;
    out.push_back(g);
  }
  return out;
}

}  // namespace

IntervalOffsets interval_offsets(const floors::Layer& upper, const DepositIndex& upper_index,
                                 const DepositIndex& lower_index) {
  // Along a piece the time each layer passes a point is piecewise linear, bending where
  // one of its spans starts or ends (where two nozzles' beads meet mid-piece, say): the
  // interval's extremes lie at the piece's ends or at those points. Between two such
  // points each layer is one stretch of bead; the interval is taken at both ends of it,
  // with the spans that cover it (a point where beads meet counts once from each side,
  // never pairing the bead above on one side with the bead below on the other).
  IntervalOffsets out;
  std::vector<double> cuts;
  for (const auto& seg : upper.segments) {
    const Eigen::Vector2d a = upper.start_m(seg), b = upper.end_m(seg);
    const double length_m = (b - a).norm();
    if (length_m < 1e-12) continue;
    const Eigen::Vector2d e = (b - a) / length_m;
    const std::vector<Along> up = along_piece(upper_index, seg.wall_id, a, e, length_m);
    const std::vector<Along> low = along_piece(lower_index, seg.wall_id, a, e, length_m);
    if (up.empty() || low.empty()) continue;  // over an opening, or not deposited
    cuts.clear();
    for (const auto* spans : {&up, &low})
      for (const Along& g : *spans)
        for (const double u : {g.ua, g.ub}) cuts.push_back(std::clamp(u, 0.0, length_m));
    std::sort(cuts.begin(), cuts.end());
    std::vector<double> kept = {0.0};
    for (const double u : cuts)
      if (u - kept.back() > kOnSpan_m && length_m - u > kOnSpan_m) kept.push_back(u);
    kept.push_back(length_m);
    for (std::size_t k = 0; k + 1 < kept.size(); ++k) {
      const double u0 = kept[k], u1 = kept[k + 1];
      const auto covers = [&](const Along& g) {
        return g.lo() <= u0 + kOnSpan_m && g.hi() >= u1 - kOnSpan_m;
      };
      if (std::none_of(up.begin(), up.end(), covers) ||
          std::none_of(low.begin(), low.end(), covers))
        continue;
      for (const double u : {u0, u1}) {
        constexpr double inf = std::numeric_limits<double>::infinity();
        double up_lo = inf, up_hi = -inf, low_lo = inf, low_hi = -inf;
        for (const Along& g : up)
          if (covers(g)) {
            up_lo = std::min(up_lo, g.time_at(u));
            up_hi = std::max(up_hi, g.time_at(u));
          }
        for (const Along& g : low)
          if (covers(g)) {
            low_lo = std::min(low_lo, g.time_at(u));
            low_hi = std::max(low_hi, g.time_at(u));
          }
        ++out.ends;
        const Eigen::Vector2d p = a + u * e;
        const PieceEnd where{seg.wall_id, seg.piece + 1, p.x(), p.y()};
        out.each.push_back({up_lo, up_hi, low_lo, low_hi, where});
        if (up_lo - low_hi < out.min_offset_s) {
          out.min_offset_s = up_lo - low_hi;
          out.min_at = where;
        }
        if (up_hi - low_lo > out.max_offset_s) {
          out.max_offset_s = up_hi - low_lo;
          out.max_at = where;
        }
      }
    }
  }
  return out;
}

}  // namespace ccbuild::schedule::detail
