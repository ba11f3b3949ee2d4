#pragma once
// Where a nozzle is over time, and the exact collision check between two gantries on
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
#include <optional>
#include <vector>

#include "ccbuild/planner/cost_model.hpp"
#include "ccbuild/planner/tool_path.hpp"

namespace ccbuild::planner {

enum class RailAxis { kX, kY };
std::string to_string(RailAxis axis);

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
  /// The rail coordinate of position `i`.
  static double rail(const Eigen::Vector2d& p, RailAxis axis) {
    return axis == RailAxis::kX ? p.x() : p.y();
  }

 private:
  std::vector<double> time_s_;
  std::vector<Eigen::Vector2d> position_m_;
};

/// The timeline of a sequence on a layer, as the cost model times it, starting at t = 0
/// at the path's start. `wait_before_step_s[k]` (if given) holds the nozzle before step
/// k's air move. A closed tour includes its closing move.
Timeline timeline_of(const CostModel& model, const Sequence& sequence, const PathSpec& path,
                     const std::vector<double>& wait_before_step_s = {});
/// The same, reusing the sequence's evaluation (waits change the timing, not the moves).
Timeline timeline_of(const CostModel& model, const Sequence& sequence, const PathSpec& path,
                     const Evaluation& evaluation, const std::vector<double>& wait_before_step_s);

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
