#include "ccbuild/schedule/schedule.hpp"
#include "ccbuild/schedule/margins.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <thread>
#include <unordered_map>

#include "anchor_strength.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/rules/weather.hpp"
#include "ccbuild/schedule/json_blocks.hpp"
#include "ccbuild/schedule/quantities.hpp"
#include "scheduler.hpp"

namespace ccbuild::schedule {
namespace detail {

double Scheduler::move_between(const std::string& from_key, const std::string& to_key) const {
  return planner::layer_change_s(machine_, schedule_.plans.at(from_key).waypoints,
                                 schedule_.plans.at(to_key).waypoints,
                                 project_.building.layer_height_m);
}

std::vector<std::optional<machine::GantryPose>> Scheduler::gantry_poses(const std::string& key,
                                                                        double z_top_m,
                                                                        bool last) const {
  const SchedulePlan& plan = schedule_.plans.at(key);
  std::vector<std::optional<machine::GantryPose>> out(plan.waypoints.size());
  for (std::size_t n = 0; n < plan.waypoints.size(); ++n) {
    if (plan.waypoints[n].empty()) continue;
    const planner::Waypoint& w = last ? plan.waypoints[n].back() : plan.waypoints[n].front();
    out[n] = machine::GantryPose{w.position_m.x(), w.position_m.y(),
                                 w.z_m + (z_top_m - plan.z_top_m), w.heading_rad};
  }
  return out;
}

double Scheduler::peak_flow_of(const std::string& key) {
  auto it = peak_flow_.find(key);
  if (it == peak_flow_.end()) {
    const SchedulePlan& plan = schedule_.plans.at(key);
    it = peak_flow_
             .emplace(key, peak_flow_m3_s(plan.waypoints, plan.layer, machine_.nozzle_width_m,
                                          project_.building.layer_height_m))
             .first;
  }
  return it->second;
}

double Scheduler::largest_interval_s(const IntervalOffsets& o, double below_start_s,
                                     double start_s) const {
  if (!maturity_) return start_s - below_start_s + o.max_offset_s;
  double most_s = -kInf;
  for (const auto& e : o.each)
    most_s = std::max(most_s, maturity_->age(below_start_s + e.low_lo_s, start_s + e.up_hi_s));
  return most_s;
}

double Scheduler::smallest_interval_s(const IntervalOffsets& o, double below_start_s,
                                      double start_s) const {
  if (!maturity_) return start_s - below_start_s + o.min_offset_s;
  double least_s = kInf;
  for (const auto& e : o.each)
    least_s = std::min(least_s, maturity_->age(below_start_s + e.low_hi_s, start_s + e.up_lo_s));
  return least_s;
}

const IntervalOffsets& Scheduler::offsets(const Slice& upper, const std::string& upper_key,
                                          const std::string& lower_key) {
  const auto key = std::make_pair(upper_key, lower_key);
  auto it = offsets_.find(key);
  if (it == offsets_.end())
    it = offsets_
             .emplace(key,
                      interval_offsets(upper.layer, indexes_.at(upper_key), indexes_.at(lower_key)))
             .first;
  return it->second;
}

double Scheduler::strength_ready_s(int i, int first_checked, double earliest_s, WaitReason& reason,
                                   bool& impossible) const {
  // The weight of the walls from layer j's bottom up to the new layer's top, times the
  // safety factor, must not exceed layer j's strength at its age (from its end).
  const double top_m = slices_[i].layer.z_top_m;
  const double worst_age_s = material_.age_for_strength_s(required_strength_mpa(top_m));
  double ready_s = -kInf;
  for (int j = first_checked - 1; j >= 0; --j) {
    // Older layers carry at most the whole height; once that is within their age, stop.
    if (std::isfinite(worst_age_s) && aged_s(layer_end_s_[j], worst_age_s) <= earliest_s) break;
    const double required_mpa = required_strength_mpa(top_m - slices_[j].layer.z_bottom_m);
    const double age_s = material_.age_for_strength_s(required_mpa);
    if (!std::isfinite(age_s)) {
      impossible = true;
      reason.kind = WaitKind::kStrength;
      reason.detail = printf_string(
          "%s would carry %s of wall: %.4f MPa with the safety factor %.2f, more than the "
          "material ever reaches (%.4f MPa)",
          where_text(slices_[j].floor, slices_[j].layer.index).c_str(),
          project_.length(top_m - slices_[j].layer.z_bottom_m).c_str(), required_mpa,
          material_.safety_factor, material_.strength_curve.back().strength_mpa);
      return kInf;
    }
    if (aged_s(layer_end_s_[j], age_s) > ready_s) {
      ready_s = aged_s(layer_end_s_[j], age_s);
      reason.kind = WaitKind::kStrength;
      reason.detail = printf_string(
          "%s carries %s of wall above its bottom: %.4f MPa with the safety factor %.2f; "
          "its concrete reaches that %.1f s after it was deposited",
          where_text(slices_[j].floor, slices_[j].layer.index).c_str(),
          project_.length(top_m - slices_[j].layer.z_bottom_m).c_str(), required_mpa,
          material_.safety_factor, age_s);
    }
  }
  return ready_s;
}

void Scheduler::fail(Infeasibility infeasibility) {
  // The first is the one reported in full (with its computed fix); a few more are named.
  constexpr int kNamed = 5;
  if (schedule_.feasible) {
    schedule_.feasible = false;
    schedule_.infeasibility = std::move(infeasibility);
  } else if (++further_failures_ <= kNamed) {
    schedule_.warnings.push_back("also infeasible: " + infeasibility.message);
  } else if (further_failures_ == kNamed + 1) {
    schedule_.warnings.push_back(
        "also infeasible: more layers (each is listed in the JSON by its "
        "local_interval_max_s)");
  }
}

namespace {
// The maximum-interval fix in words: its figure in whole seconds, as build_schedule proves it.
std::string max_interval_fix(double needed_s) {
  return printf_string("a maximum layer interval of at least %.0f s", needed_s);
}
}  // namespace

void Scheduler::compute_fix(Infeasibility& inf, const Slice& slice, const Planned& p, int nozzles) {
  const double layer_time_s = p.layer_time_s;
  const double deposition_s = p.deposition_s / nozzles;  // a nozzle's share
  const double required_s = inf.required_s, achieved_s = inf.achieved_s;
  const double excess_s = achieved_s - required_s;
  inf.max_interval_needed_s = std::ceil(achieved_s);
  // Faster deposition shortens the deposition share of the interval; airtime stays.
  if (deposition_s > excess_s)
    inf.deposition_speed_needed_m_s =
        machine_.deposition_speed_m_s * deposition_s / (deposition_s - excess_s);
  // More nozzles than the machine has: plan them, up to 16, until one count is fast enough
  // on its own (the layer's time plus the move to it must fit the maximum).
  // A count whose share of the deposition alone is too slow is not planned: n nozzles lay
  // the layer in no less than its deposition time over n (on the 40 x 40 rooms benchmark,
  // four 60 s plans of counts that could not be enough, bench/README.md).
  for (int n = machine_.nozzles + 1; n <= std::min(16, machine_.nozzles + 4); ++n) {
    if (achieved_s - layer_time_s + deposition_share_s(p.deposition_s, n) > required_s) continue;
    const Planned& more = planned(slice.geometry, n);
    if (more.usable && achieved_s - layer_time_s + more.layer_time_s <= required_s) {
      inf.nozzles_needed = n;
      break;
    }
  }
  std::string fix = max_interval_fix(*inf.max_interval_needed_s);
  if (inf.deposition_speed_needed_m_s)
    fix += printf_string(
        "; or a deposition speed of at least %s (now %s)",
        floors::speed_text(*inf.deposition_speed_needed_m_s, project_.building.units, 3,
                           floors::Towards::kUp)
            .c_str(),
        floors::speed_text(machine_.deposition_speed_m_s, project_.building.units).c_str());
  if (inf.nozzles_needed)
    fix += printf_string("; or %d nozzles (the machine has %d)", *inf.nozzles_needed,
                         machine_.nozzles);
  inf.fix = fix;
}

bool Scheduler::schedule_layer(int i) {
  const Slice& slice = slices_[i];
  ScheduledLayer out;
  out.floor = slice.floor;
  out.layer = slice.layer.index;
  out.z_bottom_m = slice.layer.z_bottom_m;
  out.z_top_m = slice.layer.z_top_m;
  out.geometry = slice.geometry + 1;
  const bool same_floor = i > 0 && slices_[i - 1].floor == slice.floor;
  const ScheduledLayer* below = same_floor ? &schedule_.layers.back() : nullptr;

  // The layers further below: each must carry the walls up to this layer's top, at its
  // age from its end (the one just below is checked piece by piece, with each plan).
  WaitReason strength;
  bool impossible = false;
  const double strong_s =
      strength_ready_s(i, below ? i - 1 : i, previous_end_s_, strength, impossible);
  if (impossible) {
    Infeasibility inf;
    inf.kind = InfeasibilityKind::kStrength;
    inf.floor = slice.floor;
    inf.layer = slice.layer.index;
    inf.message = where_text(slice.floor, slice.layer.index) + ": " + strength.detail;
    inf.fix = "a stronger material, or lower floors";
    fail(inf);
  }
  // The stress on the layer just below, from its bottom to this layer's top, and the age
  // its concrete needs for it.
  const double below_age_s = below ? material_.age_for_strength_s(required_strength_mpa(
                                         slice.layer.z_top_m - below->z_bottom_m))
                                   : 0.0;
  if (below && !std::isfinite(below_age_s) && !impossible) {
    Infeasibility inf;
    inf.kind = InfeasibilityKind::kStrength;
    inf.floor = slice.floor;
    inf.layer = slice.layer.index;
    inf.message = printf_string(
        "%s: floor %d layer %d would carry %s of wall, more than the material ever "
        "carries with the safety factor %.2f",
        where_text(slice.floor, slice.layer.index).c_str(), below->floor, below->layer,
        project_.length(slice.layer.z_top_m - below->z_bottom_m).c_str(), material_.safety_factor);
    inf.fix = "a stronger material, or thinner layers";
    fail(inf);
  }

  // Try the fewest nozzles fast enough up to the machine's count: the first plan that
  // keeps every interval (at one nozzle, where the geometry changes, also the plan that
  // follows the order of the layer below).
  struct Choice {
    int nozzles = 0;
    std::string key;
    const Planned* planned = nullptr;
    double start_s = 0.0, move_s = 0.0, wait_s = 0.0;
    std::vector<WaitReason> reasons;
    bool purge = false, joint = false;
    double block_s = 0.0;       ///< where the joint (or the purge, or the layer) starts
    std::string calendar_fail;  ///< no working window holds it
    IntervalOffsets offsets;
    double local_max_s = -kInf;
    /// In equivalent age, with site temperatures (else unset).
    std::optional<double> equivalent_min_s, equivalent_max_s;
    bool ok = false;
  };
  std::optional<Choice> best;
  // After a stop, a plan that keeps every interval is preferred to a planned joint: the
  // counts are tried without joints first, unless the stop alone outlasts the maximum.
  bool allow_joint =
      !stopped_since_below_ || !below ||
      previous_end_s_ + ready_extra_s_ - below->start_s > material_.max_layer_interval_s;
  std::vector<std::string> refusals;
  auto consider = [&](int n, const std::string& key, const Planned& p) {
    Choice c;
    c.nozzles = n;
    c.key = key;
    c.planned = &p;
    if (machine_.pump_capacity_m3_s &&
        peak_flow_of(c.key) > *machine_.pump_capacity_m3_s * (1 + 1e-9)) {
      refusals.push_back(printf_string(
          "%d nozzle%s: together they draw %s, more than the pump's %s", n, n == 1 ? "" : "s",
          floors::flow_text(peak_flow_of(c.key), project_.building.units, 2).c_str(),
          floors::flow_text(*machine_.pump_capacity_m3_s, project_.building.units, 2).c_str()));
      return false;
    }
    // The model's layer change, or longer where a gantry comes back from its park (or
    // parks) and its slowest axis needs more: the moves the dispatcher sends.
    c.move_s = previous_key_.empty() ? 0.0
                                     : std::max(move_between(previous_key_, c.key),
                                                yard_->longest_move_before_s(gantry_poses(
                                                    c.key, slice.layer.z_top_m, false)));
    const double earliest_s = previous_end_s_ + ready_extra_s_ + c.move_s;
    double start_s = earliest_s;
    auto require = [&](double need_s, WaitKind kind, const std::string& detail) {
      if (need_s <= earliest_s + 1e-9) return;
      c.reasons.push_back({kind, need_s - earliest_s, detail});
      start_s = std::max(start_s, need_s);
    };
    if (below) {
      c.offsets = offsets(slice, c.key, below->plan);
      // The window of the interval and of the strength the load needs, piece end by piece
      // end (in equivalent age with site weather): rules::start_window.
      const rules::AgeClock* clock = maturity_ ? &maturity_->clock() : nullptr;
      const rules::StartWindow interval_window = rules::start_window(
          c.offsets, material_.min_layer_interval_s, kInf, clock, below->start_s);
      const rules::StartWindow strength_window =
          std::isfinite(below_age_s)
              ? rules::start_window(c.offsets, below_age_s, kInf, clock, below->start_s)
              : rules::StartWindow{};
      if (c.offsets.ends > 0 && !maturity_) {
        // In real time both windows are set by the end with the smallest offset (named as
        // the offsets name it, the first of equals).
        const double earliest_local_s = earliest_s - below->start_s + c.offsets.min_offset_s;
        require(interval_window.earliest_s, WaitKind::kMinInterval,
                printf_string("%s would be covered %.1f s after it was deposited, under the "
                              "minimum interval of %.1f s",
                              piece_text(c.offsets.min_at, project_.building.units).c_str(),
                              earliest_local_s, material_.min_layer_interval_s));
        if (std::isfinite(below_age_s))
          require(strength_window.earliest_s, WaitKind::kStrength,
                  printf_string("%s (floor %d layer %d) would carry %s of wall %.1f s "
                                "after it was deposited; with the safety factor %.2f its "
                                "concrete needs %.1f s",
                                piece_text(c.offsets.min_at, project_.building.units).c_str(),
                                below->floor, below->layer,
                                project_.length(slice.layer.z_top_m - below->z_bottom_m).c_str(),
                                earliest_local_s, material_.safety_factor, below_age_s));
      } else if (c.offsets.ends > 0) {
        const double min_need_s = interval_window.earliest_s;
        const double strength_need_s = strength_window.earliest_s;
        const PieceEnd& min_at = interval_window.earliest_at;
        const PieceEnd& strength_at = strength_window.earliest_at;
        require(min_need_s, WaitKind::kMinInterval,
                printf_string("%s would be covered before its concrete is %.1f s old in "
                              "equivalent age at 20 °C, the minimum interval",
                              piece_text(min_at, project_.building.units).c_str(),
                              material_.min_layer_interval_s));
        if (std::isfinite(below_age_s))
          require(strength_need_s, WaitKind::kStrength,
                  printf_string("%s (floor %d layer %d) would carry %s of wall; with the "
                                "safety factor %.2f its concrete needs %.1f s of equivalent age",
                                piece_text(strength_at, project_.building.units).c_str(),
                                below->floor, below->layer,
                                project_.length(slice.layer.z_top_m - below->z_bottom_m).c_str(),
                                material_.safety_factor, below_age_s));
      }
    }
    if (!below && slab_ready_s_ > earliest_s + 1e-9)
      require(slab_ready_s_, WaitKind::kSlab, slab_ready_detail_);
    if (!impossible && std::isfinite(strong_s)) {
      strength.required_s = 0.0;
      if (strong_s > earliest_s + 1e-9) require(strong_s, WaitKind::kStrength, strength.detail);
    }
    // The block that starts the layer: the planned joint's treatment (crew), the purge,
    // the layer. Work that needs a crew waits for working hours; a layer pushed past
    // off-shift hours with an interval over the maximum starts on a planned joint.
    const double rules_s = start_s;
    double block_s = start_s;
    const floors::PlannedJoint& pj = material_.planned_joint;
    bool moved = stopped_since_below_;
    WaitKind pushed_by = WaitKind::kOffShift;
    for (int pass = 0; pass < 8; ++pass) {
      c.purge =
          !previous_key_.empty() && block_s + (c.joint ? pj.treatment_s : 0.0) - previous_end_s_ >
                                        machine_.nozzle_idle_limit_s + 1e-9;
      const double joint_s = c.joint ? pj.treatment_s : 0.0;
      const double crew_s = printing_attended()
                                ? joint_s + (c.purge ? machine_.purge_s : 0.0) + p.layer_time_s
                                : joint_s;
      if (calendar_ && crew_s > 0.0) {
        const double fit_s = calendar_->fit_s(block_s, crew_s);
        if (!std::isfinite(fit_s)) {
          c.calendar_fail = printf_string(
              "%s: %.2f h of work that needs a crew (%s) fits in no working window from %s (the "
              "longest is %.2f h)",
              where_text(slice.floor, slice.layer.index).c_str(), crew_s / 3600.0,
              printing_attended() ? "attended printing, with its purge and joint"
                                  : "the planned joint's treatment",
              calendar_->local_text(block_s).c_str(), calendar_->longest_window_s() / 3600.0);
          break;
        }
        if (fit_s > block_s + 1e-9) {
          moved = true;
          block_s = fit_s;
          pushed_by = WaitKind::kOffShift;
          continue;
        }
      }
      // Printing needs an air temperature within the material's placing range.
      if (maturity_) {
        const double print_s = joint_s + (c.purge ? machine_.purge_s : 0.0) + p.layer_time_s;
        const double warm_s =
            maturity_->fit_s(block_s, print_s, [this](const site::WeatherReading& r) {
              return rules::placeable_at(r.temperature_c, material_.placing_min_c,
                                         material_.placing_max_c);
            });
        if (!std::isfinite(warm_s)) {
          c.calendar_fail = printf_string(
              "%s: the air is never again within the material's placing range of %.1f to %.1f "
              "°C (the weather's last reading holds)",
              where_text(slice.floor, slice.layer.index).c_str(), material_.placing_min_c,
              material_.placing_max_c);
          break;
        }
        if (warm_s > block_s + 1e-9) {
          moved = true;
          block_s = warm_s;
          pushed_by = WaitKind::kCold;
          continue;
        }
      }
      const double layer_start_s = block_s + joint_s + (c.purge ? machine_.purge_s : 0.0);
      const bool over_max = below && c.offsets.ends > 0 &&
                            largest_interval_s(c.offsets, below->start_s, layer_start_s) >
                                material_.max_layer_interval_s + 1e-9;
      if (moved && over_max && !c.joint && allow_joint) {
        c.joint = true;
        if (below->end_s + pj.min_age_s > block_s + 1e-9) {
          block_s = below->end_s + pj.min_age_s;
          pushed_by = WaitKind::kJoint;
        }
        continue;
      }
      break;
    }
    if (!c.calendar_fail.empty()) {
      c.local_max_s = kInf;
      refusals.push_back(c.calendar_fail);
      if (!best) best = std::move(c);
      return false;
    }
    if (block_s > rules_s + 1e-9) {
      std::string detail;
      if (pushed_by == WaitKind::kJoint)
        detail = printf_string(
            "the planned joint on floor %d layer %d may be treated once it is %.1f h old",
            below->floor, below->layer, pj.min_age_s / 3600.0);
      else if (pushed_by == WaitKind::kCold)
        detail = printf_string(
            "the air is outside the material's placing range of %.1f to %.1f °C from %s; "
            "printing resumes at %s",
            material_.placing_min_c, material_.placing_max_c, when_text(rules_s).c_str(),
            when_text(block_s).c_str());
      else
        detail = printf_string(
            "%s needs a crew: %s is off-shift; the next working hours that hold it start %s",
            printing_attended() ? "printing (attended)" : "the joint's treatment",
            calendar_->local_text(rules_s).c_str(), calendar_->local_text(block_s).c_str());
      // It holds from where the rules above left the start.
      c.reasons.push_back({pushed_by, block_s - earliest_s, detail, rules_s - earliest_s});
    }
    bind_wait_reasons(c.reasons);
    c.wait_s = block_s - earliest_s;
    c.block_s = block_s;
    start_s = block_s + (c.joint ? pj.treatment_s : 0.0) + (c.purge ? machine_.purge_s : 0.0);
    c.start_s = start_s;
    if (below && c.offsets.ends > 0) {
      c.local_max_s = start_s - below->start_s + c.offsets.max_offset_s;
      if (maturity_) {
        c.equivalent_max_s = largest_interval_s(c.offsets, below->start_s, start_s);
        c.equivalent_min_s = smallest_interval_s(c.offsets, below->start_s, start_s);
      }
      c.ok = c.joint ||
             c.equivalent_max_s.value_or(c.local_max_s) <= material_.max_layer_interval_s + 1e-9;
      if (!c.ok)
        refusals.push_back(
            printf_string("%d nozzle%s (%s): %s covered after %.1f s, over the maximum of %.1f s",
                          n, n == 1 ? "" : "s", p.method.c_str(),
                          piece_text(c.offsets.max_at, project_.building.units).c_str(),
                          c.local_max_s, material_.max_layer_interval_s));
    } else {
      c.ok = true;
    }
    if (options_.objective == Objective::kShortest) {
      // Every count is tried: the one whose layer ends earliest, the fewest on a tie.
      const auto end_of = [](const Choice& x) { return x.start_s + x.planned->layer_time_s; };
      if (c.ok ? !best || !best->ok || end_of(c) < end_of(*best) - 1e-9
               : !best || (!best->ok && c.local_max_s < best->local_max_s))
        best = std::move(c);
      return false;
    }
    const bool done = c.ok;
    if (c.ok || !best || c.local_max_s < best->local_max_s) best = std::move(c);
    return done;
  };
  // A layer like the one below first tries the same plan: every interval is then the
  // same, start to start.
  const auto try_counts = [&] {
    bool placed = false;
    if (below && slices_[i - 1].geometry == slice.geometry)
      placed = consider(below->nozzles, below->plan, *registered_.at(below->plan));
    for (int n = fewest_nozzles(slice.geometry, run_between_s_[i]);
         !placed && n <= machine_.nozzles; ++n) {
      const Planned& p = planned(slice.geometry, n);
      if (p.usable && consider(n, plan_key(slice, n), p)) break;
      if (!p.usable)
        refusals.push_back(
            printf_string("%d nozzle%s: %s", n, n == 1 ? "" : "s", p.why_not.c_str()));
      if (below && n == below->nozzles) {
        const Planned& f = follow_plan(slice, below->plan, false);
        if (f.usable &&
            consider(n, register_plan(follow_key(slice, below->plan, false), slice, n, f), f))
          break;
        if (!f.usable)
          refusals.push_back(printf_string("%d nozzle%s following the layer below: %s", n,
                                           n == 1 ? "" : "s", f.why_not.c_str()));
        // At the machine's last count, the gantries in each other's way held back.
        if (!f.usable && n > 1 && n == machine_.nozzles) {
          const Planned& h = follow_plan(slice, below->plan, true);
          if (h.usable &&
              consider(n, register_plan(follow_key(slice, below->plan, true), slice, n, h), h))
            break;
          if (!h.usable)
            refusals.push_back(printf_string("%d nozzles following the layer below, held back: %s",
                                             n, h.why_not.c_str()));
        }
      }
    }
  };
  try_counts();
  if (!allow_joint && !(best && best->ok)) {
    best.reset();
    refusals.clear();
    allow_joint = true;
    try_counts();
  }
  if (!best) {
    // No nozzle count has a plan at all.
    Infeasibility inf;
    inf.kind = InfeasibilityKind::kNoPlan;
    inf.floor = slice.floor;
    inf.layer = slice.layer.index;
    std::string why;
    for (const auto& r : refusals) why += (why.empty() ? "" : "; ") + r;
    inf.message = where_text(slice.floor, slice.layer.index) + ": no usable plan: " + why;
    inf.fix = "see `ccbuild plan-layer` on this layer";
    fail(inf);
    return false;
  }
  if (!best->calendar_fail.empty()) {
    Infeasibility inf;
    inf.kind = InfeasibilityKind::kCalendar;
    inf.floor = slice.floor;
    inf.layer = slice.layer.index;
    inf.message = best->calendar_fail;
    inf.fix = "longer working hours, unattended printing, or more nozzles";
    fail(inf);
    return false;
  }
  if (!best->ok) {
    Infeasibility inf;
    inf.kind = InfeasibilityKind::kMaxInterval;
    inf.floor = slice.floor;
    inf.layer = slice.layer.index;
    inf.required_s = material_.max_layer_interval_s;
    inf.achieved_s = best->local_max_s;
    inf.message = printf_string(
        "%s: %s is covered %.1f s after it was deposited with %d nozzle%s (the best of the "
        "counts the machine allows), over the material's maximum interval of %.1f s by %.1f s",
        where_text(slice.floor, slice.layer.index).c_str(),
        piece_text(best->offsets.max_at, project_.building.units).c_str(), best->local_max_s,
        best->nozzles, best->nozzles == 1 ? "" : "s", material_.max_layer_interval_s,
        best->local_max_s - material_.max_layer_interval_s);
    if (schedule_.feasible) {  // the first one: compute its fixes
      compute_fix(inf, slice, *best->planned, best->nozzles);
      inf.message += "; fix: " + inf.fix;
    }
    fail(inf);
  }
  const Planned& p = *best->planned;
  out.plan = best->key;
  out.nozzles = best->nozzles;
  out.method = p.method;
  out.start_s = best->start_s;
  out.end_s = best->start_s + p.layer_time_s;
  out.deposition_s = p.deposition_s;
  out.airtime_s = p.airtime_s;
  out.max_idle_s = p.max_idle_s;
  out.move_before_s = best->move_s;
  out.pipes_before_s = pipes_before_s_;
  out.wait_before_s = best->wait_s;
  out.wait_reasons = best->reasons;
  out.purge_before = best->purge;
  out.planned_joint = best->joint;
  out.equivalent_interval_min_s = best->equivalent_min_s;
  out.equivalent_interval_max_s = best->equivalent_max_s;
  if (below) {
    out.interval_s = out.start_s - below->start_s;
    if (best->offsets.ends > 0) {
      out.local_interval_min_s = out.start_s - below->start_s + best->offsets.min_offset_s;
      out.local_interval_max_s = out.start_s - below->start_s + best->offsets.max_offset_s;
      out.local_min_at = best->offsets.min_at;
      out.local_max_at = best->offsets.max_at;
      out.piece_ends_checked = best->offsets.ends;
    }
    const std::optional<double>& soonest_s =
        out.equivalent_interval_min_s ? out.equivalent_interval_min_s : out.local_interval_min_s;
    if (soonest_s) {
      out.below_strength_mpa = material_.strength_at_mpa(*soonest_s);
      out.below_required_mpa = required_strength_mpa(out.z_top_m - below->z_bottom_m);
    }
  }
  if (best->joint) {
    const floors::PlannedJoint& pj = material_.planned_joint;
    const double age_s = best->block_s - below->end_s;
    Event e;
    e.kind = Event::Kind::kJoint;
    e.crew = kJointCrew;
    e.start_s = best->block_s;
    e.end_s = best->block_s + pj.treatment_s;
    e.floor = below->floor;
    e.layer = below->layer;
    e.detail = printf_string(
        "planned joint: the top of floor %d layer %d treated (%.1f h old) before floor %d layer %d",
        below->floor, below->layer, age_s / 3600.0, out.floor, out.layer);
    schedule_.events.push_back(e);
    if (age_s > pj.max_age_s + 1e-9) {
      Infeasibility inf;
      inf.kind = InfeasibilityKind::kJoint;
      inf.floor = slice.floor;
      inf.layer = slice.layer.index;
      inf.required_s = pj.max_age_s;
      inf.achieved_s = age_s;
      inf.message = printf_string(
          "%s: the planned joint on floor %d layer %d is %.1f h old when treated, over the "
          "material's %.1f h",
          where_text(slice.floor, slice.layer.index).c_str(), below->floor, below->layer,
          age_s / 3600.0, pj.max_age_s / 3600.0);
      inf.fix =
          "a joint treatment that allows older joints (planned_joint: max_age_h), fewer "
          "holidays in a row, or a stop at a floor's top";
      fail(inf);
    }
  }
  if (best->purge) {
    Event e;
    e.kind = Event::Kind::kPurge;
    e.start_s = out.start_s - machine_.purge_s;
    e.end_s = out.start_s;
    // Like every event, named after the layer it follows.
    e.floor = schedule_.layers.back().floor;
    e.layer = schedule_.layers.back().layer;
    e.detail = printf_string(
        "the nozzle idled %.1f s, over its limit of %.1f s, before floor %d layer %d",
        e.start_s - previous_end_s_, machine_.nozzle_idle_limit_s, out.floor, out.layer);
    schedule_.events.push_back(e);
  }
  layer_end_s_[i] = out.end_s;
  previous_end_s_ = out.end_s;
  previous_key_ = out.plan;
  yard_->finish_layer(gantry_poses(out.plan, slice.layer.z_top_m, true));
  schedule_.layers.push_back(out);
  ready_extra_s_ = 0.0;
  stopped_since_below_ = false;

  return true;
}

bool Scheduler::after_layer(int i) {
  const floors::Building& b = project_.building;
  const int count = static_cast<int>(slices_.size());
  const ScheduledLayer& out = schedule_.layers.back();
  // After the layer: its pipes, then (at a floor's top) the slab, then a climb.
  double t = out.end_s;
  pipes_before_s_ = 0.0;
  if (auto it = pipes_after_.find({out.floor, out.layer}); it != pipes_after_.end())
    for (const auto& a : it->second) {
      const double ready_s = t;
      if (calendar_ && calendar_->programme().pipes_need_crew) {
        const double fit_s = calendar_->fit_s(t, project_.climber->pipe_embed_s);
        stopped_since_below_ = stopped_since_below_ || fit_s > t + 1e-9;
        t = fit_s;  // a pipe is far shorter than any window: finite
      }
      Event e;
      e.kind = Event::Kind::kPipe;
      e.crew = calendar_ && !calendar_->programme().pipes_need_crew ? 0 : kPipeCrew;
      e.wait_before_s = t - ready_s;
      e.start_s = t;
      e.end_s = t += project_.climber->pipe_embed_s;
      pipes_before_s_ += project_.climber->pipe_embed_s;
      e.floor = out.floor;
      e.layer = out.layer;
      e.anchor = a;
      e.detail = "pipe " + a.id + " for unit " + project_.climber->units[a.unit].name;
      pipe_done_s_[pipe_key(a)] = e.end_s;
      schedule_.events.push_back(e);
    }
  const bool floor_top = i + 1 == count || slices_[i + 1].floor != out.floor;
  if (floor_top && b.slabs && (i + 1 < count || b.slabs->roof)) {
    t = pour_slab(out, i + 1 == count, t);
    if (!std::isfinite(t)) return false;
  } else if (floor_top && i + 1 < count) {
    Event e;
    e.kind = Event::Kind::kSlab;
    e.start_s = t;
    e.end_s = t += b.slab_stage_s;
    e.floor = out.floor;
    e.layer = out.layer;
    e.detail = "slab over floor " + std::to_string(out.floor);
    schedule_.events.push_back(e);
  }
  if (auto it = climb_after_.find({out.floor, out.layer}); it != climb_after_.end()) {
    const int c = it->second;
    const climb::ClimbStage& to = schedule_.stages[c + 1];
    Event e;
    e.kind = Event::Kind::kClimb;
    ClimbEvent ce;
    ce.from_stage = c;
    ce.to_stage = c + 1;
    ce.plan = climbs_[c];
    double ready_s = t;
    const double strength_mpa = project_.climber->anchor_strength_mpa;
    const floors::MaterialProfile& anchor_mix = project_.anchor_mix();
    const double age_needed_s = anchor_mix.age_for_strength_s(strength_mpa);
    for (const auto& a : to.anchors) {
      const auto cast = pipe_done_s_.find(pipe_key(a));
      const double cast_s = cast == pipe_done_s_.end() ? 0.0 : cast->second;
      const double strong_s = site::age_reached_s(anchor_maturity_ ? &*anchor_maturity_ : nullptr,
                                                  cast_s, age_needed_s);
      if (strong_s > ready_s + 1e-9) {
        ce.wait_reasons.push_back(
            {WaitKind::kAnchorStrength, strong_s - t,
             printf_string("anchor %s (unit %s, cast %s) reaches %.1f MPa %.1f h after it "
                           "was cast",
                           a.id.c_str(), project_.climber->units[a.unit].name.c_str(),
                           where_text(a.floor, a.layer).c_str(), strength_mpa,
                           age_needed_s / 3600.0)});
        ready_s = strong_s;
      }
    }
    if (!std::isfinite(age_needed_s)) {
      Infeasibility inf;
      inf.kind = InfeasibilityKind::kClimb;
      inf.floor = out.floor;
      inf.layer = out.layer;
      inf.message = printf_string(
          "climb %d -> %d: the material never reaches the anchors' strength of %.1f MPa", c, c + 1,
          strength_mpa);
      inf.fix = "a material that reaches the anchor strength, or a lower anchor_strength_mpa";
      fail(inf);
      return false;
    }
    // A climb is supervised (in working hours) and waits for calm air.
    const double wind_limit = project_.climber->climb_wind_limit_m_s;
    for (int pass = 0; pass < 1000 && (calendar_ || maturity_); ++pass) {
      double fit_s = ready_s;
      WaitKind kind = WaitKind::kOffShift;
      if (calendar_) fit_s = calendar_->fit_s(ready_s, ce.plan.duration_s);
      if (maturity_ && std::isfinite(fit_s) && fit_s <= ready_s + 1e-9) {
        fit_s = maturity_->fit_s(ready_s, ce.plan.duration_s,
                                 [wind_limit](const site::WeatherReading& r) {
                                   return rules::climbable_in(r.wind_m_s, wind_limit);
                                 });
        kind = WaitKind::kWind;
      }
      if (!std::isfinite(fit_s)) {
        Infeasibility inf;
        inf.kind = InfeasibilityKind::kCalendar;
        inf.floor = out.floor;
        inf.layer = out.layer;
        inf.message =
            kind == WaitKind::kWind
                ? printf_string(
                      "climb %d -> %d: the wind never again stays at or under the "
                      "machine's limit of %.1f m/s for its %.1f min",
                      c, c + 1, wind_limit, ce.plan.duration_s / 60.0)
                : printf_string(
                      "climb %d -> %d takes %.2f h, and no working window from %s "
                      "holds it (the longest is %.2f h)",
                      c, c + 1, ce.plan.duration_s / 3600.0, calendar_->local_text(ready_s).c_str(),
                      calendar_->longest_window_s() / 3600.0);
        inf.fix = kind == WaitKind::kWind ? "a weather forecast with calm spells, or a higher "
                                            "climb_wind_limit_m_s if the machine allows"
                                          : "longer working hours";
        fail(inf);
        return false;
      }
      if (fit_s <= ready_s + 1e-9) break;
      ce.wait_reasons.push_back(
          {kind, fit_s - t,
           kind == WaitKind::kWind
               ? printf_string("the wind exceeds the machine's climbing limit of %.1f m/s within "
                               "%.1f min of %s; calm from %s",
                               wind_limit, ce.plan.duration_s / 60.0, when_text(ready_s).c_str(),
                               when_text(fit_s).c_str())
               : printf_string("a climb is supervised: %s is off-shift; the next working hours "
                               "that hold its %.1f min start %s",
                               calendar_->local_text(ready_s).c_str(), ce.plan.duration_s / 60.0,
                               calendar_->local_text(fit_s).c_str()),
           ready_s - t});  // found once everything before it let the climb go
      ready_s = fit_s;
      stopped_since_below_ = true;
    }
    bind_wait_reasons(ce.wait_reasons);
    ce.wait_before_s = ready_s - t;
    ce.start_s = ready_s;
    ce.end_s = ready_s + ce.plan.duration_s;
    for (const auto& a : to.anchors) {
      const auto cast = pipe_done_s_.find(pipe_key(a));
      const double cast_s = cast == pipe_done_s_.end() ? 0.0 : cast->second;
      const double age_s = ce.start_s - cast_s;
      const double equivalent_s =
          anchor_maturity_ ? anchor_maturity_->age(cast_s, ce.start_s) : age_s;
      ce.anchors.push_back({a.id, project_.climber->units[a.unit].name, age_s,
                            anchor_mix.strength_at_mpa(equivalent_s), strength_mpa, equivalent_s});
    }
    ce.youngest_anchor_strength = detail::youngest_anchor_strength(
        ce, anchor_mix, anchor_maturity_ ? &*anchor_maturity_ : nullptr);
    if (!ce.plan.status) {
      Infeasibility inf;
      inf.kind = InfeasibilityKind::kClimb;
      inf.floor = out.floor;
      inf.layer = out.layer;
      inf.message = printf_string("climb %d -> %d: ", c, c + 1) + ce.plan.status.to_string();
      inf.fix = "see `ccbuild climb` for this building and machine";
      fail(inf);
    }
    e.start_s = ce.start_s;
    e.end_s = ce.end_s;
    e.floor = out.floor;
    e.layer = out.layer;
    e.detail = printf_string("climb from stage %d to %d", c, c + 1);
    e.crew = kClimbCrew;
    t = e.end_s;
    e.climb = std::move(ce);
    schedule_.events.push_back(std::move(e));
  }
  if (i + 1 < count) {
    t = place_lintels(i + 1, t);
    if (!std::isfinite(t)) return false;
  }
  ready_extra_s_ = t - out.end_s;
  return true;
}

Schedule Scheduler::run() {
  const auto started = Clock::now();
  prepare();
  const int count = static_cast<int>(slices_.size());
  for (int i = 0; i < count; ++i) {
    if (!schedule_layer(i) || !after_layer(i)) break;
    if (options_.progress && (i + 1) % 25 == 0)
      progress(printf_string("scheduled %d of %d layers", i + 1, count));
  }
  std::stable_sort(schedule_.events.begin(), schedule_.events.end(),
                   [](const Event& a, const Event& b) { return a.start_s < b.start_s; });
  // Quantities: each layer's concrete and peak flow, the deliveries of the material's batch.
  for (auto& l : schedule_.layers) {
    // As the JSON writes it, so that the deliveries recomputed from the JSON are these.
    l.concrete_m3 = rounded(layer_volume_m3(schedule_.plans.at(l.plan).layer,
                                            machine_.nozzle_width_m, l.z_top_m - l.z_bottom_m));
    l.peak_flow_m3_s = peak_flow_of(l.plan);
  }
  schedule_.deliveries = deliveries_of(schedule_.layers, material_.delivery_batch_m3);
  schedule_.totals = totals_of(schedule_.layers, schedule_.events);
  for (std::string& w :
       margin_warnings(schedule_, machine_, material_, {}, project_.building.units))
    schedule_.warnings.push_back(std::move(w));
  if (calendar_)
    schedule_.days =
        work_days(schedule_.layers, schedule_.events, schedule_.deliveries, *calendar_);
  schedule_.bookkeeping_s =
      seconds_since(started) - schedule_.layer_planning_s - schedule_.climb_planning_s;
  return std::move(schedule_);
}

}  // namespace detail

std::shared_ptr<PlanMemo> make_plan_memo() {
  return std::make_shared<PlanMemo>();
}

Schedule build_schedule(const Setup& project, const ScheduleOptions& given) {
  ScheduleOptions options = given;  // plans memoised, for the proof below
  if (!options.memo) options.memo = std::make_shared<PlanMemo>();
  detail::Scheduler first(project, options);
  Schedule s = first.run();
  // The maximum interval a failure proposes is proven by scheduling with it: the intervals
  // depend on the plans chosen before, so the first failing layer's interval alone may fall
  // short further up. Raised until the rule holds (a few tries, plans memoised), so that
  // the figure said, applied as written, passes the maximum interval.
  if (s.feasible || !s.infeasibility || s.infeasibility->kind != InfeasibilityKind::kMaxInterval ||
      !s.infeasibility->max_interval_needed_s)
    return s;
  Infeasibility& inf = *s.infeasibility;
  const double first_s = *inf.max_interval_needed_s;
  Setup tried = project;
  ScheduleOptions quiet = options;
  quiet.progress = nullptr;
  if (options.progress) options.progress("checking the proposed maximum interval");
  double needed_s = first_s;
  for (int attempt = 0; attempt < 4; ++attempt) {
    tried.material.max_layer_interval_s = needed_s;
    detail::Scheduler proof(tried, quiet);
    proof.take_slices_of(first);
    const Schedule t = proof.run();
    if (t.feasible || !t.infeasibility ||
        t.infeasibility->kind != InfeasibilityKind::kMaxInterval ||
        !t.infeasibility->max_interval_needed_s)
      break;
    needed_s = std::max(needed_s + 1.0, *t.infeasibility->max_interval_needed_s);
  }
  if (needed_s == first_s) return s;
  inf.max_interval_needed_s = needed_s;
  const std::string was = detail::max_interval_fix(first_s),
                    now = detail::max_interval_fix(needed_s);
  for (std::string* text : {&inf.fix, &inf.message})
    if (const auto at = text->find(was); at != std::string::npos)
      text->replace(at, was.size(), now);
  return s;
}

}  // namespace ccbuild::schedule
