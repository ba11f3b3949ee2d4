#include "ccbuild/report/multi_report.hpp"

#include <cmath>
#include <limits>

#include "ccbuild/common/format.hpp"
#include "report_common.hpp"
#include "svg.hpp"

namespace ccbuild::report {
namespace {

using detail::json;
using detail::rounded;

const char* colour(int nozzle) {
  static const char* palette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                                  "#ff7f0e", "#8c564b", "#e377c2"};
  return palette[nozzle % 7];
}

// A time for axis labels: seconds under 10 minutes, else minutes.
struct TimeAxis {
  double per = 1.0;
  std::string unit = "s";
};
TimeAxis time_axis(double end_s) {
  return end_s > 600.0 ? TimeAxis{60.0, "min"} : TimeAxis{1.0, "s"};
}

}  // namespace

nlohmann::ordered_json multi_plan_json(const ReportContext& context, const floors::Layer& layer,
                                       const machine::MachineModel& machine,
                                       const planner::MultiNozzlePlan& plan,
                                       const planner::MultiNozzleOptions& options) {
  json out = detail::header_json(context, layer, "ccbuild-layer-plan-1");
  out["machine"] = detail::machine_json(machine);
  out["pieces"] = detail::pieces_json(layer, machine.nozzle_width_m);
  out["nozzles"] = options.nozzles;
  out["gantry_width_m"] = rounded(options.gantry_width_m);
  out["rail_axis"] = planner::to_string(options.rail_axis);
  out["requested_method"] = planner::to_string(options.method);
  out["platform_width_m"] =
      options.platform_width_m ? json(rounded(*options.platform_width_m)) : json(nullptr);
  out["metric"] = planner::to_string(options.planning.metric);
  out["objective"] = planner::to_string(options.planning.objective);
  out["status"] = planner::to_string(plan.status.code());
  out["status_reason"] = plan.status.reason();
  const bool solved = static_cast<bool>(plan.status);
  out["layer_time_s"] = solved ? json(rounded(plan.layer_time_s)) : json(nullptr);
  out["single_nozzle_layer_time_s"] = rounded(plan.single_nozzle_time_s);
  out["saved_fraction"] = plan.single_nozzle_time_s > 0 && solved
                              ? json(rounded(1.0 - plan.layer_time_s / plan.single_nozzle_time_s))
                              : json(nullptr);
  out["machine_time_s"] = solved ? json(rounded(plan.machine_time_s)) : json(nullptr);
  out["platform_travel_s"] = rounded(plan.platform_travel_s);
  out["min_gap_m"] =
      solved && std::isfinite(plan.min_gap_m) ? json(rounded(plan.min_gap_m)) : json(nullptr);
  out["vertex_count"] = plan.vertex_count;
  json stages = json::array();
  for (const auto& stage : plan.stages) {
    json s;
    s["from_m"] = rounded(stage.from_m);
    s["to_m"] = rounded(stage.to_m);
    s["status"] = planner::to_string(stage.status.code());
    s["status_reason"] = stage.status.reason();
    s["method"] = stage.status ? json(planner::to_string(stage.method)) : json(nullptr);
    s["method_detail"] = stage.method_detail;
    json attempts = json::array();
    for (const auto& a : stage.attempts)
      attempts.push_back({{"method", planner::to_string(a.method)},
                          {"status", planner::to_string(a.status.code())},
                          {"reason", a.status.reason()}});
    s["attempts"] = attempts;
    s["faster_delay_s"] =
        stage.faster_delay_s ? json(rounded(*stage.faster_delay_s)) : json(nullptr);
    s["start_s"] = rounded(stage.start_s);
    s["time_s"] = rounded(stage.time_s);
    s["min_gap_m"] = stage.status && std::isfinite(stage.min_gap_m) ? json(rounded(stage.min_gap_m))
                                                                    : json(nullptr);
    json nozzles = json::array();
    for (const auto& n : stage.nozzles) {
      json j;
      j["nozzle"] = n.nozzle + 1;
      j["section_m"] = {rounded(n.section_from_m), rounded(n.section_to_m)};
      j["sequence"] = detail::sequence_json(n.layer, n.sequence);
      j["zones"] = n.zones;
      j["start_offset"] = n.start_offset;
      json waits = json::array();
      for (std::size_t k = 0; k < n.sequence.size() && k < n.wait_before_step_s.size(); ++k)
        if (n.wait_before_step_s[k] > 0)
          waits.push_back({{"before_step", k + 1}, {"wait_s", rounded(n.wait_before_step_s[k])}});
      j["waits"] = waits;
      j["busy_s"] = rounded(n.busy_s);
      j["wait_s"] = rounded(n.wait_s);
      j["finish_s"] = rounded(stage.start_s + n.finish_s);
      j["airtime_s"] = rounded(n.evaluation.airtime_s);
      j["deposition_s"] = rounded(n.evaluation.deposition_s);
      j["max_idle_s"] = rounded(n.evaluation.max_idle_s);
      j["waypoints"] = detail::waypoints_json(n.waypoints);
      nozzles.push_back(j);
    }
    s["nozzles"] = nozzles;
    stages.push_back(s);
  }
  out["stages"] = stages;
  return out;
}

