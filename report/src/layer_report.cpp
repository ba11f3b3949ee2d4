#include "ccbuild/report/layer_report.hpp"

#include <cmath>
#include <stdexcept>

#include "ccbuild/common/format.hpp"
#include "report_common.hpp"
#include "svg.hpp"

namespace ccbuild::report {

using detail::json;
using detail::rounded;

std::string ReportContext::where() const {
  return layer ? "floor " + std::to_string(floor) + " layer " + std::to_string(*layer)
               : "all walls whole";
}

std::string signed_step(const floors::Layer& layer, const planner::Step& step) {
  const auto& s = layer.segments[step.segment];
  std::string text;
  if (step.reversed) text.push_back('-');
  text.append(std::to_string(s.wall_id));
  if (s.piece_count > 1) text.append(":").append(std::to_string(s.piece + 1));
  return text;
}

std::string signed_sequence(const floors::Layer& layer, const planner::Sequence& sequence) {
  std::string text;
  for (const auto& step : sequence) {
    if (!text.empty()) text += ' ';
    text += signed_step(layer, step);
  }
  return text;
}

nlohmann::ordered_json layer_plan_json(const ReportContext& context, const floors::Layer& layer,
                                       const machine::MachineModel& machine,
                                       const planner::LayerPlan& plan) {
  const auto& e = plan.evaluation;
  json out = detail::header_json(context, layer, "ccbuild-layer-plan-1");
  out["machine"] = detail::machine_json(machine);
  out["pieces"] = detail::pieces_json(layer, machine.nozzle_width_m);
  out["nozzles"] = 1;
  out["algorithm"] = planner::to_string(plan.algorithm);
  out["metric"] = planner::to_string(plan.metric);
  out["objective"] = planner::to_string(plan.objective);
  out["closed"] = plan.path.closed;
  out["start_m"] = plan.path.closed ? json(nullptr) : detail::point_json(plan.path.start_m);
  out["piece_count"] = layer.segments.size();
  out["airtime_distance_m"] = rounded(e.airtime_distance_m);
  out["airtime_s"] = rounded(e.airtime_s);
  out["deposition_s"] = rounded(e.deposition_s);
  out["layer_time_s"] = rounded(e.layer_time_s);
  out["lower_bound_distance_m"] = rounded(plan.lower_bound_m);
  out["lower_bound_source"] = planner::to_string(plan.lower_bound_source);
  const double gap = plan.gap();
  out["gap_fraction"] = std::isnan(gap) ? json(nullptr) : json(rounded(gap));
  out["solve_s"] = rounded(plan.solve_s);
  out["stopped_by"] = planner::to_string(plan.stop);
  out["kicks"] = plan.kicks;
  out["polish_kicks"] = plan.polish_kicks ? json(*plan.polish_kicks) : json(nullptr);
  out["max_idle_s"] = rounded(e.max_idle_s);
  out["idle_limit_s"] = rounded(machine.nozzle_idle_limit_s);
  out["idle_limit_violations"] = e.idle_limit_violations;
  out["lift_count"] = e.lift_count;
  out["total_rotation_rad"] = rounded(e.total_rotation_rad);
  out["sequence"] = detail::sequence_json(layer, plan.sequence);
  json moves = json::array();
  for (const auto& m : e.moves) {
    moves.push_back({{"from_m", detail::point_json(m.from_m)},
                     {"to_m", detail::point_json(m.to_m)},
                     {"distance_m", rounded(m.distance_m)},
                     {"time_s", rounded(m.time_s)},
                     {"lifted", m.lifted},
                     {"rotation_rad", rounded(m.rotation_rad)}});
  }
  out["moves"] = moves;
  out["waypoints"] = detail::waypoints_json(plan.waypoints);
  return out;
}

nlohmann::ordered_json bound_certificate_json(const ReportContext& context,
                                              const floors::Layer& layer,
                                              const planner::LayerPlan& plan) {
  if (!plan.connected_bound || !plan.connected_bound->certificate)
    throw std::logic_error("bound_certificate_json: the plan kept no certificate");
  const planner::ConnectedBound& bound = *plan.connected_bound;
  const planner::ConnectedBoundCertificate& c = *bound.certificate;
  json out = detail::header_json(context, layer, "ccbuild-bound-certificate-1");
  out["metric"] = planner::to_string(plan.metric);
  out["closed"] = c.start < 0;
  out["lower_bound_distance_m"] = bound.lower_bound_m;
  out["rounds"] = bound.rounds;
  out["stopped_by"] = planner::to_string(bound.stopped_by);
  out["pieces"] = detail::pieces_json(layer);
  // Unrounded: a bound re-checked on rounded points would not be the one proven.
  json points = json::array();
  for (const auto& p : c.points_m) points.push_back(json::array({p.x(), p.y()}));
  out["points_m"] = std::move(points);
  json walls = json::array();
  for (const auto& s : layer.segments) walls.push_back(json::array({s.start_point, s.end_point}));
  out["walls"] = std::move(walls);
  out["start_point"] = c.start < 0 ? json(nullptr) : json(c.start);
  out["free_end_point"] = c.start < 0 ? json(nullptr) : json(c.points_m.size());
  json moats = json::array();
  for (const auto& m : c.moats)
    moats.push_back({{"points", m.points},
                     {"rhs", static_cast<int>(m.rhs)},
                     {"width_m", m.width_m},
                     {"exact", m.exact}});
  out["moats"] = std::move(moats);
  return out;
}

std::string layer_plan_svg(const ReportContext& context, const floors::Layer& layer,
                           const planner::LayerPlan& plan) {
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  detail::extend(lo, hi, layer);
  if (!plan.path.closed) {
    lo = lo.cwiseMin(plan.path.start_m);
    hi = hi.cwiseMax(plan.path.start_m);
  }
  const double margin_left = 70.0, top = 70.0;
  const detail::PlanView view = detail::plan_view(lo, hi, margin_left, top, 860.0);
  const double width = std::max(720.0, margin_left + view.width_px() + 60.0);
  const double bottom = top + view.height_px();
  const double legend_top = bottom + 72.0;
  svg::Document doc(width, legend_top + 100.0);
  const auto& e = plan.evaluation;
  const double u = floors::meters_per(context.unit);
  const std::string unit = floors::to_string(context.unit);
  doc.text(10, 22, svg::fit(context.file + ", " + context.where(), width - 20, 15, true), 15,
           "id=\"title\" font-weight=\"bold\"");
  doc.text(10, 42,
           svg::fit(printf_string("one nozzle, %s %s, %s objective: airtime %.2f %s / %.1f s, "
                                  "deposition %.1f s, layer %.1f s, %d lifts",
                                  planner::to_string(plan.algorithm).c_str(),
                                  planner::to_string(plan.metric).c_str(),
                                  planner::to_string(plan.objective).c_str(),
                                  e.airtime_distance_m / u, unit.c_str(), e.airtime_s,
                                  e.deposition_s, e.layer_time_s, e.lift_count),
                    width - 20, 12),
           12, "id=\"subtitle\"");
  detail::draw_axes(doc, view, context.unit);
  const double font = std::clamp(view.scale_px_per_m * 0.35, 8.0, 12.0);
  // Walls light, so the air moves drawn over them stay visible along them.
  std::string walls =
      "<g id=\"walls\" stroke=\"#b8b8b8\" stroke-width=\"5\" stroke-linecap=\"round\">\n";
  std::string arrows = "<g id=\"arrows\">\n";
  for (const auto& step : plan.sequence) {
    const auto& s = layer.segments[step.segment];
    Eigen::Vector2d a = layer.start_m(s), b = layer.end_m(s);
    if (step.reversed) std::swap(a, b);
    walls += "<line x1=\"" + svg::px(view.X(a.x())) + "\" y1=\"" + svg::px(view.Y(a.y())) +
             "\" x2=\"" + svg::px(view.X(b.x())) + "\" y2=\"" + svg::px(view.Y(b.y())) + "\"" +
             detail::bead_stroke(view, s) + "/>\n";
    arrows += detail::arrowhead(view, a, b, "#333");
  }
  doc.raw(walls + "</g>\n" + arrows + "</g>\n<g id=\"wall-ids\">\n");
  for (const auto& step : plan.sequence) {
    const auto& s = layer.segments[step.segment];
    detail::wall_label(doc, view, layer.start_m(s), layer.end_m(s),
                       signed_step(layer, {step.segment, false}), "#555", font);
  }
  doc.raw(
      "</g>\n<g id=\"air-moves\" fill=\"none\" stroke-width=\"1.6\" stroke-dasharray=\"5,4\">\n");
  for (const auto& m : e.moves) {
    if (m.distance_m <= 1e-9) continue;
    const char* colour = m.lifted ? "#d62728" : "#1f77b4";
    std::string points = svg::px(view.X(m.from_m.x())) + "," + svg::px(view.Y(m.from_m.y())) + " ";
    if (plan.metric == planner::Metric::kRectilinear)
      points += svg::px(view.X(m.to_m.x())) + "," + svg::px(view.Y(m.from_m.y())) + " ";
    points += svg::px(view.X(m.to_m.x())) + "," + svg::px(view.Y(m.to_m.y()));
    doc.raw("<polyline stroke=\"" + std::string(colour) + "\" points=\"" + points + "\"/>\n");
  }
  doc.raw("</g>\n");
  const Eigen::Vector2d start =
      plan.path.closed && !plan.sequence.empty()
          ? (plan.sequence.front().reversed
                 ? layer.end_m(layer.segments[plan.sequence.front().segment])
                 : layer.start_m(layer.segments[plan.sequence.front().segment]))
          : plan.path.start_m;
  doc.raw("<circle id=\"start\" cx=\"" + svg::px(view.X(start.x())) + "\" cy=\"" +
          svg::px(view.Y(start.y())) + "\" r=\"7\" fill=\"#2ca02c\" fill-opacity=\"0.85\"/>\n");
  detail::draw_scale_bar(doc, view, margin_left, bottom + 46.0, context.unit);
  const double legend_height =
      doc.legend(10, legend_top, width - 20,
                 {{"line", "#b8b8b8",
                   "wall (arrow: deposition direction; 12 = wall id, 12:2 = its 2nd piece)"},
                  {"dashed", "#1f77b4", "air move"},
                  {"dashed", "#d62728", "air move lifted over built walls"},
                  {"dot", "#2ca02c", plan.path.closed ? "start and end of the tour" : "start"}});
  doc.set_height(legend_top + legend_height + 10.0);
  return doc.str();
}

}  // namespace ccbuild::report
