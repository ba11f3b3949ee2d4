// The DXF importer's walls: face lines paired into walls, their ends joined at junctions,
// gaps between walls in line read as openings (docs/formats.md, "DXF drawings").

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "ccbuild/common/format.hpp"
#include "dxf_internal.hpp"

namespace ccbuild::import::detail {

std::string hex_handle(int handle) {
  return handle < 0 ? std::string("(no handle)") : printf_string("%X", handle);
}

/// Face lines that face each other become walls along their middle (see the header).
std::vector<FoundWall> pair_faces(const std::vector<DrawnLine>& faces, double scale,
                                  double max_thickness_m, std::vector<std::string>& notes) {
  struct Candidate {
    double distance_m;
    std::size_t i, j;
  };
  const std::size_t n = faces.size();
  std::vector<Vector2d> a(n), b(n), dir(n);
  std::vector<double> length(n);
  for (std::size_t k = 0; k < n; ++k) {
    a[k] = faces[k].a * scale;
    b[k] = faces[k].b * scale;
    length[k] = (b[k] - a[k]).norm();
    dir[k] = (b[k] - a[k]) / length[k];
  }
  // Lines by direction (mod 180 degrees, in half-degree buckets), so that only nearly
  // parallel lines are compared.
  std::map<int, std::vector<std::size_t>> by_angle;
  const auto bucket = [&](std::size_t k) {
    double angle = std::atan2(dir[k].y(), dir[k].x()) * 180.0 / M_PI;
    if (angle < 0) angle += 180.0;
    return static_cast<int>(std::floor(angle * 2.0)) % 360;
  };
  for (std::size_t k = 0; k < n; ++k) by_angle[bucket(k)].push_back(k);
  std::vector<Candidate> candidates;
  for (std::size_t i = 0; i < n; ++i) {
    const int own = bucket(i);
    for (int db : {-1, 0, 1}) {
      const auto it = by_angle.find((own + db + 360) % 360);
      if (it == by_angle.end()) continue;
      for (std::size_t j : it->second) {
        if (j <= i || std::abs(cross(dir[i], dir[j])) > 0.01) continue;
        const double d = std::abs(cross(dir[i], a[j] - a[i]));
        if (d < 0.01 || d > max_thickness_m + 1e-9) continue;
        // They must run side by side for at least half the shorter one.
        const double s0 = dir[i].dot(a[j] - a[i]), s1 = dir[i].dot(b[j] - a[i]);
        const double overlap =
            std::min(length[i], std::max(s0, s1)) - std::max(0.0, std::min(s0, s1));
        if (overlap < 0.5 * std::min(length[i], length[j])) continue;
        candidates.push_back({d, i, j});
      }
    }
  }
  // Nearest faces first; distances equal to the micrometre (the same drawing in another
  // unit) in drawing order, so that the plan does not depend on rounding.
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
    const long long dx = std::llround(x.distance_m * 1e6), dy = std::llround(y.distance_m * 1e6);
    return std::tie(dx, x.i, x.j) < std::tie(dy, y.i, y.j);
  });
  // Accepted stretches along each line (parameters from its start), so that a line is
  // paired where it has no partner yet: a long outer face with two inner faces of a wall
  // that another wall meets in a T.
  std::vector<std::vector<std::pair<double, double>>> taken(n);
  const auto free_share = [&](std::size_t k, double from, double to) {
    double covered = 0.0;
    for (const auto& [s, e] : taken[k])
      covered += std::max(0.0, std::min(to, e) - std::max(from, s));
    return 1.0 - covered / std::max(to - from, 1e-12);
  };
  std::vector<FoundWall> walls;
  for (const Candidate& c : candidates) {
    const std::size_t i = c.i, j = c.j;
    const double s0 = dir[i].dot(a[j] - a[i]), s1 = dir[i].dot(b[j] - a[i]);
    const double from = std::max(0.0, std::min(s0, s1)), to = std::min(length[i], std::max(s0, s1));
    const double t0 = dir[j].dot(a[i] + from * dir[i] - a[j]),
                 t1 = dir[j].dot(a[i] + to * dir[i] - a[j]);
    if (free_share(i, from, to) < 0.5 || free_share(j, std::min(t0, t1), std::max(t0, t1)) < 0.5)
      continue;
    taken[i].emplace_back(from, to);
    taken[j].emplace_back(std::min(t0, t1), std::max(t0, t1));
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
      notes.push_back(printf_string(
          "entity %s on layer %s: a face line from (%g, %g) to (%g, %g) with no parallel face "
          "within %g m to make a wall with; left out",
          hex_handle(faces[k].handle).c_str(), faces[k].layer.c_str(), faces[k].a.x(),
          faces[k].a.y(), faces[k].b.x(), faces[k].b.y(), max_thickness_m));
  return walls;
}

