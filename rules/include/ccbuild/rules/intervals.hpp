#pragma once
// Where and how the local interval between a layer and the one under it is taken: along
// every stretch of wall both layers cover, at both ends of it, each layer with the beads
// that cover that stretch (docs/schedule.md, "Intervals, per wall piece"). The scheduler,
// the schedule's re-checks, the dispatcher's re-plans and the simulator's refusals all
// take it here.

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

namespace ccbuild::rules {

class AgeClock;

/// A point lies on a deposited span when this close to it, m: layers merge points closer
/// than 1 mm, so a section's cut may move a wall end by up to that.
inline constexpr double kOnSpan_m = 2e-3;

/// A stretch a nozzle deposits on wall `wall` (piece `piece`, 1-based; 0 when unknown)
/// from a to b (m), between the times ta and tb (s, from whatever origin the caller's
/// index uses: a plan's start, or the site clock).
struct Span {
  Eigen::Vector2d a, b;
  double ta = 0.0, tb = 0.0;
  std::int32_t piece = 0;
};

/// When each point of a wall is deposited, by wall id.
struct DepositIndex {
  std::unordered_map<std::int64_t, std::vector<Span>> spans;
  void add(std::int64_t wall, const Span& span) { spans[wall].push_back(span); }
  bool empty() const { return spans.empty(); }
  /// Earliest and latest time the nozzles pass `p` on wall `wall` depositing; false when
  /// no span of that wall passes it.
  bool times_at(std::int64_t wall, const Eigen::Vector2d& p, double& lo, double& hi) const;
};

/// A point of a wall piece: the wall, the piece (1-based within its layer) and where, m.
struct PieceEnd {
  std::int64_t wall = 0;
  int piece = 0;
  double x_m = 0.0, y_m = 0.0;
};

/// The local intervals between a layer and the one it is deposited on, less the
/// difference of their index origins: interval at a point = origin_above - origin_below
/// + offset.
struct IntervalOffsets {
  /// One point where the interval is taken (a piece's end, or a bead's end along it, from
  /// one side): when the upper layer passes it (earliest, latest) and when the lower one
  /// did, each in its own index's time, by the beads on that side.
  struct End {
    double up_lo_s = 0.0, up_hi_s = 0.0, low_lo_s = 0.0, low_hi_s = 0.0;
    PieceEnd at;
  };
  std::vector<End> each;  ///< every point counted in `ends`
  int ends = 0;           ///< points taken (two per stretch both layers cover)
  double min_offset_s = std::numeric_limits<double>::infinity();
  double max_offset_s = -std::numeric_limits<double>::infinity();
  PieceEnd min_at, max_at;
};

/// A wall piece of the upper layer: its wall, its number (1-based within its layer) and
/// its ends, m.
struct PieceLine {
  std::int64_t wall = 0;
  int piece = 0;
  Eigen::Vector2d a, b;
};

/// Along every piece of the upper layer (`upper_pieces`) that lies on a wall deposited in
/// the layer below: at both ends of each stretch between the points where a bead of
/// either layer starts or ends (and the piece's ends) that both layers cover, with the
/// beads covering that stretch; where a stretch is passed twice, the smaller interval for
/// the minimum and the larger for the maximum. The scheduler's form: it knows the pieces.
IntervalOffsets interval_offsets(const std::vector<PieceLine>& upper_pieces,
                                 const DepositIndex& upper_index, const DepositIndex& lower_index);

/// The same rule where only the deposits are known (the dispatcher and the machines have
/// the paths, not the layer): the pieces are the upper layer's deposited spans, each
/// taken whole. Every piece is deposited by spans along it, so the stretches and their
/// ends are the layer's form's.
IntervalOffsets interval_offsets(const DepositIndex& upper_index, const DepositIndex& lower_index);

/// When the upper layer may start (in the lower index's time) so that every point of
/// `offsets` is covered no sooner than `min_interval_s` after it was laid and no later
/// than `max_interval_s`: its upper times are from the upper layer's start. Unbounded
/// when no point is shared.
struct StartWindow {
  double earliest_s = -std::numeric_limits<double>::infinity();
  double latest_s = std::numeric_limits<double>::infinity();
  int ends_covered = 0;  ///< points of the upper layer over the lower one
  /// The newest point it covers was laid then (-inf when none): a planned joint's
  /// treatment waits for it to be old enough.
  double newest_below_s = -std::numeric_limits<double>::infinity();
  /// The points that set the earliest and the latest start (the first such point).
  PieceEnd earliest_at, latest_at;
  bool empty() const { return earliest_s > latest_s; }
};
/// With `clock` (site weather), the interval is the concrete's equivalent age: covered no
/// sooner than when what lies below is `min_interval_s` old by the clock, no later than
/// `max_interval_s` old. The offsets' lower times are from `lower_origin_s` (the lower
/// layer's start, for the scheduler's offsets; 0 where they are schedule times already),
/// and the window is in schedule time. The scheduler, the dispatcher's re-plans and the
/// schedule's re-checks take the window here; a strength need is the same rule with the
/// age the load needs as its minimum.
StartWindow start_window(const IntervalOffsets& offsets, double min_interval_s,
                         double max_interval_s, const AgeClock* clock = nullptr,
                         double lower_origin_s = 0.0);

}  // namespace ccbuild::rules
