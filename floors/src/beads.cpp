// Walls as beads: the skins are the thick walls' outline offset inwards by half a bead
// (Boost.Geometry's union and buffer, so junctions are the library's, not ours), cut into
// straight stretches, each given to the wall it runs along; the core and the ties follow
// each wall's middle inside the skins.

#define BOOST_ALLOW_DEPRECATED_HEADERS
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/linestring.hpp>
#include <boost/geometry/geometries/multi_linestring.hpp>
#include <boost/geometry/geometries/multi_polygon.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>
#include <boost/geometry/index/rtree.hpp>
#undef BOOST_ALLOW_DEPRECATED_HEADERS

#include <algorithm>
#include <cmath>

#include "beads_internal.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/beads.hpp"
#include "ccbuild/floors/plane.hpp"
#include "plan_internal.hpp"

namespace ccbuild::floors {

const char* wall_pattern_name(WallPattern pattern) {
  switch (pattern) {
    case WallPattern::kSkins:
      return "skins";
    case WallPattern::kSolid:
      return "solid";
    case WallPattern::kSkinsWithTies:
      return "skins-with-ties";
  }
  return "?";
}

std::optional<WallPattern> parse_wall_pattern(const std::string& name) {
  for (auto p : {WallPattern::kSkins, WallPattern::kSolid, WallPattern::kSkinsWithTies})
    if (name == wall_pattern_name(p)) return p;
  return std::nullopt;
}

const char* bead_role_name(BeadRole role) {
  switch (role) {
    case BeadRole::kPass:
      return "pass";
    case BeadRole::kSkin:
      return "skin";
    case BeadRole::kCore:
      return "core";
    case BeadRole::kTie:
      return "tie";
  }
  return "?";
}

std::optional<BeadRole> parse_bead_role(const std::string& name) {
  for (auto r : {BeadRole::kPass, BeadRole::kSkin, BeadRole::kCore, BeadRole::kTie})
    if (name == bead_role_name(r)) return r;
  return std::nullopt;
}

WallBeads wall_beads(double thickness_m, const BeadSpec& spec) {
  constexpr double kTolerance_m = 1e-6;
  const double nozzle_m = spec.bead_width_m;
  const double narrowest_m = spec.narrowest_m > 0.0 ? spec.narrowest_m : nozzle_m;
  const double widest_m = spec.widest_m > 0.0 ? spec.widest_m : nozzle_m;
  const double t = thickness_m;
  if (t < narrowest_m - kTolerance_m) return {WallPrint::kTooThin, 0.0};
  if (t <= widest_m + kTolerance_m)
    return {WallPrint::kOnePass, std::clamp(t, narrowest_m, widest_m)};
  if (t >= 2.0 * nozzle_m - kTolerance_m) return {WallPrint::kSkinsAndFill, nozzle_m};
  if (t >= 2.0 * narrowest_m - kTolerance_m)
    return {WallPrint::kTwoSkins, std::max(0.5 * t, narrowest_m)};
  return {WallPrint::kBetween, 0.0};
}

namespace {
namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using BPoint = bg::model::d2::point_xy<double>;
using BPolygon = bg::model::polygon<BPoint>;
using BMulti = bg::model::multi_polygon<BPolygon>;
using BLine = bg::model::linestring<BPoint>;
using BLines = bg::model::multi_linestring<BLine>;
using BBox = bg::model::box<BPoint>;
using Vec = Eigen::Vector2d;

constexpr double kTolerance_m = 1e-6;
// Sine of the angle under which two directions are one: a stretch of the library's
// offset ring is parallel to its wall only to about a micrometre over its length.
constexpr double kParallel = 1e-4;

BPoint bp(const Vec& v) {
  return {v.x(), v.y()};
}
// Points the library computed, on a micrometre grid: its offsets carry rounding noise of
// about 1e-7 m, which would leave beads that should abut overlapping by that much.
Vec ev(const BPoint& p) {
  return {std::round(p.x() * 1e6) * 1e-6, std::round(p.y() * 1e6) * 1e-6};
}

// One piece of a wall in this layer, with its thickness and, at each end, how far its
// outline reaches past the end to fill the junction there (half the thickest wall met).
struct Item {
  const PieceSpec* piece = nullptr;
  double thickness_m = 0.0;
  double skin_m = 0.0;  ///< its pass's width (a thin wall) or each skin's (wall_beads)
  Vec a, b, dir, normal;
  double length_m = 0.0;
  double reach_m[2] = {0.0, 0.0};
  bool junction[2] = {false, false};
  /// Half the core of the widest wall that runs on through this end (a T's through wall
  /// not cut there): this wall's core stops at that core's side.
  double through_core_m[2] = {0.0, 0.0};

