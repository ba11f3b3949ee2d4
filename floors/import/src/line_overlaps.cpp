#include "line_overlaps.hpp"

#include <algorithm>
#include <cmath>

#include "ccbuild/common/format.hpp"
#include "ccbuild/floors/limits.hpp"
#include "segment_index.hpp"

namespace ccbuild::import::detail {

std::optional<std::size_t> remove_overlaps(
    std::vector<LinePiece>& pieces, double tolerance_m, std::size_t max_near_pairs,
    const std::function<void(std::size_t, std::size_t, double, Overlap)>& said) {
  // A piece cut back moves its ends across by at most the tolerance: pairs are looked for a
  // few tolerances apart, so that a piece cut before is still found.
  const double near_m = 4.0 * tolerance_m + 1e-9;
  std::vector<SegmentIndex::Segment> segments;
  segments.reserve(pieces.size());
  for (const LinePiece& p : pieces) segments.emplace_back(p.a, p.b);
  const SegmentIndex index(segments, near_m);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  if (const auto crowd = index.near_pairs(near_m, max_near_pairs, pairs)) return crowd;
  for (const auto& [i, j] : pairs) {  // i < j, ascending: the order of a loop over all pairs
    LinePiece& p = pieces[i];
    LinePiece& q = pieces[j];
    if (!p.alive || !q.alive) continue;
    const double length = (p.b - p.a).norm();
    const Eigen::Vector2d d = (p.b - p.a) / length, n(-d.y(), d.x());
    if (std::abs(n.dot(q.a - p.a)) > tolerance_m || std::abs(n.dot(q.b - p.a)) > tolerance_m)
      continue;
    double q0 = d.dot(q.a - p.a), q1 = d.dot(q.b - p.a);
    const bool reversed = q0 > q1;
    if (reversed) std::swap(q0, q1);
    const double overlap = std::min(length, q1) - std::max(0.0, q0);
    if (overlap <= tolerance_m) continue;
    if (q0 < -tolerance_m && q1 > length + tolerance_m) {  // p inside q
      p.alive = false;
      said(i, j, overlap, Overlap::kEarlierInsideLater);
      continue;
    }
    if (q0 >= -tolerance_m && q1 <= length + tolerance_m) {  // q inside p
      q.alive = false;
      said(i, j, overlap, Overlap::kLaterInsideEarlier);
      continue;
    }
    // Partial: q keeps what lies beyond p.
    const double from = q0 < 0.0 ? q0 : length, to = q0 < 0.0 ? 0.0 : q1;
    const Eigen::Vector2d k0 = p.a + from * d, k1 = p.a + to * d;
    q.a = reversed ? k1 : k0;
    q.b = reversed ? k0 : k1;
    if (to - from <= floors::limits::kMinWallLength_m) q.alive = false;
    said(i, j, overlap, Overlap::kLaterCutBack);
  }
  return std::nullopt;
}

std::string overlap_note(const std::string& later, const std::string& earlier, double overlap_m,
                         Overlap what) {
  return later + " and " + earlier +
         printf_string(" overlap along %.3f m on one line; ", overlap_m) +
         (what == Overlap::kLaterCutBack         ? "the first is cut back to where the second ends"
          : what == Overlap::kEarlierInsideLater ? "the second is printed as part of the first"
                                                 : "the first is printed as part of the second");
}

}  // namespace ccbuild::import::detail