/// Where face-pair walls meet, their middles stop short of each other (by half a
/// thickness at an L or a T): each end is extended along its wall to the nearest other
/// wall's middle line it reaches within the larger of the two thicknesses.
void join_ends(std::vector<FoundWall>& walls) {
  const std::vector<FoundWall> before = walls;
  for (std::size_t w = 0; w < walls.size(); ++w) {
    if (!before[w].thickness_m) continue;
    const Vector2d d = (before[w].b - before[w].a).normalized();
    for (int end = 0; end < 2; ++end) {
      const Vector2d p = end == 0 ? before[w].a : before[w].b;
      const Vector2d out = end == 0 ? Vector2d(-d) : d;
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t v = 0; v < before.size(); ++v) {
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
                                 const std::vector<DrawnLine>& glazing, double scale,
                                 double max_gap_m) {
  const std::size_t n = walls.size();
  const auto touches_other = [&](const Vector2d& p, std::size_t self) {
    for (std::size_t v = 0; v < n; ++v) {
      if (v == self) continue;
      const Vector2d e = walls[v].b - walls[v].a;
      const double t = std::clamp((p - walls[v].a).dot(e) / e.squaredNorm(), 0.0, 1.0);
      if ((walls[v].a + t * e - p).norm() <= 1e-4) return true;
    }
    return false;
  };
  // partner[2w + end] = 2v + end' of the nearest facing free end.
  std::vector<long> partner(2 * n, -1);
  std::vector<std::pair<double, std::pair<std::size_t, std::size_t>>> links;
  for (std::size_t w = 0; w < n; ++w) {
    const Vector2d dw = (walls[w].b - walls[w].a).normalized();
    for (int end = 0; end < 2; ++end) {
      const Vector2d p = end == 0 ? walls[w].a : walls[w].b;
      const Vector2d out = end == 0 ? Vector2d(-dw) : dw;
      if (touches_other(p, w)) continue;
      for (std::size_t v = w + 1; v < n; ++v) {
        if (walls[v].thickness_m.has_value() != walls[w].thickness_m.has_value() ||
            (walls[v].thickness_m &&
             std::abs(*walls[v].thickness_m - *walls[w].thickness_m) > 1e-3))
          continue;
        const Vector2d dv = (walls[v].b - walls[v].a).normalized();
        if (std::abs(cross(dw, dv)) > 1e-6) continue;
        for (int other = 0; other < 2; ++other) {
          const Vector2d q = other == 0 ? walls[v].a : walls[v].b;
          const double gap = (q - p).dot(out);
          if (gap <= 1e-3 || gap > max_gap_m || std::abs(cross(out, q - p)) > 1e-3) continue;
          // q must be v's end facing back towards p, and free.
          const Vector2d v_out = other == 0 ? Vector2d(-dv) : dv;
          if (v_out.dot(out) > -0.5 || touches_other(q, v)) continue;
          links.push_back({gap, {2 * w + end, 2 * v + other}});
        }
      }
    }
  }
  std::sort(links.begin(), links.end());
  for (const auto& [gap, ends] : links)
    if (partner[ends.first] < 0 && partner[ends.second] < 0) {
      partner[ends.first] = static_cast<long>(ends.second);
      partner[ends.second] = static_cast<long>(ends.first);
    }
  std::vector<FoundWall> out;
  std::vector<char> used(n, 0);
  for (std::size_t w = 0; w < n; ++w) {
    if (used[w]) continue;
    // The chain's start: walk from w out through its start end until an end has no
    // partner (a closed ring of gaps stops where it began).
    std::size_t first = w;
    int first_end = 0;
    {
      std::vector<char> seen(n, 0);
      seen[first] = 1;
      for (;;) {
        const long next = partner[2 * first + first_end];
        if (next < 0 || seen[next / 2]) break;
        first = static_cast<std::size_t>(next / 2);
        first_end = 1 - static_cast<int>(next % 2);
        seen[first] = 1;
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
      for (const DrawnLine& l : glazing) {
        const Vector2d mid = 0.5 * (l.a + l.b) * scale;
        const double s = (mid - p).dot(d);
        const double across = std::abs(cross(d, mid - p));
        if (s > 0.0 && s < g.width_m && across <= 0.5 * merged.thickness_m.value_or(0.0) + 0.3) {
          g.window = true;
          g.source += " (glazing: entity " + hex_handle(l.handle) + ")";
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
