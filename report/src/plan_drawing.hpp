#pragma once
// A schedule's plan drawn as `plan-layer --svg` draws one (the same axes, scale bar, wall
// ids and deposition arrows, report_common.hpp): its walls, each nozzle's path, air moves
// and starts. The report shows one per plan its layers use. Internal to the report.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "ccbuild/floors/units.hpp"
#include "ccbuild/schedule/schedule.hpp"

namespace ccbuild::report::detail {

/// A lintel as it lies on the plan: its ends (m) and what to say of it.
struct PlanLintel {
  Eigen::Vector2d start_m = Eigen::Vector2d::Zero(), end_m = Eigen::Vector2d::Zero();
  std::string text;
};

/// The drawing of `plan` titled `title`, in `unit` (axes, scale bar), with one colour per
/// nozzle from `nozzle_colours` (cycled), and the lintels set before its layers. A plan
/// known by its digests only shows its walls.
std::string schedule_plan_svg(const schedule::SchedulePlan& plan, const std::string& title,
                              floors::LengthUnit unit,
                              const std::vector<std::string>& nozzle_colours,
                              const std::vector<PlanLintel>& lintels);

}  // namespace ccbuild::report::detail
