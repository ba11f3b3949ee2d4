#pragma once
// A job's timed path as the machine follows it. On the wire it travels in path chunks
// (path_chunks.hpp).

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "ccbuild/rules/intervals.hpp"

namespace ccbuild::wire {

/// Waypoints as parallel columns, the chunk's fields: times from the job's start (s),
/// layout position and nozzle height (m), cumulative heading (rad), and while extruding
/// the wall and 1-based piece deposited up to the next waypoint (else 0).
struct TimedPath {
  std::vector<double> t_s, x_m, y_m, z_m, heading_rad;
  std::vector<bool> extruding;
  std::vector<std::int64_t> wall;
  std::vector<std::int32_t> piece;
  std::size_t size() const { return t_s.size(); }
  void push_back(double t, double x, double y, double z, double heading, bool deposits,
                 std::int64_t wall_id, std::int32_t piece_number);
};

/// Where `path` is `t_s` after its start: x, y, z (m) and heading (rad), in a straight
/// line between waypoints; its first waypoint before it, its last after it. The path must
/// not be empty.
std::array<double, 4> position_at(const TimedPath& path, double t_s);

/// The stretches `path` deposits when it starts at `origin_s` (times from then, s): every
/// one, or when it ended on a fault with `stopped_at` waypoints done (>= 0), those up to
/// that waypoint (as the machine counts them). Added to `index`, for the interval rule
/// (rules/intervals.hpp).
void add_deposits(rules::DepositIndex& index, const TimedPath& path, double origin_s,
                  int stopped_at = -1);

}  // namespace ccbuild::wire
