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

std::string MethodAttempt::to_string() const {
  return planner::to_string(method) + ": " + status.to_string();
}

namespace {

detail::MethodResult run_method(MultiMethod method, const detail::StageContext& ctx) {
  switch (method) {
    case MultiMethod::kPathCycling:
      return detail::path_cycling(ctx);
    case MultiMethod::kGlobalPathCycling:
      return detail::global_path_cycling(ctx);
    case MultiMethod::kBufferZonePathCycling:
      return detail::buffer_zone_path_cycling(ctx);
    case MultiMethod::kAuxBufferZone:
      return detail::aux_buffer_zone(ctx);
    case MultiMethod::kDelay:
      return detail::delay_method(ctx);
    case MultiMethod::kAuto:
      break;
  }
  CCBUILD_CHECK(false, "auto is not a method of its own");
  return {};
}

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
  stage.status = {PlanStatus::Code::kNotApplicable, "no method was tried"};
  for (MultiMethod method : order) {
    // A method started after the time limit would only report it again.
    if (!stage.attempts.empty()) {
      if (PlanStatus late = detail::stop_status(ctx, "the methods before it"); !late) {
        stage.attempts.push_back({method, late});
        stage.status = std::move(late);
        break;
      }
    }
    detail::MethodResult result = run_method(method, ctx);
    stage.attempts.push_back({method, result.status});
    if (!result.status) {
      stage.status = std::move(result.status);
      continue;
    }
    stage.status = PlanStatus();
    stage.method = method;
    stage.method_detail = result.detail.empty() ? to_string(method) : result.detail;
    stage.nozzles = std::move(result.paths);
    stage.vertex_count = result.vertices;
    double gap = 0.0;
    const std::string problem = detail::verify(ctx, stage.nozzles, gap);
    CCBUILD_CHECK(problem.empty(), "a returned multi-nozzle plan passes the exact check");
    stage.min_gap_m = gap;
    stage.time_s = detail::stage_time_s(stage.nozzles);
    // auto keeps the papers' order, but says so when our delay method would have been
    // faster than the papers' method it used.
    if (ctx.options.method == MultiMethod::kAuto && ctx.options.compare_with_delay &&
        method != MultiMethod::kDelay && !ctx.stop.should_stop()) {
      const detail::MethodResult alternative = detail::delay_method(ctx);
      if (alternative.status) {
        const double t = detail::stage_time_s(alternative.paths);
        if (t < stage.time_s - 1e-6) {
          stage.faster_delay_s = t;
          stage.faster_delay_detail = alternative.detail;
        }
      }
    }
    return stage;
  }
  return stage;
}

// The stage's waypoints in layer time, one list per nozzle.
void add_waypoints(Stage& stage, const machine::MachineModel& machine, Metric metric, double z_m) {
  for (auto& nozzle : stage.nozzles) {
    if (nozzle.sequence.empty()) {
      Waypoint parked;
      parked.t_s = stage.start_s;
      parked.position_m = nozzle.timeline.positions().front();
      parked.z_m = z_m;
      nozzle.waypoints = {parked};
      continue;
    }
    const CostModel model(nozzle.layer, machine, metric);
    nozzle.waypoints =
        waypoints_of(model, nozzle.sequence, PathSpec::closed_tour(), nozzle.evaluation, z_m,
                     stage.start_s, nozzle.wait_before_step_s);
  }
}

}  // namespace

