#pragma once
// A job's timed path as the machine follows it, and its path chunks on the wire
// (ccbuild_path_chunk_t, docs/dispatch.md): one mechanism for cutting a path into chunks
// of at most MAX_POINTS waypoints and putting them back together, used by the job
// builder, the dispatcher's recovery jobs and the simulated machine.

#include <cstdint>
#include <string>
#include <vector>

#include "ccbuild_lcm/ccbuild_path_chunk_t.hpp"

namespace ccbuild::machine {

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
  /// Appends waypoint k of `chunk`.
  void push_back(const ccbuild_lcm::ccbuild_path_chunk_t& chunk, int k);
};

/// `path` in chunks of at most ccbuild_path_chunk_t::MAX_POINTS waypoints, numbered from
/// 0, for `machine_id` (utime, seq and job id 0: set when sent).
std::vector<ccbuild_lcm::ccbuild_path_chunk_t> chunks_of(const TimedPath& path,
                                                         const std::string& machine_id);

/// The waypoints of `chunks`, in the order given.
TimedPath path_of(const std::vector<ccbuild_lcm::ccbuild_path_chunk_t>& chunks);

}  // namespace ccbuild::machine