  double along(const Vec& p) const { return (p - a).dot(dir); }
  double across(const Vec& p) const { return (p - a).dot(normal); }
};

double distance_to_segment(const Vec& p, const Item& s) {
  const double t = std::clamp(s.along(p), 0.0, s.length_m);
  return (p - (s.a + t * s.dir)).norm();
}

BPolygon outline_of(const Item& it) {
  const Vec a = it.a - it.reach_m[0] * it.dir, b = it.b + it.reach_m[1] * it.dir;
  const Vec h = 0.5 * it.thickness_m * it.normal;
  BPolygon poly;
  for (const Vec& v : {Vec(a - h), Vec(a + h), Vec(b + h), Vec(b - h), Vec(a - h)})
    bg::append(poly.outer(), bp(v));
  bg::correct(poly);
  return poly;
}

// The union of many polygons, pairwise so that each union stays small.
BMulti union_of(std::vector<BMulti> parts) {
  if (parts.empty()) return {};
  while (parts.size() > 1) {
    std::vector<BMulti> next;
    for (std::size_t i = 0; i + 1 < parts.size(); i += 2) {
      BMulti joined;
      bg::union_(parts[i], parts[i + 1], joined);
      next.push_back(std::move(joined));
    }
    if (parts.size() % 2 == 1) next.push_back(std::move(parts.back()));
    parts = std::move(next);
  }
  return std::move(parts.front());
}

BMulti offset_inwards(const BMulti& region, double distance_m) {
  BMulti out;
  bg::strategy::buffer::distance_symmetric<double> distance(-distance_m);
  bg::strategy::buffer::side_straight side;
  bg::strategy::buffer::join_miter join;
  bg::strategy::buffer::end_flat end;
  bg::strategy::buffer::point_square point;
  bg::buffer(region, out, distance, side, join, end, point);
  return out;
}

// Corners of an offset ring closer than this are one: the library leaves stubs of a
// micrometre or so where an offset edge ends on a corner.
constexpr double kCornerMerge_m = 1e-5;

// A ring's corners, without repeated points and without points where it runs straight on.
std::vector<Vec> corners_of(const BPolygon::ring_type& ring) {
  std::vector<Vec> pts;
  for (const auto& p : ring) {
    const Vec v = ev(p);
    if (pts.empty() || (v - pts.back()).norm() > kCornerMerge_m) pts.push_back(v);
  }
  if (pts.size() > 1 && (pts.front() - pts.back()).norm() <= kCornerMerge_m) pts.pop_back();
  bool changed = true;
  while (changed && pts.size() >= 3) {
    changed = false;
    for (std::size_t i = 0; i < pts.size() && pts.size() >= 3; ++i) {
      const Vec& prev = pts[(i + pts.size() - 1) % pts.size()];
      const Vec& next = pts[(i + 1) % pts.size()];
      const Vec u = (pts[i] - prev).normalized(), w = (next - pts[i]).normalized();
      if (std::abs(cross(u, w)) < kParallel && u.dot(w) > 0.0) {
        pts.erase(pts.begin() + static_cast<std::ptrdiff_t>(i));
        changed = true;
        break;
      }
    }
  }
  return pts;
}

class Beads {
 public:
  Beads(const FloorPlan& plan, const std::vector<PieceSpec>& pieces, const SliceOptions& options)
      : plan_(plan), bead_m_(plan.beads.bead_width_m), merge_m_(options.merge_tolerance_m) {
    for (const auto& p : pieces) {
      Item it;
      it.piece = &p;
      const Wall* wall = plan.find_wall(p.wall_id);
      it.thickness_m = wall && wall->thickness_m ? *wall->thickness_m : bead_m_;
      it.a = p.start_m;
      it.b = p.end_m;
      it.length_m = (it.b - it.a).norm();
      if (it.length_m <= merge_m_) continue;
      it.dir = (it.b - it.a) / it.length_m;
      it.normal = Vec(-it.dir.y(), it.dir.x());
      const WallBeads beads = wall_beads(it.thickness_m, plan.beads);
      if (beads.how == WallPrint::kTooThin || beads.how == WallPrint::kBetween)
        throw InputError(at(wall->source, "thickness",
                            "wall " + std::to_string(wall->id) + " is " +
                                std::to_string(it.thickness_m) +
                                " m thick, which no bead or two skins of the machine's bead "
                                "widths make up"));
      it.skin_m = beads.bead_width_m;
      (beads.how == WallPrint::kOnePass ? thin_ : thick_).push_back(it);
    }
    // The skins' ring is the outline offset by half the narrowest skin, so that every thick
    // wall keeps an inside; each stretch is then moved onto its own wall's skin line.
    for (const Item& it : thick_)
      ring_inset_m_ =
          ring_inset_m_ > 0.0 ? std::min(ring_inset_m_, 0.5 * it.skin_m) : 0.5 * it.skin_m;
  }

