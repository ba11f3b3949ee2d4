#pragma once
// One motion planned with OMPL in a box of joint values: RRTConnect, seeded, simplified,
// and re-checked at four times the planner's resolution. Internal to climb/.
//
// Why RRTConnect: each motion is a single query between two known joint states in one to
// four dimensions, mostly free space with a few walls in the way; growing trees from both
// ends connects such queries in a handful of samples, and OMPL's shortcutting then removes
// the random detours. An asymptotically optimal planner (RRT*, BIT*) would spend its whole
// budget improving paths that the simplifier already makes nearly straight, and a climb
// must plan within a second; PRM's roadmap would pay off only over many queries in one
// unchanging scene, while every climb sees a new set of walls.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "scene.hpp"

namespace ccbuild::climb::detail {

struct MotionProblem {
  std::vector<double> lower, upper;  ///< the joint box (limits, margins included)
  std::vector<double> start, goal;
  /// The validity of a state; must be callable from the planner's thread.
  std::function<Verdict(const std::vector<double>&)> valid;
  std::uint64_t seed = 1;
  double time_s = 1.0;
  long max_iterations = 50000;  ///< a count, so that failing does not depend on speed
  double resolution = 0.004;    ///< of the box's diagonal, between checked states
};

struct MotionResult {
  Verdict verdict;                        ///< ok, or why no motion was found
  std::vector<std::vector<double>> path;  ///< from start to goal
  double planning_s = 0.0;
  bool timed_out = false;
};

MotionResult plan_motion(const MotionProblem& problem);

}  // namespace ccbuild::climb::detail
