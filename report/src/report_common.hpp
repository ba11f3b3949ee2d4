#pragma once
// Pieces shared by the single- and multi-nozzle reports: the JSON blocks every plan
// carries (where it came from, the machine's limits, the layer's pieces, sequences,
// waypoints) and the plan view of the drawings (scale, axes, scale bar). Internal.

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "ccbuild/floors/slice.hpp"
#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/planner/timeline.hpp"
#include "ccbuild/planner/tool_path.hpp"
#include "ccbuild/report/layer_report.hpp"
#include "ccbuild/schedule/json_blocks.hpp"
#include "svg.hpp"

namespace ccbuild::report::detail {

using json = nlohmann::ordered_json;

// The blocks the reports share with the schedule's JSON.
using schedule::pieces_json;
using schedule::point_json;
using schedule::rounded;
using schedule::waypoints_json;

/// format, file, floor, layer, z_bottom_m, z_top_m, seed.
json header_json(const ReportContext& context, const floors::Layer& layer,
                 const std::string& format);
/// The machine's limits an independent check needs.
json machine_json(const machine::MachineModel& machine);
/// [{wall, piece, reversed}] of a sequence on `layer`.
json sequence_json(const floors::Layer& layer, const planner::Sequence& sequence);

/// Layout coordinates (m, y up) to drawing coordinates (px, y down).
struct PlanView {
  Eigen::Vector2d lo = Eigen::Vector2d::Zero(), hi = Eigen::Vector2d::Zero();
  double left_px = 0.0, top_px = 0.0, scale_px_per_m = 1.0;
  double X(double x_m) const { return left_px + (x_m - lo.x()) * scale_px_per_m; }
  double Y(double y_m) const { return top_px + (hi.y() - y_m) * scale_px_per_m; }
  double width_px() const { return (hi.x() - lo.x()) * scale_px_per_m; }
  double height_px() const { return (hi.y() - lo.y()) * scale_px_per_m; }
};

/// A view of [lo, hi] at (left, top) whose longer side is `size_px`.
PlanView plan_view(Eigen::Vector2d lo, Eigen::Vector2d hi, double left_px, double top_px,
                   double size_px);
/// Extent of a layer's points.
void extend(Eigen::Vector2d& lo, Eigen::Vector2d& hi, const floors::Layer& layer);

/// A frame around the view with ticks and labels along the bottom (x) and left (y), in
/// the user's unit, and the axis names with the unit.
void draw_axes(svg::Document& doc, const PlanView& view, floors::LengthUnit unit);
/// A scale bar of a round length at (x, y) (its left end, baseline).
void draw_scale_bar(svg::Document& doc, const PlanView& view, double x_px, double y_px,
                    floors::LengthUnit unit);
/// An arrowhead at the middle of a -> b (m), pointing from a to b.
/// For a bead of a wall thicker than one bead (width_m set), the stroke attributes that
/// draw it at its width; empty for a wall in one pass (drawn as the
/// group says).
std::string bead_stroke(const PlanView& view, const floors::LayerSegment& segment);

std::string arrowhead(const PlanView& view, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                      const std::string& colour, double size_px = 6.0);
/// The wall-id label of a piece ("12", "12:2"), placed beside its middle.
void wall_label(svg::Document& doc, const PlanView& view, const Eigen::Vector2d& a,
                const Eigen::Vector2d& b, const std::string& label, const std::string& colour,
                double font_px);

}  // namespace ccbuild::report::detail
