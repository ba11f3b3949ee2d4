#pragma once
// Reports of a multi-nozzle layer plan: JSON, and an SVG with the sections, each
// nozzle's path, and the x/t curves of all nozzles on a time axis.

#include <nlohmann/json.hpp>
#include <string>

#include "ccbuild/planner/multi_nozzle.hpp"

namespace ccbuild::orchestrator {

nlohmann::ordered_json multi_plan_json(const planner::MultiNozzlePlan& plan,
                                       const planner::MultiNozzleOptions& options);

std::string multi_plan_svg(const planner::MultiNozzlePlan& plan,
                           const planner::MultiNozzleOptions& options, const std::string& title);

}  // namespace ccbuild::orchestrator
