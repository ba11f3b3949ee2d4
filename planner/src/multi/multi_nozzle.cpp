#include <algorithm>
#include <cmath>
#include <numeric>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/planner/multi_nozzle.hpp"
#include "multi_internal.hpp"

namespace ccbuild::planner {

std::string to_string(MultiMethod method) {
  switch (method) {
    case MultiMethod::kAuto:
      return "auto";
    case MultiMethod::kPathCycling:
      return "path-cycling";
    case MultiMethod::kGlobalPathCycling:
      return "global-path-cycling";
    case MultiMethod::kBufferZonePathCycling:
      return "bz-path-cycling";
    case MultiMethod::kAuxBufferZone:
      return "aux-buffer-zone";
    case MultiMethod::kDelay:
      return "delay";
  }
  return "?";
}

std::optional<MultiMethod> parse_multi_method(const std::string& text) {
  for (MultiMethod m :
       {MultiMethod::kAuto, MultiMethod::kPathCycling, MultiMethod::kGlobalPathCycling,
        MultiMethod::kBufferZonePathCycling, MultiMethod::kAuxBufferZone, MultiMethod::kDelay})
    if (to_string(m) == text) return m;
  return std::nullopt;
}

namespace {

using detail::rail_coordinate;

// Plans one stage with the chosen method (auto: the papers' order, then delay).
Stage plan_stage(detail::StageContext& ctx) {
  Stage stage;
  stage.from_m = ctx.from_m;
  stage.to_m = ctx.to_m;
  std::vector<MultiMethod> order;
  if (ctx.options.method == MultiMethod::kAuto)
    order = {MultiMethod::kPathCycling, MultiMethod::kBufferZonePathCycling,
             MultiMethod::kAuxBufferZone, MultiMethod::kDelay};
  else
    order = {ctx.options.method};
  for (MultiMethod method : order) {
    std::string why, detail;
    int vertices = 0;
    std::optional<std::vector<NozzlePath>> paths;
    switch (method) {
      case MultiMethod::kPathCycling:
        paths = detail::path_cycling(ctx, why, vertices);
        break;
      case MultiMethod::kGlobalPathCycling:
        paths = detail::global_path_cycling(ctx, why, vertices);
        break;
      case MultiMethod::kBufferZonePathCycling:
        paths = detail::buffer_zone_path_cycling(ctx, why, vertices);
        break;
      case MultiMethod::kAuxBufferZone:
        paths = detail::aux_buffer_zone(ctx, why, vertices);
        break;
      case MultiMethod::kDelay:
        paths = detail::delay_method(ctx, why, vertices, detail);
        break;
      case MultiMethod::kAuto:
        break;
    }
    if (!paths) {
      stage.attempts.push_back(to_string(method) + ": " + why);
      continue;
    }
    stage.method = method;
    stage.method_detail = detail.empty() ? to_string(method) : detail;
    stage.attempts.push_back(to_string(method) + ": collision-free");
    stage.nozzles = std::move(*paths);
    stage.vertex_count = vertices;
    double gap = 0.0;
    const std::string problem = detail::verify(ctx, stage.nozzles, gap);
    CCBUILD_CHECK(problem.empty(), "a returned multi-nozzle plan passes the exact check");
    stage.min_gap_m = gap;
    stage.time_s = detail::stage_time_s(stage.nozzles);
    // auto keeps the papers' order, but says so when our delay method would have been
    // faster than the papers' method it used.
    if (ctx.options.method == MultiMethod::kAuto && method != MultiMethod::kDelay &&
        !ctx.stop.should_stop()) {
      std::string delay_why, delay_detail;
      int delay_vertices = 0;
      if (const auto alternative =
              detail::delay_method(ctx, delay_why, delay_vertices, delay_detail)) {
        const double t = detail::stage_time_s(*alternative);
        if (t < stage.time_s - 1e-6) {
          stage.faster_delay_s = t;
          stage.attempts.push_back("delay: would take " + seconds(t) + " against " +
                                   seconds(stage.time_s) + " (" + delay_detail +
                                   "); not used: auto keeps the papers' order");
        }
      }
    }
    return stage;
  }
  return stage;
}

}  // namespace

MultiNozzlePlan plan_layer_multi(const floors::Layer& layer, const machine::MachineModel& machine,
                                 const MultiNozzleOptions& requested) {
  // No single-nozzle bound is reported here, and the sections' tours, the delay method's
  // lone tour and the single-nozzle reference are many: the cheap bound serves them all.
  MultiNozzleOptions options = requested;
  options.planning.bound = BoundKind::kMatching;
  const int n = options.nozzles;
  const double w = options.gantry_width_m;
  if (n < 2) throw InputError("", 0, "--nozzles", "must be at least 2 for multi-nozzle planning");
  if (!(w > 0.0)) throw InputError("", 0, "--gantry-width", "must be positive");
  if (!(options.buffer_width_factor > 1.0))
    throw InputError("", 0, "buffer_width_factor", "must exceed 1");
  if (layer.segments.empty()) throw InputError("", 0, "layer", "has no walls to plan");
  const RailAxis axis = options.rail_axis;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& p : layer.points) {
    lo = std::min(lo, rail_coordinate(p, axis));
    hi = std::max(hi, rail_coordinate(p, axis));
  }
  // The rails: as long as the machine's axis along them, centred on the layout.
  const auto& rail_joint = axis == RailAxis::kX ? machine.x : machine.y;
  const double rails = rail_joint.max_m - rail_joint.min_m;
  if ((n - 1) * w >= rails)
    throw InputError("", 0, "--nozzles",
                     std::to_string(n) + " gantries " + metres(w, 2) +
                         " wide do not fit on the machine's " + metres(rails, 2) + " of rails");
  if (hi - lo > rails)
    throw InputError("", 0, "--rail-axis",
                     "the layout is " + metres(hi - lo, 2) + " long along " + to_string(axis) +
                         " but the rails reach " + metres(rails, 2) +
                         "; use --platform-width or a machine with longer rails");
  const double rail_mid = 0.5 * (lo + hi);
  if (options.platform_width_m) {
    const double p = *options.platform_width_m;
    if (!(p > 0.0)) throw InputError("", 0, "--platform-width", "must be positive");
    if ((n - 1) * w >= p)
      throw InputError("", 0, "--platform-width",
                       std::to_string(n) + " gantries " + metres(w, 2) + " wide do not fit on a " +
                           metres(p, 2) + " platform");
  }

