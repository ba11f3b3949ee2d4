// An IFC model as a Building (ifc.hpp): storeys become floors, walls are joined where they
// meet, openings are placed on the walls they cut.

#include "ccbuild/import/ifc.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "ccbuild/common/document.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/common/limits.hpp"
#include "ccbuild/floors/limits.hpp"
#include "ccbuild/floors/plane.hpp"
#include "ifc_internal.hpp"
#include "line_overlaps.hpp"
#include "segment_index.hpp"

namespace ccbuild::import {
namespace {

using Eigen::Vector2d;
using ifc::FoundOpening;
using ifc::FoundStorey;
using ifc::FoundWall;

using floors::cross;

/// Pairs of walls near one another (within a few join tolerances) that a floor may have,
/// on average per wall: a plan has a few per wall (at its junctions).
constexpr std::size_t kMaxNearPairsPerPiece = 64;

/// Lengths rounded to the nanometre (floors::round_to_nanometre).
double clean(double value_m) {
  return floors::round_to_nanometre(value_m);
}
Vector2d clean(const Vector2d& p) {
  return {clean(p.x()), clean(p.y())};
}

/// Storeys at one elevation (within a millimetre) make one floor.
struct Level {
  std::vector<const FoundStorey*> storeys;
  double elevation_m = 0.0;
  std::string name;
  std::vector<const FoundWall*> walls;  ///< its own and those spanning into it
  double height_m = 0.0;
  bool to_storey = true;  ///< its height runs to a storey above (else from its walls)
  std::string top_note;   ///< how the top floor's height was found, without a roof slab
  double slab_m = 0.0;    ///< the slab on its walls (Floor::slab_m)
};

/// One straight piece of a wall on a floor, while the floor's plan is made.
struct Piece {
  Vector2d a, b;
  const FoundWall* wall = nullptr;
  bool alive = true;
  double modelled_m = 0.0;         ///< its length as modelled, before ends were joined
  Vector2d a0 = Vector2d::Zero();  ///< its start as modelled
  std::size_t index = 0;           ///< in its wall's pieces
};

/// The lowest and highest of a wall's tops above `level`, where its body's outline says.
std::optional<std::pair<double, double>> top_range(const FoundWall& w, const Level& level) {
  std::optional<std::pair<double, double>> range;
  for (const auto& outline : w.piece_tops)
    for (const auto& [s, z] : outline) {
      const double t = z - level.elevation_m;
      range = range ? std::make_pair(std::min(range->first, t), std::max(range->second, t))
                    : std::make_pair(t, t);
    }
  return range;
}

/// Where a plan wall made of `piece` stops above its floor (floors::Wall::top_m): its
/// body's outline along the piece, from where the piece now starts to where it ends, above
/// the level; empty where the wall stands the floor's full height (within a millimetre).
/// One height along the whole piece is one point. `length_m`: the plan wall's, between the
/// vertices its ends were merged into.
std::vector<std::pair<double, double>> top_on_level(const Piece& piece, const Level& level,
                                                    double length_m) {
  const FoundWall& w = *piece.wall;
  if (piece.index >= w.piece_tops.size() || w.piece_tops[piece.index].empty()) return {};
  const auto& outline = w.piece_tops[piece.index];
  const Vector2d d = (piece.b - piece.a).normalized();
  const double shift_m = d.dot(piece.a - piece.a0);  // how far joining moved its start
  // The outline at `s` along the piece as it now is (the plan's own reading of a top).
  const auto at = [&](double s) { return floors::top_at(outline, s + shift_m); };
  std::vector<std::pair<double, double>> top = {{0.0, at(0.0)}};
  for (const auto& [s, z] : outline)
    if (s - shift_m > top.back().first + 1e-9 && s - shift_m < length_m - 1e-9)
      top.emplace_back(s - shift_m, z);
  top.emplace_back(length_m, at(length_m));
  bool lower = false, level_top = true;
  for (auto& [s, t] : top) {
    t = std::max(clean(t - level.elevation_m), 0.001);  // a top at the floor: in no layer
    s = clean(s);
    lower = lower || t < level.height_m - 1e-3;
    level_top = level_top && std::abs(t - top.front().second) < 1e-9;
  }
  if (!lower) return {};
  if (level_top) return {{0.0, top.front().second}};
  return top;
}

/// The part of a wall's NetVolume that one of its pieces on `level` takes: the piece's
/// share of the wall's modelled length, times the share of the wall's body within the
/// level's floor (from its level up to the slab over it: a wall's part in the slab's depth
/// is cast with the slab, not printed). The body's share is of its volume where its solids
/// are uncut (a leaf that stops under a ring beam has less there), else of its height; the
/// whole without a body.
std::optional<double> model_volume_m3(const Piece& piece, const Level& level) {
  const FoundWall& w = *piece.wall;
  if (!w.net_volume_m3) return std::nullopt;
  double modelled_m = 0.0;
  for (const auto& [a, b] : w.pieces) modelled_m += (b - a).norm();
  if (!(modelled_m > 0.0)) return std::nullopt;
  double height_share = 1.0;
  const double top_m = level.elevation_m + level.height_m;
  const double body_m3 = body_volume_between_m3(w, -std::numeric_limits<double>::infinity(),
                                                std::numeric_limits<double>::infinity());
  if (body_m3 > 0.0) {
    height_share =
        std::clamp(body_volume_between_m3(w, level.elevation_m, top_m) / body_m3, 0.0, 1.0);
  } else if (w.bottom_m && w.top_m && *w.top_m > *w.bottom_m) {
    height_share =
        std::clamp((std::min(*w.top_m, top_m) - std::max(*w.bottom_m, level.elevation_m)) /
                       (*w.top_m - *w.bottom_m),
                   0.0, 1.0);
  }
  const double m3 = *w.net_volume_m3 * (piece.modelled_m / modelled_m) * height_share;
  if (!floors::limits::kWallVolume_m3.contains(m3)) return std::nullopt;
  return m3;
}

/// Where walls meet, an axis stops short of the other wall's axis (at its face) or runs past
/// it (to the far face): each end not already at another wall's end is moved along its wall
/// to the nearest other wall's axis it reaches within the larger of the two thicknesses.
void join_ends(std::vector<Piece>& pieces, double tolerance_m) {
  const std::vector<Piece> before = pieces;
  double thickest_m = 0.0;
  std::vector<import::detail::SegmentIndex::Segment> segments;
  for (const Piece& p : before) {
    thickest_m = std::max(thickest_m, p.wall->thickness_m);
    segments.emplace_back(p.a, p.b);
  }
  // The axis an end reaches lies within twice the larger thickness (and the tolerance) of
  // it: the hit at most that far along the end's direction, on the other axis at most that
  // far past its ends.
  const double near_m = 2.0 * (thickest_m + tolerance_m) + 1e-9;
  const import::detail::SegmentIndex index(segments, near_m);
  for (std::size_t w = 0; w < pieces.size(); ++w) {
    const Vector2d d = (before[w].b - before[w].a).normalized();
    for (int end = 0; end < 2; ++end) {
      const Vector2d p = end == 0 ? before[w].a : before[w].b;
      bool shared = false;
      for (const std::size_t v : index.near_point(p, tolerance_m)) {
        shared = v != w && ((before[v].a - p).norm() <= tolerance_m ||
                            (before[v].b - p).norm() <= tolerance_m);
        if (shared) break;
      }
      if (shared) continue;
      const Vector2d out = end == 0 ? Vector2d(-d) : d;
      double best = std::numeric_limits<double>::infinity();
      for (const std::size_t v : index.near_point(p, near_m)) {  // ascending, as all of them
        if (v == w) continue;
        const Vector2d e = before[v].b - before[v].a;
        const double denom = cross(out, e);
        if (std::abs(denom) < 1e-6 * e.norm()) continue;  // parallel
        const double reach =
            std::max(before[w].wall->thickness_m, before[v].wall->thickness_m) + tolerance_m;
        const double t = cross(before[v].a - p, e) / denom;    // along `out`
        const double u = cross(before[v].a - p, out) / denom;  // along v, 0..1 on it
        const double slack = reach / e.norm();
        if (std::abs(t) > reach || u < -slack || u > 1.0 + slack) continue;
        if (std::abs(t) < std::abs(best)) best = t;
      }
      if (!std::isfinite(best) || std::abs(best) <= 1e-12) continue;
      (end == 0 ? pieces[w].a : pieces[w].b) = p + best * out;
    }
  }
}

/// Two pieces on one line sharing a stretch would be printed twice: the later keeps only
/// what the earlier does not cover (or, when the earlier lies inside it, the earlier goes).
/// Throws InputError when the floor's walls crowd beyond any plan.
void remove_overlaps(std::vector<Piece>& pieces, double tolerance_m, ifc::Notes& notes,
                     const std::string& floor, const std::string& file) {
  std::vector<import::detail::LinePiece> lines;
  for (const Piece& p : pieces) lines.push_back({p.a, p.b, p.alive});
  const auto crowd = import::detail::remove_overlaps(
      lines, tolerance_m, kMaxNearPairsPerPiece * lines.size() + 65536,
      [&](std::size_t i, std::size_t j, double overlap_m, import::detail::Overlap what) {
        notes.add(
            "walls overlapping on one line",
            "floor '" + floor + "': " +
                import::detail::overlap_note(pieces[j].wall->what.describe(),
                                             pieces[i].wall->what.describe(), overlap_m, what));
      });
  if (crowd)
    throw InputError(file, 0, pieces[*crowd].wall->what.describe(),
                     printf_string("floor '%s': more than %zu pairs of walls per wall lie within "
                                   "%.4f m of each other around this one: a floor's walls are "
                                   "modelled once each",
                                   floor.c_str(), kMaxNearPairsPerPiece, 4.0 * tolerance_m));
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    pieces[k].a = lines[k].a;
    pieces[k].b = lines[k].b;
    pieces[k].alive = lines[k].alive;
  }
}

/// An axis may run on past its wall's body where the modeller joined it to something the
/// plan does not hold (a curtain wall, a wall left out): an end that meets no other piece
/// is moved back to where the body's outline along the piece stops, so that the wall is
/// printed where its concrete is. Only ever shortened; said per wall.
void trim_free_ends(std::vector<Piece>& pieces, double tolerance_m, ifc::Notes& notes,
                    const std::string& floor) {
  std::vector<import::detail::SegmentIndex::Segment> segments;
  for (const Piece& p : pieces) segments.emplace_back(p.a, p.b);
  const import::detail::SegmentIndex index(segments, tolerance_m);
  const auto free_end = [&](std::size_t w, const Vector2d& p) {
    for (const std::size_t v : index.near_point(p, tolerance_m)) {
      if (v == w || !pieces[v].alive) continue;
      const Vector2d a = segments[v].first, e = segments[v].second - a;
      const double t = std::clamp((p - a).dot(e) / std::max(e.squaredNorm(), 1e-18), 0.0, 1.0);
      if ((a + t * e - p).norm() <= tolerance_m) return false;
    }
    return true;
  };
  for (std::size_t w = 0; w < pieces.size(); ++w) {
    Piece& piece = pieces[w];
    const FoundWall& wall = *piece.wall;
    if (!piece.alive || piece.index >= wall.piece_tops.size() ||
        wall.piece_tops[piece.index].empty())
      continue;
    double body_from_m = std::numeric_limits<double>::infinity(), body_to_m = -body_from_m;
    for (const auto& [s, z] : wall.piece_tops[piece.index]) {
      body_from_m = std::min(body_from_m, s);
      body_to_m = std::max(body_to_m, s);
    }
    const Vector2d d = (piece.b - piece.a).normalized();
    const double from_m = d.dot(piece.a - piece.a0), to_m = d.dot(piece.b - piece.a0);
    double cut_m = 0.0;
    if (body_from_m > from_m + tolerance_m && body_from_m < to_m &&
        free_end(w, segments[w].first)) {
      cut_m += body_from_m - from_m;
      piece.a = piece.a0 + body_from_m * d;
    }
    if (body_to_m < to_m - tolerance_m && body_to_m > from_m && free_end(w, segments[w].second)) {
      cut_m += to_m - body_to_m;
      piece.b = piece.a0 + body_to_m * d;
    }
    if (cut_m > 0.0)
      notes.add("walls whose axis runs past their body at a free end, printed to the body",
                printf_string("floor '%s': %s: its axis runs %.3f m past its body where no other "
                              "wall meets it; printed to its body",
                              floor.c_str(), wall.what.describe().c_str(), cut_m));
  }
}

floors::FloorPlan make_plan(const Level& level, const std::string& file, const IfcOptions& options,
                            ifc::Notes& notes, int& openings_left_out) {
  std::vector<Piece> pieces;
  for (const FoundWall* w : level.walls)
    for (std::size_t k = 0; k < w->pieces.size(); ++k) {
      const auto& [a, b] = w->pieces[k];
      pieces.push_back({a, b, w, true, (b - a).norm(), a, k});
    }
  join_ends(pieces, options.join_tolerance_m);
  for (Piece& p : pieces)
    if ((p.b - p.a).norm() <= floors::limits::kMinWallLength_m) {
      p.alive = false;
      notes.left_out("walls of which 1 mm or less is left where they meet others left out",
                     "floor '" + level.name + "': " + p.wall->what.describe() +
                         ": 1 mm or less of it is left where it meets other walls; left out");
    }
  remove_overlaps(pieces, options.join_tolerance_m, notes, level.name, file);
  trim_free_ends(pieces, options.join_tolerance_m, notes, level.name);

  floors::FloorPlan plan;
  plan.source_file = file;
  std::map<std::pair<long long, long long>, std::int64_t> vertex_at;
  const double cell = std::max(options.join_tolerance_m, 1e-6);
  const auto vertex = [&](const Vector2d& p) {
    const long long gx = std::llround(p.x() / cell), gy = std::llround(p.y() / cell);
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy) {
        const auto it = vertex_at.find({gx + dx, gy + dy});
        if (it != vertex_at.end() &&
            (plan.vertices[it->second - 1].position_m - p).norm() <= options.join_tolerance_m)
          return it->second;
      }
    const auto id = static_cast<std::int64_t>(plan.vertices.size()) + 1;
    plan.vertices.push_back({id, clean(p), {file, 0, "vertex " + std::to_string(id)}});
    vertex_at[{gx, gy}] = id;
    return id;
  };
  struct Made {
    std::int64_t id;
    const Piece* piece;
  };
  std::vector<Made> made;
  std::map<const FoundWall*, std::vector<std::size_t>> made_of;  // a wall's pieces in `made`
  for (const Piece& p : pieces) {
    if (!p.alive) continue;
    const std::int64_t s = vertex(p.a), e = vertex(p.b);
    if (s == e) continue;
    floors::Wall wall;
    wall.id = static_cast<std::int64_t>(plan.walls.size()) + 1;
    wall.start_vertex = s;
    wall.end_vertex = e;
    wall.thickness_m = clean(p.wall->thickness_m);
    wall.global_id = p.wall->what.guid;
    wall.model_volume_m3 = model_volume_m3(p, level);
    wall.top_m = top_on_level(
        p, level, (plan.vertices[e - 1].position_m - plan.vertices[s - 1].position_m).norm());
    wall.source = {file, 0, p.wall->what.describe()};
    plan.walls.push_back(wall);
    made_of[p.wall].push_back(made.size());
    made.push_back({wall.id, &p});
  }
  // Openings accepted, by wall and offset, to find one another's clashes in log time; the
  // widest on each wall bounds how far back a clash can start.
  std::map<std::int64_t, std::multimap<double, std::size_t>> accepted;
  std::map<std::int64_t, double> widest_m;
  // Openings: on the piece of their wall they lie on, within the floor's height.
  const auto at = [&](std::int64_t id) { return plan.vertices[id - 1].position_m; };
  for (const FoundWall* w : level.walls)
    for (const FoundOpening& o : w->openings) {
      double z0 = std::numeric_limits<double>::infinity(), z1 = -z0;
      for (const auto& c : o.corners_m) {
        z0 = std::min(z0, c.z());
        z1 = std::max(z1, c.z());
      }
      const double sill = std::max(0.0, z0 - level.elevation_m);
      const double head = std::min(level.height_m, z1 - level.elevation_m);
      if (head - sill <= 1e-3) continue;  // not on this floor
      const std::string what =
          o.what.describe() + (o.filled_by.empty() ? "" : ", filled by " + o.filled_by);
      const floors::Wall* on = nullptr;
      double s0 = 0.0, s1 = 0.0, nearest = std::numeric_limits<double>::infinity();
      static const std::vector<std::size_t> kNone;
      const auto own = made_of.find(w);
      for (const std::size_t k : own == made_of.end() ? kNone : own->second) {
        const Made& m = made[k];
        const floors::Wall& wall = plan.walls[m.id - 1];
        const Vector2d a = at(wall.start_vertex), b = at(wall.end_vertex);
        const double length = (b - a).norm();
        const Vector2d d = (b - a) / length;
        double lo = std::numeric_limits<double>::infinity(), hi = -lo, off = 0.0;
        for (const auto& c : o.corners_m) {
          lo = std::min(lo, d.dot(c.head<2>() - a));
          hi = std::max(hi, d.dot(c.head<2>() - a));
          off += std::abs(cross(d, c.head<2>() - a)) / static_cast<double>(o.corners_m.size());
        }
        const double mid = 0.5 * (lo + hi);
        if (mid < 0.0 || mid > length || off >= nearest) continue;
        nearest = off;
        on = &wall;
        s0 = std::clamp(lo, 0.0, length);
        s1 = std::clamp(hi, 0.0, length);
      }
      if (!on) {
        notes.left_out("openings not on what is left of their wall left out",
                       "floor '" + level.name + "': " + what + ": not on what is left of " +
                           w->what.describe() + "; left out");
        ++openings_left_out;
        continue;
      }
      if (s1 - s0 <= 1e-3) {
        notes.left_out(
            "openings with no width along their wall left out",
            "floor '" + level.name + "': " + what + ": no width along its wall; left out");
        ++openings_left_out;
        continue;
      }
      floors::Opening opening;
      opening.id = o.label.empty() ? o.what.guid : o.label;
      opening.wall_id = on->id;
      opening.offset_m = clean(s0);
      opening.width_m = clean(s1 - s0);
      opening.sill_m = clean(sill);
      opening.head_m = clean(head);
      opening.global_id = o.what.guid;
      opening.source = {file, 0, what};
      // Two openings sharing a stretch and a height band: the later is left out (said with
      // the first it clashes with).
      std::multimap<double, std::size_t>& on_wall = accepted[opening.wall_id];
      double& widest = widest_m[opening.wall_id];
      std::optional<std::size_t> clash;
      for (auto it = on_wall.lower_bound(opening.offset_m - widest - 1e-6);
           it != on_wall.end() && it->first < opening.offset_m + opening.width_m; ++it) {
        const floors::Opening& other = plan.openings[it->second];
        if (std::min(other.offset_m + other.width_m, opening.offset_m + opening.width_m) -
                    std::max(other.offset_m, opening.offset_m) >
                1e-6 &&
            std::min(other.head_m, opening.head_m) - std::max(other.sill_m, opening.sill_m) > 1e-6)
          clash = std::min(clash.value_or(it->second), it->second);
      }
      if (clash) {
        notes.left_out("openings overlapping another left out",
                       "floor '" + level.name + "': " + what + ": overlaps " +
                           plan.openings[*clash].source.path + "; left out");
        ++openings_left_out;
        continue;
      }
      on_wall.emplace(opening.offset_m, plan.openings.size());
      widest = std::max(widest, opening.width_m);
      plan.openings.push_back(opening);
    }
  return plan;
}

}  // namespace

