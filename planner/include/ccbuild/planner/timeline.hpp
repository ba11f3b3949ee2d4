#pragma once
// Where a nozzle is over time: its waypoints (every breakpoint of its motion, for the
// schedule, the dispatcher and independent checks), the timeline of its position along
// the rails derived from them, and the exact collision check between two gantries on
// common rails.
//
// A timeline is piecewise linear: breakpoints (t, position), straight between them,
// held after the last one. It follows the cost model's timing of each step: an air move
// holds still while lifting (and, when rotation does not overlap motion, while turning),
// travels at constant speed over its motion time (rectilinear moves do x first, then y,
// each for its share of the time), then holds while lowering or finishing its turn; a wall
// is deposited at constant speed. A wait holds still at the end of the previous wall.
//
// Two gantries collide when their rail coordinates come closer than the gantry width.
// Both rail curves are piecewise linear, so their gap is piecewise linear with
// breakpoints only where either curve has one: the gap's minimum over any stretch
// between consecutive breakpoints is at one of its ends. Checking the gap at every
// breakpoint of either curve is therefore exact; sampling at fixed times is not.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "ccbuild/planner/cost_model.hpp"
#include "ccbuild/planner/tool_path.hpp"

namespace ccbuild::planner {

using machine::RailAxis;
using machine::to_string;

/// A point's coordinate along the rails, m: the one place that says which axis it is.
inline double rail_coordinate(const Eigen::Vector2d& p, RailAxis axis) {
  return axis == RailAxis::kX ? p.x() : p.y();
}
/// `p` moved to rail coordinate `rail_m`, its other coordinate kept.
inline Eigen::Vector2d with_rail_coordinate(Eigen::Vector2d p, RailAxis axis, double rail_m) {
  (axis == RailAxis::kX ? p.x() : p.y()) = rail_m;
  return p;
}
/// The machine axis the rails run along (its range is the rails' length).
inline const machine::AxisLimits& rail_axis_limits(const machine::MachineModel& machine,
                                                   RailAxis axis) {
  return axis == RailAxis::kX ? machine.x : machine.y;
}

class Timeline {
 public:
  /// Adds a breakpoint; times must not decrease.
  void append(double time_s, const Eigen::Vector2d& position_m);
  /// Holds still for `duration_s` at the last position.
  void hold(double duration_s);
  /// Moves in a straight line to `position_m` over `duration_s`.
  void move_to(const Eigen::Vector2d& position_m, double duration_s);

  bool empty() const { return time_s_.empty(); }
  std::size_t size() const { return time_s_.size(); }
  double end_s() const { return time_s_.empty() ? 0.0 : time_s_.back(); }
  const std::vector<double>& times() const { return time_s_; }
  const std::vector<Eigen::Vector2d>& positions() const { return position_m_; }
  /// Position at `time_s` (the first position before the start, the last after the end).
  Eigen::Vector2d at(double time_s) const;

 private:
  std::vector<double> time_s_;
  std::vector<Eigen::Vector2d> position_m_;
};

/// One breakpoint of a nozzle's timed path. Between two consecutive waypoints the nozzle
/// moves in a straight line at constant speed: position, height and heading all change
/// linearly with time. It deposits wall `wall` (piece `piece`) from one waypoint to the
/// next when the first of the two says `extruding`.
struct Waypoint {
  double t_s = 0.0;                                      ///< layer time
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();  ///< layout coordinates
  double z_m = 0.0;          ///< nozzle height: the layer's top, higher while lifted
  double heading_rad = 0.0;  ///< cumulative heading (the stopper counts whole turns)
  bool extruding = false;
  std::int64_t wall = 0;  ///< when extruding: the wall's id (else 0)
  int piece = 0;          ///< when extruding: 1-based piece of the wall (else 0)
};

/// The waypoints of a sequence on a layer, timed exactly as the cost model times it
/// (see below), from `start_s` at the path's start, at nozzle height `z_m` (lifts rise
/// by the machine's lift height). `wait_before_step_s[k]` (if given) holds the nozzle
/// before step k's air move. A closed tour includes its closing move.
///
/// An air move: lift (z rises, if lifted); turn first when the machine cannot rotate
/// while moving; travel at constant speed for travel + acceleration delay (rectilinear:
/// x, then y, each for its share of the time), turning meanwhile when it can; finish a
/// turn longer than the travel; lower. A wall: at the deposition speed along the wall.
std::vector<Waypoint> waypoints_of(const CostModel& model, const Sequence& sequence,
                                   const PathSpec& path, const Evaluation& evaluation, double z_m,
                                   double start_s = 0.0,
                                   const std::vector<double>& wait_before_step_s = {});

/// The timeline of a sequence on a layer, as the cost model times it, starting at t = 0
/// at the path's start: waypoints_of's positions (the same timing). `wait_before_step_s[k]`
/// (if given) holds the nozzle before step k's air move. A closed tour includes its
/// closing move.
Timeline timeline_of(const CostModel& model, const Sequence& sequence, const PathSpec& path,
                     const std::vector<double>& wait_before_step_s = {});
/// The same, reusing the sequence's evaluation (waits change the timing, not the moves).
Timeline timeline_of(const CostModel& model, const Sequence& sequence, const PathSpec& path,
                     const Evaluation& evaluation, const std::vector<double>& wait_before_step_s);

/// Time to bring every nozzle from where its path on one layer ends (`from[n].back()`) to
/// where its path on the next layer starts (`to[n].front()`), one `layer_height_m` up, s:
/// the slowest nozzle's move, then the rise at the z speed. Unlike an air move within a
/// layer (CostModel::move_time_s), the nozzle has stopped at the layer's end: it goes in
/// a straight line at the travel speed, turns through the whole change of its cumulative
/// heading (the stopper counts turns, so none is taken the short way), overlapping or one
/// after the other as the machine says, and the acceleration delay comes after that, even
/// for a nozzle that only rises. Nozzles with no path on either layer are skipped.
double layer_change_s(const machine::MachineModel& machine,
                      const std::vector<std::vector<Waypoint>>& from,
                      const std::vector<std::vector<Waypoint>>& to, double layer_height_m);

/// A timeline that stays at one point from t = 0 (an idle or parked gantry).
Timeline parked_at(const Eigen::Vector2d& position_m);

struct Conflict {
  double time_s = 0.0;  ///< first moment the gap is below the gantry width
  double left_m = 0.0;  ///< rail coordinates of the two gantries then
  double right_m = 0.0;
};

/// The first moment `right` (the gantry with the larger rail coordinate) comes closer
/// than `gantry_width_m` to `left`, exactly (see above); nullopt when never.
std::optional<Conflict> first_conflict(const Timeline& left, const Timeline& right, RailAxis axis,
                                       double gantry_width_m);

/// The smallest rail gap (right - left) over all time; negative when they swap order.
double min_gap_m(const Timeline& left, const Timeline& right, RailAxis axis);

}  // namespace ccbuild::planner