  const StopCondition stop(options.planning.time_limit_s, options.planning.cancel);
  MultiNozzlePlan plan;
  if (options.single_nozzle_time_s) {
    plan.single_nozzle_time_s = *options.single_nozzle_time_s;
  } else {
    PlanOptions single = options.planning;
    single.algorithm = Algorithm::kCcTsp;
    single.path = PathSpec::closed_tour();
    single.time_limit_s = std::max(0.05, std::min(single.time_limit_s, stop.remaining_s()));
    plan.single_nozzle_time_s = plan_layer(layer, machine, single).evaluation.layer_time_s;
  }

  // Stages: the whole layer, or platform-wide strips of equal width.
  std::vector<std::pair<double, double>> strips{{lo, hi}};
  if (options.platform_width_m && hi - lo > *options.platform_width_m) {
    const int count = static_cast<int>(std::ceil((hi - lo) / *options.platform_width_m - 1e-9));
    strips.clear();
    for (int k = 0; k < count; ++k)
      strips.emplace_back(lo + (hi - lo) * k / count, lo + (hi - lo) * (k + 1) / count);
  }
  std::vector<double> strip_cuts;
  for (std::size_t k = 1; k < strips.size(); ++k) strip_cuts.push_back(strips[k].first);
  const detail::CutLayer by_strip = detail::cut_layer(layer, axis, strip_cuts);

  plan.collision_free = true;
  plan.min_gap_m = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < strips.size(); ++k) {
    const std::vector<int> segments = by_strip.segments_in(static_cast<int>(k));
    if (segments.empty()) continue;
    detail::StageContext ctx{
        machine,         options,          stop, floors::sub_layer(by_strip.layer, segments),
        strips[k].first, strips[k].second, 0.0,  0.0,
        nullptr,         nullptr};
    if (options.platform_width_m) {
      const double mid = 0.5 * (strips[k].first + strips[k].second);
      ctx.rail_min_m = mid - 0.5 * *options.platform_width_m;
      ctx.rail_max_m = mid + 0.5 * *options.platform_width_m;
    } else {
      ctx.rail_min_m = rail_mid - 0.5 * rails;
      ctx.rail_max_m = rail_mid + 0.5 * rails;
    }
    Stage stage = plan_stage(ctx);
    if (stage.nozzles.empty()) {
      plan.collision_free = false;
      plan.failure = "stage " + std::to_string(k + 1) + " (" + metres(strips[k].first, 2) + " to " +
                     metres(strips[k].second, 2) + "): no method found a collision-free plan";
    } else {
      plan.layer_time_s += stage.time_s;
      plan.vertex_count += stage.vertex_count;
      plan.min_gap_m = std::min(plan.min_gap_m, stage.min_gap_m);
      for (const auto& nozzle : stage.nozzles) plan.machine_time_s += nozzle.busy_s;
      if (!plan.stages.empty()) {
        // The platform moves from one stage's middle to the next along the rails.
        const double distance = 0.5 * (stage.from_m + stage.to_m) -
                                0.5 * (plan.stages.back().from_m + plan.stages.back().to_m);
        const double speed = axis == RailAxis::kX ? machine.x.speed_m_s : machine.y.speed_m_s;
        plan.platform_travel_s += std::abs(distance) / speed + machine.accel_delay_s;
      }
    }
    plan.stages.push_back(std::move(stage));
  }
  plan.layer_time_s += plan.platform_travel_s;
  return plan;
}

}  // namespace ccbuild::planner
