#pragma once
// Synthetic floor plans that look like buildings, for benchmarks and property tests: a
// rectangular footprint divided into rooms by recursive subdivision (so interior walls end
// in T-junctions), walls split at every junction, door gaps in interior walls and window
// gaps in exterior walls. Deterministic for a seed.

#include <cstdint>

#include "ccbuild/floors/plan.hpp"

namespace ccbuild::floors {

struct PlanGeneratorOptions {
  int rooms = 8;
  std::uint64_t seed = 1;
  double min_room_side_m = 2.4;
  double door_probability = 0.7;    ///< per interior wall long enough for a door
  double window_probability = 0.8;  ///< per exterior wall long enough for a window
  double door_width_m = 0.9;
  double window_width_m = 1.2;
};

/// A valid plan (validate_plan passes) with about `rooms` rooms. Doors: sill 0, head
/// 2.1 m; windows: sill 0.9 m, head 2.1 m; so a layer at 1.0-2.0 m cuts both.
FloorPlan generate_plan(const PlanGeneratorOptions& options);

/// A plan whose layer at mid-height 1.5 m has about `segments` wall pieces (the room
/// count is searched for), for sizing benchmarks by what the planner sees.
FloorPlan generate_plan_with_segments(int segments, std::uint64_t seed);

}  // namespace ccbuild::floors
