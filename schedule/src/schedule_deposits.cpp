#include "schedule_deposits.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"

namespace ccbuild::schedule::detail {

void label_pieces(std::vector<planner::Waypoint>& path, const floors::Layer& layer) {
  std::unordered_map<std::int64_t, std::vector<int>> by_wall;
  for (int s = 0; s < static_cast<int>(layer.segments.size()); ++s)
    by_wall[layer.segments[s].wall_id].push_back(s);
  auto on = [&](int s, const Eigen::Vector2d& p) {
    const auto& seg = layer.segments[s];
    const Eigen::Vector2d a = layer.start_m(seg), d = layer.end_m(seg) - a;
    const double u = std::clamp((p - a).dot(d) / std::max(d.squaredNorm(), 1e-18), 0.0, 1.0);
    return (a + u * d - p).norm() <= kOnSpan_m;
  };
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    if (!path[k].extruding) continue;
    const Eigen::Vector2d mid = 0.5 * (path[k].position_m + path[k + 1].position_m);
    int found = -1;
    if (auto it = by_wall.find(path[k].wall); it != by_wall.end())
      for (int s : it->second)
        if (on(s, mid)) found = s;
    for (int s = 0; found < 0 && s < static_cast<int>(layer.segments.size()); ++s)
      if (on(s, mid)) found = s;
    CCBUILD_CHECK(found >= 0,
                  printf_string("a deposited span of wall %lld from (%.4f, %.4f) to "
                                "(%.4f, %.4f) lies on no wall piece of its layer",
                                static_cast<long long>(path[k].wall), path[k].position_m.x(),
                                path[k].position_m.y(), path[k + 1].position_m.x(),
                                path[k + 1].position_m.y()));
    path[k].wall = layer.segments[found].wall_id;
    path[k].piece = layer.segments[found].piece + 1;
  }
}

DepositIndex index_of(const std::vector<std::vector<planner::Waypoint>>& nozzles) {
  DepositIndex index;
  for (const auto& path : nozzles)
    for (std::size_t k = 0; k + 1 < path.size(); ++k)
      if (path[k].extruding)
        index.add(path[k].wall, {path[k].position_m, path[k + 1].position_m, path[k].t_s,
                                 path[k + 1].t_s, path[k].piece});
  return index;
}

IntervalOffsets interval_offsets(const floors::Layer& upper, const DepositIndex& upper_index,
                                 const DepositIndex& lower_index) {
  std::vector<rules::PieceLine> pieces;
  pieces.reserve(upper.segments.size());
  for (const auto& seg : upper.segments)
    pieces.push_back({seg.wall_id, seg.piece + 1, upper.start_m(seg), upper.end_m(seg)});
  return rules::interval_offsets(pieces, upper_index, lower_index);
}

}  // namespace ccbuild::schedule::detail
