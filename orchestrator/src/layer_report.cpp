#include "ccbuild/orchestrator/layer_report.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace ccbuild::orchestrator {
namespace {

std::string number(double v, int decimals = 3) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, v);
  return text;
}

// Rounded for stable, readable JSON: micrometres and microseconds are plenty.
double rounded(double v) {
  return std::round(v * 1e6) / 1e6;
}

}  // namespace

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

nlohmann::ordered_json layer_plan_json(const floors::Layer& layer, const planner::LayerPlan& plan) {
  using json = nlohmann::ordered_json;
  const auto& e = plan.evaluation;
  json out;
  out["algorithm"] = planner::to_string(plan.algorithm);
  out["metric"] = planner::to_string(plan.metric);
  out["objective"] = planner::to_string(plan.objective);
  out["closed"] = plan.path.closed;
  if (!plan.path.closed)
    out["start"] = {rounded(plan.path.start_m.x()), rounded(plan.path.start_m.y())};
  out["walls"] = layer.segments.size();
  out["airtime_distance"] = rounded(e.airtime_distance_m);
  out["airtime_s"] = rounded(e.airtime_s);
  out["deposition_s"] = rounded(e.deposition_s);
  out["layer_time_s"] = rounded(e.layer_time_s);
  out["lower_bound_distance"] = rounded(plan.lower_bound_m);
  out["lower_bound_source"] = plan.lower_bound_source;
  const double gap = plan.gap();
  out["gap"] = std::isnan(gap) ? json(nullptr) : json(rounded(gap));
  out["solve_s"] = rounded(plan.solve_s);
  out["stopped_by"] = planner::to_string(plan.stop);
  out["kicks"] = plan.kicks;
  out["max_idle_s"] = rounded(e.max_idle_s);
  out["idle_limit_violations"] = e.idle_limit_violations;
  out["lifts"] = e.lift_count;
  out["total_rotation_rad"] = rounded(e.total_rotation_rad);
  json sequence = json::array(), pieces = json::array();
  for (const auto& step : plan.sequence) {
    const auto& s = layer.segments[step.segment];
    sequence.push_back(step.reversed ? -s.wall_id : s.wall_id);
    pieces.push_back(s.piece);
  }
  out["sequence"] = sequence;
  out["sequence_pieces"] = pieces;
  json moves = json::array();
  for (const auto& m : e.moves) {
    moves.push_back({{"from", {rounded(m.from_m.x()), rounded(m.from_m.y())}},
                     {"to", {rounded(m.to_m.x()), rounded(m.to_m.y())}},
                     {"distance", rounded(m.distance_m)},
                     {"time_s", rounded(m.time_s)},
                     {"lifted", m.lifted},
                     {"rotation_rad", rounded(m.rotation_rad)}});
  }
  out["moves"] = moves;
  out["length_unit"] = "m";
  return out;
}

