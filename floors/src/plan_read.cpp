// Readers for the plan encodings: a YAML/JSON document tree, and the table text.

#include <charconv>
#include <cmath>
#include <sstream>

#include "ccbuild/common/document.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/plan.hpp"
#include "plan_internal.hpp"

namespace ccbuild::floors {

LengthUnit read_units(const Field& field) {
  const std::string text = field.as_string();
  const auto unit = parse_length_unit(text);
  if (!unit) field.fail("expected 'm' or 'ft', got '" + text + "'");
  return *unit;
}

SourceRef source_of(const Field& field) {
  return SourceRef{field.file(), field.line(), field.path()};
}

Opening read_opening(const Field& field, LengthUnit unit) {
  MapReader map(field, {"id", "kind", "wall", "offset", "width", "sill", "head"});
  map.reject_unknown();
  const double scale = meters_per(unit);
  Opening opening;
  opening.source = source_of(field);
  if (auto id = map.optional("id")) opening.id = id->as_string();
  bool door = false;
  if (auto kind = map.optional("kind")) {
    const std::string k = kind->as_string();
    if (k != "door" && k != "window") kind->fail("expected 'door' or 'window', got '" + k + "'");
    door = k == "door";
  }
  opening.wall_id = map.required("wall").as_positive_id();
  opening.offset_m = map.required("offset").as_number() * scale;
  opening.width_m = map.required("width").as_number() * scale;
  // A forgotten sill must not turn a window into a door: only doors may leave it out.
  if (auto sill = map.optional("sill")) {
    opening.sill_m = sill->as_number() * scale;
    if (door && opening.sill_m != 0.0) sill->fail("a door has sill 0");
  } else if (!door) {
    map.required("sill");
  }
  opening.head_m = map.required("head").as_number() * scale;
  return opening;
}

FloorPlan read_plan(const Field& field, LengthUnit default_unit) {
  MapReader map(field, {"name", "units", "vertices", "walls", "openings"});
  map.reject_unknown();
  LengthUnit unit = default_unit;
  if (auto u = map.optional("units")) unit = read_units(*u);
  const double scale = meters_per(unit);

  FloorPlan plan;
  plan.source_file = field.file();
  for (const Field& item : map.required("vertices").items()) {
    MapReader v(item, {"id", "x", "y"});
    v.reject_unknown();
    Vertex vertex;
    vertex.source = source_of(item);
    vertex.id = v.required("id").as_positive_id();
    vertex.position_m = {v.required("x").as_number() * scale, v.required("y").as_number() * scale};
    plan.vertices.push_back(vertex);
  }
  for (const Field& item : map.required("walls").items()) {
    MapReader w(item, {"id", "start", "end", "thickness"});
    w.reject_unknown();
    Wall wall;
    wall.source = source_of(item);
    wall.id = w.required("id").as_positive_id();
    wall.start_vertex = w.required("start").as_positive_id();
    wall.end_vertex = w.required("end").as_positive_id();
    if (auto t = w.optional("thickness")) wall.thickness_m = t->as_number() * scale;
    plan.walls.push_back(wall);
  }
  if (auto openings = map.optional("openings")) {
    for (const Field& item : openings->items()) plan.openings.push_back(read_opening(item, unit));
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
  TableReader(const std::string& file, LengthUnit unit) : file_(file), scale_(meters_per(unit)) {}

  [[noreturn]] void fail(int line, const std::string& field, const std::string& message) const {
    throw InputError(file_, line, field, message);
  }

  std::int64_t id(const std::string& word, int line, const std::string& field) const {
    std::int64_t value = 0;
    const auto [ptr, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (ec != std::errc() || ptr != word.data() + word.size() || value <= 0)
      fail(line, field, "expected a positive integer id, got '" + word + "'");
    return value;
  }

  double length(const std::string& word, int line, const std::string& field) const {
    std::string text = word;
    if (!text.empty() && text.front() == '+') text.erase(0, 1);
    double value = 0.0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || ec != std::errc() || ptr != text.data() + text.size())
      fail(line, field, "expected a number, got '" + word + "'");
    if (!std::isfinite(value))
      fail(line, field,
           "expected a finite number, got '" + word + "' (NaN and infinity are not allowed)");
    return value * scale_;
  }

  SourceRef source(int line, const std::string& section) const { return {file_, line, section}; }

 private:
  std::string file_;
  double scale_;
};

}  // namespace

FloorPlan parse_plan_table(const std::string& text, const std::string& file, LengthUnit unit) {
  const TableReader reader(file, unit);
  FloorPlan plan;
  plan.source_file = file;
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
      reader.fail(number, "",
                  "expected a section header 'vertices' before data, got '" + words[0] + "'");
    if (section == "vertices") {
      if (words.size() != 3)
        reader.fail(
            number, "vertices",
            "expected 'id x y' (3 values), got " + std::to_string(words.size()) + " value(s)");
      Vertex v;
      v.source = reader.source(number, "vertices");
      v.id = reader.id(words[0], number, "vertices: id");
      v.position_m = {reader.length(words[1], number, "vertices: x"),
                      reader.length(words[2], number, "vertices: y")};
      plan.vertices.push_back(v);
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
      if (words.size() == 4) w.thickness_m = reader.length(words[3], number, "walls: thickness");
      plan.walls.push_back(w);
    } else {
      if (words.size() != 5)
        reader.fail(number, "openings",
                    "expected 'wall offset width sill head' (5 values), got " +
                        std::to_string(words.size()) + " value(s)");
      Opening o;
      o.source = reader.source(number, "openings");
      o.wall_id = reader.id(words[0], number, "openings: wall");
      o.offset_m = reader.length(words[1], number, "openings: offset");
      o.width_m = reader.length(words[2], number, "openings: width");
      o.sill_m = reader.length(words[3], number, "openings: sill");
      o.head_m = reader.length(words[4], number, "openings: head");
      plan.openings.push_back(o);
    }
  }
  if (!saw_vertices) reader.fail(0, "vertices", "missing the 'vertices' section");
  if (!saw_walls) reader.fail(0, "walls", "missing the 'walls' section");
  return plan;
}

}  // namespace ccbuild::floors
