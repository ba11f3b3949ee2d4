// A planned layer as text (plan_text.hpp).

#include "ccbuild/report/plan_text.hpp"

#include <cmath>

#include "ccbuild/common/format.hpp"

namespace ccbuild::report {

void write_multi_plan_text(std::ostream& out, const schedule::Project& project,
                           const ReportContext& context, const floors::Layer& layer,
                           const planner::MultiNozzlePlan& plan,
                           const planner::MultiNozzleOptions& options, const PlanTextOptions& o) {
  auto L = [&](double m) { return project.length(m, 3); };
  out << printf_string(
      "%s, %s: %zu walls, %d nozzles on %s rails, gantries %s wide%s\n", context.file.c_str(),
      context.where().c_str(), layer.segments.size(), options.nozzles, o.rail_axis.c_str(),
      L(options.gantry_width_m).c_str(),
      options.platform_width_m ? (", platform " + L(*options.platform_width_m)).c_str() : "");
  out << printf_string("  %-13s %s\n", "machine", project.machine_origin.c_str());
  if (plan.status) {
    out << printf_string("  %-13s %.2f s; one nozzle %.2f s: %.1f%% saved\n", "layer time",
                         plan.layer_time_s, plan.single_nozzle_time_s,
                         100.0 * (1.0 - plan.layer_time_s / plan.single_nozzle_time_s));
    out << printf_string("  %-13s %.2f s (busy time summed over nozzles)\n", "machine time",
                         plan.machine_time_s);
    out << printf_string("  %-13s %s (gantry width %s): collision-free\n", "min gap",
                         L(plan.min_gap_m).c_str(), L(options.gantry_width_m).c_str());
    if (plan.platform_travel_s > 0)
      out << printf_string("  %-13s %.2f s\n", "platform", plan.platform_travel_s);
  } else {
    out << printf_string("  %-13s none found (%s): %s\n", "plan",
                         planner::to_string(plan.status.code()).c_str(),
                         plan.status.reason().c_str());
  }
  for (std::size_t k = 0; k < plan.stages.size(); ++k) {
    const auto& stage = plan.stages[k];
    if (plan.stages.size() > 1)
      out << (stage.status
                  ? printf_string("  stage %zu       %s %s to %s, from %.2f s for %.2f s\n", k + 1,
                                  o.rail_axis.c_str(), L(stage.from_m).c_str(),
                                  L(stage.to_m).c_str(), stage.start_s, stage.time_s)
                  : printf_string("  stage %zu       %s %s to %s: no plan\n", k + 1,
                                  o.rail_axis.c_str(), L(stage.from_m).c_str(),
                                  L(stage.to_m).c_str()));
    out << printf_string("  %-13s %s\n", "method",
                         stage.status ? stage.method_detail.c_str() : "none");
    for (const auto& attempt : stage.attempts)
      out << printf_string("  %-13s %s\n", "", attempt.to_string().c_str());
    if (stage.faster_delay_s)
      out << printf_string(
          "  %-13s delay would take %.1f s against %.1f s (%s); not used: auto keeps the "
          "papers' order\n",
          "", *stage.faster_delay_s, stage.time_s, stage.faster_delay_detail.c_str());
    for (const auto& n : stage.nozzles) {
      out << printf_string(
          "  nozzle %-6d section %s %s to %s, %zu walls, start offset %d, busy %.2f s, waits "
          "%.2f s\n",
          n.nozzle + 1, o.rail_axis.c_str(), L(n.section_from_m).c_str(), L(n.section_to_m).c_str(),
          n.sequence.size(), n.start_offset, n.busy_s, n.wait_s);
      if (!n.sequence.empty())
        out << printf_string("  %-13s %s\n", "", signed_sequence(n.layer, n.sequence).c_str());
    }
  }
}

void write_layer_plan_text(std::ostream& out, const schedule::Project& project,
                           const ReportContext& context, const floors::Layer& layer,
                           const planner::LayerPlan& plan, const PlanTextOptions& o) {
  const auto& e = plan.evaluation;
  const machine::MachineModel& machine = project.machine_model();
  auto L = [&](double m) { return project.length(m); };
  out << printf_string("%s, %s: %zu walls\n", context.file.c_str(), context.where().c_str(),
                       layer.segments.size());
  out << printf_string("  %-13s %s, %s metric, %s objective, %s\n", "algorithm",
                       o.algorithm.c_str(), o.metric.c_str(), o.objective.c_str(),
                       plan.path.closed ? "closed tour" : "open path from the start vertex");
  out << printf_string("  %-13s %s\n", "machine", project.machine_origin.c_str());
  out << printf_string("  %-13s %s, %.2f s (%d lifts, %.1f turns of the nozzle)\n", "airtime",
                       L(e.airtime_distance_m).c_str(), e.airtime_s, e.lift_count,
                       e.total_rotation_rad / (2 * M_PI));
  out << printf_string("  %-13s %.2f s\n", "deposition", e.deposition_s);
  out << printf_string("  %-13s %.2f s\n", "layer time", e.layer_time_s);
  const double gap = plan.gap();
  out << printf_string(
      "  %-13s %s (%s), gap %s\n", "lower bound", L(plan.lower_bound_m).c_str(),
      planner::to_string(plan.lower_bound_source).c_str(),
      std::isnan(gap) ? "n/a (bound is 0)"
      : plan.objective == planner::Objective::kTime
          // The bound is on distance; the fastest tour may travel further to avoid lifts.
          ? printf_string("%.2f%% in distance (time objective)", 100.0 * gap).c_str()
          : printf_string("%.2f%%", 100.0 * gap).c_str());
  if (plan.connected_bound && o.connected_asked) {
    const planner::ConnectedBound& c = *plan.connected_bound;
    const bool out_of_time = c.stopped_by == planner::BoundStop::kTimeLimit;
    out << printf_string(
        "  %-13s %s after %d round%s (%s%s)\n", "connected", L(c.lower_bound_m).c_str(), c.rounds,
        c.rounds == 1 ? "" : "s", planner::to_string(c.stopped_by).c_str(),
        out_of_time ? ": the bound gets a third of --time-limit; a longer one runs more rounds"
                    : "");
    if (c.certificate)
      out << printf_string("  %-13s %s: %zu moats (tests/tools/check_bound.py %s re-checks it)\n",
                           "certificate", o.bound_certificate.c_str(), c.certificate->moats.size(),
                           o.bound_certificate.c_str());
  }
  out << printf_string(
      "  %-13s %.2f s (limit %.0f s)%s\n", "longest idle", e.max_idle_s,
      machine.nozzle_idle_limit_s,
      e.idle_limit_violations
          ? printf_string(": %d move(s) over the limit", e.idle_limit_violations).c_str()
          : "");
  out << printf_string(
      "  %-13s %.3f s, %s%s%s\n", "solve", plan.solve_s, planner::to_string(plan.stop).c_str(),
      plan.kicks ? printf_string(" after %ld kicks", plan.kicks).c_str() : "",
      plan.polish_kicks ? printf_string(", exact-time polish %ld kicks", *plan.polish_kicks).c_str()
                        : "");
  // An anytime answer depends on the machine's speed; these flags give it again without
  // the clock. Not when the clock came during a first descent (nothing to count then),
  // or before the time objective's polish could start.
  const bool cut_in_descent =
      planner::cut_short(plan.stop) &&
      (plan.objective == planner::Objective::kTime ? plan.polish_kicks.value_or(0) == 0
                                                   : plan.kicks == 0);
  if (o.anytime && o.algorithm == "cc-tsp" && !cut_in_descent)
    out << printf_string(
        "  %-13s --max-kicks %ld%s (the same plan without the clock)\n", "replay", plan.kicks,
        plan.polish_kicks ? printf_string(" --polish-kicks %ld", *plan.polish_kicks).c_str() : "");
  out << printf_string("  %-13s %s\n", "sequence", signed_sequence(layer, plan.sequence).c_str());
  if (!o.drawing.empty()) out << printf_string("  %-13s %s\n", "drawing", o.drawing.c_str());
}

}  // namespace ccbuild::report
