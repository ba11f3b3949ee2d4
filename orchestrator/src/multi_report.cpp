#include "ccbuild/orchestrator/multi_report.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "ccbuild/orchestrator/layer_report.hpp"

namespace ccbuild::orchestrator {
namespace {

double rounded(double v) {
  return std::round(v * 1e6) / 1e6;
}

std::string number(double v, int decimals = 1) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, v);
  return text;
}

const char* colour(int nozzle) {
  static const char* palette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                                  "#ff7f0e", "#8c564b", "#e377c2"};
  return palette[nozzle % 7];
}

}  // namespace

nlohmann::ordered_json multi_plan_json(const planner::MultiNozzlePlan& plan,
                                       const planner::MultiNozzleOptions& options) {
  using json = nlohmann::ordered_json;
  json out;
  out["nozzles"] = options.nozzles;
  out["gantry_width_m"] = rounded(options.gantry_width_m);
  out["rail_axis"] = planner::to_string(options.rail_axis);
  out["requested_method"] = planner::to_string(options.method);
  if (options.platform_width_m) out["platform_width_m"] = rounded(*options.platform_width_m);
  out["collision_free"] = plan.collision_free;
  if (!plan.collision_free) out["failure"] = plan.failure;
  out["layer_time_s"] = rounded(plan.layer_time_s);
  out["single_nozzle_layer_time_s"] = rounded(plan.single_nozzle_time_s);
  out["saved_vs_single"] = plan.single_nozzle_time_s > 0 && plan.collision_free
                               ? json(rounded(1.0 - plan.layer_time_s / plan.single_nozzle_time_s))
                               : json(nullptr);
  out["machine_time_s"] = rounded(plan.machine_time_s);
  out["platform_travel_s"] = rounded(plan.platform_travel_s);
  out["min_gap_m"] = std::isfinite(plan.min_gap_m) ? json(rounded(plan.min_gap_m)) : json(nullptr);
  out["vertex_count"] = plan.vertex_count;
  json stages = json::array();
  for (const auto& stage : plan.stages) {
    json s;
    s["from_m"] = rounded(stage.from_m);
    s["to_m"] = rounded(stage.to_m);
    s["method"] = stage.nozzles.empty() ? json(nullptr) : json(planner::to_string(stage.method));
    s["method_detail"] = stage.method_detail;
    s["attempts"] = stage.attempts;
    s["time_s"] = rounded(stage.time_s);
    s["faster_delay_s"] =
        stage.faster_delay_s ? json(rounded(*stage.faster_delay_s)) : json(nullptr);
    s["min_gap_m"] =
        std::isfinite(stage.min_gap_m) ? json(rounded(stage.min_gap_m)) : json(nullptr);
    json nozzles = json::array();
    for (const auto& n : stage.nozzles) {
      json j;
      j["nozzle"] = n.nozzle + 1;
      j["section"] = {rounded(n.section_from_m), rounded(n.section_to_m)};
      json sequence = json::array(), pieces = json::array(), waits = json::array();
      for (std::size_t k = 0; k < n.sequence.size(); ++k) {
        const auto& seg = n.layer.segments[n.sequence[k].segment];
        sequence.push_back(n.sequence[k].reversed ? -seg.wall_id : seg.wall_id);
        pieces.push_back(seg.piece);
        if (k < n.wait_before_step_s.size() && n.wait_before_step_s[k] > 0)
          waits.push_back({{"before_step", k}, {"wait_s", rounded(n.wait_before_step_s[k])}});
      }
      j["sequence"] = sequence;
      j["sequence_pieces"] = pieces;
      j["zones"] = n.zones;
      j["start_offset"] = n.start_offset;
      j["busy_s"] = rounded(n.busy_s);
      j["wait_s"] = rounded(n.wait_s);
      j["finish_s"] = rounded(n.finish_s);
      j["airtime_s"] = rounded(n.evaluation.airtime_s);
      j["deposition_s"] = rounded(n.evaluation.deposition_s);
      j["waits"] = waits;
      nozzles.push_back(j);
    }
    s["nozzles"] = nozzles;
    stages.push_back(s);
  }
  out["stages"] = stages;
  out["length_unit"] = "m";
  return out;
}

