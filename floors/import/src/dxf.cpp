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
#include <optional>
#include <set>
#include <sstream>
#include <tuple>
#include <unordered_map>

#include "ccbuild/common/document.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/limits.hpp"
#include "dxf_internal.hpp"
#include "segment_index.hpp"

namespace ccbuild::import {
namespace {

using detail::cross;
using detail::DrawnLine;
using detail::FoundGap;
using detail::FoundWall;
using detail::hex_handle;
using Eigen::Vector2d;

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// An ATTRIB of an insert: its value as drawn and its own handle.
struct DrawnAttribute {
  std::string value;
  int handle = -1;
};

struct DrawnInsert {
  std::string block, layer;
  Vector2d at;
  double sx = 1.0, sy = 1.0, angle_deg = 0.0;
  int handle = -1;
  std::map<std::string, DrawnAttribute> attributes{};  ///< by upper-case tag
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
  detail::NoteLog notes;  ///< curved segments (bulges) left out
  std::optional<int> insunits;

  void setVariableInt(const std::string& key, int value, int) override {
    if (key == "$INSUNITS") insunits = value;
  }
  void addBlock(const DL_BlockData& data) override {
    end_polyline();
    attributes_open_ = false;
    block_ = data.name;
  }
  void endBlock() override {
    end_polyline();
    block_.reset();
  }
  void addLine(const DL_LineData& d) override {
    end_polyline();
    attributes_open_ = false;
    segment({d.x1, d.y1}, {d.x2, d.y2});
  }
  void addPolyline(const DL_PolylineData& d) override {
    end_polyline();
    attributes_open_ = false;
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
    attributes_open_ = false;
    if (block_) return;  // nested blocks: not read
    count();
    inserts.push_back({d.name,
                       attributes.getLayer(),
                       {d.ipx, d.ipy},
                       d.sx,
                       d.sy,
                       d.angle,
                       attributes.getHandle()});
    attributes_open_ = true;  // its ATTRIBs follow, up to a SEQEND
  }
  // An ATTRIB belongs to the INSERT just before it (group 66 = 1, ended by a SEQEND).
  void addAttribute(const DL_AttributeData& d) override {
    if (block_ || !attributes_open_ || inserts.empty()) return;
    std::string tag = d.tag;
    for (char& ch : tag) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    inserts.back().attributes[tag] = {d.text, attributes.getHandle()};
  }
  void endEntity() override {}
  // A POLYLINE's VERTEX entities end at its SEQEND; an LWPOLYLINE's with the next entity
  // (dxflib calls endSection after every entity, so that cannot end one).
  void endSequence() override {
    end_polyline();
    attributes_open_ = false;
  }
  void finish() { end_polyline(); }

