#include "ccbuild/planner/follow_below.hpp"

#include <algorithm>
#include <limits>

#include "ccbuild/common/format.hpp"
#include "ccbuild/planner/plan_layer.hpp"

namespace ccbuild::planner {

FollowPlan plan_following(const floors::Layer& layer, const machine::MachineModel& machine,
                          const FollowRequest& request) {
  const int nozzles = static_cast<int>(request.order.size());
  FollowPlan out;
  PlanOptions options;
  options.objective = Objective::kTime;
  std::vector<Timeline> rails;
  const RailAxis axis = machine.rail_axis;
  for (int n = 0; n < nozzles; ++n) {
    const auto& steps = request.order[n];
    if (steps.empty()) {
      out.waypoints.push_back({});
      rails.push_back(parked_at(request.parked_m.at(n)));
      continue;
    }
    // The nozzle's own pieces as a layer: sequence steps index into it.
    std::vector<int> segments;
    for (const auto& s : steps) segments.push_back(s.segment);
    const floors::Layer own = nozzles == 1 ? layer : floors::sub_layer(layer, segments);
    Sequence sequence;
    for (std::size_t j = 0; j < steps.size(); ++j)
      sequence.push_back(
          {nozzles == 1 ? steps[j].segment : static_cast<int>(j), steps[j].reversed});
    const LayerPlan plan = time_sequence(own, machine, sequence, options);
    out.layer_time_s = std::max(out.layer_time_s, plan.evaluation.layer_time_s);
    out.deposition_s += plan.evaluation.deposition_s;
    out.airtime_s += plan.evaluation.airtime_s;
    out.max_idle_s = std::max(out.max_idle_s, plan.evaluation.max_idle_s);
    if (plan.evaluation.idle_limit_violations > 0 && out.idle_limit_violations == 0)
      out.violating_idle_s = plan.evaluation.max_idle_s;
    out.idle_limit_violations += plan.evaluation.idle_limit_violations;
    Timeline rail;
    for (const auto& w : plan.waypoints) rail.append(w.t_s, w.position_m);
    rails.push_back(rail);
    out.waypoints.push_back(plan.waypoints);
  }
  const bool idle_ok = out.idle_limit_violations == 0;
  // Held back: a nozzle that would come too close to the one before it starts later.
  if (request.hold_back && idle_ok)
    for (int n = 1; n < nozzles; ++n) {
      if (out.waypoints[n].empty() || out.waypoints[n - 1].empty() ||
          !first_conflict(rails[n - 1], rails[n], axis, machine.gantry_width_m))
        continue;
      for (double delay_s = 5.0; delay_s <= machine.nozzle_idle_limit_s; delay_s += 5.0) {
        Timeline later;
        later.append(0.0, out.waypoints[n].front().position_m);
        for (const auto& w : out.waypoints[n]) later.append(w.t_s + delay_s, w.position_m);
        if (first_conflict(rails[n - 1], later, axis, machine.gantry_width_m)) continue;
        rails[n] = later;
        Waypoint parked = out.waypoints[n].front();
        parked.extruding = false;
        parked.wall = 0;
        parked.piece = 0;
        for (auto& w : out.waypoints[n]) w.t_s += delay_s;
        out.waypoints[n].insert(out.waypoints[n].begin(), parked);
        out.layer_time_s = std::max(out.layer_time_s, out.waypoints[n].back().t_s);
        out.airtime_s += delay_s;
        out.max_idle_s = std::max(out.max_idle_s, delay_s);
        break;
      }
    }
  // The gantries must keep their gap: checked exactly at every breakpoint of either, up
  // to the first pair that does not.
  out.min_gap_m = std::numeric_limits<double>::infinity();
  for (int n = 0; n + 1 < nozzles && idle_ok && out.gap_broken.empty(); ++n) {
    out.min_gap_m = std::min(out.min_gap_m, min_gap_m(rails[n], rails[n + 1], axis));
    if (auto conflict = first_conflict(rails[n], rails[n + 1], axis, machine.gantry_width_m))
      out.gap_broken = printf_string("gantries %d and %d come within %.3f m at %.1f s", n + 1,
                                     n + 2, conflict->right_m - conflict->left_m, conflict->time_s);
  }
  if (nozzles == 1) out.min_gap_m = 0.0;
  return out;
}

}  // namespace ccbuild::planner
