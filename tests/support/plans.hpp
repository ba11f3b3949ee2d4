#pragma once
// Floor plans written in tests as lists of walls.

#include <array>
#include <optional>
#include <vector>

#include "ccbuild/floors/plan.hpp"

namespace ccbuild::testing {

/// A plan from (x0, y0, x1, y1) walls, each `thicknesses[i]` thick when given (unset: the
/// nozzle's width); shared points become shared vertices. Validated.
inline floors::FloorPlan plan_from_walls(const std::vector<std::array<double, 4>>& walls,
                                         const std::vector<double>& thicknesses = {}) {
  floors::FloorPlan plan;
  auto vertex = [&](double x, double y) {
    for (const auto& v : plan.vertices)
      if (v.position_m.x() == x && v.position_m.y() == y) return v.id;
    plan.vertices.push_back({static_cast<std::int64_t>(plan.vertices.size()) + 1, {x, y}, {}});
    return plan.vertices.back().id;
  };
  for (std::size_t i = 0; i < walls.size(); ++i) {
    const auto& w = walls[i];
    const auto a = vertex(w[0], w[1]);
    const auto b = vertex(w[2], w[3]);
    plan.walls.push_back(
        {static_cast<std::int64_t>(plan.walls.size()) + 1,
         a,
         b,
         i < thicknesses.size() ? std::optional<double>(thicknesses[i]) : std::nullopt,
         {}});
  }
  floors::validate_plan(plan);
  return plan;
}

}  // namespace ccbuild::testing
