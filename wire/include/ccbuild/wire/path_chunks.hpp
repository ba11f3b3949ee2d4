#pragma once
// A timed path on the wire (ccbuild_path_chunk_t, docs/dispatch.md): one mechanism for
// cutting a path into chunks of at most MAX_POINTS waypoints and putting them back
// together, used where jobs become messages (the dispatcher) and back (the simulated
// machine).

#include <string>
#include <vector>

#include "ccbuild/wire/timed_path.hpp"
#include "ccbuild_lcm/ccbuild_path_chunk_t.hpp"

namespace ccbuild::wire {

/// Appends waypoint k of `chunk` to `path`.
void append_waypoint(TimedPath& path, const ccbuild_lcm::ccbuild_path_chunk_t& chunk, int k);

/// `path` in chunks of at most ccbuild_path_chunk_t::MAX_POINTS waypoints, numbered from
/// 0, for `machine_id` (utime, seq and job id 0: set when sent).
std::vector<ccbuild_lcm::ccbuild_path_chunk_t> chunks_of(const TimedPath& path,
                                                         const std::string& machine_id);

/// The waypoints of `chunks`, in the order given.
TimedPath path_of(const std::vector<ccbuild_lcm::ccbuild_path_chunk_t>& chunks);

}  // namespace ccbuild::wire
