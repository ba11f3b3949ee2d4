#pragma once
// A planned layer as the text `ccbuild plan-layer` prints: one nozzle's tour (airtime,
// deposition, bounds, the search) or several nozzles' plan (stages, sections, methods).

#include <ostream>
#include <string>

#include "ccbuild/planner/multi_nozzle.hpp"
#include "ccbuild/planner/plan_layer.hpp"
#include "ccbuild/report/layer_report.hpp"
#include "ccbuild/schedule/project.hpp"

namespace ccbuild::report {

/// What the command was asked, as the user named it.
struct PlanTextOptions {
  std::string rail_axis = "x";  ///< several nozzles: the rails' axis
  std::string algorithm, metric, objective;
  bool connected_asked = false;   ///< --bound-rounds or --bound-certificate given
  std::string bound_certificate;  ///< the certificate file written, or empty
  bool anytime = false;           ///< --time-limit given: a replay line
  std::string drawing;            ///< the SVG written, or empty
};

/// Several nozzles' plan of `layer`.
void write_multi_plan_text(std::ostream& out, const schedule::Project& project,
                           const ReportContext& context, const floors::Layer& layer,
                           const planner::MultiNozzlePlan& plan,
                           const planner::MultiNozzleOptions& options, const PlanTextOptions& o);

/// One nozzle's plan of `layer`.
void write_layer_plan_text(std::ostream& out, const schedule::Project& project,
                           const ReportContext& context, const floors::Layer& layer,
                           const planner::LayerPlan& plan, const PlanTextOptions& o);

}  // namespace ccbuild::report
