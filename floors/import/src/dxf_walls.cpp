// The DXF importer's walls: face lines paired into walls, their ends joined at junctions,
// gaps between walls in line read as openings (docs/formats.md, "DXF drawings").

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include "ccbuild/common/format.hpp"
#include "dxf_internal.hpp"
#include "segment_index.hpp"

namespace ccbuild::import::detail {

std::string hex_handle(int handle) {
  return handle < 0 ? std::string("(no handle)") : printf_string("%X", handle);
}

namespace {

/// The stretches of a face line already paired (parameters from its start), by start:
/// what share of a stretch is still free, in log time however many partners it has.
class Taken {
 public:
  bool empty() const { return by_start_.empty(); }
  void add(double from, double to) {
    by_start_.emplace(from, to);
    longest_ = std::max(longest_, to - from);
  }
  /// 1 minus the taken stretches' overlaps with [from, to], each counted, over its length.
  double free_share(double from, double to) const {
    double covered = 0.0;
    // Only stretches starting after from - longest can reach past from.
    for (auto it = by_start_.lower_bound(from - longest_); it != by_start_.end() && it->first < to;
         ++it)
      covered += std::max(0.0, std::min(to, it->second) - std::max(from, it->first));
    return 1.0 - covered / std::max(to - from, 1e-12);
  }

 private:
  std::multimap<double, double> by_start_;
  double longest_ = 0.0;
};

}  // namespace

/// Face lines that face each other become walls along their middle (see the header).
std::vector<FoundWall> pair_faces(const std::vector<DrawnLine>& faces, double scale,
                                  double max_thickness_m, NoteLog& notes) {
  struct Candidate {
    double distance_m;
    std::size_t i, j;
  };
  const std::size_t n = faces.size();
  std::vector<Vector2d> a(n), b(n), dir(n);
  std::vector<double> length(n);
  std::vector<int> bucket(n);
  std::vector<SegmentIndex::Segment> segments(n);
  for (std::size_t k = 0; k < n; ++k) {
    a[k] = faces[k].a * scale;
    b[k] = faces[k].b * scale;
    length[k] = (b[k] - a[k]).norm();
    dir[k] = (b[k] - a[k]) / length[k];
    // Direction mod 180 degrees in half-degree buckets: only nearly parallel lines (this
    // bucket or the next) are compared.
    double angle = std::atan2(dir[k].y(), dir[k].x()) * 180.0 / M_PI;
    if (angle < 0) angle += 180.0;
    bucket[k] = static_cast<int>(std::floor(angle * 2.0)) % 360;
    segments[k] = {a[k], b[k]};
  }
  // Faces that pair run side by side over at least half the shorter, at most the maximum
  // thickness apart where they do: the shorter's middle lies that close to the longer. So
  // only lines that near each other are compared.
  const double near_m = max_thickness_m + 1e-6;
  const SegmentIndex index(segments, near_m);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> near;
  if (const auto crowd = index.near_pairs(near_m, kMaxNearPairsPerLine * n + 65536, near))
    throw CrowdedLines{*crowd, near_m};
  std::vector<Candidate> candidates;
  for (const auto& [i, j] : near) {  // i < j
    const int apart = std::abs(bucket[i] - bucket[j]);
    if (apart > 1 && apart < 359) continue;
    if (std::abs(cross(dir[i], dir[j])) > 0.01) continue;
    const double d = std::abs(cross(dir[i], a[j] - a[i]));
    if (d < 0.01 || d > max_thickness_m + 1e-9) continue;
    // They must run side by side for at least half the shorter one.
    const double s0 = dir[i].dot(a[j] - a[i]), s1 = dir[i].dot(b[j] - a[i]);
    const double from = std::max(0.0, std::min(s0, s1)), to = std::min(length[i], std::max(s0, s1));
    const double overlap = to - from;
    if (overlap < 0.5 * std::min(length[i], length[j])) continue;
    // And no further apart than the maximum at either end of that stretch (lines that are
    // not quite parallel drift apart).
    const double along = dir[i].dot(dir[j]), drift = cross(dir[i], dir[j]);
    const double apart_at_a = cross(dir[i], a[j] - a[i]);
    if (std::abs(apart_at_a + (from - s0) / along * drift) > max_thickness_m + 1e-9 ||
        std::abs(apart_at_a + (to - s0) / along * drift) > max_thickness_m + 1e-9)
      continue;
    candidates.push_back({d, i, j});
  }
  // Nearest faces first; distances equal to the micrometre (the same drawing in another
  // unit) in drawing order, so that the plan does not depend on rounding.
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
    const long long dx = std::llround(x.distance_m * 1e6), dy = std::llround(y.distance_m * 1e6);
    return std::tie(dx, x.i, x.j) < std::tie(dy, y.i, y.j);
  });
  // Accepted stretches along each line, so that a line is paired where it has no partner
  // yet: a long outer face with two inner faces of a wall that another wall meets in a T.
  std::vector<Taken> taken(n);
  std::vector<FoundWall> walls;
  for (const Candidate& c : candidates) {
    const std::size_t i = c.i, j = c.j;
    const double s0 = dir[i].dot(a[j] - a[i]), s1 = dir[i].dot(b[j] - a[i]);
    const double from = std::max(0.0, std::min(s0, s1)), to = std::min(length[i], std::max(s0, s1));
    const double t0 = dir[j].dot(a[i] + from * dir[i] - a[j]),
                 t1 = dir[j].dot(a[i] + to * dir[i] - a[j]);
    if (taken[i].free_share(from, to) < 0.5 ||
        taken[j].free_share(std::min(t0, t1), std::max(t0, t1)) < 0.5)
      continue;
    taken[i].add(from, to);
    taken[j].add(std::min(t0, t1), std::max(t0, t1));
    const Vector2d normal = Vector2d(-dir[i].y(), dir[i].x());
    const double side = normal.dot(a[j] - a[i]) > 0 ? 1.0 : -1.0;
    const Vector2d half = normal * side * 0.5 * c.distance_m;
    walls.push_back({a[i] + from * dir[i] + half, a[i] + to * dir[i] + half, c.distance_m,
                     faces[i].handle == faces[j].handle
                         ? "entity " + hex_handle(faces[i].handle) +
                               " (two of its segments) on layer " + faces[i].layer
                         : "entities " + hex_handle(faces[i].handle) + " and " +
                               hex_handle(faces[j].handle) + " on layer " + faces[i].layer});
  }
  for (std::size_t k = 0; k < n; ++k)
    if (taken[k].empty())
      notes.left_out(
          "face lines with no parallel face to make a wall with; left out",
          printf_string("entity %s on layer %s: a face line from (%g, %g) to (%g, %g) with "
                        "no parallel face within %g m to make a wall with; left out",
                        hex_handle(faces[k].handle).c_str(), faces[k].layer.c_str(), faces[k].a.x(),
                        faces[k].a.y(), faces[k].b.x(), faces[k].b.y(), max_thickness_m));
  return walls;
}

