#include "ccbuild/floors/plan.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "ccbuild/common/document.hpp"
#include "ccbuild/common/input_error.hpp"

namespace ccbuild::floors {

const Vertex* FloorPlan::find_vertex(std::int64_t id) const {
  for (const auto& v : vertices)
    if (v.id == id) return &v;
  return nullptr;
}

const Wall* FloorPlan::find_wall(std::int64_t id) const {
  for (const auto& w : walls)
    if (w.id == id) return &w;
  return nullptr;
}

Eigen::Vector2d FloorPlan::wall_start_m(const Wall& wall) const {
  const Vertex* v = find_vertex(wall.start_vertex);
  CCBUILD_CHECK(v != nullptr, "wall start vertex exists (plan not validated?)");
  return v->position_m;
}

Eigen::Vector2d FloorPlan::wall_end_m(const Wall& wall) const {
  const Vertex* v = find_vertex(wall.end_vertex);
  CCBUILD_CHECK(v != nullptr, "wall end vertex exists (plan not validated?)");
  return v->position_m;
}

double FloorPlan::wall_length_m(const Wall& wall) const {
  return (wall_end_m(wall) - wall_start_m(wall)).norm();
}

std::string to_string(LintelSpec::Type type) {
  return type == LintelSpec::Type::kPrecast ? "precast" : "formwork";
}

double top_at(const std::vector<std::pair<double, double>>& top, double s_m) {
  if (s_m <= top.front().first) return top.front().second;
  if (s_m >= top.back().first) return top.back().second;
  const auto next = std::upper_bound(top.begin(), top.end(), s_m,
                                     [](double v, const auto& p) { return v < p.first; });
  const auto& [s1, t1] = *next;
  const auto& [s0, t0] = *std::prev(next);
  return s1 > s0 ? t0 + (t1 - t0) * (s_m - s0) / (s1 - s0) : t1;
}

std::vector<std::pair<double, double>> wall_gaps_above(const Wall& wall, double length_m,
                                                       double mid_m) {
  std::vector<std::pair<double, double>> gaps;
  const auto& top = wall.top_m;
  if (top.empty()) return gaps;
  // Between consecutive breakpoints the top is linear: the part at or below mid_m is one
  // end of the stretch, up to where the top crosses mid_m.
  std::vector<double> at = {0.0};
  for (const auto& [s, t] : top)
    if (s > 0.0 && s < length_m) at.push_back(s);
  at.push_back(length_m);
  const auto add = [&](double from, double to) {
    if (to - from <= 1e-12) return;
    if (!gaps.empty() && from <= gaps.back().second + 1e-12)
      gaps.back().second = std::max(gaps.back().second, to);
    else
      gaps.emplace_back(from, to);
  };
  for (std::size_t k = 0; k + 1 < at.size(); ++k) {
    const double u = at[k], v = at[k + 1];
    const double tu = top_at(top, u), tv = top_at(top, v);
    const bool low_u = tu <= mid_m, low_v = tv <= mid_m;
    if (low_u && low_v) {
      add(u, v);
    } else if (low_u || low_v) {
      const double c = u + (mid_m - tu) / (tv - tu) * (v - u);
      low_u ? add(u, c) : add(c, v);
    }
  }
  return gaps;
}

OpeningState opening_state(const Opening& opening, const LintelSpec& lintel, double mid_m) {
  if (mid_m >= opening.sill_m && mid_m < opening.head_m) return OpeningState::kOpen;
  if (lintel.type == LintelSpec::Type::kPrecast && mid_m >= opening.head_m &&
      mid_m < opening.head_m + lintel.height_m)
    return OpeningState::kLintel;
  return OpeningState::kWall;
}

std::pair<double, double> opening_gap_m(const Opening& opening, const LintelSpec& lintel,
                                        OpeningState state, double wall_length_m) {
  const double bearing_m = state == OpeningState::kLintel ? lintel.bearing_m : 0.0;
  return {std::max(0.0, opening.offset_m - bearing_m),
          std::min(wall_length_m, opening.offset_m + opening.width_m + bearing_m)};
}

namespace {
bool near(double a, double b, double tolerance) {
  return std::abs(a - b) <= tolerance;
}
}  // namespace

bool same_model(const FloorPlan& a, const FloorPlan& b, double tolerance_m) {
  if (a.vertices.size() != b.vertices.size() || a.walls.size() != b.walls.size() ||
      a.openings.size() != b.openings.size())
    return false;
  for (std::size_t i = 0; i < a.vertices.size(); ++i) {
    const auto& u = a.vertices[i];
    const auto& v = b.vertices[i];
    if (u.id != v.id || !near(u.position_m.x(), v.position_m.x(), tolerance_m) ||
        !near(u.position_m.y(), v.position_m.y(), tolerance_m))
      return false;
  }
  for (std::size_t i = 0; i < a.walls.size(); ++i) {
    const auto& u = a.walls[i];
    const auto& v = b.walls[i];
    if (u.id != v.id || u.start_vertex != v.start_vertex || u.end_vertex != v.end_vertex ||
        u.thickness_m.has_value() != v.thickness_m.has_value() ||
        (u.thickness_m && !near(*u.thickness_m, *v.thickness_m, tolerance_m)) ||
        u.global_id != v.global_id || u.top_m.size() != v.top_m.size() ||
        !std::equal(u.top_m.begin(), u.top_m.end(), v.top_m.begin(),
                    [&](const auto& p, const auto& q) {
                      return near(p.first, q.first, tolerance_m) &&
                             near(p.second, q.second, tolerance_m);
                    }) ||
        u.model_volume_m3.has_value() != v.model_volume_m3.has_value() ||
        (u.model_volume_m3 && !near(*u.model_volume_m3, *v.model_volume_m3, 1e-9)))
      return false;
  }
  for (std::size_t i = 0; i < a.openings.size(); ++i) {
    const auto& u = a.openings[i];
    const auto& v = b.openings[i];
    if (u.id != v.id || u.wall_id != v.wall_id || !near(u.offset_m, v.offset_m, tolerance_m) ||
        !near(u.width_m, v.width_m, tolerance_m) || !near(u.sill_m, v.sill_m, tolerance_m) ||
        !near(u.head_m, v.head_m, tolerance_m) || u.global_id != v.global_id)
      return false;
  }
  return true;
}

PlanFormat detect_plan_format(const std::filesystem::path& path, const std::string& text) {
  const std::string ext = path.extension().string();
  if (ext == ".json") return PlanFormat::kJson;
  if (ext == ".yaml" || ext == ".yml") return PlanFormat::kYaml;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    const auto begin = line.find_first_not_of(" \t\r");
    if (begin == std::string::npos) continue;
    const auto end = line.find_last_not_of(" \t\r");
    const std::string first = line.substr(begin, end - begin + 1);
    const bool table = first == "vertices" || first == "walls" || first == "openings";
    return table ? PlanFormat::kTable : PlanFormat::kYaml;
  }
  return PlanFormat::kTable;  // empty: the table reader says what is missing
}

FloorPlan plan_from_text(const std::string& text, const std::filesystem::path& path,
                         LengthUnit default_unit, PlanFormat format) {
  if (format == PlanFormat::kAuto) format = detect_plan_format(path, text);
  FloorPlan plan;
  switch (format) {
    case PlanFormat::kTable:
      plan = parse_plan_table(text, path.string(), default_unit);
      break;
    case PlanFormat::kJson:
      plan = read_plan(Field::root(parse_json(text, path.string())), default_unit);
      break;
    case PlanFormat::kYaml:
    case PlanFormat::kAuto:
      plan = read_plan(Field::root(parse_yaml(text, path.string())), default_unit);
      break;
  }
  plan.source_file = path.string();
  return plan;
}

FloorPlan load_plan(const std::filesystem::path& path, LengthUnit default_unit, PlanFormat format) {
  FloorPlan plan = plan_from_text(read_text_file(path), path, default_unit, format);
  validate_plan(plan);
  return plan;
}

}  // namespace ccbuild::floors
