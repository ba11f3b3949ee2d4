#pragma once
// The exact, sequential cost of a tool path. Every reported time comes from here; the
// optimisers may approximate, but their answers are re-evaluated by CostModel::evaluate.
//
// Rules (SI units throughout):
// - Heading on a wall is its travel direction. The nozzle's cumulative heading must stay
//   inside the stopper range [stopper_min_rad, stopper_max_rad]; between walls it turns
//   the cheapest way the stopper allows from where it is, and when the short way would
//   pass the stopper the long way is taken and costed.
// - Each path begins already facing its first wall. A closed tour's last move returns to
//   the first wall's start and turns back to the starting cumulative heading (unwinding
//   whole turns too), so the next layer can repeat it; without a stopper (a continuous
//   nozzle joint) it simply turns the short way.
// - An air move between distinct points costs travel (distance / travel speed, or per axis
//   for rectilinear moves) plus the fixed acceleration delay; rotation overlaps it
//   (max) when the machine rotates while moving, else adds to it; lift and lower are
//   added when its travel path crosses a wall deposited earlier in this layer. Touching a
//   wall only at the move's own two ends is not crossing.
// - A move between coincident points (a corner) has no travel, no delay and no lift; it
//   costs only the rotation, if the heading changes.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "ccbuild/floors/slice.hpp"
#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/planner/tool_path.hpp"

namespace ccbuild::planner {

/// One air move (non-depositing travel) of a path.
struct Move {
  Eigen::Vector2d from_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d to_m = Eigen::Vector2d::Zero();
  double distance_m = 0.0;    ///< in the metric in use
  double travel_s = 0.0;      ///< motion only (without the acceleration delay)
  double rotation_rad = 0.0;  ///< signed change of cumulative heading
  double rotation_s = 0.0;
  bool lifted = false;
  double time_s = 0.0;  ///< the move's whole cost: the nozzle is idle this long
  int next_step = 0;    ///< index of the step this move leads to; -1 for a closing move
};

struct Evaluation {
  double airtime_distance_m = 0.0;
  double airtime_s = 0.0;
  double deposition_s = 0.0;
  double layer_time_s = 0.0;  ///< deposition + airtime
  double max_idle_s = 0.0;    ///< longest single move
  int lift_count = 0;
  int idle_limit_violations = 0;  ///< moves longer than the nozzle idle limit
  double total_rotation_rad = 0.0;
  double final_heading_rad = 0.0;  ///< cumulative, after the last move
  std::vector<Move> moves;         ///< in order, one before each step (plus the closing move)
};

/// Where a nozzle is partway along a path, for evaluating it step by step.
struct PathState {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  int point = -1;                    ///< layer point the nozzle is at, -1 elsewhere
  double heading_rad = 0.0;          ///< cumulative (stopper) heading
  double initial_heading_rad = 0.0;  ///< cumulative heading at the first wall
  int steps = 0;                     ///< steps deposited so far
};

/// Cost model of one layer for one machine. Holds a spatial index of the layer's walls
/// for the crossing tests, and shares ownership of the layer (and copies the machine),
/// so it never refers to an object its caller may destroy.
///
/// Thread safety: a CostModel is not thread-safe. evaluate() and the crossing queries
/// fill caches inside it, so each thread needs its own CostModel. Distinct CostModels
/// (even of one shared layer) may be used on different threads at once: they share no
/// mutable state, and neither does any other function of the planner.
class CostModel {
 public:
  /// Throws InputError (field `MachineModel::...`) when the machine's speeds are not
  /// positive; InternalError when `layer` is null.
  CostModel(std::shared_ptr<const floors::Layer> layer, const machine::MachineModel& machine,
            Metric metric);
  /// The same, on a copy of `layer`.
  CostModel(const floors::Layer& layer, const machine::MachineModel& machine, Metric metric);
  ~CostModel();
  CostModel(CostModel&&) noexcept;

  /// Exact evaluation of `sequence` (must hold each segment of the layer at most once;
  /// checked). Evaluates partial sequences too (for sections and tests).
  Evaluation evaluate(const Sequence& sequence, const PathSpec& path) const;

