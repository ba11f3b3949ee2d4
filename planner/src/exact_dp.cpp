// Exact solver for small layers: dynamic programming over the set of walls built, the
// last wall and its direction, and (for the time objective with a stopper) how many whole
// turns the nozzle's cumulative heading is wound. Lifts depend only on the set built, so
// the state is complete and the answer exact under CostModel::evaluate.

#include <cmath>
#include <limits>

#include "ccbuild/common/input_error.hpp"
#include "geometry.hpp"
#include "search_internal.hpp"

namespace ccbuild::planner::detail {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

std::optional<Sequence> exact_sequence(const CostModel& model, const std::vector<int>& segments,
                                       const PathSpec& path, Objective objective,
                                       double upper_bound, const StopCondition& stop) {
  const int n = static_cast<int>(segments.size());
  CCBUILD_CHECK(n >= 1 && n <= 20, "exact search is for small layers");
  const int S = 2 * n;  // state = 2 * wall + reversed
  const auto& machine = model.machine();
  const bool timed = objective == Objective::kTime;
  const bool winding = timed && model.has_stopper();
  const int offset = winding
                         ? static_cast<int>(std::ceil(std::max(std::abs(machine.stopper_min_rad),
                                                               std::abs(machine.stopper_max_rad)) /
                                                      (2.0 * M_PI)))
                         : 0;
  const int K = 2 * offset + 1;

  auto step_of = [&](int s) { return Step{segments[s / 2], (s & 1) != 0}; };
  std::vector<Vec2> entry(S), exit(S);
  std::vector<double> heading(S);
  for (int s = 0; s < S; ++s) {
    entry[s] = model.step_start_m(step_of(s));
    exit[s] = model.step_end_m(step_of(s));
    heading[s] = model.heading_rad(step_of(s));
  }
  // Per pair of states: distance, motion time and the walls the air move would cross.
  std::vector<double> dist(S * S), motion(S * S);
  std::vector<std::uint32_t> crosses(S * S, 0);
  std::vector<int> local(model.layer().segments.size(), -1);
  for (int i = 0; i < n; ++i) local[segments[i]] = i;
  for (int a = 0; a < S; ++a) {
    for (int b = 0; b < S; ++b) {
      const int ab = a * S + b;
      dist[ab] = model.distance_m(exit[a], entry[b]);
      motion[ab] =
          dist[ab] > 1e-9 ? model.travel_s(exit[a], entry[b]) + machine.accel_delay_s : 0.0;
      if (timed && dist[ab] > 1e-9) {
        for (int c : model.crossed_segments(exit[a], entry[b]))
          if (local[c] >= 0) crosses[ab] |= 1u << local[c];
      }
    }
  }
  auto move_time = [&](int ab, double turn, bool lifted) {
    return model.combine_move_s(motion[ab], model.turn_s(turn), lifted && dist[ab] > 1e-9);
  };
  // Turn from (state a, winding ka) to state b, and the winding after it.
  std::vector<double> turn(S * K * S, 0.0);
  std::vector<int> wind_after(S * K * S, offset);
  if (timed) {
    for (int a = 0; a < S; ++a)
      for (int ka = 0; ka < K; ++ka)
        for (int b = 0; b < S; ++b) {
          const double from = heading[a] + 2.0 * M_PI * (ka - offset);
          const double t = model.stopper_turn_rad(from, heading[b]);
          const int idx = (a * K + ka) * S + b;
          turn[idx] = t;
          if (winding)
            wind_after[idx] = std::clamp(
                static_cast<int>(std::lround((from + t - heading[b]) / (2.0 * M_PI))) + offset, 0,
                K - 1);
        }
  }

  const std::size_t masks = std::size_t{1} << n;
  const std::uint32_t full = static_cast<std::uint32_t>(masks - 1);
  // Every wall not yet built still needs one air move into it, which costs at least the
  // cheapest such move from anywhere (short-way turn, no lift): a bound on what remains,
  // used to prune states that cannot beat the best tour known.
  std::vector<double> cheapest_in(n, kInf);
  for (int a = 0; a < S; ++a) {
    for (int b = 0; b < S; ++b) {
      if (a / 2 == b / 2) continue;
      const int ab = a * S + b;
      double c = dist[ab];
      if (timed)
        c = model.combine_move_s(motion[ab], model.turn_s(wrap_angle(heading[b] - heading[a])),
                                 false);
      cheapest_in[b / 2] = std::min(cheapest_in[b / 2], c);
    }
  }
  std::vector<double> remaining(masks, 0.0);  // bound for the walls outside each mask
  for (std::uint32_t mask = 0; mask < masks; ++mask) {
    double sum = 0.0;
    for (int j = 0; j < n; ++j)
      if (!(mask >> j & 1)) sum += cheapest_in[j];
    remaining[mask] = sum;
  }
  std::vector<double> value(masks * S * K);
  std::vector<std::int32_t> parent(masks * S * K);
  auto index = [&](std::uint32_t mask, int s, int k) {
    return (static_cast<std::size_t>(mask) * S + s) * K + k;
  };

  double best = upper_bound;
  std::optional<Sequence> best_sequence;

  // One DP from a set of initial states (a closed tour with the time objective runs one
  // per first step, since where a tour starts changes its lifts and its unwinding).
  auto run = [&](const std::vector<std::pair<int, double>>& initial, int closing_first) -> bool {
    std::fill(value.begin(), value.end(), kInf);
    std::uint32_t required = 0;
    for (const auto& [s, v] : initial) {
      value[index(1u << (s / 2), s, offset)] = v;
      parent[index(1u << (s / 2), s, offset)] = -1;
      if (initial.size() == 1) required = 1u << (s / 2);
    }
    for (std::uint32_t mask = 1; mask < masks; ++mask) {
      if ((mask & required) != required) continue;
      if ((mask & 255) == 0 && stop.should_stop()) return false;
      for (int a = 0; a < S; ++a) {
        if (!(mask >> (a / 2) & 1)) continue;
        for (int ka = 0; ka < K; ++ka) {
          const double v = value[index(mask, a, ka)];
          if (v + remaining[mask] >= best) continue;
          for (int b = 0; b < S; ++b) {
            const int j = b / 2;
            if (mask >> j & 1) continue;
            const int ab = a * S + b;
            double cost;
            int kb = offset;
            if (!timed) {
              cost = dist[ab];
            } else {
              const int t = (a * K + ka) * S + b;
              cost = move_time(ab, turn[t], (crosses[ab] & mask) != 0);
              kb = wind_after[t];
            }
            const double w = v + cost;
            const std::size_t target = index(mask | (1u << j), b, kb);
            if (w < value[target] && w + remaining[mask | (1u << j)] < best) {
              value[target] = w;
              parent[target] = a * K + ka;
            }
          }
        }
      }
    }
    // Best finish.
    int best_a = -1, best_k = 0;
    for (int a = 0; a < S; ++a) {
      for (int ka = 0; ka < K; ++ka) {
        double v = value[index(full, a, ka)];
        if (v == kInf) continue;
        if (closing_first >= 0) {
          const int ab = a * S + closing_first;
          if (!timed) {
            v += dist[ab];
          } else {
            const double from = heading[a] + 2.0 * M_PI * (ka - offset);
            const double back = model.has_stopper()
                                    ? heading[closing_first] - from
                                    : model.stopper_turn_rad(from, heading[closing_first]);
            v += move_time(ab, back, crosses[ab] != 0);
          }
        }
        if (v < best) {
          best = v;
          best_a = a;
          best_k = ka;
        }
      }
    }
    if (best_a >= 0) {
      Sequence sequence;
      std::uint32_t mask = full;
      int a = best_a, ka = best_k;
      while (true) {
        sequence.push_back(step_of(a));
        const std::int32_t p = parent[index(mask, a, ka)];
        if (p < 0) break;
        mask &= ~(1u << (a / 2));
        a = p / K;
        ka = p % K;
      }
      std::reverse(sequence.begin(), sequence.end());
      best_sequence = std::move(sequence);
    }
    return true;
  };

  auto first_move = [&](int s) {
    if (!timed) return model.distance_m(path.start_m, entry[s]);
    return model.move_time_s(path.start_m, entry[s], 0.0, false);  // nothing built yet: no lift
  };
  if (!path.closed) {
    std::vector<std::pair<int, double>> initial;
    for (int s = 0; s < S; ++s) {
      if (path.first && (segments[s / 2] != path.first->segment || (s & 1) != path.first->reversed))
        continue;
      initial.emplace_back(s, first_move(s));
    }
    if (!run(initial, -1)) return std::nullopt;
  } else if (!timed) {
    // Distance is the same from any start and in either direction: fix wall 0 forwards.
    if (!run({{0, 0.0}}, 0)) return std::nullopt;
  } else {
    for (int f = 0; f < S; ++f)
      if (!run({{f, 0.0}}, f)) return std::nullopt;
  }
  return best_sequence;
}

}  // namespace ccbuild::planner::detail
