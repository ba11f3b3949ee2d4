#include "ccbuild/rules/intervals.hpp"

#include "ccbuild/rules/age_clock.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ccbuild::rules {

bool DepositIndex::times_at(std::int64_t wall, const Eigen::Vector2d& p, double& lo,
                            double& hi) const {
  const auto it = spans.find(wall);
  if (it == spans.end()) return false;
  bool found = false;
  for (const Span& s : it->second) {
    const Eigen::Vector2d d = s.b - s.a;
    const double len2 = d.squaredNorm();
    const double u = len2 > 0 ? std::clamp((p - s.a).dot(d) / len2, 0.0, 1.0) : 0.0;
    if ((s.a + u * d - p).norm() > kOnSpan_m) continue;
    const double t = s.ta + u * (s.tb - s.ta);
    lo = found ? std::min(lo, t) : t;
    hi = found ? std::max(hi, t) : t;
    found = true;
  }
  return found;
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

/// The intervals along one piece from `a` in direction `e` (unit) over `length_m`.
void intervals_along(std::int64_t wall, int piece, const Eigen::Vector2d& a,
                     const Eigen::Vector2d& e, double length_m, const DepositIndex& upper_index,
                     const DepositIndex& lower_index, std::vector<double>& cuts,
                     IntervalOffsets& out) {
  // Along a piece the time each layer passes a point is piecewise linear, bending where
  // one of its spans starts or ends (where two nozzles' beads meet mid-piece, say): the
  // interval's extremes lie at the piece's ends or at those points. Between two such
  // points each layer is one stretch of bead; the interval is taken at both ends of it,
  // with the spans that cover it (a point where beads meet counts once from each side,
  // never pairing the bead above on one side with the bead below on the other).
  const std::vector<Along> up = along_piece(upper_index, wall, a, e, length_m);
  const std::vector<Along> low = along_piece(lower_index, wall, a, e, length_m);
  if (up.empty() || low.empty()) return;  // over an opening, or not deposited
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
    if (std::none_of(up.begin(), up.end(), covers) || std::none_of(low.begin(), low.end(), covers))
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
      const PieceEnd where{wall, piece, p.x(), p.y()};
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

}  // namespace

IntervalOffsets interval_offsets(const std::vector<PieceLine>& upper_pieces,
                                 const DepositIndex& upper_index, const DepositIndex& lower_index) {
  IntervalOffsets out;
  std::vector<double> cuts;
  for (const PieceLine& piece : upper_pieces) {
    const double length_m = (piece.b - piece.a).norm();
    if (length_m < 1e-12) continue;
    intervals_along(piece.wall, piece.piece, piece.a, (piece.b - piece.a) / length_m, length_m,
                    upper_index, lower_index, cuts, out);
  }
  return out;
}

IntervalOffsets interval_offsets(const DepositIndex& upper_index, const DepositIndex& lower_index) {
  IntervalOffsets out;
  std::vector<double> cuts;
  // Walls in id order, so that ties name the same point whatever the index's order.
  std::vector<std::int64_t> walls;
  for (const auto& [wall, spans] : upper_index.spans)
    if (lower_index.spans.count(wall)) walls.push_back(wall);
  std::sort(walls.begin(), walls.end());
  for (const std::int64_t wall : walls)
    for (const Span& s : upper_index.spans.at(wall)) {
      const double length_m = (s.b - s.a).norm();
      if (length_m < 1e-12) continue;
      intervals_along(wall, s.piece, s.a, (s.b - s.a) / length_m, length_m, upper_index,
                      lower_index, cuts, out);
    }
  return out;
}

StartWindow start_window(const IntervalOffsets& offsets, double min_interval_s,
                         double max_interval_s, const AgeClock* clock, double lower_origin_s) {
  const AgeClock real_time;
  const AgeClock& aged = clock ? *clock : real_time;
  StartWindow w;
  for (const IntervalOffsets::End& e : offsets.each) {
    // Covered at start + up: from the latest pass below, no sooner than the minimum; from
    // the earliest, no later than the maximum.
    const double earliest_s = aged.after(lower_origin_s + e.low_hi_s, min_interval_s) - e.up_lo_s;
    if (earliest_s > w.earliest_s) w.earliest_s = earliest_s, w.earliest_at = e.at;
    const double latest_s = aged.after(lower_origin_s + e.low_lo_s, max_interval_s) - e.up_hi_s;
    if (latest_s < w.latest_s) w.latest_s = latest_s, w.latest_at = e.at;
    w.newest_below_s = std::max(w.newest_below_s, lower_origin_s + e.low_hi_s);
  }
  w.ends_covered = offsets.ends;
  return w;
}

}  // namespace ccbuild::rules