  std::vector<PieceSpec> run() {
    std::vector<PieceSpec> out;
    if (thick_.empty()) {
      for (const Item& it : thin_) out.push_back(bead(it, it.a, it.b, it.skin_m, BeadRole::kPass));
      return out;
    }
    find_junctions();
    std::vector<BMulti> parts;
    for (const Item& it : thick_) parts.push_back(BMulti{outline_of(it)});
    region_ = union_of(std::move(parts));
    for (std::size_t i = 0; i < thick_.size(); ++i) index_.insert({box_of(thick_[i]), i});
    skins(out);
    passes(out);
    if (plan_.beads.pattern != WallPattern::kSkins) cores(out);
    return out;
  }

 private:
  using Entry = std::pair<BBox, std::size_t>;

  PieceSpec bead(const Item& it, const Vec& p, const Vec& q, double width_m, BeadRole role) const {
    PieceSpec s = *it.piece;
    s.start_m = p;
    s.end_m = q;
    // Beads keep the order of their wall's pieces, then run along the piece.
    s.along_m =
        it.piece->along_m + std::clamp(std::min(it.along(p), it.along(q)), 0.0, it.length_m);
    s.width_m = width_m;
    s.role = role;
    return s;
  }

  BBox box_of(const Item& it) const {
    const double r = 0.5 * it.thickness_m + std::max(it.reach_m[0], it.reach_m[1]) + bead_m_;
    return BBox(BPoint(std::min(it.a.x(), it.b.x()) - r, std::min(it.a.y(), it.b.y()) - r),
                BPoint(std::max(it.a.x(), it.b.x()) + r, std::max(it.a.y(), it.b.y()) + r));
  }

