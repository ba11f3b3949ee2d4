#include <algorithm>
#include <cmath>
#include <map>

#include "ccbuild/common/format.hpp"
#include "ccbuild/schedule/margins.hpp"

namespace ccbuild::schedule {

namespace {

/// "floor 0 layers 3-7, floor 1 layers 2-9": runs of the layers in building order.
std::string layers_text(const std::vector<const ScheduledLayer*>& layers) {
  std::string out;
  for (std::size_t k = 0; k < layers.size();) {
    std::size_t end = k;
    while (end + 1 < layers.size() && layers[end + 1]->floor == layers[k]->floor &&
           layers[end + 1]->layer == layers[end]->layer + 1)
      ++end;
    out += (out.empty() ? "" : ", ") +
           (end == k ? printf_string("floor %d layer %d", layers[k]->floor, layers[k]->layer)
                     : printf_string("floor %d layers %d-%d", layers[k]->floor, layers[k]->layer,
                                     layers[end]->layer));
    k = end + 1;
  }
  return out;
}

}  // namespace

std::vector<std::string> margin_warnings(const Schedule& schedule,
                                         const machine::MachineModel& machine,
                                         const floors::MaterialProfile& material,
                                         const MarginThresholds& t, floors::LengthUnit unit) {
  const double per = floors::meters_per(unit);
  const std::string unit_name = floors::to_string(unit);
  auto fine = [unit](double m) { return floors::fine_length_text(m, unit); };
  std::vector<std::string> out;
  // Gantries: per plan with several nozzles, its nearest approach less the gantry width.
  std::map<std::string, std::vector<const ScheduledLayer*>> users;
  for (const ScheduledLayer& l : schedule.layers) users[l.plan].push_back(&l);
  for (const auto& [key, plan] : schedule.plans) {
    if (plan.nozzles < 2 || !users.count(key)) continue;
    const double clearance_m = plan.min_gap_m - machine.gantry_width_m;
    if (clearance_m >= t.gantry_clearance_m) continue;
    out.push_back(
        printf_string("margin: the %d gantries of plan %s come within %s of each other (%s between "
                      "centres, %s wide), on %s; warned under %s",
                      plan.nozzles, key.c_str(), fine(clearance_m).c_str(),
                      floors::length_text(plan.min_gap_m, unit).c_str(),
                      floors::length_text(machine.gantry_width_m, unit).c_str(),
                      layers_text(users.at(key)).c_str(), fine(t.gantry_clearance_m).c_str()));
  }
  // Climbs: the nearest approach of a moving link to a wall.
  const Event* closest_climb = nullptr;
  int tight_climbs = 0;
  for (const Event& e : schedule.events) {
    if (!e.climb || e.climb->plan.min_clearance_m >= t.climb_clearance_m) continue;
    ++tight_climbs;
    if (!closest_climb ||
        e.climb->plan.min_clearance_m < closest_climb->climb->plan.min_clearance_m)
      closest_climb = &e;
  }
  if (closest_climb)
    out.push_back(printf_string(
        "margin: %d climb%s pass%s within %s of a wall; the closest, from stage %d to %d (after "
        "floor %d layer %d), passes %s from it",
        tight_climbs, tight_climbs == 1 ? "" : "s", tight_climbs == 1 ? "es" : "",
        fine(t.climb_clearance_m).c_str(), closest_climb->climb->from_stage,
        closest_climb->climb->to_stage, closest_climb->floor, closest_climb->layer,
        fine(closest_climb->climb->plan.min_clearance_m).c_str()));
  // Intervals: the longest local interval (in equivalent age with weather) against the
  // maximum, on the layers it binds.
  const ScheduledLayer* closest_layer = nullptr;
  double closest_interval_s = 0.0;
  int tight_layers = 0;
  const double max_s = material.max_layer_interval_s;
  for (const ScheduledLayer& l : schedule.layers) {
    const std::optional<double> longest_s =
        l.equivalent_interval_max_s ? l.equivalent_interval_max_s : l.local_interval_max_s;
    if (l.planned_joint || !longest_s || *longest_s <= t.interval_share * max_s) continue;
    ++tight_layers;
    if (!closest_layer || *longest_s > closest_interval_s) {
      closest_layer = &l;
      closest_interval_s = *longest_s;
    }
  }
  if (closest_layer) {
    const PieceEnd& at = closest_layer->local_max_at;
    out.push_back(printf_string(
        "margin: %d layer%s cover a piece after more than %.0f%% of the material's maximum "
        "interval of %.1f s; the closest, floor %d layer %d, covers wall %lld piece %d at "
        "(%.3f, %.3f) %s after %.1f s%s (%.1f%%)",
        tight_layers, tight_layers == 1 ? "" : "s", t.interval_share * 100.0, max_s,
        closest_layer->floor, closest_layer->layer, static_cast<long long>(at.wall), at.piece,
        at.x_m / per, at.y_m / per, unit_name.c_str(), closest_interval_s,
        closest_layer->equivalent_interval_max_s ? " of equivalent age" : "",
        100.0 * closest_interval_s / max_s));
  }
  // Idle spells: a layer's longest air move against the nozzle's limit.
  const ScheduledLayer* idlest = nullptr;
  int idle_layers = 0;
  const double idle_limit_s = machine.nozzle_idle_limit_s;
  for (const ScheduledLayer& l : schedule.layers) {
    if (l.max_idle_s <= t.idle_share * idle_limit_s || l.max_idle_s > idle_limit_s) continue;
    ++idle_layers;
    if (!idlest || l.max_idle_s > idlest->max_idle_s) idlest = &l;
  }
  if (idlest)
    out.push_back(printf_string(
        "margin: %d layer%s leave a nozzle idle for more than %.0f%% of its limit of %.1f s "
        "(concrete left longer clogs it); the longest, on floor %d layer %d, %.1f s (%.1f%%)",
        idle_layers, idle_layers == 1 ? "" : "s", t.idle_share * 100.0, idle_limit_s, idlest->floor,
        idlest->layer, idlest->max_idle_s, 100.0 * idlest->max_idle_s / idle_limit_s));
  return out;
}

}  // namespace ccbuild::schedule
