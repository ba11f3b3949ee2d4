#include "ccbuild/planner/timeline.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ccbuild/common/input_error.hpp"

namespace ccbuild::planner {

std::string to_string(RailAxis axis) {
  return axis == RailAxis::kX ? "x" : "y";
}

void Timeline::append(double time_s, const Eigen::Vector2d& position_m) {
  CCBUILD_CHECK(time_s_.empty() || time_s >= time_s_.back() - 1e-12,
                "timeline times do not decrease");
  time_s_.push_back(time_s_.empty() ? time_s : std::max(time_s, time_s_.back()));
  position_m_.push_back(position_m);
}

void Timeline::hold(double duration_s) {
  if (duration_s > 0.0) append(end_s() + duration_s, position_m_.back());
}

void Timeline::move_to(const Eigen::Vector2d& position_m, double duration_s) {
  append(end_s() + std::max(0.0, duration_s), position_m);
}

Eigen::Vector2d Timeline::at(double time_s) const {
  CCBUILD_CHECK(!time_s_.empty(), "timeline has a point");
  if (time_s <= time_s_.front()) return position_m_.front();
  if (time_s >= time_s_.back()) return position_m_.back();
  const auto it = std::upper_bound(time_s_.begin(), time_s_.end(), time_s);
  const std::size_t i = static_cast<std::size_t>(it - time_s_.begin());
  const double t0 = time_s_[i - 1], t1 = time_s_[i];
  if (t1 - t0 <= 1e-15) return position_m_[i];
  const double f = (time_s - t0) / (t1 - t0);
  return position_m_[i - 1] + f * (position_m_[i] - position_m_[i - 1]);
}

Timeline parked_at(const Eigen::Vector2d& position_m) {
  Timeline t;
  t.append(0.0, position_m);
  return t;
}

Timeline timeline_of(const CostModel& model, const Sequence& sequence, const PathSpec& path,
                     const std::vector<double>& wait_before_step_s) {
  return timeline_of(model, sequence, path, model.evaluate(sequence, path), wait_before_step_s);
}

Timeline timeline_of(const CostModel& model, const Sequence& sequence, const PathSpec& path,
                     const Evaluation& e, const std::vector<double>& wait_before_step_s) {
  const auto& machine = model.machine();
  Timeline t;
  const Eigen::Vector2d start =
      path.closed && !sequence.empty() ? model.step_start_m(sequence.front()) : path.start_m;
  t.append(0.0, start);
  auto air_move = [&](const Move& m) {
    const double lift = m.lifted ? machine.lift_time_s : 0.0;
    const double lower = m.lifted ? machine.lower_time_s : 0.0;
    if (m.distance_m <= 1e-9) {
      t.hold(m.time_s);  // a turn on the spot
      return;
    }
    const double motion = m.travel_s + machine.accel_delay_s;
    const double turn_first = machine.rotate_while_moving ? 0.0 : m.rotation_s;
    t.hold(lift + turn_first);
    if (model.metric() == Metric::kRectilinear) {
      // x first, then y, each for its share of the motion time.
      const Eigen::Vector2d corner(m.to_m.x(), m.from_m.y());
      const double tx = std::abs(m.to_m.x() - m.from_m.x()) / machine.x.speed_m_s;
      const double ty = std::abs(m.to_m.y() - m.from_m.y()) / machine.y.speed_m_s;
      const double share = tx + ty > 0.0 ? tx / (tx + ty) : 1.0;
      t.move_to(corner, motion * share);
      t.move_to(m.to_m, motion * (1.0 - share));
    } else {
      t.move_to(m.to_m, motion);
    }
    t.hold(m.time_s - lift - turn_first - motion - lower);  // rest of a longer turn
    t.hold(lower);
  };
  // Moves come one before each step (a closed tour's first move is its closing move).
  std::size_t move = 0;
  for (std::size_t k = 0; k < sequence.size(); ++k) {
    if (k < wait_before_step_s.size()) t.hold(wait_before_step_s[k]);
    if (k > 0 || !path.closed) air_move(e.moves[move++]);
    const double length = model.layer().segments[sequence[k].segment].length_m;
    t.move_to(model.step_end_m(sequence[k]), length / machine.deposition_speed_m_s);
  }
  if (path.closed && !sequence.empty()) air_move(e.moves[move++]);
  return t;
}

namespace {

// Breakpoint times of both curves, merged.
std::vector<double> merged_times(const Timeline& a, const Timeline& b) {
  std::vector<double> times;
  times.reserve(a.size() + b.size() + 1);
  std::merge(a.times().begin(), a.times().end(), b.times().begin(), b.times().end(),
             std::back_inserter(times));
  times.insert(times.begin(), 0.0);
  times.erase(std::unique(times.begin(), times.end()), times.end());
  return times;
}

}  // namespace

std::optional<Conflict> first_conflict(const Timeline& left, const Timeline& right, RailAxis axis,
                                       double gantry_width_m) {
  const std::vector<double> times = merged_times(left, right);
  constexpr double kTolerance = 1e-9;
  double previous_t = 0.0, previous_gap = 0.0;
  for (std::size_t i = 0; i < times.size(); ++i) {
    const double t = times[i];
    const double l = Timeline::rail(left.at(t), axis), r = Timeline::rail(right.at(t), axis);
    const double gap = r - l;
    if (gap < gantry_width_m - kTolerance) {
      double when = t;
      if (i > 0 && previous_gap > gap) {
        // The gap is linear between breakpoints: the first moment it reaches the width.
        when =
            previous_t + (previous_gap - gantry_width_m) / (previous_gap - gap) * (t - previous_t);
        when = std::clamp(when, previous_t, t);
      }
      return Conflict{when, Timeline::rail(left.at(when), axis),
                      Timeline::rail(right.at(when), axis)};
    }
    previous_t = t;
    previous_gap = gap;
  }
  return std::nullopt;
}

double min_gap_m(const Timeline& left, const Timeline& right, RailAxis axis) {
  double gap = std::numeric_limits<double>::infinity();
  for (double t : merged_times(left, right))
    gap = std::min(gap, Timeline::rail(right.at(t), axis) - Timeline::rail(left.at(t), axis));
  return gap;
}

}  // namespace ccbuild::planner
