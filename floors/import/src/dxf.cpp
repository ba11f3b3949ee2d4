#include "ccbuild/import/dxf.hpp"

#include <dxflib/dl_creationadapter.h>
#include <dxflib/dl_dxf.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include "ccbuild/common/document.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/limits.hpp"

namespace ccbuild::import {
namespace {

using Eigen::Vector2d;

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string hex_handle(int handle) {
  return handle < 0 ? std::string("(no handle)") : printf_string("%X", handle);
}

/// A straight line of the drawing, in drawing units.
struct DrawnLine {
  Vector2d a, b;
  int handle = -1;
  std::string layer;
};

struct DrawnInsert {
  std::string block, layer;
  Vector2d at;
  double sx = 1.0, sy = 1.0, angle_deg = 0.0;
  int handle = -1;
};

/// Collects what the importer needs while dxflib reads: lines and polylines of the model
/// space by layer, block definitions' extents, inserts, the unit.
class Collector : public DL_CreationAdapter {
 public:
  std::map<std::string, long> entities_per_layer;  ///< model space, by lower-case layer
  std::map<std::string, std::string> layer_names;  ///< lower-case -> as drawn
  std::vector<DrawnLine> lines;                    ///< model space, every layer
  std::vector<DrawnInsert> inserts;
  std::map<std::string, std::pair<Vector2d, Vector2d>> block_extent;  ///< min, max
  std::vector<std::string> skipped;  ///< curved segments (bulges), non-finite points
  std::optional<int> insunits;

  void setVariableInt(const std::string& key, int value, int) override {
    if (key == "$INSUNITS") insunits = value;
  }
  void addBlock(const DL_BlockData& data) override {
    end_polyline();
    block_ = data.name;
  }
  void endBlock() override {
    end_polyline();
    block_.reset();
  }
  void addLine(const DL_LineData& d) override {
    end_polyline();
    segment({d.x1, d.y1}, {d.x2, d.y2});
  }
  void addPolyline(const DL_PolylineData& d) override {
    end_polyline();
    polyline_ = Polyline{};
    polyline_->closed = (d.flags & 1) != 0;
    polyline_->handle = attributes.getHandle();
    polyline_->layer = attributes.getLayer();
  }
  void addVertex(const DL_VertexData& d) override {
    if (!polyline_) return;
    polyline_->points.emplace_back(d.x, d.y);
    polyline_->bulges.push_back(d.bulge);
  }
  void addInsert(const DL_InsertData& d) override {
    end_polyline();
    if (block_) return;  // nested blocks: not read
    count();
    inserts.push_back({d.name,
                       attributes.getLayer(),
                       {d.ipx, d.ipy},
                       d.sx,
                       d.sy,
                       d.angle,
                       attributes.getHandle()});
  }
  void endEntity() override {}
  // A POLYLINE's VERTEX entities end at its SEQEND; an LWPOLYLINE's with the next entity
  // (dxflib calls endSection after every entity, so that cannot end one).
  void endSequence() override { end_polyline(); }
  void finish() { end_polyline(); }

