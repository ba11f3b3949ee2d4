#pragma once
// Reports of a building's climbs on a climbing machine: JSON (docs/json.md) and an SVG
// with the platform, units and pipes in plan and in elevation.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "ccbuild/climb/climb.hpp"
#include "ccbuild/orchestrator/project.hpp"

namespace ccbuild::orchestrator {

/// Every stage and the climbs between them (those planned: `climbs[k]` goes from stage
/// climbs[k].from_stage).
struct ClimbReport {
  /// A fixed gantry: the building is within its reach (Project checked it), no stages.
  bool fixed_gantry = false;
  climb::StagePlan stages;
  std::vector<climb::ClimbPlan> climbs;
  /// Solved when every stage was placed and every climb planned (or none is needed).
  climb::ClimbStatus status() const;
  double climb_time_s() const;
  double planning_s() const;
};

/// Places the stages and plans the climbs (of every stage, or those that end a stage on
/// floor `floor` when given). On a fixed gantry the report says so and has no stages:
/// opening the project already checked that the building is within its reach. Throws
/// InputError when `floor` is not a floor.
ClimbReport plan_climbs(const Project& project, std::optional<int> floor,
                        const climb::ClimbOptions& options);

/// The names of the climbing machine's units, by index (empty on a fixed gantry).
std::vector<std::string> unit_names(const Project& project);
/// One pipe: id, unit (named by `units`), floor, wall, after_layer (null in the
/// foundation), centre, outward.
nlohmann::ordered_json anchor_json(const std::vector<std::string>& units,
                                   const climb::Anchor& anchor);
/// One stage: platform height, first and last layer printed, top, anchors.
nlohmann::ordered_json stage_json(const std::vector<std::string>& units,
                                  const climb::ClimbStage& stage);
/// One climb: status, duration, clearance, and its phases with their timed joint paths.
/// Planning times only `with_planning_time` (they differ from run to run).
nlohmann::ordered_json climb_plan_json(const std::vector<std::string>& units,
                                       const climb::ClimbPlan& plan, bool with_planning_time);
nlohmann::ordered_json climb_report_json(const Project& project, const ClimbReport& report);

/// The platform, the units' pins and the walls: in plan (the top floor) and in elevation
/// (x against height: floors, platform stages, pipes), in the building's unit.
std::string climb_report_svg(const Project& project, const ClimbReport& report);

}  // namespace ccbuild::orchestrator
