// Readers for the plan encodings: a YAML/JSON document tree, and the table text.

#include <charconv>
#include <cmath>
#include <sstream>

#include "ccbuild/common/document.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/plan.hpp"
#include "plan_internal.hpp"

namespace ccbuild::floors {

LengthUnit read_units(const Field& field) {
  const std::string text = field.as_string();
  const auto unit = parse_length_unit(text);
  if (!unit) field.fail("expected 'm' or 'ft', got '" + echoed(text) + "'");
  return *unit;
}

double read_length(const Field& field, const Range& range_m, LengthUnit unit) {
  return field.as_number_in(range_m, to_string(unit), meters_per(unit));
}

std::int64_t read_id(const Field& field) {
  const std::int64_t id = field.as_positive_id();
  if (id > limits::kMaxId)
    field.fail("ids are 1 to " + std::to_string(limits::kMaxId) + ", got " + std::to_string(id));
  return id;
}

void check_count(const Field& list, std::size_t count, std::size_t most, const char* what) {
  if (count > most)
    list.fail("holds " + std::to_string(count) + " " + what + "; ccbuild accepts at most " +
              std::to_string(most));
}

SourceRef source_of(const Field& field) {
  return SourceRef{field.file(), field.line(), field.path()};
}

// `top: H` (the wall H high along its length) or `top: [[offset, H], ...]` (a top that
// changes along it: offsets increasing).
std::vector<std::pair<double, double>> read_wall_top(const Field& field, LengthUnit unit) {
  if (!field.is_sequence()) return {{0.0, read_length(field, limits::kWallTop_m, unit)}};
  const auto items = field.items();
  if (items.empty()) field.fail("expected a height, or a list of [offset, height] points");
  check_count(field, items.size(), limits::kMaxWallTopPoints, "points");
  std::vector<std::pair<double, double>> top;
  for (const Field& point : items) {
    if (!point.is_sequence() || point.items().size() != 2)
      point.fail("expected a point [offset along the wall, height above the floor]");
    const auto xy = point.items();
    const double s = read_length(xy[0], limits::kAlongWall_m, unit);
    if (!top.empty() && s <= top.back().first)
      xy[0].fail("the points' offsets must increase along the wall");
    top.emplace_back(s, read_length(xy[1], limits::kWallTop_m, unit));
  }
  return top;
}

Opening read_opening(const Field& field, LengthUnit unit) {
  MapReader map(field, {"id", "kind", "wall", "offset", "width", "sill", "head", "guid"});
  map.reject_unknown();
  Opening opening;
  opening.source = source_of(field);
  if (auto id = map.optional("id")) opening.id = id->as_string();
  bool door = false;
  if (auto kind = map.optional("kind")) {
    const std::string k = kind->as_string();
    if (k != "door" && k != "window")
      kind->fail("expected 'door' or 'window', got '" + echoed(k) + "'");
    door = k == "door";
  }
  opening.wall_id = read_id(map.required("wall"));
  opening.offset_m = read_length(map.required("offset"), limits::kAlongWall_m, unit);
  opening.width_m = read_length(map.required("width"), limits::kOpeningWidth_m, unit);
  // A forgotten sill must not turn a window into a door: only doors may leave it out.
  if (auto sill = map.optional("sill")) {
    opening.sill_m = read_length(*sill, limits::kOpeningHeight_m, unit);
    if (door && opening.sill_m != 0.0) sill->fail("a door has sill 0");
  } else if (!door) {
    map.required("sill");
  }
  opening.head_m = read_length(map.required("head"), limits::kOpeningHeight_m, unit);
  if (auto guid = map.optional("guid")) opening.global_id = guid->as_string();
  return opening;
}

FloorPlan read_plan(const Field& field, LengthUnit default_unit) {
  MapReader map(field, {"name", "units", "vertices", "walls", "openings"});
  map.reject_unknown();
  LengthUnit unit = default_unit;
  if (auto u = map.optional("units")) unit = read_units(*u);

  FloorPlan plan;
  plan.source_file = field.file();
  plan.units = unit;
  const Field vertices = map.required("vertices");
  const auto vertex_items = vertices.items();
  check_count(vertices, vertex_items.size(), limits::kMaxVertices, "vertices");
  for (const Field& item : vertex_items) {
    MapReader v(item, {"id", "x", "y"});
    v.reject_unknown();
    Vertex vertex;
    vertex.source = source_of(item);
    vertex.id = read_id(v.required("id"));
    vertex.position_m = {read_length(v.required("x"), limits::kCoordinate_m, unit),
                         read_length(v.required("y"), limits::kCoordinate_m, unit)};
    plan.vertices.push_back(vertex);
  }
  const Field walls = map.required("walls");
  const auto wall_items = walls.items();
  check_count(walls, wall_items.size(), limits::kMaxWalls, "walls");
  for (const Field& item : wall_items) {
    MapReader w(item, {"id", "start", "end", "thickness", "guid", "model_volume", "top"});
    w.reject_unknown();
    Wall wall;
    wall.source = source_of(item);
    wall.id = read_id(w.required("id"));
    wall.start_vertex = read_id(w.required("start"));
    wall.end_vertex = read_id(w.required("end"));
    if (auto t = w.optional("thickness"))
      wall.thickness_m = read_length(*t, limits::kWallThickness_m, unit);
    if (auto guid = w.optional("guid")) wall.global_id = guid->as_string();
    if (auto v = w.optional("model_volume")) {
      const double per_m = meters_per(unit);
      wall.model_volume_m3 =
          v->as_number_in(limits::kWallVolume_m3, to_string(unit) + "³", per_m * per_m * per_m);
    }
    if (auto top = w.optional("top")) wall.top_m = read_wall_top(*top, unit);
    plan.walls.push_back(wall);
  }
  if (auto openings = map.optional("openings")) {
    const auto items = openings->items();
    check_count(*openings, items.size(), limits::kMaxOpenings, "openings");
    for (const Field& item : items) plan.openings.push_back(read_opening(item, unit));
  }
  return plan;
}

namespace {

std::vector<std::string> split_words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> words;
  std::string word;
  while (in >> word) words.push_back(word);
  return words;
}

class TableReader {
 public:
  TableReader(const std::string& file, LengthUnit unit) : file_(file), unit_(unit) {}

