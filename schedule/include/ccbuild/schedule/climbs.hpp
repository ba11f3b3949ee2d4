#pragma once
// A building's climbs on a climbing machine: every stage and the climbs between them, as
// `ccbuild climb` reports them and the scheduler plans them (climb/climb.hpp).

#include <optional>

#include "ccbuild/climb/climb.hpp"
#include "ccbuild/schedule/setup.hpp"

namespace ccbuild::schedule {

/// Every stage and the climbs between them (those planned: `climbs[k]` goes from stage
/// climbs[k].from_stage).
struct ClimbReport {
  /// A fixed gantry: the building is within its reach (opening it checked), no stages.
  bool fixed_gantry = false;
  climb::StagePlan stages;
  std::vector<climb::ClimbPlan> climbs;
  /// Solved when every stage was placed and every climb planned (or none is needed).
  climb::ClimbStatus status() const;
  double climb_time_s() const;
  double planning_s() const;
};

/// Throws InputError (field `floor`) when `floor` is not a floor of the building.
void check_floor(const Setup& setup, int floor);

/// Places the stages and plans the climbs (of every stage, or those that end a stage on
/// floor `floor` when given). On a fixed gantry the report says so and has no stages.
/// Throws InputError when `floor` is not a floor.
ClimbReport plan_climbs(const Setup& setup, std::optional<int> floor,
                        const climb::ClimbOptions& options);

}  // namespace ccbuild::schedule
