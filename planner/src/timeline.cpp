#include "ccbuild/planner/timeline.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "ccbuild/common/input_error.hpp"

namespace ccbuild::planner {

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

double layer_change_s(const machine::MachineModel& machine,
                      const std::vector<std::vector<Waypoint>>& from,
                      const std::vector<std::vector<Waypoint>>& to, double layer_height_m) {
  double longest_s = 0.0;
  for (std::size_t n = 0; n < to.size() && n < from.size(); ++n) {
    if (from[n].empty() || to[n].empty()) continue;
    const Waypoint& a = from[n].back();
    const Waypoint& b = to[n].front();
    const double travel_s = (b.position_m - a.position_m).norm() / machine.travel_speed_m_s;
    const double turn_s = std::abs(b.heading_rad - a.heading_rad) / machine.rotation_speed_rad_s;
    const double move_s =
        machine.rotate_while_moving ? std::max(travel_s, turn_s) : travel_s + turn_s;
    longest_s = std::max(longest_s, move_s + machine.accel_delay_s);
  }
  return longest_s + layer_height_m / machine.z.speed_m_s;
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

namespace {

// Walks a path as the cost model times it and reports every breakpoint of its motion:
// visit(waypoint, position_break) where `position_break` is false only for a turn that
// ends while the nozzle travels on in a straight line, which a position timeline can
// leave out.
template <class Visit>
void walk_path(const CostModel& model, const Sequence& sequence, const PathSpec& path,
               const Evaluation& e, double z_m, double start_s,
               const std::vector<double>& wait_before_step_s, Visit&& visit) {
  const auto& machine = model.machine();
  const auto& layer = model.layer();
  Waypoint at;
  at.t_s = start_s;
  at.position_m =
      path.closed && !sequence.empty() ? model.step_start_m(sequence.front()) : path.start_m;
  at.z_m = z_m;
  at.heading_rad = sequence.empty() ? 0.0 : model.heading_rad(sequence.front());
  visit(at, true);
  auto emit = [&](double duration_s, bool position_break) {
    at.t_s += std::max(0.0, duration_s);
    at.extruding = false;
    at.wall = 0;
    at.piece = 0;
    visit(at, position_break);
  };
  auto air_move = [&](const Move& m) {
    const double heading0 = at.heading_rad;
    if (m.distance_m <= 1e-9) {  // a turn on the spot
      if (m.time_s > 0.0) {
        at.heading_rad = heading0 + m.rotation_rad;
        emit(m.time_s, true);
      }
      return;
    }
    const double lift = m.lifted ? machine.lift_time_s : 0.0;
    const double lower = m.lifted ? machine.lower_time_s : 0.0;
    const double motion = m.travel_s + machine.accel_delay_s;
    if (lift > 0.0) {
      at.z_m = z_m + machine.lift_height_m;
      emit(lift, true);
    }
    // The turn overlaps the motion from its start, or comes before it.
    double turned_s = 0.0;
    if (!machine.rotate_while_moving && m.rotation_s > 0.0) {
      at.heading_rad = heading0 + m.rotation_rad;
      turned_s = m.rotation_s;
      emit(m.rotation_s, true);
    }
    // Breakpoints inside the motion: the rectilinear corner, the end of an overlapping
    // turn, the arrival.
    const Eigen::Vector2d from = m.from_m, to = m.to_m;
    const bool two_legs = model.metric() == Metric::kRectilinear &&
                          std::abs(to.x() - from.x()) > 1e-12 &&
                          std::abs(to.y() - from.y()) > 1e-12;
    const Eigen::Vector2d corner(to.x(), from.y());
    double corner_s = motion;
    if (two_legs) {
      const double tx = std::abs(to.x() - from.x()) / machine.x.speed_m_s;
      const double ty = std::abs(to.y() - from.y()) / machine.y.speed_m_s;
      corner_s = motion * (tx / (tx + ty));
    }
    auto position_at = [&](double s) -> Eigen::Vector2d {
      if (s >= motion) return to;
      if (two_legs) {
        if (s <= corner_s) return from + (corner - from) * (s / corner_s);
        return corner + (to - corner) * ((s - corner_s) / (motion - corner_s));
      }
      return from + (to - from) * (s / motion);
    };
    const bool turning = machine.rotate_while_moving && m.rotation_s > 0.0;
    auto heading_at = [&](double s) {
      if (!turning) return heading0 + (turned_s > 0.0 ? m.rotation_rad : 0.0);
      return heading0 + m.rotation_rad * std::min(1.0, s / m.rotation_s);
    };
    // (time into the motion, position break): at most three, no allocation per move.
    std::array<std::pair<double, bool>, 3> breaks;
    std::size_t count = 0;
    if (two_legs) breaks[count++] = {corner_s, true};
    if (turning && m.rotation_s < motion) breaks[count++] = {m.rotation_s, false};
    breaks[count++] = {motion, true};
    std::sort(breaks.begin(), breaks.begin() + count);
    double done = 0.0;
    for (std::size_t b = 0; b < count; ++b) {
      const auto [s, position_break] = breaks[b];
      if (s <= done && s < motion) continue;
      at.position_m = position_at(s);
      at.heading_rad = heading_at(s);
      emit(s - done, position_break);
      done = s;
    }
    at.position_m = to;
    // The rest of a turn longer than the travel.
    const double rest = m.time_s - lift - turned_s - motion - lower;
    if (rest > 1e-12) {
      at.heading_rad = heading0 + m.rotation_rad;
      emit(rest, true);
    }
    at.heading_rad = heading0 + m.rotation_rad;
    if (lower > 0.0) {
      at.z_m = z_m;
      emit(lower, true);
    }
  };
  // Moves come one before each step (a closed tour's first move is its closing move).
  std::size_t move = 0;
  for (std::size_t k = 0; k < sequence.size(); ++k) {
    if (k < wait_before_step_s.size() && wait_before_step_s[k] > 0.0)
      emit(wait_before_step_s[k], true);
    if (k > 0 || !path.closed) air_move(e.moves[move++]);
    const Step& step = sequence[k];
    const auto& segment = layer.segments[step.segment];
    // This breakpoint begins the wall: it says what is deposited until the next one.
    at.extruding = true;
    at.wall = segment.wall_id;
    at.piece = segment.piece + 1;
    visit(at, true);
    at.position_m = model.step_end_m(step);
    emit(segment.length_m / machine.deposition_speed_m_s, true);
  }
  if (path.closed && !sequence.empty()) air_move(e.moves[move++]);
}

}  // namespace

std::vector<Waypoint> waypoints_of(const CostModel& model, const Sequence& sequence,
                                   const PathSpec& path, const Evaluation& evaluation, double z_m,
                                   double start_s, const std::vector<double>& wait_before_step_s) {
  std::vector<Waypoint> out;
  walk_path(model, sequence, path, evaluation, z_m, start_s, wait_before_step_s,
            [&](const Waypoint& w, bool) {
              // A wall's first breakpoint replaces the arrival at its start (same time,
              // same place): one waypoint per breakpoint.
              if (!out.empty() && w.extruding && out.back().t_s == w.t_s && !out.back().extruding)
                out.back() = w;
              else
                out.push_back(w);
            });
  return out;
}

Timeline timeline_of(const CostModel& model, const Sequence& sequence, const PathSpec& path,
                     const Evaluation& e, const std::vector<double>& wait_before_step_s) {
  Timeline t;
  walk_path(model, sequence, path, e, 0.0, 0.0, wait_before_step_s,
            [&](const Waypoint& w, bool position_break) {
              // A turn ending mid-travel lies on a straight stretch of the position curve,
              // and a repeated point adds nothing: leaving them out changes nothing.
              if (!position_break) return;
              if (!t.empty() && w.t_s == t.end_s() && w.position_m == t.positions().back()) return;
              t.append(w.t_s, w.position_m);
            });
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
    const double l = rail_coordinate(left.at(t), axis), r = rail_coordinate(right.at(t), axis);
    const double gap = r - l;
    if (gap < gantry_width_m - kTolerance) {
      double when = t;
      if (i > 0 && previous_gap > gap) {
        // The gap is linear between breakpoints: the first moment it reaches the width.
        when =
            previous_t + (previous_gap - gantry_width_m) / (previous_gap - gap) * (t - previous_t);
        when = std::clamp(when, previous_t, t);
      }
      return Conflict{when, rail_coordinate(left.at(when), axis),
                      rail_coordinate(right.at(when), axis)};
    }
    previous_t = t;
    previous_gap = gap;
  }
  return std::nullopt;
}

double min_gap_m(const Timeline& left, const Timeline& right, RailAxis axis) {
  double gap = std::numeric_limits<double>::infinity();
  for (double t : merged_times(left, right))
    gap = std::min(gap, rail_coordinate(right.at(t), axis) - rail_coordinate(left.at(t), axis));
  return gap;
}

}  // namespace ccbuild::planner