/// Where face-pair walls meet, their middles stop short of each other (by half a
/// thickness at an L or a T): each end is extended along its wall to the nearest other
/// wall's middle line it reaches within the larger of the two thicknesses.
void join_ends(std::vector<FoundWall>& walls) {
  const std::vector<FoundWall> before = walls;
  double thickest_m = 0.0;
  std::vector<SegmentIndex::Segment> segments;
  for (const FoundWall& w : before) {
    thickest_m = std::max(thickest_m, w.thickness_m.value_or(0.0));
    segments.emplace_back(w.a, w.b);
  }
  // The wall an end reaches lies within twice the larger thickness of it: the hit at most
  // that far along the end's direction, on the other's line at most that far past its ends.
  const double near_m = 2.0 * (thickest_m + 1e-6) + 1e-9;
  const SegmentIndex index(segments, near_m);
  for (std::size_t w = 0; w < walls.size(); ++w) {
    if (!before[w].thickness_m) continue;
    const Vector2d d = (before[w].b - before[w].a).normalized();
    for (int end = 0; end < 2; ++end) {
      const Vector2d p = end == 0 ? before[w].a : before[w].b;
      const Vector2d out = end == 0 ? Vector2d(-d) : d;
      double best = std::numeric_limits<double>::infinity();
      for (const std::size_t v : index.near_point(p, near_m)) {
        if (v == w || !before[v].thickness_m) continue;
        const Vector2d e = before[v].b - before[v].a;
        const double denom = cross(out, e);
        if (std::abs(denom) < 1e-9 * e.norm()) continue;  // parallel: a wall going on
        const double reach = std::max(*before[w].thickness_m, *before[v].thickness_m) + 1e-6;
        const double t = cross(before[v].a - p, e) / denom;    // along `out`
        const double u = cross(before[v].a - p, out) / denom;  // along v, 0..1 on it
        const double slack = reach / e.norm();
        if (t < -1e-9 || t > reach || u < -slack || u > 1.0 + slack) continue;
        best = std::min(best, std::max(t, 0.0));
      }
      if (std::isfinite(best)) (end == 0 ? walls[w].a : walls[w].b) = p + best * out;
    }
  }
}