std::string multi_plan_svg(const ReportContext& context, const floors::Layer& layer,
                           const planner::MultiNozzlePlan& plan,
                           const planner::MultiNozzleOptions& options) {
  const planner::RailAxis axis = options.rail_axis;
  const bool solved = static_cast<bool>(plan.status);
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  detail::extend(lo, hi, layer);
  double end_s = 0.0;
  for (const auto& stage : plan.stages)
    for (const auto& n : stage.nozzles)
      for (const auto& w : n.waypoints) {
        lo = lo.cwiseMin(w.position_m);
        hi = hi.cwiseMax(w.position_m);
        end_s = std::max(end_s, w.t_s);
      }
  end_s = std::max({end_s, plan.layer_time_s, 1.0});
  const double margin_left = 70.0, top = 70.0;
  const detail::PlanView view = detail::plan_view(lo, hi, margin_left, top, 800.0);
  const double width = std::max(760.0, margin_left + view.width_px() + 60.0);
  const double plan_bottom = top + view.height_px();
  const double u = floors::meters_per(context.unit);
  const std::string unit = floors::to_string(context.unit);
  svg::Document doc(width, plan_bottom + 600.0);
  doc.text(10, 22, svg::fit(context.file + ", " + context.where(), width - 20, 15, true), 15,
           "id=\"title\" font-weight=\"bold\"");
  const std::string summary =
      solved ? printf_string(
                   "%d nozzles on %s rails, gantries %.2f %s wide: layer %.1f s (one "
                   "nozzle %.1f s), collision-free, closest gap %.2f %s",
                   options.nozzles, planner::to_string(axis).c_str(), options.gantry_width_m / u,
                   unit.c_str(), plan.layer_time_s, plan.single_nozzle_time_s, plan.min_gap_m / u,
                   unit.c_str())
             : printf_string(
                   "%d nozzles on %s rails, gantries %.2f %s wide: NO collision-free "
                   "plan",
                   options.nozzles, planner::to_string(axis).c_str(), options.gantry_width_m / u,
                   unit.c_str());
  doc.text(10, 42, svg::fit(summary, width - 20, 12), 12,
           std::string("id=\"subtitle\"") + (solved ? "" : " fill=\"#d62728\""));
  detail::draw_axes(doc, view, context.unit);

  // The layer's walls, grey: what every nozzle's coloured work is drawn over.
  std::string walls =
      "<g id=\"walls\" stroke=\"#d0d0d0\" stroke-width=\"5\" stroke-linecap=\"round\">\n";
  for (const auto& s : layer.segments) {
    const auto a = layer.start_m(s), b = layer.end_m(s);
    walls += "<line x1=\"" + svg::px(view.X(a.x())) + "\" y1=\"" + svg::px(view.Y(a.y())) +
             "\" x2=\"" + svg::px(view.X(b.x())) + "\" y2=\"" + svg::px(view.Y(b.y())) + "\"" +
             detail::bead_stroke(view, s) + "/>\n";
  }
  doc.raw(walls + "</g>\n");
  const double font = std::clamp(view.scale_px_per_m * 0.3, 7.0, 11.0);
  std::vector<svg::Document::LegendItem> legend;
  for (const auto& stage : plan.stages) {
    for (const auto& n : stage.nozzles) {
      const std::string c = colour(n.nozzle);
      // The section as a light band across the plan.
      if (n.section_to_m > n.section_from_m) {
        const double a = n.section_from_m, b = n.section_to_m;
        const bool x = axis == planner::RailAxis::kX;
        const double rx = x ? view.X(a) : view.left_px, ry = x ? view.top_px : view.Y(b);
        const double rw = x ? (b - a) * view.scale_px_per_m : view.width_px();
        const double rh = x ? view.height_px() : (b - a) * view.scale_px_per_m;
        doc.raw("<rect class=\"section\" x=\"" + svg::px(rx) + "\" y=\"" + svg::px(ry) +
                "\" width=\"" + svg::px(rw) + "\" height=\"" + svg::px(rh) + "\" fill=\"" + c +
                "\" fill-opacity=\"0.07\"/>\n");
      }
      std::string g = "<g class=\"nozzle-walls\" stroke=\"" + c + "\" stroke-width=\"3\">\n";
      std::string arrows;
      for (std::size_t k = 0; k < n.sequence.size(); ++k) {
        const auto& seg = n.layer.segments[n.sequence[k].segment];
        Eigen::Vector2d a = n.layer.start_m(seg), b = n.layer.end_m(seg);
        if (n.sequence[k].reversed) std::swap(a, b);
        const bool working = k >= n.zones.size() || n.zones[k] == "working";
        g += "<line x1=\"" + svg::px(view.X(a.x())) + "\" y1=\"" + svg::px(view.Y(a.y())) +
             "\" x2=\"" + svg::px(view.X(b.x())) + "\" y2=\"" + svg::px(view.Y(b.y())) + "\"" +
             (working ? "" : " stroke-opacity=\"0.55\" stroke-width=\"5\"") + "/>\n";
        arrows += detail::arrowhead(view, a, b, c, 5.0);
      }
      doc.raw(g + "</g>\n<g class=\"arrows\">\n" + arrows + "</g>\n");
      // Wall ids beside each wall, and the order the nozzle builds them on the other side.
      doc.raw("<g class=\"wall-ids\">\n");
      for (std::size_t k = 0; k < n.sequence.size(); ++k) {
        const auto& seg = n.layer.segments[n.sequence[k].segment];
        const auto a = n.layer.start_m(seg), b = n.layer.end_m(seg);
        detail::wall_label(doc, view, a, b, signed_step(n.layer, {n.sequence[k].segment, false}),
                           "#444", font);
        std::string order = "#";  // built so ("#" + number trips a GCC 12 false warning)
        order += std::to_string(k + 1);
        detail::wall_label(doc, view, b, a, order, c, font * 0.9);
      }
      doc.raw("</g>\n");
      // Air moves: where the waypoints do not extrude.
      std::string moves;
      for (std::size_t k = 0; k + 1 < n.waypoints.size(); ++k) {
        const auto& w = n.waypoints[k];
        const auto& next = n.waypoints[k + 1];
        if (w.extruding || (next.position_m - w.position_m).norm() < 1e-9) continue;
        moves += "<line x1=\"" + svg::px(view.X(w.position_m.x())) + "\" y1=\"" +
                 svg::px(view.Y(w.position_m.y())) + "\" x2=\"" +
                 svg::px(view.X(next.position_m.x())) + "\" y2=\"" +
                 svg::px(view.Y(next.position_m.y())) + "\"/>\n";
      }
      doc.raw("<g class=\"air-moves\" fill=\"none\" stroke=\"" + c +
              "\" stroke-width=\"1.2\" stroke-dasharray=\"4,3\">\n" + moves + "</g>\n");
      if (!n.waypoints.empty()) {
        const auto& start = n.waypoints.front().position_m;
        doc.raw("<circle class=\"start\" cx=\"" + svg::px(view.X(start.x())) + "\" cy=\"" +
                svg::px(view.Y(start.y())) + "\" r=\"6\" fill=\"" + c + "\"/>\n");
      }
    }
  }
  if (solved) {
    for (int k = 0; k < options.nozzles; ++k)
      legend.push_back({"line", colour(k), "nozzle " + std::to_string(k + 1)});
    legend.push_back({"band", colour(0), "its section"});
    legend.push_back({"dashed", "#555", "air move"});
    legend.push_back({"dot", "#555", "start"});
    legend.push_back({"line", "#d0d0d0", "wall (arrow: direction; 12 = wall id, #3 = 3rd built)"});
  } else {
    // No paths to draw: the walls with their ids, and (below) why there is no plan.
    doc.raw("<g class=\"wall-ids\">\n");
    for (std::size_t s = 0; s < layer.segments.size(); ++s) {
      const auto& seg = layer.segments[s];
      detail::wall_label(doc, view, layer.start_m(seg), layer.end_m(seg),
                         signed_step(layer, {static_cast<int>(s), false}), "#444", font);
    }
    doc.raw("</g>\n");
    legend.push_back({"line", "#d0d0d0", "wall to build (12 = wall id, 12:2 = its 2nd piece)"});
    legend.push_back(
        {"line", "#d62728", "no collision-free plan: the methods' reasons below the plan"});
  }
  detail::draw_scale_bar(doc, view, margin_left, plan_bottom + 46.0, context.unit);

  double y = plan_bottom + 72.0;
  if (!solved) {
    // No made-up chart: what was tried, and why each failed.
    doc.raw("<g id=\"no-plan\">\n");
    doc.text(10, y, svg::fit("No collision-free plan: " + plan.status.reason(), width - 20, 13), 13,
             "fill=\"#d62728\" font-weight=\"bold\"");
    y += 20;
    for (std::size_t k = 0; k < plan.stages.size(); ++k) {
      const auto& stage = plan.stages[k];
      if (plan.stages.size() > 1) {
        doc.text(10, y,
                 printf_string("stage %zu (%.2f to %.2f %s):", k + 1, stage.from_m / u,
                               stage.to_m / u, unit.c_str()),
                 12);
        y += 17;
      }
      for (const auto& attempt : stage.attempts) {
        doc.text(24, y, svg::fit(attempt.to_string(), width - 34, 12), 12);
        y += 17;
      }
    }
    doc.raw("</g>\n");
    y += 10;
  } else {
    // The x/t chart over the whole layer: rail position against time, every stage.
    double rail_lo = std::numeric_limits<double>::infinity(), rail_hi = -rail_lo;
    for (const auto& stage : plan.stages)
      for (const auto& n : stage.nozzles)
        for (const auto& w : n.waypoints) {
          rail_lo = std::min(rail_lo, planner::rail_coordinate(w.position_m, axis));
          rail_hi = std::max(rail_hi, planner::rail_coordinate(w.position_m, axis));
        }
    rail_lo -= 0.5 * options.gantry_width_m;
    rail_hi += 0.5 * options.gantry_width_m;
    const double chart_left = margin_left, chart_width = width - margin_left - 30.0;
    const double chart_top = y + 24.0, chart_height = 300.0;
    const TimeAxis ta = time_axis(end_s);
    auto TX = [&](double t) { return chart_left + t / end_s * chart_width; };
    auto RY = [&](double r) {
      return chart_top + chart_height - (r - rail_lo) / (rail_hi - rail_lo) * chart_height;
    };
    doc.text(chart_left, chart_top - 8,
             planner::to_string(axis) + " (" + unit + ") of each gantry over time (" + ta.unit +
                 "); shading: the gantry's width",
             12, "id=\"chart-title\"");
    std::string g = "<g id=\"xt-chart\">\n<rect x=\"" + svg::px(chart_left) + "\" y=\"" +
                    svg::px(chart_top) + "\" width=\"" + svg::px(chart_width) + "\" height=\"" +
                    svg::px(chart_height) + "\" fill=\"none\" stroke=\"#999\"/>\n";
    const auto t_ticks = svg::ticks(0.0, end_s / ta.per, std::max(2, int(chart_width / 90)));
    const double t_step = t_ticks.size() > 1 ? t_ticks[1] - t_ticks[0] : 1.0;
    for (double t : t_ticks) {
      g += "<line class=\"tick\" stroke=\"#999\" x1=\"" + svg::px(TX(t * ta.per)) + "\" y1=\"" +
           svg::px(chart_top + chart_height) + "\" x2=\"" + svg::px(TX(t * ta.per)) + "\" y2=\"" +
           svg::px(chart_top + chart_height + 5) + "\"/>\n";
      g += "<text class=\"tick-label\" x=\"" + svg::px(TX(t * ta.per)) + "\" y=\"" +
           svg::px(chart_top + chart_height + 17) +
           "\" text-anchor=\"middle\" font-family=\"sans-serif\" font-size=\"11\" fill=\"#555\">" +
           svg::tick_label(t, t_step) + "</text>\n";
    }
    const auto r_ticks = svg::ticks(rail_lo / u, rail_hi / u, 6);
    const double r_step = r_ticks.size() > 1 ? r_ticks[1] - r_ticks[0] : 1.0;
    for (double r : r_ticks) {
      g += "<line class=\"tick\" stroke=\"#999\" x1=\"" + svg::px(chart_left - 5) + "\" y1=\"" +
           svg::px(RY(r * u)) + "\" x2=\"" + svg::px(chart_left) + "\" y2=\"" + svg::px(RY(r * u)) +
           "\"/>\n";
      g += "<text class=\"tick-label\" x=\"" + svg::px(chart_left - 8) + "\" y=\"" +
           svg::px(RY(r * u) + 4) +
           "\" text-anchor=\"end\" font-family=\"sans-serif\" font-size=\"11\" fill=\"#555\">" +
           svg::tick_label(r, r_step) + "</text>\n";
    }
    // Stage borders and platform moves.
    for (std::size_t k = 0; plan.stages.size() > 1 && k < plan.stages.size(); ++k) {
      const double x = TX(plan.stages[k].start_s);
      g += "<line class=\"stage-start\" x1=\"" + svg::px(x) + "\" y1=\"" + svg::px(chart_top) +
           "\" x2=\"" + svg::px(x) + "\" y2=\"" + svg::px(chart_top + chart_height) +
           "\" stroke=\"#666\" stroke-dasharray=\"3,3\"/>\n";
      g += "<text x=\"" + svg::px(x + 3) + "\" y=\"" + svg::px(chart_top + 12) +
           "\" font-family=\"sans-serif\" font-size=\"11\" fill=\"#666\">stage " +
           std::to_string(k + 1) + "</text>\n";
    }
    const double band_px =
        std::max(1.0, options.gantry_width_m / (rail_hi - rail_lo) * chart_height);
    for (const auto& stage : plan.stages) {
      for (const auto& n : stage.nozzles) {
        std::string points;
        for (const auto& w : n.waypoints)
          points += svg::px(TX(w.t_s)) + "," +
                    svg::px(RY(planner::rail_coordinate(w.position_m, axis))) + " ";
        // Held where it ends until its stage does.
        const double stage_end = stage.start_s + stage.time_s;
        if (!n.waypoints.empty())
          points += svg::px(TX(stage_end)) + "," +
                    svg::px(RY(planner::rail_coordinate(n.waypoints.back().position_m, axis)));
        g += "<polyline class=\"gantry-band\" fill=\"none\" stroke=\"" +
             std::string(colour(n.nozzle)) + "\" stroke-width=\"" + svg::px(band_px) +
             "\" stroke-opacity=\"0.15\" points=\"" + points + "\"/>\n";
        g += "<polyline class=\"xt\" fill=\"none\" stroke=\"" + std::string(colour(n.nozzle)) +
             "\" stroke-width=\"1.2\" points=\"" + points + "\"/>\n";
      }
    }
    doc.raw(g + "</g>\n");
    doc.text(chart_left + chart_width, chart_top + chart_height + 32, "time (" + ta.unit + ")", 12,
             "text-anchor=\"end\" fill=\"#555\"");
    y = chart_top + chart_height + 44.0;
    legend.push_back({"band", "#555", "gantry width (x/t chart)"});
  }
  const double legend_height = doc.legend(10, y, width - 20, legend);
  doc.set_height(y + legend_height + 10.0);
  return doc.str();
}

}  // namespace ccbuild::report