std::string multi_plan_svg(const planner::MultiNozzlePlan& plan,
                           const planner::MultiNozzleOptions& options, const std::string& title) {
  // Extent of everything drawn in plan view.
  Eigen::Vector2d lo(1e18, 1e18), hi(-1e18, -1e18);
  double end_time = 1.0;
  for (const auto& stage : plan.stages)
    for (const auto& n : stage.nozzles) {
      for (const auto& p : n.layer.points) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
      for (const auto& p : n.timeline.positions()) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
      end_time = std::max(end_time, n.timeline.end_s());
    }
  if (lo.x() > hi.x()) lo = hi = Eigen::Vector2d::Zero();
  const double extent = std::max({hi.x() - lo.x(), hi.y() - lo.y(), 1e-3});
  const double margin = 40.0, plan_px = 900.0;
  const double scale = (plan_px - 2 * margin) / extent;
  const double width = (hi.x() - lo.x()) * scale + 2 * margin;
  const double plan_height = (hi.y() - lo.y()) * scale + 2 * margin;
  const double chart_top = 30 + plan_height + 20, chart_height = 320;
  const double height = chart_top + chart_height + 50;
  auto X = [&](double x) { return number(margin + (x - lo.x()) * scale); };
  auto Y = [&](double y) { return number(30 + margin + (hi.y() - y) * scale); };
  const bool x_rails = options.rail_axis == planner::RailAxis::kX;

  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << number(std::max(width, 600.0), 0)
      << "\" height=\"" << number(height, 0)
      << "\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg << "<text x=\"10\" y=\"20\" font-family=\"sans-serif\" font-size=\"14\">" << title << " — "
      << options.nozzles << " nozzles on " << planner::to_string(options.rail_axis)
      << " rails, layer " << number(plan.layer_time_s) << " s (one nozzle "
      << number(plan.single_nozzle_time_s) << " s), "
      << (plan.collision_free ? "collision-free" : "NO collision-free plan") << "</text>\n";
  for (const auto& stage : plan.stages) {
    for (const auto& n : stage.nozzles) {
      const char* c = colour(n.nozzle);
      // The section as a light band across the plan.
      if (n.section_to_m > n.section_from_m) {
        if (x_rails)
          svg << "<rect x=\"" << X(n.section_from_m) << "\" y=\"" << Y(hi.y()) << "\" width=\""
              << number((n.section_to_m - n.section_from_m) * scale) << "\" height=\""
              << number((hi.y() - lo.y()) * scale) << "\" fill=\"" << c
              << "\" fill-opacity=\"0.07\"/>\n";
        else
          svg << "<rect x=\"" << X(lo.x()) << "\" y=\"" << Y(n.section_to_m) << "\" width=\""
              << number((hi.x() - lo.x()) * scale) << "\" height=\""
              << number((n.section_to_m - n.section_from_m) * scale) << "\" fill=\"" << c
              << "\" fill-opacity=\"0.07\"/>\n";
      }
      for (std::size_t k = 0; k < n.sequence.size(); ++k) {
        const auto& seg = n.layer.segments[n.sequence[k].segment];
        const auto a = n.layer.start_m(seg), b = n.layer.end_m(seg);
        const bool working = k >= n.zones.size() || n.zones[k] == "working";
        svg << "<line x1=\"" << X(a.x()) << "\" y1=\"" << Y(a.y()) << "\" x2=\"" << X(b.x())
            << "\" y2=\"" << Y(b.y()) << "\" stroke=\"" << c << "\" stroke-width=\""
            << (working ? 3 : 5) << "\" stroke-opacity=\"" << (working ? "0.9" : "0.5") << "\"/>\n";
      }
      // Its moves, dashed: the timeline's path without the walls is hard to tell apart,
      // so draw the whole trajectory thin.
      svg << "<polyline fill=\"none\" stroke=\"" << c
          << "\" stroke-width=\"0.8\" stroke-dasharray=\"4,3\" points=\"";
      for (const auto& p : n.timeline.positions()) svg << X(p.x()) << "," << Y(p.y()) << " ";
      svg << "\"/>\n";
      const auto start = n.timeline.positions().front();
      svg << "<circle cx=\"" << X(start.x()) << "\" cy=\"" << Y(start.y()) << "\" r=\"6\" fill=\""
          << c << "\"/>\n";
    }
  }
  // x/t chart: time to the right, rail position up.
  double rail_lo = x_rails ? lo.x() : lo.y(), rail_hi = x_rails ? hi.x() : hi.y();
  if (rail_hi - rail_lo < 1e-6) rail_hi = rail_lo + 1.0;
  const double chart_left = margin, chart_width = std::max(width, 600.0) - 2 * margin;
  auto TX = [&](double t) { return number(chart_left + t / end_time * chart_width); };
  auto RY = [&](double r) {
    return number(chart_top + chart_height - (r - rail_lo) / (rail_hi - rail_lo) * chart_height);
  };
  svg << "<rect x=\"" << number(chart_left) << "\" y=\"" << number(chart_top) << "\" width=\""
      << number(chart_width) << "\" height=\"" << number(chart_height)
      << "\" fill=\"none\" stroke=\"#999\"/>\n";
  svg << "<text x=\"" << number(chart_left) << "\" y=\"" << number(chart_top + chart_height + 18)
      << "\" font-family=\"sans-serif\" font-size=\"12\">0 s</text><text x=\""
      << number(chart_left + chart_width - 60) << "\" y=\"" << number(chart_top + chart_height + 18)
      << "\" font-family=\"sans-serif\" font-size=\"12\">" << number(end_time)
      << " s</text><text x=\"" << number(chart_left + 4) << "\" y=\"" << number(chart_top + 14)
      << "\" font-family=\"sans-serif\" font-size=\"12\">" << planner::to_string(options.rail_axis)
      << " (m) over time: gantry centres; shading = gantry width</text>\n";
  double stage_offset = 0.0;
  for (const auto& stage : plan.stages) {
    for (const auto& n : stage.nozzles) {
      const char* c = colour(n.nozzle);
      std::ostringstream centre, band_top, band_bottom;
      const auto& ts = n.timeline.times();
      const auto& ps = n.timeline.positions();
      for (std::size_t i = 0; i < ts.size(); ++i) {
        const double r = x_rails ? ps[i].x() : ps[i].y();
        centre << TX(stage_offset + ts[i]) << "," << RY(r) << " ";
      }
      // Held position to the end of the chart.
      const double r_end = x_rails ? ps.back().x() : ps.back().y();
      centre << TX(end_time) << "," << RY(r_end);
      svg << "<polyline fill=\"none\" stroke=\"" << c << "\" stroke-width=\""
          << number(std::max(1.0, options.gantry_width_m / (rail_hi - rail_lo) * chart_height), 1)
          << "\" stroke-opacity=\"0.15\" points=\"" << centre.str() << "\"/>\n";
      svg << "<polyline fill=\"none\" stroke=\"" << c << "\" stroke-width=\"1.2\" points=\""
          << centre.str() << "\"/>\n";
    }
    stage_offset += stage.time_s;
  }
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace ccbuild::orchestrator
