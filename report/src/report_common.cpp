#include "report_common.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ccbuild::report::detail {

json header_json(const ReportContext& context, const floors::Layer& layer,
                 const std::string& format) {
  json out;
  out["format"] = format;
  out["file"] = context.file;
  out["floor"] = context.floor;
  out["layer"] = context.layer ? json(*context.layer) : json(nullptr);
  out["z_bottom_m"] = rounded(layer.z_bottom_m);
  out["z_top_m"] = rounded(layer.z_top_m);
  out["seed"] = context.seed;
  return out;
}

json machine_json(const machine::MachineModel& m) {
  return schedule::machine_limits_json(schedule::machine_limits(m));
}

json sequence_json(const floors::Layer& layer, const planner::Sequence& sequence) {
  json out = json::array();
  for (const auto& step : sequence) {
    const auto& s = layer.segments[step.segment];
    out.push_back({{"wall", s.wall_id}, {"piece", s.piece + 1}, {"reversed", step.reversed}});
  }
  return out;
}

PlanView plan_view(Eigen::Vector2d lo, Eigen::Vector2d hi, double left_px, double top_px,
                   double size_px) {
  if (!(lo.x() <= hi.x())) lo = hi = Eigen::Vector2d::Zero();
  // A margin of 3% around the walls so arrows and labels at the edge stay inside.
  const Eigen::Vector2d span = (hi - lo).cwiseMax(Eigen::Vector2d(1e-3, 1e-3));
  const double pad = 0.03 * std::max(span.x(), span.y());
  PlanView view;
  view.lo = lo - Eigen::Vector2d(pad, pad);
  view.hi = hi + Eigen::Vector2d(pad, pad);
  view.left_px = left_px;
  view.top_px = top_px;
  const double extent = std::max(view.hi.x() - view.lo.x(), view.hi.y() - view.lo.y());
  view.scale_px_per_m = size_px / extent;
  return view;
}

