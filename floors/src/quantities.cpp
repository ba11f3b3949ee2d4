// Printed volume per wall against the model's (quantities.hpp).

#include "ccbuild/floors/quantities.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "ccbuild/common/format.hpp"
#include "ccbuild/floors/slice.hpp"

namespace ccbuild::floors {

std::optional<double> FloorQuantities::difference() const {
  if (!model_m3 || !(*model_m3 > 0.0)) return std::nullopt;
  return printed_modelled_m3 / *model_m3 - 1.0;
}

bool FloorQuantities::off() const {
  const auto d = difference();
  return d && std::abs(*d) > kModelVolumeTolerance;
}

FloorQuantities floor_quantities(const Floor& floor, double layer_height_m,
                                 double one_pass_width_m) {
  const std::vector<Layer> layers = slice_floor(floor, layer_height_m);
  std::vector<const Layer*> each;
  for (const Layer& layer : layers) each.push_back(&layer);
  return floor_quantities(floor, each, one_pass_width_m);
}

FloorQuantities floor_quantities(const Floor& floor, const std::vector<const Layer*>& layers,
                                 double one_pass_width_m) {
  std::map<std::int64_t, double> printed_m3;  // by wall id
  // Walls by id, looked up once per piece of every layer (FloorPlan::find_wall searches).
  std::map<std::int64_t, const Wall*> wall_of;
  for (const Wall& w : floor.plan.walls) wall_of.emplace(w.id, &w);
  for (const Layer* each : layers) {
    const Layer& layer = *each;
    const double thick_m = layer.z_top_m - layer.z_bottom_m;
    for (const LayerSegment& s : layer.segments) {
      double width_m = s.width_m > 0.0 ? s.width_m : one_pass_width_m;
      if (!(width_m > 0.0))
        if (const auto w = wall_of.find(s.wall_id); w != wall_of.end() && w->second->thickness_m)
          width_m = *w->second->thickness_m;
      printed_m3[s.wall_id] += s.length_m * width_m * thick_m;
    }
  }
  FloorQuantities q;
  std::map<std::string, std::size_t> element_of;  // GlobalId -> index in q.elements
  for (const Wall& w : floor.plan.walls) {
    const double wall_m3 = printed_m3.count(w.id) ? printed_m3.at(w.id) : 0.0;
    q.printed_m3 += wall_m3;
    if (w.model_volume_m3) {
      q.model_m3 = q.model_m3.value_or(0.0) + *w.model_volume_m3;
      q.printed_modelled_m3 += wall_m3;
      ++q.walls_modelled;
    } else {
      ++q.walls_unmodelled;
    }
    std::size_t k = q.elements.size();
    if (!w.global_id.empty()) {
      const auto [it, added] = element_of.emplace(w.global_id, k);
      k = it->second;
      if (added) q.elements.push_back({w.global_id, {}, 0.0, std::nullopt});
    } else {
      q.elements.push_back({"", {}, 0.0, std::nullopt});
    }
    ElementVolume& e = q.elements[k];
    e.walls.push_back(w.id);
    e.printed_m3 += wall_m3;
    if (w.model_volume_m3) e.model_m3 = e.model_m3.value_or(0.0) + *w.model_volume_m3;
  }
  return q;
}

std::string quantities_text(const std::string& name, const FloorQuantities& q) {
  std::string out =
      printf_string("floor '%s': prints %.2f m³ of walls", name.c_str(), q.printed_m3);
  const auto d = q.difference();
  if (!d) return out + " (the model states no volume of its walls)";
  out += printf_string(
      "; the model's NetVolume of the %d wall%s that state%s one is %.2f m³, "
      "printed %.2f m³ (%+.1f%%)",
      q.walls_modelled, q.walls_modelled == 1 ? "" : "s", q.walls_modelled == 1 ? "s" : "",
      *q.model_m3, q.printed_modelled_m3,
      std::abs(*d) < 0.0005 ? 0.0 : 100.0 * *d);  // +0.0% whichever side of 0 the sums fell
  if (q.walls_unmodelled > 0)
    out += printf_string("; %d wall%s state%s none", q.walls_unmodelled,
                         q.walls_unmodelled == 1 ? "" : "s", q.walls_unmodelled == 1 ? "s" : "");
  if (!q.off()) return out;
  out += printf_string(" — OFF by more than %.0f%%: ", 100.0 * kModelVolumeTolerance);
  std::vector<const ElementVolume*> by_gap;
  for (const auto& e : q.elements)
    if (e.model_m3) by_gap.push_back(&e);
  std::stable_sort(by_gap.begin(), by_gap.end(), [](const auto* a, const auto* b) {
    return std::abs(a->printed_m3 - *a->model_m3) > std::abs(b->printed_m3 - *b->model_m3);
  });
  for (std::size_t k = 0; k < by_gap.size() && k < 3; ++k) {
    const ElementVolume& e = *by_gap[k];
    out += printf_string("%s%s (wall%s", k ? "; " : "",
                         e.global_id.empty() ? "a wall" : e.global_id.c_str(),
                         e.walls.size() == 1 ? "" : "s");
    for (std::size_t i = 0; i < e.walls.size() && i < 4; ++i)
      out += (i ? ", " : " ") + std::to_string(e.walls[i]);
    if (e.walls.size() > 4) out += ", ...";
    out += printf_string(") prints %.2f m³, the model says %.2f m³", e.printed_m3, *e.model_m3);
  }
  return out;
}

}  // namespace ccbuild::floors