MultiNozzlePlan plan_layer_multi(const floors::Layer& layer, const machine::MachineModel& machine,
                                 const MultiNozzleOptions& requested) {
  // No single-nozzle bound is reported here, and the sections' tours, the delay method's
  // lone tour and the single-nozzle reference are many: the cheap bound serves them all.
  MultiNozzleOptions options = requested;
  // Sections and the one-nozzle reference keep the 2-opt/Or-opt search: the methods'
  // splits and checks were tuned on its tours, and the Lin–Kernighan search has not been
  // measured on them (issue 14 left them).
  options.planning.neighbourhood = Neighbourhood::kTwoOptOrOpt;
  options.planning.bound = BoundKind::kMatching;
  // The time limit is shared by every section's search and every method after them: a
  // section searching until it (anytime) left the methods no time and no plan.
  options.planning.anytime = false;
  const int n = options.nozzles;
  const double w = options.gantry_width_m;
  if (n < 2 || n > kMaxNozzles)
    throw InputError("", 0, "MultiNozzleOptions::nozzles",
                     "must be from 2 to " + std::to_string(kMaxNozzles) +
                         " for multi-nozzle planning, got " + std::to_string(n));
  if (!(w > 0.0) || !std::isfinite(w))
    throw InputError("", 0, "MultiNozzleOptions::gantry_width_m", "must be positive");
  if (!(options.buffer_width_factor > 1.0) || !std::isfinite(options.buffer_width_factor))
    throw InputError("", 0, "MultiNozzleOptions::buffer_width_factor", "must exceed 1");
  if (!(options.planning.time_limit_s > 0.0))
    throw InputError("", 0, "PlanOptions::time_limit_s", "must be positive");
  if (layer.segments.empty())
    throw InputError("", 0, "layer", "has no walls to plan (every wall is inside an opening?)");
  const RailAxis axis = options.rail_axis;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& p : layer.points) {
    lo = std::min(lo, rail_coordinate(p, axis));
    hi = std::max(hi, rail_coordinate(p, axis));
  }
  // The rails: as long as the machine's axis along them, centred on the layout.
  const auto& rail_joint = rail_axis_limits(machine, axis);
  const double rails = rail_joint.max_m - rail_joint.min_m;
  // Gantries fit when their centres can stand a gantry width apart: n - 1 gaps.
  if ((n - 1) * w >= rails)
    throw InputError("", 0, "MultiNozzleOptions::nozzles",
                     std::to_string(n) + " gantries " + detail::length(options, w) +
                         " wide do not fit on the machine's " + detail::length(options, rails) +
                         " of rails");
  if (hi - lo > rails)
    throw InputError("", 0, "MultiNozzleOptions::rail_axis",
                     "the layout is " + detail::length(options, hi - lo) + " long along " +
                         to_string(axis) + " but the rails reach " +
                         detail::length(options, rails) +
                         "; use a platform or a machine with longer rails");
  const double rail_mid = 0.5 * (lo + hi);
  if (options.platform_width_m) {
    const double p = *options.platform_width_m;
    if (!(p > 0.0) || !std::isfinite(p))
      throw InputError("", 0, "MultiNozzleOptions::platform_width_m", "must be positive");
    if ((n - 1) * w >= p)
      throw InputError("", 0, "MultiNozzleOptions::platform_width_m",
                       std::to_string(n) + " gantries " + detail::length(options, w) +
                           " wide do not fit on a " + detail::length(options, p) + " platform");
  }

  const StopCondition stop(options.planning.time_limit_s, options.planning.cancel);
  MultiNozzlePlan plan;
  if (options.single_nozzle_time_s) {
    plan.single_nozzle_time_s = *options.single_nozzle_time_s;
  } else if (options.plan_single_nozzle_reference) {
    PlanOptions single = options.planning;
    single.algorithm = Algorithm::kCcTsp;
    single.path = PathSpec::closed_tour();
    single.waypoints = false;  // only its time is kept
    // The reference takes a share of the time, not all of it.
    single.time_limit_s = std::max(0.01, 0.25 * stop.remaining_s());
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

  plan.status = PlanStatus();
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
    if (!stage.status) {
      if (plan.status)
        plan.status = {
            stage.status.code(),
            "stage " + std::to_string(k + 1) + " (" + detail::length(options, strips[k].first) +
                " to " + detail::length(options, strips[k].second) +
                "): no method found a collision-free plan; the last: " + stage.status.reason()};
    } else {
      if (!plan.stages.empty()) {
        // The platform moves from one stage's middle to the next along the rails.
        const double distance = 0.5 * (stage.from_m + stage.to_m) -
                                0.5 * (plan.stages.back().from_m + plan.stages.back().to_m);
        const double speed = rail_axis_limits(machine, axis).speed_m_s;
        const double travel_s = std::abs(distance) / speed + machine.accel_delay_s;
        plan.platform_travel_s += travel_s;
        plan.layer_time_s += travel_s;
      }
      stage.start_s = plan.layer_time_s;
      add_waypoints(stage, machine, options.planning.metric, layer.z_top_m);
      plan.layer_time_s += stage.time_s;
      plan.vertex_count += stage.vertex_count;
      plan.min_gap_m = std::min(plan.min_gap_m, stage.min_gap_m);
      for (const auto& nozzle : stage.nozzles) plan.machine_time_s += nozzle.busy_s;
    }
    plan.stages.push_back(std::move(stage));
  }
  return plan;
}

}  // namespace ccbuild::planner