 private:
  struct Polyline {
    std::vector<Vector2d> points;
    std::vector<double> bulges;
    bool closed = false;
    int handle = -1;
    std::string layer;
  };
  bool attributes_open_ = false;  ///< the last insert's ATTRIBs may follow
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
      notes.add("curved segments not read",
                "entity " + hex_handle(handle) + " on layer " + layer +
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

/// The longest line dxflib reads (DL_DXF_MAXLINE); on a longer one it loops forever.
constexpr std::size_t kDxflibMaxLine = 1024;

/// What dxflib does not check: every real-valued group (codes 10-59, 110-149, 210-239,
/// 1010-1059) a finite number (dxflib reads "nan" or "1e999x" as 0 or garbage), and the
/// drawing whole, up to its EOF (dxflib reads a cut-off file as far as it goes). Returns
/// the text to give dxflib: up to the EOF, every value longer than dxflib reads (only
/// text, which ccbuild does not use, is that long) cut short. `handle_lines` gets the line of
/// each entity's handle (group 5, upper-case hex as hex_handle writes it), the first one's
/// when a handle repeats, so that errors about an entity say where it is.
std::string checked_dxf_text(const std::string& text, const std::string& file,
                             std::unordered_map<std::string, int>& handle_lines) {
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
          "expected a DXF group code (an integer), got '" + echoed(code_line.substr(0, 40)) + "'");
    if (!std::getline(in, value))
      throw InputError(file, line, "", "the drawing ends after a group code: truncated?");
    ++line;
    if (!value.empty() && value.back() == '\r') value.pop_back();
    if (code == 5) {
      std::string hex = value.substr(0, 16);
      hex.erase(
          std::remove_if(hex.begin(), hex.end(),
                         [](char ch) { return std::isspace(static_cast<unsigned char>(ch)); }),
          hex.end());
      for (char& ch : hex) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
      hex.erase(0, std::min(hex.find_first_not_of('0'), hex.size() - (hex.empty() ? 0 : 1)));
      handle_lines.emplace(hex, line);
    }
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
                         "expected a finite number, got '" + echoed(value.substr(0, 40)) + "'");
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

/// Face lines without the copies of one drawn again (its ends within 0.1 mm of the first's,
/// either way round): each copy is said and left out. By the lines' ends snapped to a
/// 0.1 mm grid, in n log n, however many copies there are.
std::vector<DrawnLine> without_duplicates(std::vector<DrawnLine> lines, double scale,
                                          detail::NoteLog& notes) {
  std::map<std::pair<long long, long long>, std::vector<std::pair<Vector2d, std::size_t>>> cells;
  std::size_t points = 0;
  // The first point (of the ends seen so far) within 0.1 mm of p, else p as a new one.
  const auto point = [&](const Vector2d& p) {
    const long long gx = std::llround(p.x() * 1e4), gy = std::llround(p.y() * 1e4);
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy) {
        const auto it = cells.find({gx + dx, gy + dy});
        if (it == cells.end()) continue;
        for (const auto& [q, id] : it->second)
          if ((q - p).norm() <= 1e-4) return id;
      }
    cells[{gx, gy}].emplace_back(p, points);
    return points++;
  };
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> drawn;  // ends -> first line
  std::vector<DrawnLine> out;
  for (DrawnLine& l : lines) {
    const std::size_t s = point(l.a * scale), e = point(l.b * scale);
    const auto [it, fresh] = drawn.emplace(std::minmax(s, e), out.size());
    if (fresh) {
      out.push_back(std::move(l));
      continue;
    }
    const DrawnLine& first = out[it->second];
    notes.add("face lines drawn twice, read once",
              "entity " + hex_handle(l.handle) + " on layer " + l.layer +
                  printf_string(" from (%g, %g) to (%g, %g)", l.a.x(), l.a.y(), l.b.x(), l.b.y()) +
                  " is drawn over entity " + hex_handle(first.handle) + " on layer " + first.layer +
                  ", end to end: read once");
  }
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

/// An insert's SILL or HEAD attribute (tag in any case) in metres, when it has one: a number
/// in the drawing's unit (`scale` metres each), or with a unit (mm, cm, m: "900mm"), from 0
/// to 10 m. Anything else is an InputError naming the insert's handle and the tag.
std::optional<double> height_attribute(const DrawnInsert& in, const std::string& tag, double scale,
                                       const std::string& file) {
  const auto it = in.attributes.find(tag);
  if (it == in.attributes.end()) return std::nullopt;
  const std::string& value = it->second.value;
  const auto refuse = [&](const std::string& why) {
    throw InputError(file, 0, "entity " + hex_handle(in.handle),
                     "insert " + hex_handle(in.handle) + " of block " + in.block +
                         ": its attribute " + tag + " (ATTRIB " + hex_handle(it->second.handle) +
                         ") is '" + value + "', " + why);
  };
  const char* begin = value.c_str();
  char* end = nullptr;
  const double number = std::strtod(begin, &end);
  if (end == begin) refuse("not a number (a height: 900, 900mm, 0.9m)");
  std::string unit = lower(std::string(end));
  unit.erase(std::remove_if(unit.begin(), unit.end(),
                            [](char ch) { return std::isspace(static_cast<unsigned char>(ch)); }),
             unit.end());
  double metres_each = scale;
  if (unit == "mm")
    metres_each = 0.001;
  else if (unit == "cm")
    metres_each = 0.01;
  else if (unit == "m")
    metres_each = 1.0;
  else if (!unit.empty())
    refuse("not a number with a unit ccbuild knows (mm, cm, m; none: the drawing's unit)");
  const double metres = number * metres_each;
  if (!std::isfinite(metres)) refuse("not a finite number");
  if (metres < 0.0 || metres > 10.0)
    refuse(printf_string("%.3f m: not a sill or head height above the floor (0 to 10 m; %s)",
                         metres, unit.empty() ? "in the drawing's unit" : "in the unit given"));
  return metres;
}

DxfPlan read_dxf_plan(const std::filesystem::path& path, const DxfOptions& options) {
  const std::string file = path.string();
  const std::string text = read_text_file(path);  // size limit, and its errors
  if (text.rfind("AutoCAD Binary DXF", 0) == 0)
    throw InputError(file, 0, "", "a binary DXF: save the drawing as an ASCII DXF");
  if (text.find("SECTION") == std::string::npos)
    throw InputError(file, 0, "", "not a DXF drawing (no SECTION in it)");
  std::unordered_map<std::string, int> handle_lines;
  const std::string drawing = checked_dxf_text(text, file, handle_lines);
  const auto line_of = [&](int handle) {
    const auto it = handle_lines.find(hex_handle(handle));
    return it == handle_lines.end() ? 0 : it->second;
  };
  Collector c;
  {
    std::istringstream stream(drawing);
    DL_Dxf dxf;
    if (!dxf.in(stream, &c))
      throw InputError(file, 0, "", "dxflib could not read it as a DXF drawing");
    c.finish();
  }
  DxfPlan out;
  detail::NoteLog& notes = c.notes;
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
  std::map<std::string, DxfOptions::Heights> layer_heights;  // by lower-case layer
  for (const auto& [name, h] : options.layer_heights) {
    if (!doors_on.count(lower(name)) && !windows_on.count(lower(name)))
      throw InputError(file, 0, "layer_heights",
                       "layer '" + name +
                           "' is not among the door or window layers; sill and head are given "
                           "for the layers whose blocks are doors or windows");
    layer_heights[lower(name)] = h;
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
      notes.left_out("lines of 1 mm or less left out", "entity " + hex_handle(l.handle) +
                                                           " on layer " + l.layer +
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
    // A face drawn twice is one face: each of its copies would pair with every copy of the
    // face opposite (a centreline drawn twice stays two walls, which validation refuses).
    const std::vector<DrawnLine> faces = without_duplicates(wall_lines, scale, notes);
    try {
      found = pair_faces(faces, scale, options.max_thickness_m, notes);
    } catch (const detail::CrowdedLines& crowd) {
      // Where the face lines crowd beyond any plan: an input error naming a line there.
      const DrawnLine& near = faces[crowd.line];
      throw InputError(
          file, line_of(near.handle), "entity " + hex_handle(near.handle),
          printf_string("more than %zu pairs of face lines per line lie within %.4f m of each "
                        "other, around this entity's line from (%g, %g) to (%g, %g) on layer "
                        "%s: a floor plan's walls are drawn once each; is the linework drawn "
                        "over and over (or hatched on a wall layer)?",
                        detail::kMaxNearPairsPerLine, crowd.within_m, near.a.x(), near.a.y(),
                        near.b.x(), near.b.y(), near.layer.c_str()));
    }
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
    notes.left_out("walls of 1 mm or less left out",
                   w.source + printf_string(": a wall of %.4f m at (%.3f, %.3f) m, 1 mm or less; "
                                            "left out",
                                            (w.b - w.a).norm(), w.a.x(), w.a.y()));
  }
  found.swap(kept);
  // Door and window blocks, where they are drawn: in a gap of the wall lines (as drafters
  // draw them, the lines broken at the opening) the block is that gap's opening; on a wall
  // drawn through, an opening of the block's width.
  struct Mark {
    const DrawnInsert* insert = nullptr;
    bool door = false;
    std::string what;
  };
  std::vector<Mark> mark_of;
  std::vector<detail::OpeningMark> marks;
  for (const DrawnInsert& in : c.inserts) {
    const bool door = doors_on.count(lower(in.layer)) > 0;
    if (!door && !windows_on.count(lower(in.layer))) continue;
    const std::string what =
        "insert " + hex_handle(in.handle) + " of block " + in.block + " on layer " + in.layer;
    const auto extent = c.block_extent.find(in.block);
    if (extent == c.block_extent.end() || extent->second.second.x() <= extent->second.first.x()) {
      notes.left_out("inserts whose block draws nothing left out",
                     what + ": its block draws nothing to measure its width by; left out");
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
    mark_of.push_back({&in, door, what});
    marks.push_back({p0, p1, !door});
  }
  if ((options.gap_openings || !marks.empty()) && !found.empty()) {
    std::vector<DrawnLine> glazing;
    for (const DrawnLine& l : c.lines)
      if (windows_on.count(lower(l.layer))) glazing.push_back(l);
    found =
        join_gaps(std::move(found), glazing, marks, options.gap_openings, scale, options.max_gap_m);
  }
  // A door's or window's sill and head: the insert's SILL and HEAD attributes, else its
  // layer's (layer_heights), else the defaults for its kind.
  const auto heights = [&](const Mark& m, floors::Opening& o) {
    o.sill_m = m.door ? 0.0 : options.window_sill_m;
    o.head_m = m.door ? options.door_head_m : options.window_head_m;
    std::string sill_from = m.door ? "a door's, on the floor" : "the windows' default",
                head_from = m.door ? "the doors' default" : "the windows' default";
    if (const auto layer = layer_heights.find(lower(m.insert->layer));
        layer != layer_heights.end()) {
      if (layer->second.sill_m) {
        o.sill_m = *layer->second.sill_m;
        sill_from = "layer " + m.insert->layer + "'s";
      }
      if (layer->second.head_m) {
        o.head_m = *layer->second.head_m;
        head_from = "layer " + m.insert->layer + "'s";
      }
    }
    if (const auto sill = height_attribute(*m.insert, "SILL", scale, file)) {
      o.sill_m = *sill;
      sill_from = "attribute SILL";
    }
    if (const auto head = height_attribute(*m.insert, "HEAD", scale, file)) {
      o.head_m = *head;
      head_from = "attribute HEAD";
    }
    if (!(o.sill_m < o.head_m))
      throw InputError(
          file, 0, "entity " + hex_handle(m.insert->handle),
          printf_string("%s: its sill (%.3f m, %s) is not below its head (%.3f m, %s)",
                        m.what.c_str(), o.sill_m, sill_from.c_str(), o.head_m, head_from.c_str()));
  };
  std::vector<char> in_a_gap(marks.size(), 0);
  if (found.empty()) {
    std::string asked;
    for (const std::string& name : options.wall_layers) asked += (asked.empty() ? "" : ", ") + name;
    throw InputError(
        file, 0, "wall_layers",
        printf_string("no wall found on layer(s) %s among %zu line segments", asked.c_str(),
                      wall_lines.size()) +
            (notes.empty() ? std::string() : " (" + notes.first() + ")") +
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
      o.wall_id = id;
      o.offset_m = g.offset_m;
      o.width_m = g.width_m;
      if (g.mark) {  // the block in the gap: its kind, its heights, the gap's width
        const Mark& m = mark_of[*g.mark];
        in_a_gap[*g.mark] = 1;
        o.id = (m.door ? "D" : "W") + hex_handle(m.insert->handle);
        heights(m, o);
        o.source = {file, 0, m.what + ", in " + g.source};
      } else {
        o.id = printf_string("%s%zu", g.window ? "GW" : "GD", plan.openings.size() + 1);
        o.sill_m = g.window ? options.window_sill_m : 0.0;
        o.head_m = g.window ? options.window_head_m : options.door_head_m;
        o.source = {file, 0, g.source};
      }
      plan.openings.push_back(o);
    }
  }
  // Openings: each insert's block extent along its x axis, on the wall it lies on.
  // Vertex ids are 1..n in order (made above): a wall's ends without a search.
  const auto at = [&](std::int64_t id) { return plan.vertices[id - 1].position_m; };
  // An opening lies on a wall when its middle is within half the wall's thickness and
  // 0.3 m of it: the walls near the middle are the ones to look at.
  double thickest_m = 0.0;
  std::vector<detail::SegmentIndex::Segment> wall_segments;
  for (const floors::Wall& w : plan.walls) {
    thickest_m = std::max(thickest_m, w.thickness_m.value_or(0.0));
    wall_segments.emplace_back(at(w.start_vertex), at(w.end_vertex));
  }
  const double on_wall_m = 0.5 * thickest_m + 0.3 + 1e-9;
  const detail::SegmentIndex wall_index(wall_segments, on_wall_m);
  for (std::size_t k = 0; k < marks.size(); ++k) {
    if (in_a_gap[k]) continue;  // the gap's opening already
    const DrawnInsert& in = *mark_of[k].insert;
    const bool door = mark_of[k].door;
    const std::string& what = mark_of[k].what;
    const Vector2d p0 = marks[k].a, p1 = marks[k].b;
    const Vector2d centre = 0.5 * (p0 + p1);
    const floors::Wall* on = nullptr;
    double nearest = std::numeric_limits<double>::infinity();
    for (const std::size_t k : wall_index.near_point(centre, on_wall_m)) {  // in wall order
      const floors::Wall& w = plan.walls[k];
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
      notes.left_out("inserts on no wall left out",
                     what + printf_string(": at (%.3f, %.3f) m, on no wall; left out", centre.x(),
                                          centre.y()));
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
    heights(mark_of[k], o);
    o.source = {file, 0, what};
    if (o.width_m <= 1e-3) {
      notes.left_out("inserts across their wall left out",
                     what + ": crosses its wall rather than lying along it; left out");
      continue;
    }
    if (plan.openings.size() >= floors::limits::kMaxOpenings)
      throw InputError(file, line_of(in.handle), "entity " + hex_handle(in.handle),
                       printf_string("%s: more than %zu openings; ccbuild takes at most that many "
                                     "on a floor",
                                     what.c_str(), floors::limits::kMaxOpenings));
    plan.openings.push_back(o);
  }
  out.notes = notes.lines();
  return out;
}

floors::ImportedPlan read_drawing(const Field& plan, const std::filesystem::path& base,
                                  floors::LengthUnit unit) {
  MapReader map(plan, {"dxf", "wall_layers", "door_layers", "window_layers", "wall_lines", "unit",
                       "max_thickness", "door_head", "window_sill", "window_head", "gap_openings",
                       "max_gap", "layer_heights"});
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
      lines->fail("expected faces (each wall drawn as its two faces) or centrelines, got '" +
                  echoed(how) + "'");
  }
  if (auto u = map.optional("unit")) {
    o.metres_per_unit = unit_metres(u->as_string());
    if (!o.metres_per_unit)
      u->fail("expected mm, cm, m, in or ft, got '" + echoed(u->as_string()) + "'");
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
  if (auto heights = map.optional("layer_heights")) {
    if (!heights->is_sequence())
      heights->fail(
          "expected a list of {layer: NAME, sill: S, head: H} (sill or head may be "
          "left out)");
    for (const Field& item : heights->items()) {
      MapReader h(item, {"layer", "sill", "head"});
      h.reject_unknown();
      DxfOptions::Heights given;
      if (auto f = h.optional("sill"))
        given.sill_m = f->as_number_in(floors::limits::kOpeningHeight_m, unit_name, per);
      if (auto f = h.optional("head"))
        given.head_m = f->as_number_in(floors::limits::kOpeningHeight_m, unit_name, per);
      if (!given.sill_m && !given.head_m) item.fail("give the layer's sill, its head or both");
      const Field layer = h.required("layer");
      if (!o.layer_heights.emplace(layer.as_string(), given).second)
        layer.fail("layer '" + echoed(layer.as_string()) + "' is given twice");
    }
  }
  DxfPlan read = read_dxf_plan(file, o);
  read.plan.units = unit;  // messages speak the building's unit
  return {std::move(read.plan), std::move(read.notes), file};
}

}  // namespace ccbuild::import
