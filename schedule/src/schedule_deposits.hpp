#pragma once
// Where and when a plan deposits each wall: the scheduler's view of a plan's waypoints,
// for the local intervals between a layer and the one under it (their rule is
// rules/intervals.hpp), and for labelling a plan's spans with the pieces of the layer
// that uses it. Internal to the scheduler.

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

#include "ccbuild/floors/slice.hpp"
#include "ccbuild/planner/timeline.hpp"
#include "ccbuild/rules/intervals.hpp"
#include "ccbuild/schedule/schedule.hpp"

namespace ccbuild::schedule::detail {

using rules::DepositIndex;
using rules::IntervalOffsets;
using rules::kOnSpan_m;
using rules::Span;

/// Labels each extruding waypoint with the wall and 1-based piece of `layer` it lies on.
/// Throws InternalError when a span lies on no piece.
void label_pieces(std::vector<planner::Waypoint>& path, const floors::Layer& layer);

/// The deposit index of a plan's nozzles.
DepositIndex index_of(const std::vector<std::vector<planner::Waypoint>>& nozzles);

/// The local intervals between `upper` (its pieces) and the layer below, by the rule of
/// rules/intervals.hpp.
IntervalOffsets interval_offsets(const floors::Layer& upper, const DepositIndex& upper_index,
                                 const DepositIndex& lower_index);

}  // namespace ccbuild::schedule::detail