  [[noreturn]] void fail(int line, const std::string& field, const std::string& message) const {
    throw InputError(file_, line, field, message);
  }

  std::int64_t id(const std::string& word, int line, const std::string& field) const {
    std::int64_t value = 0;
    const auto [ptr, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (ec != std::errc() || ptr != word.data() + word.size() || value <= 0)
      fail(line, field, "expected a positive integer id, got '" + echoed(word) + "'");
    if (value > limits::kMaxId)
      fail(line, field,
           "ids are 1 to " + std::to_string(limits::kMaxId) + ", got " + std::to_string(value));
    return value;
  }

  double length(const std::string& word, int line, const std::string& field,
                const Range& range_m) const {
    std::string text = word;
    if (!text.empty() && text.front() == '+') text.erase(0, 1);
    double value = 0.0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || ec != std::errc() || ptr != text.data() + text.size())
      fail(line, field, "expected a number, got '" + echoed(word) + "'");
    if (!std::isfinite(value))
      fail(line, field,
           "expected a finite number, got '" + echoed(word) +
               "' (NaN and infinity are not allowed)");
    const double value_m = value * meters_per(unit_);
    const std::string wrong = range_m.violation(value_m, word + " " + to_string(unit_),
                                                to_string(unit_), meters_per(unit_));
    if (!wrong.empty()) fail(line, field, wrong);
    return value_m;
  }

  SourceRef source(int line, const std::string& section) const { return {file_, line, section}; }

