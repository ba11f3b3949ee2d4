#include "ccbuild/schedule/what_if.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "ccbuild/common/format.hpp"

namespace ccbuild::schedule {
namespace {

// The time climbs were held by their anchors, and by nothing else then.
double anchor_waits_s(const Schedule& s) {
  double total = 0.0;
  for (const auto& e : s.events)
    if (e.climb) total += binding_s(e.climb->wait_reasons, WaitKind::kAnchorStrength);
  return total;
}

AnchorWhatIf scheduled(AnchorWhatIf w, const Setup& variant, const ScheduleOptions& options) {
  ScheduleOptions quiet = options;
  quiet.progress = nullptr;
  const Schedule s = build_schedule(variant, quiet);
  w.feasible = s.feasible;
  w.makespan_s = s.totals.makespan_s;
  w.anchor_waits_s = anchor_waits_s(s);
  return w;
}

Setup with_climber(const Setup& setup, std::shared_ptr<const machine::ClimbingMachine> climber) {
  Setup variant = setup;
  variant.climber = std::move(climber);
  return variant;
}

// The same machine, its anchors loaded from `mpa`.
Setup with_anchor_strength(const Setup& setup, double mpa) {
  auto machine = std::make_shared<machine::ClimbingMachine>(*setup.climber);
  machine->anchor_strength_mpa = mpa;
  return with_climber(setup, std::move(machine));
}

AnchorWhatIf what_if(AnchorWhatIf::Kind kind, double value, std::string change) {
  AnchorWhatIf w;
  w.kind = kind;
  w.value = value;
  w.change = std::move(change);
  return w;
}

// The anchors' equivalent age with the site's weather, as the scheduler counts it (none
// without weather: real age).
std::optional<site::EquivalentAge> anchor_maturity(const Setup& setup) {
  std::optional<site::EquivalentAge> maturity;
  if (setup.conditions) maturity.emplace(*setup.conditions, setup.anchor_mix().maturity);
  return maturity;
}

}  // namespace

std::vector<AnchorWait> anchor_waits(const Setup& setup, const Schedule& s) {
  std::vector<AnchorWait> out;
  if (!setup.climber) return out;
  std::map<PipeKey, const Event*> pipes;
  for (const auto& e : s.events)
    if (e.kind == Event::Kind::kPipe && e.anchor) pipes[pipe_key(*e.anchor)] = &e;
  const double required_mpa = setup.climber->anchor_strength_mpa;
  const floors::MaterialProfile& mix = setup.anchor_mix();
  const double age_s = mix.age_for_strength_s(required_mpa);
  const std::optional<site::EquivalentAge> maturity = anchor_maturity(setup);
  for (const auto& e : s.events) {
    if (!e.climb) continue;
    const ClimbEvent& c = *e.climb;
    AnchorWait w;
    w.from_stage = c.from_stage;
    w.to_stage = c.to_stage;
    w.floor = e.floor;
    w.layer = e.layer;
    w.wait_s = binding_s(c.wait_reasons, WaitKind::kAnchorStrength);
    w.ready_s = c.start_s - c.wait_before_s;
    w.required_mpa = required_mpa;
    w.strong_s = -std::numeric_limits<double>::infinity();
    for (const auto& a : s.stages[c.to_stage].anchors) {
      const auto it = pipes.find(pipe_key(a));
      const double cast_s = it == pipes.end() ? 0.0 : it->second->end_s;
      const double strong_s = site::age_reached_s(maturity ? &*maturity : nullptr, cast_s, age_s);
      if (strong_s > w.strong_s) {
        w.strong_s = strong_s;
        w.cast_s = cast_s;
        w.anchor = a.id;
        w.cast_floor = a.floor;
        w.cast_layer = a.layer;
      }
    }
    out.push_back(w);
  }
  return out;
}

std::vector<AnchorWhatIf> anchor_what_ifs(const Setup& setup, const Schedule& base,
                                          const ScheduleOptions& options,
                                          const floors::MaterialProfile* faster_mix) {
  std::vector<AnchorWhatIf> all;
  if (!setup.climber || !base.feasible) return all;
  const std::vector<AnchorWait> waits = anchor_waits(setup, base);
  double waited_s = 0.0;
  for (const auto& w : waits) waited_s += w.wait_s;
  if (waited_s <= 0.0) return all;
  const machine::ClimbingMachine& m = *setup.climber;

  // 1. Pipes cast a storey earlier: in the top layer of the floor below the one each
  // climb's pipes are cast in now. The legs must reach that much lower from the stage
  // climbed to (the lowest pipe a leg reaches: its foot at the stroke's usable end).
  {
    const machine::Kinematics& robot = *m.robot;
    const auto zero = robot.link_poses(Eigen::Isometry3d::Identity(), robot.zero());
    double lowest_reach_m = std::numeric_limits<double>::infinity();  // below the platform
    for (const auto& unit : m.units)
      lowest_reach_m = std::min(lowest_reach_m, zero[unit.foot_link].translation().z() -
                                                    m.usable_range(unit.joints[3]).second);
    std::map<int, double> top_mid_m;  // per floor: its top layer's middle
    for (const auto& l : base.layers) top_mid_m[l.floor] = 0.5 * (l.z_bottom_m + l.z_top_m);
    double extra_m = 0.0;
    for (const auto& w : waits) {
      const auto below = top_mid_m.find(w.cast_floor - 1);
      if (w.wait_s <= 0.0 || w.cast_floor < 1 || below == top_mid_m.end()) continue;
      const double reach_m = base.stages[w.to_stage].platform_z_m + lowest_reach_m;
      extra_m = std::max(extra_m, reach_m - below->second);
    }
    if (extra_m > 0.0) {
      // Up to the hundredth of the building's unit above, so the figure said is the one used.
      const double per_m = floors::meters_per(setup.building.units);
      extra_m = floors::rounded(extra_m / per_m, 2, floors::Towards::kUp) * per_m;
      const auto [stroke_min_m, stroke_max_m] = m.usable_range(m.units.front().joints[3]);
      (void)stroke_min_m;
      const AnchorWhatIf w = what_if(
          AnchorWhatIf::Kind::kEarlierPipes, extra_m,
          printf_string("cast each climb's pipes a storey earlier (in the top layers of the floor "
                        "below), which the legs reach %s longer (stroke to %s, the "
                        "URDF's upper limit +%s)",
                        setup.length(extra_m, 2).c_str(),
                        setup.length(stroke_max_m + m.stroke_end_margin_m + extra_m, 2).c_str(),
                        setup.length(extra_m, 2).c_str()));
      all.push_back(
          scheduled(w, with_climber(setup, machine::with_longer_legs(m, extra_m)), options));
    }
  }

  // 2. A faster-hardening mix for the layers the pipes are cast in.
  if (faster_mix) {
    const double now_s = setup.anchor_mix().age_for_strength_s(m.anchor_strength_mpa);
    const double then_s = faster_mix->age_for_strength_s(m.anchor_strength_mpa);
    if (then_s < now_s) {
      Setup variant = setup;
      variant.anchor_material = *faster_mix;
      all.push_back(scheduled(
          what_if(AnchorWhatIf::Kind::kFasterMix, then_s,
                  printf_string(
                      "pour the anchors' layers with %s (%.1f MPa after %.1f h instead of %.1f h)",
                      faster_mix->name.c_str(), m.anchor_strength_mpa, then_s / 3600.0,
                      now_s / 3600.0)),
          variant, options));
    }
  }

  // 3. A lower anchor strength: what the youngest anchor of the worst-held climb has when
  // the climb is otherwise ready, to the half MPa below.
  {
    const std::optional<site::EquivalentAge> maturity = anchor_maturity(setup);
    double lowest_mpa = std::numeric_limits<double>::infinity();
    for (const auto& w : waits)
      if (w.wait_s > 0.0) {
        const double age_s = maturity ? maturity->age(w.cast_s, std::max(w.cast_s, w.ready_s))
                                      : std::max(0.0, w.ready_s - w.cast_s);
        lowest_mpa = std::min(lowest_mpa, setup.anchor_mix().strength_at_mpa(age_s));
      }
    const double mpa = std::floor(lowest_mpa * 2.0 + 1e-9) / 2.0;
    // Only a strength a machine may state (a pipe in younger concrete would tear out).
    if (std::isfinite(mpa) && machine::kAnchorStrength_mpa.contains(mpa) &&
        mpa < m.anchor_strength_mpa) {
      all.push_back(scheduled(
          what_if(AnchorWhatIf::Kind::kLowerStrength, mpa,
                  printf_string("load the anchors from %.1f MPa instead of %.1f MPa, if the "
                                "climbing units' maker allows it (the strength the youngest "
                                "anchor has when its climb is otherwise ready)",
                                mpa, m.anchor_strength_mpa)),
          with_anchor_strength(setup, mpa), options));
    }
  }

  // 4. More units sharing the load: while units_per_transfer change pipes the rest hold
  // the platform, each anchor its share of the weight; two more units lower that share.
  {
    const int units = static_cast<int>(m.units.size());
    const int more = std::min(units + 2, 16);
    const int holding_now = units - m.units_per_transfer;
    const int holding_then = more - m.units_per_transfer;
    const double mpa = m.anchor_strength_mpa * holding_now / std::max(1, holding_then);
    if (more > units && holding_now > 0 && machine::kAnchorStrength_mpa.contains(mpa)) {
      all.push_back(scheduled(
          what_if(AnchorWhatIf::Kind::kMoreUnits, more,
                  printf_string("%d units instead of %d: %d hold the platform in a transfer "
                                "instead of %d, each anchor carrying %d/%d of today's load, so "
                                "%.1f MPa suffices (refit the machine for the mounts; the climbs' "
                                "motions here are today's)",
                                more, units, holding_then, holding_now, holding_now, holding_then,
                                mpa)),
          with_anchor_strength(setup, mpa), options));
    }
  }
  // Only what could be done: a variant that is not feasible is no way to build.
  std::vector<AnchorWhatIf> out;
  for (AnchorWhatIf& w : all)
    if (w.feasible) out.push_back(std::move(w));
  return out;
}

}  // namespace ccbuild::schedule
