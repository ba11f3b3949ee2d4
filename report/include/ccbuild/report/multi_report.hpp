#pragma once
// Reports of a multi-nozzle layer plan: JSON (docs/json.md), and an SVG with the
// sections, each nozzle's path and order, and the x/t curves of all nozzles over the
// whole layer (every platform stage) on a time axis.

#include <nlohmann/json.hpp>
#include <string>

#include "ccbuild/planner/multi_nozzle.hpp"
#include "ccbuild/report/layer_report.hpp"

namespace ccbuild::report {

/// The plan as one JSON object: where it came from, the machine's limits, the layer's
/// pieces, the status and totals, and per stage and nozzle its sequence, waits and
/// waypoints (in layer time).
nlohmann::ordered_json multi_plan_json(const ReportContext& context, const floors::Layer& layer,
                                       const machine::MachineModel& machine,
                                       const planner::MultiNozzlePlan& plan,
                                       const planner::MultiNozzleOptions& options);

/// The drawing. Without a plan it shows the layer and every method's reason instead of
/// paths and chart.
std::string multi_plan_svg(const ReportContext& context, const floors::Layer& layer,
                           const planner::MultiNozzlePlan& plan,
                           const planner::MultiNozzleOptions& options);

}  // namespace ccbuild::report
