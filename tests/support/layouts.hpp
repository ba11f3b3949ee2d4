#pragma once
// Layers for planner tests: hand-made ones, small random ones, generated floor plans.

#include <array>
#include <random>

#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/generate.hpp"
#include "ccbuild/floors/plan.hpp"
#include "ccbuild/floors/slice.hpp"
#include "ccbuild/machine/machine_model.hpp"
#include "plans.hpp"

namespace ccbuild::testing {

inline floors::Layer layer_from_walls(const std::vector<std::array<double, 4>>& walls) {
  return floors::plan_as_layer(plan_from_walls(walls));
}

/// `count` walls between random points of a 0..10 m grid, none overlapping another
/// along a line (crossings allowed: they exercise lifts).
inline floors::Layer random_layer(int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<std::array<double, 4>> walls;
  while (static_cast<int>(walls.size()) < count) {
    std::array<double, 4> w{double(rng() % 11), double(rng() % 11), double(rng() % 11),
                            double(rng() % 11)};
    auto candidate = walls;
    candidate.push_back(w);
    try {
      plan_from_walls(candidate);
      walls = candidate;
    } catch (const InputError&) {
    }
  }
  return layer_from_walls(walls);
}

/// A generated floor plan cut at mid-height 1.5 m (doors and windows open).
inline floors::Layer floor_plan_layer(int rooms, std::uint64_t seed) {
  floors::PlanGeneratorOptions o;
  o.rooms = rooms;
  o.seed = seed;
  return floors::slice_plan_at(floors::generate_plan(o), 1.0, 2.0);
}

/// Round numbers for hand computation: 1 m/s travel, 1 rad/s turns, 1 s accel, lifts
/// 2 s + 3 s, deposition 0.5 m/s, +-360 degree stopper.
inline machine::MachineModel simple_machine() {
  machine::MachineModel m = machine::MachineModel::defaults();
  m.travel_speed_m_s = 1.0;
  m.x.speed_m_s = 1.0;
  m.y.speed_m_s = 0.5;
  m.rotation_speed_rad_s = 1.0;
  m.accel_delay_s = 1.0;
  m.lift_time_s = 2.0;
  m.lower_time_s = 3.0;
  m.deposition_speed_m_s = 0.5;
  m.rotate_while_moving = true;
  return m;
}

}  // namespace ccbuild::testing
