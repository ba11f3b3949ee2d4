#pragma once
// Where and when a plan deposits each wall: the scheduler's view of a plan's waypoints,
// for the local intervals between a layer and the one under it, and for labelling a
// plan's spans with the pieces of the layer that uses it. Internal to the scheduler.

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

#include "ccbuild/floors/slice.hpp"
#include "ccbuild/planner/timeline.hpp"
#include "ccbuild/schedule/schedule.hpp"

namespace ccbuild::schedule::detail {

/// A point lies on a deposited span when this close to it: layers merge points closer
/// than 1 mm, so a section's cut may move a wall end by up to that.
inline constexpr double kOnSpan_m = 2e-3;

/// A stretch a nozzle deposits: from a to b, between the times ta and tb (plan time).
struct Span {
  Eigen::Vector2d a, b;
  double ta = 0.0, tb = 0.0;
};

/// When each point of a wall is deposited in one plan, by wall id.
struct DepositIndex {
  std::unordered_map<std::int64_t, std::vector<Span>> spans;
  /// Earliest and latest time the nozzles pass `p` on wall `wall` depositing; false when
  /// no span of that wall passes it.
  bool times_at(std::int64_t wall, const Eigen::Vector2d& p, double& lo, double& hi) const {
    const auto it = spans.find(wall);
    if (it == spans.end()) return false;
    bool found = false;
    for (const Span& s : it->second) {
      const Eigen::Vector2d d = s.b - s.a;
      const double len2 = d.squaredNorm();
      const double u = len2 > 0 ? std::clamp((p - s.a).dot(d) / len2, 0.0, 1.0) : 0.0;
      if ((s.a + u * d - p).norm() > kOnSpan_m) continue;
      const double t = s.ta + u * (s.tb - s.ta);
      lo = found ? std::min(lo, t) : t;
      hi = found ? std::max(hi, t) : t;
      found = true;
    }
    return found;
  }
};

/// Labels each extruding waypoint with the wall and 1-based piece of `layer` it lies on.
/// Throws InternalError when a span lies on no piece.
void label_pieces(std::vector<planner::Waypoint>& path, const floors::Layer& layer);

/// The deposit index of a plan's nozzles.
DepositIndex index_of(const std::vector<std::vector<planner::Waypoint>>& nozzles);

/// The local intervals between a layer and the one it is deposited on, less the
/// difference of their starts: interval at an end = start_above - start_below + offset.
struct IntervalOffsets {
  /// One point where the interval is taken (a piece's end, or a bead's end along it, from
  /// one side): when the upper plan passes it (earliest, latest) and when the lower one
  /// did, each from its own layer's start, by the beads on that side.
  struct End {
    double up_lo_s = 0.0, up_hi_s = 0.0, low_lo_s = 0.0, low_hi_s = 0.0;
    PieceEnd at;
  };
  std::vector<End> each;  ///< every end counted in `ends`
  int ends = 0;           ///< points taken (two per stretch both layers cover)
  double min_offset_s = std::numeric_limits<double>::infinity();
  double max_offset_s = -std::numeric_limits<double>::infinity();
  PieceEnd min_at, max_at;
};

/// Along every piece of `upper` that lies on a wall deposited in the layer below: at both
/// ends of each stretch between the points where a bead of either layer starts or ends
/// (and the piece's ends) that both layers cover, with the beads covering that stretch;
/// where a stretch is passed twice, the smaller interval for the minimum and the larger
/// for the maximum (docs/schedule.md, "Intervals, per wall piece").
IntervalOffsets interval_offsets(const floors::Layer& upper, const DepositIndex& upper_index,
                                 const DepositIndex& lower_index);

}  // namespace ccbuild::schedule::detail