  // Where a thick piece's end meets another piece (its end or its middle), the outline
  // reaches half the thickest such piece past the end: L, T and X corners are filled.
  void find_junctions() {
    std::vector<const Item*> all;
    for (const Item& it : thick_) all.push_back(&it);
    for (const Item& it : thin_) all.push_back(&it);
    bgi::rtree<Entry, bgi::quadratic<16>> near;
    for (std::size_t i = 0; i < all.size(); ++i) {
      const Item& it = *all[i];
      near.insert({BBox(BPoint(std::min(it.a.x(), it.b.x()) - merge_m_,
                               std::min(it.a.y(), it.b.y()) - merge_m_),
                        BPoint(std::max(it.a.x(), it.b.x()) + merge_m_,
                               std::max(it.a.y(), it.b.y()) + merge_m_)),
                   i});
    }
    for (Item& it : thick_) {
      for (int end = 0; end < 2; ++end) {
        const Vec p = end == 0 ? it.a : it.b;
        std::vector<Entry> found;
        near.query(bgi::intersects(BBox(bp(p), bp(p))), std::back_inserter(found));
        for (const auto& [box, j] : found) {
          const Item& other = *all[j];
          if (&other == &it || distance_to_segment(p, other) > merge_m_) continue;
          it.junction[end] = true;
          it.reach_m[end] = std::max(it.reach_m[end], 0.5 * other.thickness_m);
          const double s = other.along(p);
          if (s > merge_m_ && s < other.length_m - merge_m_)
            it.through_core_m[end] =
                std::max(it.through_core_m[end], 0.5 * (other.thickness_m - 2.0 * other.skin_m));
        }
      }
    }
  }

  // The thick piece a stretch of skin belongs to: one it runs along over its own length,
  // else one it runs along in the junction its outline fills, else (a return across an
  // end) the one whose outline holds it.
  const Item* owner(const Vec& mid, const Vec& dir) const {
    std::vector<Entry> found;
    index_.query(bgi::intersects(BBox(bp(mid), bp(mid))), std::back_inserter(found));
    std::sort(found.begin(), found.end(),
              [](const Entry& x, const Entry& y) { return x.second < y.second; });
    const Item* best = nullptr;
    int best_rank = 4;
    for (const auto& [box, i] : found) {
      const Item& it = thick_[i];
      const double s = it.along(mid);
      if (std::abs(it.across(mid)) > 0.5 * it.thickness_m + kTolerance_m) continue;
      if (s < -it.reach_m[0] - kTolerance_m || s > it.length_m + it.reach_m[1] + kTolerance_m)
        continue;
      const bool parallel = std::abs(cross(dir, it.dir)) < kParallel;
      const bool inside = s >= -kTolerance_m && s <= it.length_m + kTolerance_m;
      const int rank = parallel ? (inside ? 0 : 1) : (inside ? 2 : 3);
      if (rank < best_rank) best = &it, best_rank = rank;
    }
    return best;
  }

  void skins(std::vector<PieceSpec>& out) const {
    const BMulti rings = offset_inwards(region_, ring_inset_m_);
    auto ring_beads = [&](const BPolygon::ring_type& ring) {
      const std::vector<Vec> pts = exact_corners(corners_of(ring));
      for (std::size_t k = 0; k < pts.size() && pts.size() >= 2; ++k)
        edge_beads(pts[k], pts[(k + 1) % pts.size()], out);
    };
    for (const auto& poly : rings) {
      ring_beads(poly.outer());
      for (const auto& inner : poly.inners()) ring_beads(inner);
    }
  }

  // The line a stretch of skin from p to q lies on, exactly: half a bead inside the face
  // of the wall it runs along, or inside the end of the wall it closes; the library's
  // offset is only within about a micrometre of it (more far from the origin).
  std::pair<Vec, Vec> exact_line(const Vec& p, const Vec& q) const {
    const Vec dir = (q - p).normalized(), mid = 0.5 * (p + q);
    const Item* it = owner(mid, dir);
    if (!it) return {p, dir};
    const double inset = 0.5 * it->thickness_m - 0.5 * it->skin_m;
    if (std::abs(cross(dir, it->dir)) < kParallel) {
      const double side = it->across(mid) >= 0.0 ? 1.0 : -1.0;
      return {Vec(it->a + side * inset * it->normal), it->dir};
    }
    if (std::abs(dir.dot(it->dir)) < kParallel) {  // a return across an end
      const double s = it->along(mid);
      const double at = s < 0.5 * it->length_m ? -it->reach_m[0] + 0.5 * it->skin_m
                                               : it->length_m + it->reach_m[1] - 0.5 * it->skin_m;
      return {Vec(it->a + at * it->dir), it->normal};
    }
    return {p, dir};
  }