/// Gaps in wall lines as openings: two walls in line (parallel, on one line within
/// 1 mm, equal thickness), each with a free end (no other wall within 0.1 mm of it)
/// facing the other's across at most `max_gap_m`, become one wall with an opening in the
/// gap; a window when a line on a window layer has its middle in the gap, else a door.
/// Each free end joins its nearest such partner; chains (wall, gap, wall, gap, wall)
/// become one wall.
std::vector<FoundWall> join_gaps(std::vector<FoundWall> walls,
                                 const std::vector<DrawnLine>& glazing,
                                 const std::vector<OpeningMark>& marks, bool every_gap,
                                 double scale, double max_gap_m) {
  const std::size_t n = walls.size();
  double thickest_m = 0.0;
  std::vector<SegmentIndex::Segment> segments;
  for (const FoundWall& w : walls) {
    thickest_m = std::max(thickest_m, w.thickness_m.value_or(0.0));
    segments.emplace_back(w.a, w.b);
  }
  // Door and window blocks by their middles: a gap's opening is the first in drawing order
  // whose middle lies in it, along it.
  std::vector<SegmentIndex::Segment> mark_middles;
  for (const OpeningMark& m : marks)
    mark_middles.emplace_back(0.5 * (m.a + m.b), 0.5 * (m.a + m.b));
  const double reach_m = 0.5 * (max_gap_m + 2e-3) + 0.5 * thickest_m + 0.3 + 1e-6;
  const SegmentIndex mark_index(mark_middles, reach_m);
  const auto mark_in = [&](const Vector2d& p, const Vector2d& q,
                           double thickness_m) -> std::optional<std::size_t> {
    const double width_m = (q - p).norm();
    const Vector2d d = (q - p) / width_m;
    const double within_m = 0.5 * thickness_m + 0.3;
    for (const std::size_t k :
         mark_index.near_point(0.5 * (p + q), 0.5 * width_m + within_m + 1e-6)) {
      const Vector2d mid = mark_middles[k].first;
      const double s = (mid - p).dot(d);
      const Vector2d along = marks[k].b - marks[k].a;
      if (s > 0.0 && s < width_m && std::abs(cross(d, mid - p)) <= within_m &&
          along.norm() > 1e-3 && std::abs(cross(d, along.normalized())) <= 0.1)
        return k;
    }
    return std::nullopt;
  };
  const SegmentIndex wall_index(segments, 1e-4);
  const auto touches_other = [&](const Vector2d& p, std::size_t self) {
    for (const std::size_t v : wall_index.near_point(p, 1e-4)) {
      if (v == self) continue;
      const Vector2d e = walls[v].b - walls[v].a;
      const double t = std::clamp((p - walls[v].a).dot(e) / e.squaredNorm(), 0.0, 1.0);
      if ((walls[v].a + t * e - p).norm() <= 1e-4) return true;
    }
    return false;
  };
  // Free ends (2w + end), and where they are: the ends a free end may face.
  std::vector<char> free_end(2 * n, 0);
  std::vector<SegmentIndex::Segment> ends(2 * n);
  for (std::size_t w = 0; w < n; ++w)
    for (int end = 0; end < 2; ++end) {
      const Vector2d p = end == 0 ? walls[w].a : walls[w].b;
      free_end[2 * w + end] = touches_other(p, w) ? 0 : 1;
      ends[2 * w + end] = {p, p};
    }
  // Facing ends lie along a free end's direction, at most the widest gap and 1 mm across
  // away: within half a gap and a millimetre of the middle of that stretch.
  const double half_m = 0.5 * max_gap_m + 2e-3;
  const SegmentIndex end_index(ends, half_m);
  // partner[2w + end] = 2v + end' of the nearest facing free end.
  std::vector<long> partner(2 * n, -1);
  std::vector<std::pair<double, std::pair<std::size_t, std::size_t>>> links, own;
  for (std::size_t w = 0; w < n; ++w) {
    const Vector2d dw = (walls[w].b - walls[w].a).normalized();
    for (int end = 0; end < 2; ++end) {
      if (!free_end[2 * w + end]) continue;
      const Vector2d p = end == 0 ? walls[w].a : walls[w].b;
      const Vector2d out = end == 0 ? Vector2d(-dw) : dw;
      own.clear();
      for (const std::size_t e : end_index.near_point(p + 0.5 * max_gap_m * out, half_m)) {
        const std::size_t v = e / 2;
        const int other = static_cast<int>(e % 2);
        // Each pair from the wall that comes first; the other finds it from there.
        if (v <= w || !free_end[e]) continue;
        if (walls[v].thickness_m.has_value() != walls[w].thickness_m.has_value() ||
            (walls[v].thickness_m &&
             std::abs(*walls[v].thickness_m - *walls[w].thickness_m) > 1e-3))
          continue;
        const Vector2d dv = (walls[v].b - walls[v].a).normalized();
        if (std::abs(cross(dw, dv)) > 1e-6) continue;
        const Vector2d q = other == 0 ? walls[v].a : walls[v].b;
        const double gap = (q - p).dot(out);
        if (gap <= 1e-3 || gap > max_gap_m || std::abs(cross(out, q - p)) > 1e-3) continue;
        // q must be v's end facing back towards p.
        const Vector2d v_out = other == 0 ? Vector2d(-dv) : dv;
        if (v_out.dot(out) > -0.5) continue;
        if (!every_gap && !mark_in(p, q, walls[w].thickness_m.value_or(0.0))) continue;
        own.push_back({gap, {2 * w + end, e}});
      }
      // Only the nearest few: a free end joins its nearest partner (a farther one only when
      // a nearer one joined another end first).
      if (own.size() > kMaxGapPartners) {
        std::partial_sort(own.begin(), own.begin() + kMaxGapPartners, own.end());
        own.resize(kMaxGapPartners);
      }
      links.insert(links.end(), own.begin(), own.end());
    }
  }
  std::sort(links.begin(), links.end());
  for (const auto& [gap, pair] : links)
    if (partner[pair.first] < 0 && partner[pair.second] < 0) {
      partner[pair.first] = static_cast<long>(pair.second);
      partner[pair.second] = static_cast<long>(pair.first);
    }
  // Glazing lines by their middles, in metres: a gap's window is the first in drawing order
  // whose middle lies in it.
  std::vector<SegmentIndex::Segment> middles;
  for (const DrawnLine& l : glazing) {
    const Vector2d mid = 0.5 * (l.a + l.b) * scale;
    middles.emplace_back(mid, mid);
  }
  const double glazing_reach_m = 0.5 * (max_gap_m + 2e-3) + 0.5 * thickest_m + 0.3 + 1e-6;
  const SegmentIndex glazing_index(middles, glazing_reach_m);
  std::vector<FoundWall> out;
  std::vector<char> used(n, 0);
  std::vector<std::size_t> seen(n, 0);  // the chain walk that saw each wall last
  std::size_t walk = 0;
  for (std::size_t w = 0; w < n; ++w) {
    if (used[w]) continue;
    // The chain's start: walk from w out through its start end until an end has no
    // partner (a closed ring of gaps stops where it began).
    std::size_t first = w;
    int first_end = 0;
    {
      ++walk;
      seen[first] = walk;
      for (;;) {
        const long next = partner[2 * first + first_end];
        if (next < 0 || seen[next / 2] == walk) break;
        first = static_cast<std::size_t>(next / 2);
        first_end = 1 - static_cast<int>(next % 2);
        seen[first] = walk;
      }
    }
    // From `first`, its chain-free end `first_end` is where the merged wall starts.
    FoundWall merged = walls[first];
    if (first_end == 1) std::swap(merged.a, merged.b);
    merged.gaps.clear();
    std::size_t at = first;
    int out_end = 1 - first_end;
    used[at] = 1;
    for (;;) {
      const long next = partner[2 * at + out_end];
      if (next < 0 || used[next / 2]) break;
      const std::size_t v = static_cast<std::size_t>(next / 2);
      const int in_end = static_cast<int>(next % 2);
      const Vector2d p = out_end == 0 ? walls[at].a : walls[at].b;
      const Vector2d q = in_end == 0 ? walls[v].a : walls[v].b;
      const Vector2d far = in_end == 0 ? walls[v].b : walls[v].a;
      FoundGap g;
      // To the nanometre: a drawing in millimetres gives 0.8000000000000003 m.
      g.offset_m = floors::round_to_nanometre((p - merged.a).norm());
      g.width_m = floors::round_to_nanometre((q - p).norm());
      g.source = "the gap between " + walls[at].source + " and " + walls[v].source;
      const Vector2d d = (q - p) / g.width_m;
      const double within_m = 0.5 * merged.thickness_m.value_or(0.0) + 0.3;
      g.mark = mark_in(p, q, merged.thickness_m.value_or(0.0));  // its kind then the mark's
      for (const std::size_t k :
           g.mark ? std::vector<std::size_t>{}
                  : glazing_index.near_point(0.5 * (p + q), 0.5 * g.width_m + within_m + 1e-6)) {
        const Vector2d mid = middles[k].first;
        const double s = (mid - p).dot(d);
        const double across = std::abs(cross(d, mid - p));
        if (s > 0.0 && s < g.width_m && across <= within_m) {
          g.window = true;
          g.source += " (glazing: entity " + hex_handle(glazing[k].handle) + ")";
          break;
        }
      }
      merged.gaps.push_back(std::move(g));
      merged.b = far;
      merged.source += ", " + walls[v].source;
      used[v] = 1;
      at = v;
      out_end = 1 - in_end;
    }
    out.push_back(std::move(merged));
  }
  return out;
}

}  // namespace ccbuild::import::detail