  /// Incremental form of evaluate(): start a path, bring the nozzle to each step in
  /// turn (the returned move is the air move before it; `deposited(segment)` says which
  /// walls are built already), then close a closed tour.
  PathState begin(const PathSpec& path) const;
  template <class Deposited>
  Move advance(PathState& state, const Step& step, const PathSpec& path,
               Deposited&& deposited) const;
  template <class Deposited>
  Move close(PathState& state, const Step& first, Deposited&& deposited) const;

  /// Points no farther apart than this are one point: a move between them does not move.
  static constexpr double kCoincident_m = 1e-9;
  // The three below are in the header: the searches call them for every candidate move
  // (a quarter of a large layer's planning time, out of line; bench/README.md, issue 50).
  /// Distance between two points in this model's metric, m.
  double distance_m(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const {
    return metric_distance_m(metric_, a, b);
  }
  /// Motion time of an air move between two distinct points, without delays, s.
  double travel_s(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const {
    const Eigen::Vector2d d = b - a;
    if (metric_ == Metric::kEuclidean) return d.norm() / machine_.travel_speed_m_s;
    // One axis at a time, each at its own speed.
    return std::abs(d.x()) / machine_.x.speed_m_s + std::abs(d.y()) / machine_.y.speed_m_s;
  }
  /// Time of a move of `distance_m` turning by `rotation_rad` (absolute), lifted or not:
  /// the rule above, for optimisers that approximate.
  double move_time_s(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double rotation_rad,
                     bool lifted) const {
    const bool coincident = distance_m(a, b) <= kCoincident_m;
    const double motion_s = coincident ? 0.0 : travel_s(a, b) + machine_.accel_delay_s;
    return combine_move_s(motion_s, turn_s(rotation_rad), lifted && !coincident);
  }
  /// Time of a turn by `rotation_rad` (either sign) at the nozzle's rotation speed, s.
  double turn_s(double rotation_rad) const {
    return std::abs(rotation_rad) / machine_.rotation_speed_rad_s;
  }
  /// The move-time rule from its parts, s: `motion_s` is travel plus the acceleration
  /// delay (0 between coincident points), `turn_s` the turn's time; rotation overlaps
  /// motion or adds to it as the machine says, and a lift adds lift and lower times.
  double combine_move_s(double motion_s, double turn_s, bool lifted) const {
    const double t = machine_.rotate_while_moving ? std::max(motion_s, turn_s) : motion_s + turn_s;
    return lifted ? t + machine_.lift_time_s + machine_.lower_time_s : t;
  }
  /// True when travelling a -> b (in this metric's path shape) crosses segment `index`.
  bool path_crosses(const Eigen::Vector2d& a, const Eigen::Vector2d& b, int segment) const;
  /// Segments whose walls the path a -> b crosses, whatever has been deposited. Results
  /// are cached (moves run between a small set of points); not thread-safe.
  const std::vector<int>& crossed_segments(const Eigen::Vector2d& a,
                                           const Eigen::Vector2d& b) const;

  /// Crossed segments of a move between two layer points (cached by point pair).
  const std::vector<int>& crossed_between_points(int from_point, int to_point) const;

  /// Heading of a step's wall, rad in (-pi, pi].
  double heading_rad(const Step& step) const {
    const double h = segment_heading_rad_[step.segment];
    return step.reversed ? (h > 0.0 ? h - M_PI : h + M_PI) : h;
  }
  int step_start_point(const Step& step) const {
    const auto& s = layer_->segments[step.segment];
    return step.reversed ? s.end_point : s.start_point;
  }
  int step_end_point(const Step& step) const {
    const auto& s = layer_->segments[step.segment];
    return step.reversed ? s.start_point : s.end_point;
  }
  const Eigen::Vector2d& step_start_m(const Step& step) const {
    return layer_->points[step_start_point(step)];
  }
  const Eigen::Vector2d& step_end_m(const Step& step) const {
    return layer_->points[step_end_point(step)];
  }
  /// The cheapest signed turn from cumulative heading `from_rad` to heading `target_rad`
  /// that keeps the cumulative heading inside the stopper range.
  double stopper_turn_rad(double from_rad, double target_rad) const;
  /// False for a continuous nozzle joint (no stopper: always the short way).
  bool has_stopper() const {
    return std::isfinite(machine_.stopper_min_rad) && std::isfinite(machine_.stopper_max_rad);
  }

  const floors::Layer& layer() const { return *layer_; }
  const machine::MachineModel& machine() const { return machine_; }
  Metric metric() const { return metric_; }
  double deposition_s() const { return deposition_s_; }

 private:
  struct Index;
  template <class Deposited>
  Move make_move(const PathState& state, int to_point, double rotation_rad, int next_step,
                 Deposited&& deposited) const;
  std::shared_ptr<const floors::Layer> layer_;
  machine::MachineModel machine_;
  Metric metric_;
  double deposition_s_ = 0.0;
  std::vector<double> segment_heading_rad_;
  std::unique_ptr<Index> index_;
};

template <class Deposited>
Move CostModel::make_move(const PathState& state, int to_point, double rotation_rad, int next_step,
                          Deposited&& deposited) const {
  Move m;
  m.from_m = state.position_m;
  m.to_m = layer_->points[to_point];
  m.distance_m = distance_m(m.from_m, m.to_m);
  m.rotation_rad = rotation_rad;
  m.rotation_s = turn_s(rotation_rad);
  m.next_step = next_step;
  const bool moves = m.distance_m > kCoincident_m;  // as move_time_s
  if (moves) {
    // Euclidean: the distance over the speed, as travel_s has it, without a second root.
    m.travel_s = metric_ == Metric::kEuclidean ? m.distance_m / machine_.travel_speed_m_s
                                               : travel_s(m.from_m, m.to_m);
    const std::vector<int>& crossed = state.point >= 0
                                          ? crossed_between_points(state.point, to_point)
                                          : crossed_segments(m.from_m, m.to_m);
    for (int s : crossed) {
      if (deposited(s)) {
        m.lifted = true;
        break;
      }
    }
  }
  // The move-time rule on the parts worked out above (move_time_s would work them out again).
  m.time_s =
      combine_move_s(moves ? m.travel_s + machine_.accel_delay_s : 0.0, m.rotation_s, m.lifted);
  return m;
}

template <class Deposited>
Move CostModel::advance(PathState& state, const Step& step, const PathSpec& path,
                        Deposited&& deposited) const {
  const double heading = heading_rad(step);
  const int start = step_start_point(step);
  const bool first = state.steps == 0;
  if (first) {
    state.heading_rad = state.initial_heading_rad = heading;  // paths begin facing their first wall
    if (path.closed) {
      state.position_m = layer_->points[start];
      state.point = start;
    }
  }
  const double turn = first ? 0.0 : stopper_turn_rad(state.heading_rad, heading);
  Move move = make_move(state, start, turn, state.steps, deposited);
  state.heading_rad += turn;
  state.point = step_end_point(step);
  state.position_m = layer_->points[state.point];
  ++state.steps;
  return move;
}

template <class Deposited>
Move CostModel::close(PathState& state, const Step& first, Deposited&& deposited) const {
  const int to = step_start_point(first);
  // With a stopper the nozzle unwinds to where it began; without one it turns the short way.
  const double turn = has_stopper()
                          ? state.initial_heading_rad - state.heading_rad
                          : stopper_turn_rad(state.heading_rad, state.initial_heading_rad);
  Move move = make_move(state, to, turn, -1, deposited);
  state.heading_rad += turn;
  state.point = to;
  state.position_m = layer_->points[to];
  return move;
}

/// True when `sequence` deposits every segment of the layer exactly once.
bool covers_every_segment_once(const Sequence& sequence, std::size_t segment_count);

/// The time a layer's walls take to lay, s: their length at the machine's deposition
/// speed, whatever their order and however many nozzles share them.
double deposition_time_s(const floors::Layer& layer, const machine::MachineModel& machine);

}  // namespace ccbuild::planner