  // A ring's corners moved onto the exact lines of its stretches: each corner where the
  // lines of the stretches before and after it cross (kept when they are parallel, or
  // when the crossing is not within a micrometre-scale distance of it).
  std::vector<Vec> exact_corners(const std::vector<Vec>& pts) const {
    const std::size_t n = pts.size();
    if (n < 3) return pts;
    std::vector<std::pair<Vec, Vec>> lines;
    // How far each stretch moves onto its line: the ring lies half the narrowest skin in,
    // a wall of wider skins has its stretches further in.
    std::vector<double> moved_m;
    for (std::size_t k = 0; k < n; ++k) {
      lines.push_back(exact_line(pts[k], pts[(k + 1) % n]));
      const auto& [p, d] = lines.back();
      moved_m.push_back(std::abs(cross(d, 0.5 * (pts[k] + pts[(k + 1) % n]) - p)));
    }
    std::vector<Vec> out = pts;
    for (std::size_t k = 0; k < n; ++k) {
      const auto& [p0, d0] = lines[(k + n - 1) % n];
      const auto& [p1, d1] = lines[k];
      const double det = cross(d0, d1);
      const double moved = moved_m[(k + n - 1) % n] + moved_m[k];
      if (std::abs(det) < 1e-9) {  // one line on: the corner is put on it
        const Vec on = p1 + (pts[k] - p1).dot(d1) * d1;
        if ((on - pts[k]).norm() <= 1e-4 + moved) out[k] = on;
        continue;
      }
      const double t = cross(p1 - p0, d1) / det;
      const Vec corner = p0 + t * d0;
      if ((corner - pts[k]).norm() <= 1e-4 + 2.0 * moved / std::max(std::abs(det), 0.1))
        out[k] = corner;
    }
    return out;
  }

  // One straight stretch of skin, split where the wall it runs along changes.
  void edge_beads(const Vec& p, const Vec& q, std::vector<PieceSpec>& out) const {
    const double length = (q - p).norm();
    if (length <= merge_m_) return;
    const Vec dir = (q - p) / length;
    std::vector<double> cuts{0.0, length};
    std::vector<Entry> found;
    index_.query(bgi::intersects(BBox(BPoint(std::min(p.x(), q.x()), std::min(p.y(), q.y())),
                                      BPoint(std::max(p.x(), q.x()), std::max(p.y(), q.y())))),
                 std::back_inserter(found));
    for (const auto& [box, i] : found) {
      const Item& it = thick_[i];
      if (std::abs(cross(dir, it.dir)) >= kParallel) continue;
      for (const Vec& end : {it.a, it.b}) {
        const double s = (end - p).dot(dir);
        if (s > merge_m_ && s < length - merge_m_) cuts.push_back(s);
      }
    }
    std::sort(cuts.begin(), cuts.end());
    const Item* current = nullptr;
    double from = 0.0;
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
      if (cuts[k + 1] - cuts[k] <= kTolerance_m) continue;
      const Item* it = owner(p + 0.5 * (cuts[k] + cuts[k + 1]) * dir, dir);
      CCBUILD_CHECK(it != nullptr, "a skin lies inside some wall's outline");
      if (current && it != current) {
        out.push_back(
            bead(*current, p + from * dir, p + cuts[k] * dir, current->skin_m, BeadRole::kSkin));
        from = cuts[k];
      }
      current = it;
    }
    if (current) out.push_back(bead(*current, p + from * dir, q, current->skin_m, BeadRole::kSkin));
  }

  // Walls one bead thick: one pass along the middle, outside the thick walls' outline.
  void passes(std::vector<PieceSpec>& out) const {
    for (const Item& it : thin_) {
      BLine line{bp(it.a), bp(it.b)};
      BLines outside;
      bg::difference(line, region_, outside);
      for (const auto& part : outside)
        for (std::size_t k = 0; k + 1 < part.size(); ++k)
          out.push_back(bead(it, ev(part[k]), ev(part[k + 1]), it.skin_m, BeadRole::kPass));
    }
  }

