#include "plan_drawing.hpp"

#include <algorithm>

#include "ccbuild/common/format.hpp"
#include "ccbuild/report/layer_report.hpp"
#include "report_common.hpp"

namespace ccbuild::report::detail {

std::string schedule_plan_svg(const schedule::SchedulePlan& plan, const std::string& title,
                              floors::LengthUnit unit,
                              const std::vector<std::string>& nozzle_colours,
                              const std::vector<PlanLintel>& lintels) {
  const floors::Layer& layer = plan.layer;
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  extend(lo, hi, layer);
  for (const auto& nozzle : plan.waypoints)
    for (const auto& w : nozzle) {
      lo = lo.cwiseMin(w.position_m);
      hi = hi.cwiseMax(w.position_m);
    }
  if (lo.x() > hi.x()) lo = hi = Eigen::Vector2d::Zero();
  const double margin_left = 70.0, top = 44.0;
  const PlanView view = plan_view(lo, hi, margin_left, top, 1000.0);
  const double width = std::max(700.0, margin_left + view.width_px() + 40.0);
  const double bottom = top + view.height_px();
  const double legend_top = bottom + 70.0;
  svg::Document doc(width, legend_top + 80.0);
  doc.text(10, 20, svg::fit(title, width - 20, 14, false), 14, "class=\"plan-title\"");
  draw_axes(doc, view, unit);
  const double font = std::clamp(view.scale_px_per_m * 0.35, 8.0, 11.0);
  std::string walls =
      "<g class=\"walls\" stroke=\"#c4c9d1\" stroke-width=\"5\" stroke-linecap=\"round\">\n";
  for (const auto& s : layer.segments) {
    const Eigen::Vector2d a = layer.start_m(s), b = layer.end_m(s);
    walls += "<line x1=\"" + svg::px(view.X(a.x())) + "\" y1=\"" + svg::px(view.Y(a.y())) +
             "\" x2=\"" + svg::px(view.X(b.x())) + "\" y2=\"" + svg::px(view.Y(b.y())) + "\"" +
             bead_stroke(view, s) + "/>\n";
  }
  doc.raw(walls + "</g>\n");
  for (const PlanLintel& l : lintels)
    doc.raw("<line class=\"lintel\" x1=\"" + svg::px(view.X(l.start_m.x())) + "\" y1=\"" +
            svg::px(view.Y(l.start_m.y())) + "\" x2=\"" + svg::px(view.X(l.end_m.x())) +
            "\" y2=\"" + svg::px(view.Y(l.end_m.y())) +
            "\" stroke=\"#E68FAC\" stroke-width=\"7\" opacity=\"0.85\"><title>" +
            svg::escape(l.text) + "</title></line>\n");
  // Each nozzle's path: deposition solid with an arrow in its direction, air dashed (red
  // where lifted over walls built in this layer), its start a circle.
  for (std::size_t n = 0; n < plan.waypoints.size(); ++n) {
    const auto& w = plan.waypoints[n];
    const std::string& colour = nozzle_colours[n % nozzle_colours.size()];
    std::string deposit, air, lifted, arrows;
    for (std::size_t k = 0; k + 1 < w.size(); ++k) {
      const Eigen::Vector2d& a = w[k].position_m;
      const Eigen::Vector2d& b = w[k + 1].position_m;
      if ((b - a).norm() < 1e-9) continue;
      const std::string seg = printf_string(
          "M%s %sL%s %s", svg::px(view.X(a.x())).c_str(), svg::px(view.Y(a.y())).c_str(),
          svg::px(view.X(b.x())).c_str(), svg::px(view.Y(b.y())).c_str());
      if (w[k].extruding) {
        deposit += seg;
        if ((b - a).norm() * view.scale_px_per_m > 24.0) arrows += arrowhead(view, a, b, colour);
      } else if (w[k].z_m > plan.z_top_m + 1e-6 || w[k + 1].z_m > plan.z_top_m + 1e-6) {
        lifted += seg;
      } else {
        air += seg;
      }
    }
    doc.raw(
        printf_string("<g class=\"nozzle-path\" data-nozzle=\"%zu\">\n", n + 1) + "<path d=\"" +
        deposit + "\" stroke=\"" + colour + "\" stroke-width=\"1.8\" fill=\"none\"/>\n<path d=\"" +
        air + "\" stroke=\"" + colour +
        "\" stroke-width=\"1\" stroke-dasharray=\"4 3\" fill=\"none\"/>\n<path d=\"" + lifted +
        "\" stroke=\"#BE0032\" stroke-width=\"1.2\" stroke-dasharray=\"4 3\" fill=\"none\"/>\n" +
        arrows + "</g>\n");
    if (!w.empty())
      doc.raw("<circle class=\"nozzle-start\" cx=\"" + svg::px(view.X(w.front().position_m.x())) +
              "\" cy=\"" + svg::px(view.Y(w.front().position_m.y())) +
              "\" r=\"5\" fill=\"#fff\" stroke=\"" + colour + "\" stroke-width=\"2\"/>\n");
  }
  // The wall ids on top, as plan-layer --svg labels them ("12", "12:2" for a piece).
  doc.raw("<g class=\"wall-ids\">\n");
  for (std::size_t k = 0; k < layer.segments.size(); ++k) {
    const auto& s = layer.segments[k];
    wall_label(doc, view, layer.start_m(s), layer.end_m(s),
               signed_step(layer, {static_cast<int>(k), false}), "#444", font);
  }
  doc.raw("</g>\n");
  draw_scale_bar(doc, view, margin_left, bottom + 44.0, unit);
  std::vector<svg::Document::LegendItem> legend = {
      {"line", "#c4c9d1", "wall (12 = wall id, 12:2 = its 2nd piece)"}};
  for (std::size_t n = 0; n < plan.waypoints.size(); ++n)
    legend.push_back({"line", nozzle_colours[n % nozzle_colours.size()],
                      printf_string("nozzle %zu (arrow: direction; circle: start)", n + 1)});
  legend.push_back({"dashed", "#5d6d7e", "air move"});
  if (!lintels.empty()) legend.push_back({"line", "#E68FAC", "lintel set before the layer"});
  legend.push_back({"dashed", "#BE0032", "lifted over built walls"});
  if (plan.waypoints.empty())
    legend.push_back({"band", "#ffffff", "tool paths kept as digests only: walls shown"});
  const double legend_height = doc.legend(10, legend_top, width - 20, legend);
  doc.set_height(legend_top + legend_height + 8.0);
  return doc.str();
}

}  // namespace ccbuild::report::detail