void extend(Eigen::Vector2d& lo, Eigen::Vector2d& hi, const floors::Layer& layer) {
  for (const auto& p : layer.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
}

void draw_axes(svg::Document& doc, const PlanView& view, floors::LengthUnit unit) {
  const double per = floors::meters_per(unit);
  const std::string u = floors::to_string(unit);
  const double left = view.left_px, top = view.top_px;
  const double right = left + view.width_px(), bottom = top + view.height_px();
  std::string g = "<g id=\"axes\" stroke=\"#999\" fill=\"none\">\n<rect x=\"" + svg::px(left) +
                  "\" y=\"" + svg::px(top) + "\" width=\"" + svg::px(right - left) +
                  "\" height=\"" + svg::px(bottom - top) + "\"/>\n";
  auto axis = [&](double lo_m, double hi_m, double length_px, bool horizontal) {
    const int wanted = std::max(2, static_cast<int>(length_px / 90.0));
    const std::vector<double> values = svg::ticks(lo_m / per, hi_m / per, wanted);
    const double step = values.size() > 1 ? values[1] - values[0] : 1.0;
    for (double v : values) {
      const double m = v * per;
      if (horizontal) {
        const double x = view.X(m);
        g += "<line class=\"tick\" x1=\"" + svg::px(x) + "\" y1=\"" + svg::px(bottom) + "\" x2=\"" +
             svg::px(x) + "\" y2=\"" + svg::px(bottom + 5) + "\"/>\n";
        doc.raw(
            "<text class=\"tick-label\" x=\"" + svg::px(x) + "\" y=\"" + svg::px(bottom + 17) +
            "\" text-anchor=\"middle\" font-family=\"sans-serif\" font-size=\"11\" fill=\"#555\">" +
            svg::tick_label(v, step) + "</text>\n");
      } else {
        const double y = view.Y(m);
        g += "<line class=\"tick\" x1=\"" + svg::px(left - 5) + "\" y1=\"" + svg::px(y) +
             "\" x2=\"" + svg::px(left) + "\" y2=\"" + svg::px(y) + "\"/>\n";
        doc.raw(
            "<text class=\"tick-label\" x=\"" + svg::px(left - 8) + "\" y=\"" + svg::px(y + 4) +
            "\" text-anchor=\"end\" font-family=\"sans-serif\" font-size=\"11\" fill=\"#555\">" +
            svg::tick_label(v, step) + "</text>\n");
      }
    }
  };
  axis(view.lo.x(), view.hi.x(), right - left, true);
  axis(view.lo.y(), view.hi.y(), bottom - top, false);
  g += "</g>\n";
  doc.raw(g);
  doc.text(right, bottom + 32, "x (" + u + ")", 12, "text-anchor=\"end\" fill=\"#555\"");
  doc.text(left - 8, top - 8, "y (" + u + ")", 12, "text-anchor=\"end\" fill=\"#555\"");
}

void draw_scale_bar(svg::Document& doc, const PlanView& view, double x_px, double y_px,
                    floors::LengthUnit unit) {
  const double per = floors::meters_per(unit);
  // About a fifth of the drawing's width, in round units of the user's unit.
  const double length_units = svg::round_length(0.2 * view.width_px() / view.scale_px_per_m / per);
  const double length_px = length_units * per * view.scale_px_per_m;
  doc.raw("<g id=\"scale-bar\">\n<rect x=\"" + svg::px(x_px) + "\" y=\"" + svg::px(y_px - 6) +
          "\" width=\"" + svg::px(length_px / 2) + "\" height=\"6\" fill=\"#333\"/>\n<rect x=\"" +
          svg::px(x_px + length_px / 2) + "\" y=\"" + svg::px(y_px - 6) + "\" width=\"" +
          svg::px(length_px / 2) + "\" height=\"6\" fill=\"white\" stroke=\"#333\"/>\n");
  doc.text(x_px, y_px + 14, "0", 11);
  doc.text(x_px + length_px, y_px + 14,
           svg::tick_label(length_units, length_units) + " " + floors::to_string(unit), 11,
           "text-anchor=\"end\"");
  doc.raw("</g>\n");
}

std::string bead_stroke(const PlanView& view, const floors::LayerSegment& segment) {
  if (segment.role == floors::BeadRole::kPass || segment.width_m <= 0.0) return "";
  // A pixel less than the bead, so that beads side by side stay apart on the drawing;
  // a skin's square ends fill the corners where it turns.
  return " stroke-width=\"" + svg::px(std::max(1.0, segment.width_m * view.scale_px_per_m - 1.0)) +
         "\" stroke-linecap=\"" + (segment.role == floors::BeadRole::kSkin ? "square" : "butt") +
         "\"";
}

std::string arrowhead(const PlanView& view, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                      const std::string& colour, double size_px) {
  // In drawing coordinates (y down), so the head keeps its size at any scale.
  const Eigen::Vector2d pa(view.X(a.x()), view.Y(a.y())), pb(view.X(b.x()), view.Y(b.y()));
  const Eigen::Vector2d d = pb - pa;
  if (d.norm() < 1e-9) return "";
  const Eigen::Vector2d u = d.normalized(), n(-u.y(), u.x());
  const Eigen::Vector2d m = 0.5 * (pa + pb);
  const Eigen::Vector2d tip = m + u * size_px, left = m - u * size_px + n * size_px * 0.7,
                        right = m - u * size_px - n * size_px * 0.7;
  return "<polygon class=\"arrow\" fill=\"" + colour + "\" points=\"" + svg::px(tip.x()) + "," +
         svg::px(tip.y()) + " " + svg::px(left.x()) + "," + svg::px(left.y()) + " " +
         svg::px(right.x()) + "," + svg::px(right.y()) + "\"/>\n";
}

void wall_label(svg::Document& doc, const PlanView& view, const Eigen::Vector2d& a,
                const Eigen::Vector2d& b, const std::string& label, const std::string& colour,
                double font_px) {
  const Eigen::Vector2d pa(view.X(a.x()), view.Y(a.y())), pb(view.X(b.x()), view.Y(b.y()));
  Eigen::Vector2d n(-(pb - pa).y(), (pb - pa).x());
  if (n.norm() < 1e-9) return;
  n.normalize();
  // Beside the wall's middle, clear of the arrow on it: beside a steep wall the text
  // starts (or ends) there; beside a flat one it is centred above or below.
  const bool steep = std::abs(n.x()) > 0.5;
  const Eigen::Vector2d at = 0.5 * (pa + pb) + n * (steep ? 9.0 : 4.0 + font_px * 0.7);
  const char* anchor = !steep ? "middle" : n.x() > 0 ? "start" : "end";
  doc.raw("<text class=\"wall-id\" x=\"" + svg::px(at.x()) + "\" y=\"" +
          svg::px(at.y() + font_px * 0.35) + "\" text-anchor=\"" + anchor +
          "\" font-family=\"sans-serif\" font-size=\"" + svg::px(font_px) + "\" fill=\"" + colour +
          "\">" + svg::escape(label) + "</text>\n");
}

}  // namespace ccbuild::report::detail