 private:
  struct Polyline {
    std::vector<Vector2d> points;
    std::vector<double> bulges;
    bool closed = false;
    int handle = -1;
    std::string layer;
  };
  void count() {
    const std::string layer = attributes.getLayer();
    ++entities_per_layer[lower(layer)];
    layer_names.emplace(lower(layer), layer);
  }
  void segment(const Vector2d& a, const Vector2d& b, int handle, const std::string& layer,
               double bulge) {
    if (block_) {  // a block's definition: only its extent matters (openings)
      auto [it, fresh] = block_extent.try_emplace(*block_, a, a);
      for (const Vector2d& p : {a, b}) {
        if (!p.allFinite()) continue;
        it->second.first = it->second.first.cwiseMin(p);
        it->second.second = it->second.second.cwiseMax(p);
      }
      return;
    }
    if (bulge != 0.0) {
      skipped.push_back("entity " + hex_handle(handle) + " on layer " + layer +
                        printf_string(": a curved segment from (%g, %g) to (%g, %g) is not "
                                      "read (ccbuild prints straight walls)",
                                      a.x(), a.y(), b.x(), b.y()));
      return;
    }
    lines.push_back({a, b, handle, layer});
  }
  void segment(const Vector2d& a, const Vector2d& b) {
    if (!block_) count();
    segment(a, b, attributes.getHandle(), attributes.getLayer(), 0.0);
  }
  void end_polyline() {
    if (!polyline_) return;
    Polyline p = std::move(*polyline_);
    polyline_.reset();
    if (!block_) {
      ++entities_per_layer[lower(p.layer)];
      layer_names.emplace(lower(p.layer), p.layer);
    }
    const std::size_t n = p.points.size();
    const std::size_t edges = p.closed ? n : (n == 0 ? 0 : n - 1);
    for (std::size_t k = 0; k < edges; ++k)
      segment(p.points[k], p.points[(k + 1) % n], p.handle, p.layer, p.bulges[k]);
  }
  std::optional<std::string> block_;
  std::optional<Polyline> polyline_;
};

/// A gap in a wall's line read as an opening, from the wall's start.
struct FoundGap {
  double offset_m = 0.0, width_m = 0.0;
  bool window = false;
  std::string source;
};

/// A wall found: its centreline in metres, its thickness (unset: drawn as a centreline).
struct FoundWall {
  Vector2d a, b;
  std::optional<double> thickness_m;
  std::string source;  ///< "entity 1A on layer A-WALL" (and its partner)
  std::vector<FoundGap> gaps;
};

double cross(const Vector2d& u, const Vector2d& v) {
  return u.x() * v.y() - u.y() * v.x();
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
      const auto nm = [](double v) { return std::round(v * 1e9) / 1e9; };
      g.offset_m = nm((p - merged.a).norm());
      g.width_m = nm((q - p).norm());
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

/// The longest line dxflib reads (DL_DXF_MAXLINE); on a longer one it loops forever.
constexpr std::size_t kDxflibMaxLine = 1024;

/// What dxflib does not check: every real-valued group (codes 10-59, 110-149, 210-239,
/// 1010-1059) a finite number (dxflib reads "nan" or "1e999x" as 0 or garbage), and the
/// drawing whole, up to its EOF (dxflib reads a cut-off file as far as it goes). Returns
/// the text to give dxflib: up to the EOF, every value longer than dxflib reads (only
/// text, which ccbuild does not use, is that long) cut short.
std::string checked_dxf_text(const std::string& text, const std::string& file) {
  std::string out;
  out.reserve(text.size());
  std::istringstream in(text);
  std::string code_line, value;
  int line = 0;
  bool ended = false;
  while (std::getline(in, code_line)) {
    ++line;
    if (!code_line.empty() && code_line.back() == '\r') code_line.pop_back();
    if (code_line.find_first_not_of(" \t") == std::string::npos) continue;
    char* end = nullptr;
    const long code = std::strtol(code_line.c_str(), &end, 10);
    if (code_line.size() > 16 || end == code_line.c_str() ||
        std::string(end).find_first_not_of(" \t") != std::string::npos)
      throw InputError(
          file, line, "",
          "expected a DXF group code (an integer), got '" + code_line.substr(0, 40) + "'");
    if (!std::getline(in, value))
      throw InputError(file, line, "", "the drawing ends after a group code: truncated?");
    ++line;
    if (!value.empty() && value.back() == '\r') value.pop_back();
    const bool real = (code >= 10 && code <= 59) || (code >= 110 && code <= 149) ||
                      (code >= 210 && code <= 239) || (code >= 1010 && code <= 1059);
    if (real) {
      const std::string trimmed = value.substr(value.find_first_not_of(" \t") == std::string::npos
                                                   ? value.size()
                                                   : value.find_first_not_of(" \t"));
      const double v = std::strtod(trimmed.c_str(), &end);
      if (end == trimmed.c_str() ||
          std::string(end).find_first_not_of(" \t") != std::string::npos || !std::isfinite(v))
        throw InputError(file, line, printf_string("group %ld", code),
                         "expected a finite number, got '" + value.substr(0, 40) + "'");
    }
    out += code_line;
    out += '\n';
    if (value.size() > kDxflibMaxLine - 24) {
      if (real)
        throw InputError(file, line, printf_string("group %ld", code), "a number that long");
      value.resize(kDxflibMaxLine - 24);
    }
    out += value;
    out += '\n';
    if (code == 0 && value.find("EOF") != std::string::npos) {
      ended = true;
      break;  // what follows the EOF is not the drawing's
    }
  }
  if (!ended)
    throw InputError(file, line, "",
                     "the drawing ends without its EOF marker (0 / EOF): truncated? Export it "
                     "again");
  return out;
}

}  // namespace

std::optional<double> insunits_metres(int code) {
  switch (code) {
    case 1:
      return 0.0254;
    case 2:
      return 0.3048;
    case 4:
      return 0.001;
    case 5:
      return 0.01;
    case 6:
      return 1.0;
    case 14:
      return 0.1;  // decimetres
    default:
      return std::nullopt;
  }
}

std::optional<double> unit_metres(const std::string& name) {
  const std::string n = lower(name);
  if (n == "mm") return 0.001;
  if (n == "cm") return 0.01;
  if (n == "m") return 1.0;
  if (n == "in") return 0.0254;
  if (n == "ft") return 0.3048;
  return std::nullopt;
}

DxfPlan read_dxf_plan(const std::filesystem::path& path, const DxfOptions& options) {
  const std::string file = path.string();
  const std::string text = read_text_file(path);  // size limit, and its errors
  if (text.rfind("AutoCAD Binary DXF", 0) == 0)
    throw InputError(file, 0, "", "a binary DXF: save the drawing as an ASCII DXF");
  if (text.find("SECTION") == std::string::npos)
    throw InputError(file, 0, "", "not a DXF drawing (no SECTION in it)");
  const std::string drawing = checked_dxf_text(text, file);
  Collector c;
  {
    std::istringstream stream(drawing);
    DL_Dxf dxf;
    if (!dxf.in(stream, &c))
      throw InputError(file, 0, "", "dxflib could not read it as a DXF drawing");
    c.finish();
  }
  DxfPlan out;
  out.notes = c.skipped;
  // The unit.
  if (options.metres_per_unit) {
    out.metres_per_unit = *options.metres_per_unit;
  } else {
    const auto from_header = c.insunits ? insunits_metres(*c.insunits) : std::nullopt;
    if (!from_header)
      throw InputError(file, 0, "unit",
                       c.insunits
                           ? printf_string("the drawing's $INSUNITS is %d, not a length "
                                           "ccbuild knows (1 in, 2 ft, 4 mm, 5 cm, 6 m, 14 dm): "
                                           "say the unit (unit: mm, cm, m, in or ft)",
                                           *c.insunits)
                           : "the drawing does not say its unit ($INSUNITS): say it (unit: "
                             "mm, cm, m, in or ft)");
    out.metres_per_unit = *from_header;
  }
  const double scale = out.metres_per_unit;
  // The layers asked for must exist.
  const auto layer_list = [&] {
    std::string list;
    for (const auto& [key, name] : c.layer_names)
      list +=
          (list.empty() ? "" : ", ") + name + printf_string(" (%ld)", c.entities_per_layer[key]);
    return list.empty() ? std::string("none") : list;
  };
  if (options.wall_layers.empty())
    throw InputError(
        file, 0, "wall_layers",
        "say which layers hold the walls; the drawing's layers (entities): " + layer_list());
  std::set<std::string> walls_on, doors_on, windows_on;
  for (const auto& [names, into, field] :
       {std::tuple{&options.wall_layers, &walls_on, "wall_layers"},
        std::tuple{&options.door_layers, &doors_on, "door_layers"},
        std::tuple{&options.window_layers, &windows_on, "window_layers"}})
    for (const std::string& name : *names) {
      if (!c.entities_per_layer.count(lower(name)))
        throw InputError(file, 0, field,
                         "the drawing has no entity on layer '" + name +
                             "'; its layers (entities): " + layer_list());
      into->insert(lower(name));
    }
  // Wall lines, in metres, checked.
  std::vector<DrawnLine> wall_lines;
  for (const DrawnLine& l : c.lines) {
    if (!walls_on.count(lower(l.layer))) continue;
    for (const Vector2d& p : {l.a, l.b}) {
      const Vector2d m = p * scale;
      if (!m.allFinite() || !floors::limits::kCoordinate_m.contains(m.x()) ||
          !floors::limits::kCoordinate_m.contains(m.y()))
        throw InputError(file, 0, "entity " + hex_handle(l.handle),
                         printf_string("a point (%g, %g) on layer %s is not a coordinate ccbuild "
                                       "takes (%s)",
                                       p.x(), p.y(), l.layer.c_str(),
                                       floors::limits::kCoordinate_m.describe("m").c_str()));
    }
    if ((l.b - l.a).norm() * scale <= floors::limits::kMinWallLength_m) {
      out.notes.push_back("entity " + hex_handle(l.handle) + " on layer " + l.layer +
                          ": a line of 1 mm or less; left out");
      continue;
    }
    wall_lines.push_back(l);
  }
  if (wall_lines.size() > 2 * floors::limits::kMaxWalls)
    throw InputError(file, 0, "wall_layers",
                     printf_string("%zu wall lines; ccbuild reads at most %zu", wall_lines.size(),
                                   2 * floors::limits::kMaxWalls));
  std::vector<FoundWall> found;
  if (options.wall_lines == DxfOptions::WallLines::kFaces) {
    found = pair_faces(wall_lines, scale, options.max_thickness_m, out.notes);
    join_ends(found);
  } else {
    for (const DrawnLine& l : wall_lines)
      found.push_back({l.a * scale, l.b * scale, std::nullopt,
                       "entity " + hex_handle(l.handle) + " on layer " + l.layer});
  }
  // Walls of 1 mm or less (where face pairs barely overlap) would vanish from every layer.
  std::vector<FoundWall> kept;
  for (FoundWall& w : found) {
    if ((w.b - w.a).norm() > floors::limits::kMinWallLength_m) {
      kept.push_back(std::move(w));
      continue;
    }
    out.notes.push_back(
        w.source + printf_string(": a wall of %.4f m at (%.3f, %.3f) m, 1 mm or less; left out",
                                 (w.b - w.a).norm(), w.a.x(), w.a.y()));
  }
  found.swap(kept);
  if (options.gap_openings && !found.empty()) {
    std::vector<DrawnLine> glazing;
    for (const DrawnLine& l : c.lines)
      if (windows_on.count(lower(l.layer))) glazing.push_back(l);
    found = join_gaps(std::move(found), glazing, scale, options.max_gap_m);
  }
  if (found.empty()) {
    std::string asked;
    for (const std::string& name : options.wall_layers) asked += (asked.empty() ? "" : ", ") + name;
    throw InputError(
        file, 0, "wall_layers",
        printf_string("no wall found on layer(s) %s among %zu line segments", asked.c_str(),
                      wall_lines.size()) +
            (out.notes.empty() ? std::string() : " (" + out.notes.front() + ")") +
            (options.wall_lines == DxfOptions::WallLines::kFaces
                 ? "; read as face lines: are they centrelines? (wall_lines: centrelines)"
                 : ""));
  }
  // Vertices: ends closer than 0.1 mm are one.
  floors::FloorPlan& plan = out.plan;
  plan.source_file = file;
  std::map<std::pair<long long, long long>, std::int64_t> vertex_at;
  const auto vertex = [&](const Vector2d& p) {
    const long long gx = std::llround(p.x() * 1e4), gy = std::llround(p.y() * 1e4);
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy) {
        const auto it = vertex_at.find({gx + dx, gy + dy});
        if (it != vertex_at.end() && (plan.vertices[it->second - 1].position_m - p).norm() <= 1e-4)
          return it->second;
      }
    const auto id = static_cast<std::int64_t>(plan.vertices.size()) + 1;
    plan.vertices.push_back({id, p, {file, 0, "vertex " + std::to_string(id)}});
    vertex_at[{gx, gy}] = id;
    return id;
  };
  for (const FoundWall& w : found) {
    const std::int64_t s = vertex(w.a), e = vertex(w.b);
    if (s == e) continue;
    const auto id = static_cast<std::int64_t>(plan.walls.size()) + 1;
    plan.walls.push_back({id, s, e, w.thickness_m, {file, 0, w.source}});
    for (const FoundGap& g : w.gaps) {
      floors::Opening o;
      o.id = printf_string("%s%zu", g.window ? "GW" : "GD", plan.openings.size() + 1);
      o.wall_id = id;
      o.offset_m = g.offset_m;
      o.width_m = g.width_m;
      o.sill_m = g.window ? options.window_sill_m : 0.0;
      o.head_m = g.window ? options.window_head_m : options.door_head_m;
      o.source = {file, 0, g.source};
      plan.openings.push_back(o);
    }
  }
  // Openings: each insert's block extent along its x axis, on the wall it lies on.
  // Vertex ids are 1..n in order (made above): a wall's ends without a search.
  const auto at = [&](std::int64_t id) { return plan.vertices[id - 1].position_m; };
  for (const DrawnInsert& in : c.inserts) {
    const bool door = doors_on.count(lower(in.layer)) > 0;
    if (!door && !windows_on.count(lower(in.layer))) continue;
    const std::string what =
        "insert " + hex_handle(in.handle) + " of block " + in.block + " on layer " + in.layer;
    const auto extent = c.block_extent.find(in.block);
    if (extent == c.block_extent.end() || extent->second.second.x() <= extent->second.first.x()) {
      out.notes.push_back(what + ": its block draws nothing to measure its width by; left out");
      continue;
    }
    const auto [lo, hi] = extent->second;
    const double angle = in.angle_deg * M_PI / 180.0;
    const Eigen::Rotation2Dd turn(angle);
    const double mid_y = 0.5 * (lo.y() + hi.y()) * in.sy;
    const Vector2d p0 = (in.at + turn * Vector2d(lo.x() * in.sx, mid_y)) * scale;
    const Vector2d p1 = (in.at + turn * Vector2d(hi.x() * in.sx, mid_y)) * scale;
    if (!p0.allFinite() || !p1.allFinite())
      throw InputError(file, 0, "entity " + hex_handle(in.handle),
                       "an insert whose position, scale or angle is not a finite number");
    const Vector2d centre = 0.5 * (p0 + p1);
    const floors::Wall* on = nullptr;
    double nearest = std::numeric_limits<double>::infinity();
    for (const floors::Wall& w : plan.walls) {
      const Vector2d a = at(w.start_vertex), b = at(w.end_vertex);
      const Vector2d d = (b - a).normalized();
      if (std::abs(cross(d, (p1 - p0).normalized())) > 0.1) continue;  // not along it
      const double s = d.dot(centre - a);
      if (s < 0.0 || s > (b - a).norm()) continue;
      const double off = std::abs(cross(d, centre - a));
      const double within = 0.5 * w.thickness_m.value_or(0.0) + 0.3;
      if (off <= within && off < nearest) {
        nearest = off;
        on = &w;
      }
    }
    if (!on) {
      out.notes.push_back(what + printf_string(": at (%.3f, %.3f) m, on no wall; left out",
                                               centre.x(), centre.y()));
      continue;
    }
    const Vector2d a = at(on->start_vertex), b = at(on->end_vertex);
    const Vector2d d = (b - a).normalized();
    const double s0 = std::clamp(d.dot(p0 - a), 0.0, (b - a).norm());
    const double s1 = std::clamp(d.dot(p1 - a), 0.0, (b - a).norm());
    floors::Opening o;
    o.id = (door ? "D" : "W") + hex_handle(in.handle);
    o.wall_id = on->id;
    o.offset_m = std::min(s0, s1);
    o.width_m = std::abs(s1 - s0);
    o.sill_m = door ? 0.0 : options.window_sill_m;
    o.head_m = door ? options.door_head_m : options.window_head_m;
    o.source = {file, 0, what};
    if (o.width_m <= 1e-3) {
      out.notes.push_back(what + ": crosses its wall rather than lying along it; left out");
      continue;
    }
    plan.openings.push_back(o);
  }
  return out;
}

floors::ImportedPlan read_drawing(const Field& plan, const std::filesystem::path& base,
                                  floors::LengthUnit unit) {
  MapReader map(plan, {"dxf", "wall_layers", "door_layers", "window_layers", "wall_lines", "unit",
                       "max_thickness", "door_head", "window_sill", "window_head", "gap_openings",
                       "max_gap"});
  map.reject_unknown();
  const Field file_field = map.required("dxf");
  const std::string name = file_field.as_string();
  const std::filesystem::path file = (base / name).lexically_normal();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    file_field.fail("drawing '" + name + "' not found (looked for " + file.string() + ")");
  DxfOptions o;
  const auto names = [&](const char* key) {
    std::vector<std::string> out;
    if (auto f = map.optional(key)) {
      if (f->is_sequence()) {
        for (const Field& item : f->items()) out.push_back(item.as_string());
      } else {
        out.push_back(f->as_string());
      }
    }
    return out;
  };
  o.wall_layers = names("wall_layers");
  if (o.wall_layers.empty()) map.required("wall_layers").fail("name at least one layer");
  o.door_layers = names("door_layers");
  o.window_layers = names("window_layers");
  if (auto lines = map.optional("wall_lines")) {
    const std::string how = lines->as_string();
    if (how == "centrelines" || how == "centerlines")
      o.wall_lines = DxfOptions::WallLines::kCentrelines;
    else if (how != "faces")
      lines->fail("expected faces (each wall drawn as its two faces) or centrelines, got '" + how +
                  "'");
  }
  if (auto u = map.optional("unit")) {
    o.metres_per_unit = unit_metres(u->as_string());
    if (!o.metres_per_unit) u->fail("expected mm, cm, m, in or ft, got '" + u->as_string() + "'");
  }
  const std::string unit_name = floors::to_string(unit);
  const double per = floors::meters_per(unit);
  if (auto t = map.optional("max_thickness"))
    o.max_thickness_m = t->as_number_in(floors::limits::kWallThickness_m, unit_name, per);
  if (auto g = map.optional("gap_openings")) o.gap_openings = g->as_bool();
  if (auto g = map.optional("max_gap"))
    o.max_gap_m = g->as_number_in(floors::limits::kOpeningWidth_m, unit_name, per);
  if (auto h = map.optional("door_head"))
    o.door_head_m = h->as_number_in(floors::limits::kOpeningHeight_m, unit_name, per);
  if (auto h = map.optional("window_sill"))
    o.window_sill_m = h->as_number_in(floors::limits::kOpeningHeight_m, unit_name, per);
  if (auto h = map.optional("window_head"))
    o.window_head_m = h->as_number_in(floors::limits::kOpeningHeight_m, unit_name, per);
  DxfPlan read = read_dxf_plan(file, o);
  read.plan.units = unit;  // messages speak the building's unit
  return {std::move(read.plan), std::move(read.notes), file};
}

}  // namespace ccbuild::import
