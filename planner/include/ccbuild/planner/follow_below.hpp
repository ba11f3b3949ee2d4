#pragma once
// A layer deposited in the order of the layer below (paper 000 §5, our addition): each
// nozzle lays its own pieces in the order and direction it laid the walls under them, so
// that every piece is covered about one layer time after the one under it. Where openings
// begin or end, an optimised plan may cover first what the layer below did last; this one
// does not. The scheduler decides which nozzle lays which piece (from the layer below's
// paths); this plans their timed paths, keeps the gantries a gantry width apart (checked
// exactly at every breakpoint), and may hold a gantry back. SI units.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "ccbuild/floors/slice.hpp"
#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/planner/timeline.hpp"

namespace ccbuild::planner {

/// One piece of the layer (a segment index) laid in a direction.
struct FollowStep {
  int segment = 0;
  bool reversed = false;
};

struct FollowRequest {
  /// Per nozzle, in rail order: its pieces in the order it lays them.
  std::vector<std::vector<FollowStep>> order;
  /// Per nozzle: where it stands when it has nothing to lay (for the gap checks).
  std::vector<Eigen::Vector2d> parked_m;
  /// A gantry that would come within the gantry width of the one before it starts later,
  /// by the first of 5 s steps that clears it, up to the nozzle idle limit, parked at its
  /// first waypoint meanwhile.
  bool hold_back = false;
};

struct FollowPlan {
  std::vector<std::vector<Waypoint>> waypoints;  ///< per nozzle, layer time
  double layer_time_s = 0.0, deposition_s = 0.0, airtime_s = 0.0, max_idle_s = 0.0;
  double min_gap_m = 0.0;  ///< nearest approach of two gantries (0 for one nozzle)
  /// The air move longest over the nozzle idle limit, if one is (then not usable).
  int idle_limit_violations = 0;
  double violating_idle_s = 0.0;
  /// Why the gantries cannot keep their gap, when they cannot (not usable).
  std::string gap_broken;
  bool usable() const { return idle_limit_violations == 0 && gap_broken.empty(); }
};

/// Plans `layer` on `machine`'s gantries in the order `request` gives (the time
/// objective's timing).
FollowPlan plan_following(const floors::Layer& layer, const machine::MachineModel& machine,
                          const FollowRequest& request);

}  // namespace ccbuild::planner