bool is_ifc_path(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".ifc";
}

IfcImport read_ifc_building(const std::filesystem::path& path, const IfcOptions& options) {
  const std::string file = path.string();
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec && size > ccbuild::limits::kMaxInputFileBytes)
    throw InputError(file, 0, "",
                     printf_string("is %.1f MiB; ccbuild reads IFC models of at most %llu MiB: "
                                   "export only what is to be printed (the storeys and their "
                                   "walls, without furniture and services)",
                                   static_cast<double>(size) / (1024.0 * 1024.0),
                                   static_cast<unsigned long long>(
                                       ccbuild::limits::kMaxInputFileBytes / (1024 * 1024))));
  std::string text = read_text_file(path);
  IfcImport out;
  out.schema = ifc::check_step_text(text, file, options.max_entities).schema;
  ifc::ModelContents model = ifc::read_model(std::move(text), file, options);
  out.metres_per_unit = model.metres_per_unit;
  ifc::Notes notes = std::move(model.notes);
  int left_out = model.left_out;

  // Levels: storeys by elevation, those at one elevation together.
  std::vector<const FoundStorey*> storeys;
  for (const auto& s : model.storeys) storeys.push_back(&s);
  std::stable_sort(storeys.begin(), storeys.end(), [](const FoundStorey* a, const FoundStorey* b) {
    return a->elevation_m < b->elevation_m;
  });
  std::vector<Level> levels;
  for (const FoundStorey* s : storeys) {
    if (levels.empty() || s->elevation_m - levels.back().elevation_m > 1e-3) {
      levels.push_back({});
      levels.back().elevation_m = s->elevation_m;
    } else {
      notes.add("storeys at one elevation made one floor",
                s->what.describe() + printf_string(" stands at the elevation of ") +
                    levels.back().storeys.front()->what.describe() +
                    printf_string(" (%.3f m): one floor", s->elevation_m));
    }
    Level& l = levels.back();
    l.storeys.push_back(s);
    const std::string name = s->what.name.empty() ? s->what.guid : s->what.name;
    l.name += (l.name.empty() ? "" : " + ") + name;
  }
  // Every wall is matched against every level below (walls spanning storeys): the levels
  // are as many as the floors a building may have.
  if (levels.size() > static_cast<std::size_t>(floors::limits::kMaxFloors))
    throw InputError(file, 0,
                     levels[static_cast<std::size_t>(floors::limits::kMaxFloors)]
                         .storeys.front()
                         ->what.describe(),
                     printf_string("the model has storeys at %zu elevations; ccbuild takes "
                                   "buildings of at most %d floors",
                                   levels.size(), floors::limits::kMaxFloors));
  // Heights to the next level; the top one's from its walls.
  const auto wall_top = [&](const Level& l) {
    double top = -std::numeric_limits<double>::infinity();
    for (const FoundStorey* s : l.storeys)
      for (const FoundWall& w : s->walls)
        if (w.top_m) top = std::max(top, *w.top_m);
    return top - l.elevation_m;
  };
  for (std::size_t k = 0; k < levels.size(); ++k)
    levels[k].height_m = k + 1 < levels.size() ? levels[k + 1].elevation_m - levels[k].elevation_m
                                               : wall_top(levels[k]);
  // Walls on their storey's level, and on every level above or below they fill half of.
  for (std::size_t k = 0; k < levels.size(); ++k)
    for (const FoundStorey* s : levels[k].storeys)
      for (const FoundWall& w : s->walls)
        for (std::size_t f = 0; f < levels.size(); ++f) {
          Level& l = levels[f];
          bool on = f == k;
          if (!on && w.bottom_m && w.top_m && l.height_m > 0.0) {
            const double overlap = std::min(*w.top_m, l.elevation_m + l.height_m) -
                                   std::max(*w.bottom_m, l.elevation_m);
            on = overlap >= 0.5 * l.height_m;
            if (on)
              notes.add("walls spanning storeys", w.what.describe() + " of storey '" +
                                                      levels[k].name + "' also stands on storey '" +
                                                      l.name + "' (it spans both)");
          }
          if (on) l.walls.push_back(&w);
        }
  // Levels without walls make no floor; the heights of those kept run to the next kept one.
  std::vector<Level> kept;
  for (std::size_t k = 0; k < levels.size(); ++k) {
    if (levels[k].walls.empty()) {
      notes.add("storeys without walls",
                printf_string("storey '%s' at %.3f m has no walls ccbuild prints; no "
                              "floor is made of it",
                              levels[k].name.c_str(), levels[k].elevation_m));
      continue;
    }
    kept.push_back(levels[k]);
    Level& l = kept.back();
    std::size_t next = k + 1;
    while (next < levels.size() && levels[next].walls.empty()) ++next;
    if (next < levels.size()) {
      l.height_m = levels[next].elevation_m - l.elevation_m;
    } else if (k + 1 < levels.size()) {
      l.height_m = levels[k + 1].elevation_m - l.elevation_m;
      next = k + 1;
    } else {
      l.height_m = wall_top(l);
      l.to_storey = false;
      if (!(l.height_m > 1e-3) || !std::isfinite(l.height_m)) {
        l.height_m = options.default_storey_height_m;
        l.top_note =
            (printf_string("storey '%s', the top one: no storey above it and no "
                           "wall height says its height; %.3f m taken",
                           l.name.c_str(), l.height_m));
      } else {
        l.top_note =
            (printf_string("storey '%s', the top one: %.3f m high, as its "
                           "tallest wall (no storey above it)",
                           l.name.c_str(), l.height_m));
      }
      continue;
    }
    if (next > k + 1)
      notes.add("storeys running across storeys without walls",
                printf_string("storey '%s' runs up to storey '%s' at %.3f m (%.3f m), "
                              "across storeys without walls",
                              l.name.c_str(), levels[next].name.c_str(), levels[next].elevation_m,
                              l.height_m));
  }
  // Slabs: a floor's walls stop under the slab placed on them. The storey's elevation is
  // the top of its floor's slab (as Revit and ArchiCAD export it), so the slab over a floor
  // is one whose underside lies in the floor's upper half, up to the next storey's
  // elevation: the next storey's floor slab (whichever storey contains it) or a roof slab.
  // Over the top floor, a roof slab only. The lowest underside sets the height.
  for (Level& l : kept) {
    const double h = l.height_m;
    const ifc::FoundSlab* over = nullptr;
    for (const auto& slab : model.slabs) {
      if (!l.to_storey && !slab.roof) continue;
      if (slab.bottom_m <= l.elevation_m + 0.5 * h) continue;
      if (l.to_storey && slab.bottom_m > l.elevation_m + h + 1e-3) continue;
      if (!over || slab.bottom_m < over->bottom_m - 1e-9) over = &slab;
    }
    if (!over) {
      if (!l.top_note.empty()) notes.add("the top floor's height", l.top_note);
      if (l.to_storey && !model.slabs.empty())
        notes.add(
            "floors without a slab over them",
            printf_string(
                "floor '%s': no slab found under the storey above (FLOOR, BASESLAB or ROOF, its "
                "underside between %.3f and %.3f m); its walls run to the storey above, %.3f m",
                l.name.c_str(), l.elevation_m + 0.5 * h, l.elevation_m + h, h));
      continue;
    }
    l.height_m = std::min(h, over->bottom_m - l.elevation_m);
    if (!l.to_storey) l.height_m = over->bottom_m - l.elevation_m;
    l.slab_m = std::max(
        0.0, l.to_storey ? l.elevation_m + h - over->bottom_m : over->top_m - over->bottom_m);
    notes.add(
        "floors under their slab",
        printf_string(
            "floor '%s': %.3f m high, from its level (%.3f m) to the underside of %s (%s slab, "
            "%.3f m thick, in storey '%s') at %.3f m; %s",
            l.name.c_str(), l.height_m, l.elevation_m, over->what.describe().c_str(),
            over->kind.c_str(), over->thickness_m, over->storey.c_str(), over->bottom_m,
            !l.to_storey ? printf_string("%.3f m of slab over it (the roof)", l.slab_m).c_str()
            : l.slab_m > 1e-6
                ? printf_string("%.3f m of slab up to the next floor's level", l.slab_m).c_str()
                : "the storey above stands at its underside"));
  }
  if (model.slabs.empty())
    notes.add(
        "the model's slabs",
        "the model has no slab (IfcSlab FLOOR, BASESLAB or ROOF) in its storeys: each floor's "
        "walls run up to the storey above (the top one's: its tallest wall)");
  if (kept.empty()) {
    std::string why;
    int shown = 0;
    for (const auto& note : notes.left_out_lines())
      if (++shown <= 3) why += "; " + note;
    throw InputError(file, 0, "",
                     printf_string("no wall ccbuild can print in any of the model's %zu storeys",
                                   levels.size()) +
                         why);
  }

  floors::Building& b = out.building;
  b.name = model.building_name.empty() ? path.stem().string() : model.building_name;
  b.source_file = file;
  b.files_read.push_back(path);
  b.units = floors::LengthUnit::kMeter;
  b.layer_height_m = options.layer_height_m;
  if (std::abs(kept.front().elevation_m) > 1e-6)
    notes.add("the lowest floor's level",
              printf_string("the lowest floor, '%s', stands at %.3f m in the model; the "
                            "building's heights are counted from it",
                            kept.front().name.c_str(), kept.front().elevation_m));
  DiagnosticSink sink;
  double base_m = 0.0;
  int walls = 0, openings = 0;
  for (std::size_t k = 0; k < kept.size(); ++k) {
    Level& l = kept[k];
    const FoundStorey& first = *l.storeys.front();
    if (!floors::limits::kFloorHeight_m.contains(l.height_m))
      throw InputError(file, 0, first.what.describe(),
                       printf_string("storey '%s' is %.3f m high, not a floor height ccbuild "
                                     "takes (%s)",
                                     l.name.c_str(), l.height_m,
                                     floors::limits::kFloorHeight_m.describe("m").c_str()));
    for (const FoundWall* w : l.walls) {
      if (const auto top = top_range(*w, l); top && top->first < l.height_m - 1e-3) {
        if (top->second - top->first < 1e-3)
          notes.add(
              "walls lower than their floor, printed to their own top",
              printf_string("floor '%s': %s stops %.3f m above the floor's level (its "
                            "body's top; the floor is %.3f m high): printed up to there",
                            l.name.c_str(), w->what.describe().c_str(), top->first, l.height_m));
        else
          notes.add("walls lower than their floor, printed to their own top",
                    printf_string("floor '%s': %s has a top from %.3f to %.3f m above the "
                                  "floor's level (its body's outline in elevation: a gable, "
                                  "say; the floor is %.3f m high): printed up to it",
                                  l.name.c_str(), w->what.describe().c_str(), top->first,
                                  top->second, l.height_m));
      }
      if (w->clipped)
        notes.add("walls whose body is cut by what ccbuild does not read",
                  "floor '" + l.name + "': " + w->what.describe() +
                      ": its body is cut by something other than a plane's half-space; "
                      "ccbuild prints it as if uncut, up to its body's top or the floor's "
                      "height, the lower");
      if (w->bounded_cut)
        notes.add("walls cut by bounded half-spaces, read as unbounded",
                  "floor '" + l.name + "': " + w->what.describe() +
                      ": its body is cut by a polygonal bounded half-space, read as the "
                      "whole plane's half-space");
    }
    floors::Floor floor;
    floor.name = l.name;
    floor.index = static_cast<int>(k);
    floor.height_m = clean(l.height_m);
    floor.slab_m = clean(l.slab_m);
    floor.base_elevation_m = base_m;
    floor.level_m = clean(l.elevation_m);
    floor.source = {file, 0, first.what.describe()};
    std::size_t pieces = 0;
    for (const FoundWall* w : l.walls) pieces += w->pieces.size();
    if (pieces > floors::limits::kMaxWalls)
      throw InputError(file, 0, first.what.describe(),
                       printf_string("%zu walls on one floor; ccbuild takes at most %zu", pieces,
                                     floors::limits::kMaxWalls));
    floor.plan = make_plan(l, file, options, notes, left_out);
    base_m += floor.height_m + floor.slab_m;
    if (floor.plan.walls.size() > floors::limits::kMaxWalls)
      throw InputError(file, 0, first.what.describe(),
                       printf_string("%zu walls on one floor; ccbuild takes at most %zu",
                                     floor.plan.walls.size(), floors::limits::kMaxWalls));
    try {
      floors::validate_plan(floor.plan, floor.height_m, "floor '" + floor.name + "'");
    } catch (const InputError& error) {
      for (const auto& d : error.diagnostics()) sink.add(d);
    }
    walls += static_cast<int>(floor.plan.walls.size());
    openings += static_cast<int>(floor.plan.openings.size());
    b.floors.push_back(std::move(floor));
  }
  sink.throw_if_any();
  double layers = 0.0;
  for (const auto& f : b.floors) layers += std::ceil(f.height_m / b.layer_height_m - 1e-9);
  if (layers > static_cast<double>(floors::limits::kMaxLayers))
    throw InputError(file, 0, "",
                     printf_string("%.0f layers of %.3f m make this building; ccbuild plans at "
                                   "most %ld",
                                   layers, b.layer_height_m, floors::limits::kMaxLayers));
  notes.add(
      "the summary",
      printf_string(
          "imported %d walls and %d openings on %zu floor%s (%s, 1 unit = %g m); left out: %d "
          "element%s (each said above)",
          walls, openings, b.floors.size(), b.floors.size() == 1 ? "" : "s", out.schema.c_str(),
          out.metres_per_unit, left_out, left_out == 1 ? "" : "s"));
  out.notes = notes.lines();
  b.import_notes = out.notes;
  // The filters it was read with: the building's print spec, as an import writes it.
  b.print.stated = true;
  b.print.wall_types = options.wall_types;
  b.print.excluded_materials = options.excluded_materials;
  return out;
}

}  // namespace ccbuild::import