std::string layer_plan_svg(const floors::Layer& layer, const planner::LayerPlan& plan,
                           const std::string& title) {
  Eigen::Vector2d lo = layer.points.empty() ? Eigen::Vector2d::Zero() : layer.points[0];
  Eigen::Vector2d hi = lo;
  for (const auto& p : layer.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  if (!plan.path.closed) {
    lo = lo.cwiseMin(plan.path.start_m);
    hi = hi.cwiseMax(plan.path.start_m);
  }
  const double extent = std::max({hi.x() - lo.x(), hi.y() - lo.y(), 1e-3});
  const double size_px = 1000.0, margin = 40.0;
  const double scale = (size_px - 2 * margin) / extent;
  const double width = (hi.x() - lo.x()) * scale + 2 * margin;
  const double height = (hi.y() - lo.y()) * scale + 2 * margin + 30;
  auto X = [&](double x) { return number(margin + (x - lo.x()) * scale, 1); };
  auto Y = [&](double y) { return number(30 + margin + (hi.y() - y) * scale, 1); };  // y up
  const double font = std::clamp(extent * scale / 80.0, 7.0, 14.0);

  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << number(width, 0) << "\" height=\""
      << number(height, 0) << "\" viewBox=\"0 0 " << number(width, 0) << " " << number(height, 0)
      << "\">\n";
  svg << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  const auto& e = plan.evaluation;
  svg << "<text x=\"10\" y=\"20\" font-family=\"sans-serif\" font-size=\"14\">" << title << " — "
      << planner::to_string(plan.algorithm) << ", airtime " << number(e.airtime_distance_m, 2)
      << " m / " << number(e.airtime_s, 1) << " s, layer " << number(e.layer_time_s, 1)
      << " s</text>\n";
  // Walls, each with an arrow at its middle pointing the way it is deposited.
  std::ostringstream arrows;
  svg << "<g stroke=\"#333\" stroke-width=\"3\" fill=\"none\">\n";
  for (const auto& step : plan.sequence) {
    const auto& s = layer.segments[step.segment];
    Eigen::Vector2d a = layer.start_m(s), b = layer.end_m(s);
    if (step.reversed) std::swap(a, b);
    svg << "<line x1=\"" << X(a.x()) << "\" y1=\"" << Y(a.y()) << "\" x2=\"" << X(b.x())
        << "\" y2=\"" << Y(b.y()) << "\"/>\n";
    // An arrowhead at the middle, pointing the way the wall is deposited (y is up).
    const Eigen::Vector2d d = (b - a).normalized();
    const Eigen::Vector2d m = 0.5 * (a + b);
    const double size = 7.0 / scale;
    const Eigen::Vector2d tip = m + d * size, n(-d.y(), d.x());
    const Eigen::Vector2d left = m - d * size + n * size * 0.7,
                          right = m - d * size - n * size * 0.7;
    arrows << "<polygon points=\"" << X(tip.x()) << "," << Y(tip.y()) << " " << X(left.x()) << ","
           << Y(left.y()) << " " << X(right.x()) << "," << Y(right.y()) << "\"/>\n";
  }
  svg << "</g>\n<g fill=\"#333\">\n" << arrows.str() << "</g>\n";
  // Air moves, dashed and numbered in order; lifted moves in red.
  svg << "<g fill=\"none\" stroke-width=\"1.2\" stroke-dasharray=\"5,4\">\n";
  int number_of_move = 0;
  for (const auto& m : e.moves) {
    ++number_of_move;
    if (m.distance_m <= 1e-9) continue;
    const char* colour = m.lifted ? "#d62728" : "#1f77b4";
    if (plan.metric == planner::Metric::kRectilinear) {
      svg << "<polyline stroke=\"" << colour << "\" points=\"" << X(m.from_m.x()) << ","
          << Y(m.from_m.y()) << " " << X(m.to_m.x()) << "," << Y(m.from_m.y()) << " "
          << X(m.to_m.x()) << "," << Y(m.to_m.y()) << "\"/>";
    } else {
      svg << "<line stroke=\"" << colour << "\" x1=\"" << X(m.from_m.x()) << "\" y1=\""
          << Y(m.from_m.y()) << "\" x2=\"" << X(m.to_m.x()) << "\" y2=\"" << Y(m.to_m.y())
          << "\"/>";
    }
    const Eigen::Vector2d mid = 0.5 * (m.from_m + m.to_m);
    svg << "<text x=\"" << X(mid.x()) << "\" y=\"" << Y(mid.y())
        << "\" font-family=\"sans-serif\" font-size=\"" << number(font, 1) << "\" fill=\"" << colour
        << "\" stroke=\"none\">" << number_of_move << "</text>\n";
  }
  svg << "</g>\n";
  const Eigen::Vector2d start =
      plan.path.closed && !plan.sequence.empty()
          ? (plan.sequence.front().reversed
                 ? layer.end_m(layer.segments[plan.sequence.front().segment])
                 : layer.start_m(layer.segments[plan.sequence.front().segment]))
          : plan.path.start_m;
  svg << "<circle cx=\"" << X(start.x()) << "\" cy=\"" << Y(start.y())
      << "\" r=\"7\" fill=\"#2ca02c\" fill-opacity=\"0.8\"/><text x=\"" << X(start.x()) << "\" y=\""
      << Y(start.y())
      << "\" dx=\"9\" dy=\"-9\" font-family=\"sans-serif\" font-size=\"12\" "
         "fill=\"#2ca02c\">start</text>\n";
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace ccbuild::orchestrator