  // A core's end where it is exactly: the wall's end, or a bead inside a free end (where
  // it meets the return), when the library's clip is that within its rounding.
  Vec exact_core_end(const Item& it, const Vec& p) const {
    const double s = it.along(p);
    for (double exact : {0.0, it.length_m, it.skin_m, it.length_m - it.skin_m})
      if (std::abs(s - exact) <= 1e-4) return it.a + exact * it.dir;
    return p;
  }

  // Inside the skins: a core poured along each wall's middle, or a zig-zag tie.
  void cores(std::vector<PieceSpec>& out) const {
    const BMulti inside = offset_inwards(region_, bead_m_);
    if (inside.empty()) return;
    for (const Item& it : thick_) {
      const double core_m = it.thickness_m - 2.0 * it.skin_m;
      if (core_m <= merge_m_) continue;
      BLine line{bp(it.a), bp(it.b)};
      BLines parts;
      bg::intersection(line, inside, parts);
      for (const auto& part : parts) {
        if (part.size() < 2) continue;
        Vec p = exact_core_end(it, ev(part.front())), q = exact_core_end(it, ev(part.back()));
        if ((q - p).dot(it.dir) < 0.0) std::swap(p, q);
        if ((p - it.a).norm() <= merge_m_) p += std::max(0.0, it.through_core_m[0]) * it.dir;
        if ((q - it.b).norm() <= merge_m_) q -= std::max(0.0, it.through_core_m[1]) * it.dir;
        if ((q - p).dot(it.dir) <= merge_m_) continue;
        if (plan_.beads.pattern == WallPattern::kSolid)
          out.push_back(bead(it, p, q, core_m, BeadRole::kCore));
        else
          ties(it, p, q, core_m, out);
      }
    }
  }

  // A zig-zag between the skins' inner edges, its legs at about 45 degrees; kept clear of
  // junctions by half the core so that the ties of walls meeting there do not cross, and
  // of the returns at free ends by half a bead so that a slanted leg's end stays off them.
  void ties(const Item& it, Vec p, Vec q, double core_m, std::vector<PieceSpec>& out) const {
    const double bead_m = it.skin_m;             // a tie is laid at its wall's skin width
    if (core_m < bead_m - kTolerance_m) return;  // a cavity too narrow for a tie: left empty
    const bool at_a = (p - it.a).norm() <= merge_m_, at_b = (q - it.b).norm() <= merge_m_;
    p += (at_a && it.junction[0] ? 0.5 * core_m : 0.5 * bead_m) * it.dir;
    q -= (at_b && it.junction[1] ? 0.5 * core_m : 0.5 * bead_m) * it.dir;
    const double length = (q - p).dot(it.dir);
    if (length <= merge_m_) return;
    const double swing_m = 0.5 * (core_m - bead_m);
    if (swing_m <= merge_m_) {
      out.push_back(bead(it, p, q, bead_m, BeadRole::kTie));
      return;
    }
    const int legs =
        std::max(1, static_cast<int>(std::lround(length / std::max(2.0 * swing_m, 2.0 * bead_m))));
    const double step = length / legs;
    auto corner = [&](int k) {
      return Vec(p + k * step * it.dir + (k % 2 == 0 ? -swing_m : swing_m) * it.normal);
    };
    for (int k = 0; k < legs; ++k)
      out.push_back(bead(it, corner(k), corner(k + 1), bead_m, BeadRole::kTie));
  }

  const FloorPlan& plan_;
  double bead_m_;
  double ring_inset_m_ = 0.0;
  double merge_m_;
  std::vector<Item> thick_, thin_;
  BMulti region_;
  bgi::rtree<Entry, bgi::quadratic<16>> index_;
};

}  // namespace

std::vector<PieceSpec> bead_pieces(const FloorPlan& plan, const std::vector<PieceSpec>& pieces,
                                   const SliceOptions& options) {
  return Beads(plan, pieces, options).run();
}

}  // namespace ccbuild::floors