 private:
  std::string file_;
  LengthUnit unit_;
};

}  // namespace

FloorPlan parse_plan_table(const std::string& text, const std::string& file, LengthUnit unit) {
  const TableReader reader(file, unit);
  FloorPlan plan;
  plan.source_file = file;
  plan.units = unit;
  std::istringstream lines(text);
  std::string line;
  std::string section;
  bool saw_vertices = false;
  bool saw_walls = false;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    const auto words = split_words(line);
    if (words.empty()) continue;
    if (words.size() == 1 &&
        (words[0] == "vertices" || words[0] == "walls" || words[0] == "openings")) {
      section = words[0];
      if (section == "walls" && !saw_vertices)
        reader.fail(number, "walls", "the 'walls' section must come after the 'vertices' section");
      saw_vertices |= section == "vertices";
      saw_walls |= section == "walls";
      continue;
    }
    if (section.empty())
      reader.fail(
          number, "",
          "expected a section header 'vertices' before data, got '" + echoed(words[0]) + "'");
    if (section == "vertices") {
      if (words.size() != 3)
        reader.fail(
            number, "vertices",
            "expected 'id x y' (3 values), got " + std::to_string(words.size()) + " value(s)");
      Vertex v;
      v.source = reader.source(number, "vertices");
      v.id = reader.id(words[0], number, "vertices: id");
      v.position_m = {reader.length(words[1], number, "vertices: x", limits::kCoordinate_m),
                      reader.length(words[2], number, "vertices: y", limits::kCoordinate_m)};
      plan.vertices.push_back(v);
      if (plan.vertices.size() > limits::kMaxVertices)
        reader.fail(number, "vertices",
                    "more than " + std::to_string(limits::kMaxVertices) +
                        " vertices; ccbuild accepts at most that many");
    } else if (section == "walls") {
      if (words.size() != 3 && words.size() != 4)
        reader.fail(number, "walls",
                    "expected 'id a b' or 'id a b thickness', got " + std::to_string(words.size()) +
                        " value(s)");
      Wall w;
      w.source = reader.source(number, "walls");
      w.id = reader.id(words[0], number, "walls: id");
      w.start_vertex = reader.id(words[1], number, "walls: a");
      w.end_vertex = reader.id(words[2], number, "walls: b");
      if (words.size() == 4)
        w.thickness_m =
            reader.length(words[3], number, "walls: thickness", limits::kWallThickness_m);
      plan.walls.push_back(w);
      if (plan.walls.size() > limits::kMaxWalls)
        reader.fail(number, "walls",
                    "more than " + std::to_string(limits::kMaxWalls) +
                        " walls; ccbuild accepts at most that many");
    } else {
      if (words.size() != 5)
        reader.fail(number, "openings",
                    "expected 'wall offset width sill head' (5 values), got " +
                        std::to_string(words.size()) + " value(s)");
      Opening o;
      o.source = reader.source(number, "openings");
      o.wall_id = reader.id(words[0], number, "openings: wall");
      o.offset_m = reader.length(words[1], number, "openings: offset", limits::kAlongWall_m);
      o.width_m = reader.length(words[2], number, "openings: width", limits::kOpeningWidth_m);
      o.sill_m = reader.length(words[3], number, "openings: sill", limits::kOpeningHeight_m);
      o.head_m = reader.length(words[4], number, "openings: head", limits::kOpeningHeight_m);
      plan.openings.push_back(o);
      if (plan.openings.size() > limits::kMaxOpenings)
        reader.fail(number, "openings",
                    "more than " + std::to_string(limits::kMaxOpenings) +
                        " openings; ccbuild accepts at most that many");
    }
  }
  if (!saw_vertices) reader.fail(0, "vertices", "missing the 'vertices' section");
  if (!saw_walls) reader.fail(0, "walls", "missing the 'walls' section");
  return plan;
}

}  // namespace ccbuild::floors
