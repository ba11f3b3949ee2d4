// Our multi-nozzle method, delay: waits at safe points, turns, or one nozzle alone,
// whichever collision-free alternative finishes the stage first.

#include <algorithm>
#include <cmath>
#include <numeric>

#include "ccbuild/common/format.hpp"
#include "multi_internal.hpp"

namespace ccbuild::planner::detail {
namespace {

// Delay, alternative 1: waits where needed. Take the earliest conflict and make one of the
// two nozzles hold before the step it was on (or a few steps earlier), for the shortest
// hold after which it can finish that step without meeting either neighbour; failing
// that, the shortest hold that at least moves the conflict later.
MethodResult with_waits(const StageContext& ctx, const Sections& s,
                        const std::vector<int>& cycles) {
  MethodResult out;
  const int n = ctx.options.nozzles;
  const RailAxis axis = ctx.options.rail_axis;
  const double w = ctx.options.gantry_width_m;
  std::vector<std::vector<double>> waits(n);
  for (int k = 0; k < n; ++k) waits[k].assign(s.works[k].working.size(), 0.0);
  auto paths = build_paths(ctx, s.cut, s.works, cycles, waits);
  // Holds that would make the stage longer than all the nozzles' work done one after
  // another are pointless (and a nozzle finished in another's way makes them grow without
  // end): give up there.
  double one_after_another_s = 0.0;
  for (const auto& p : paths) one_after_another_s += p.busy_s;
  // Each nozzle's walls and cost model, kept for the many trial holds.
  std::vector<std::unique_ptr<SectionModel>> models;
  for (int k = 0; k < n; ++k)
    models.push_back(std::make_unique<SectionModel>(ctx, s.cut, s.works[k].section_segments));
  auto earliest = [&](const std::vector<NozzlePath>& p, int& pair) -> std::optional<Conflict> {
    std::optional<Conflict> first;
    for (int k = 0; k + 1 < n; ++k) {
      if (auto c = first_conflict(p[k].timeline, p[k + 1].timeline, axis, w);
          c && (!first || c->time_s < first->time_s)) {
        first = c;
        pair = k;
      }
    }
    return first;
  };
  for (int round = 0; round < 400 && !ctx.stop.should_stop(); ++round) {
    int pair = 0;
    const auto conflict = earliest(paths, pair);
    if (!conflict) {
      MethodResult result = checked(ctx, paths);
      if (result.status) {
        double total = 0.0;
        for (const auto& p : result.paths) total += p.wait_s;
        result.detail =
            "delay (" + std::to_string(round) + " waits, " + seconds(total) + " in all)";
      }
      return result;
    }
    if (conflict->time_s <= 1e-9) {
      out.status = {PlanStatus::Code::kCollision, "nozzles " + std::to_string(pair + 1) + " and " +
                                                      std::to_string(pair + 2) +
                                                      " start closer than a gantry width"};
      return out;
    }
    struct Hold {
      double s = std::numeric_limits<double>::infinity();
      int nozzle = -1;
      std::size_t step = 0;
    } finishes, later;  // lets the nozzle finish its step / only moves the conflict later
    for (int y : {pair, pair + 1}) {
      const int o = y == pair ? pair + 1 : pair;
      const auto& starts = paths[y].step_start_s;
      if (starts.empty()) continue;
      std::size_t current = 0;
      while (current + 1 < starts.size() && starts[current + 1] <= conflict->time_s) ++current;
      const double current_end =
          current + 1 < starts.size() ? starts[current + 1] : paths[y].finish_s;
      // Hold before the step in progress; if resting where that step begins is itself in
      // the way, hold a few steps earlier.
      for (std::size_t back = 0; back <= std::min<std::size_t>(current, 6); ++back) {
        const std::size_t step = current - back;
        std::vector<double> holds;
        for (double t : paths[o].timeline.times())
          if (t > starts[step]) holds.push_back(t - starts[step]);
        holds.push_back(paths[o].finish_s - starts[step]);
        std::sort(holds.begin(), holds.end());
        holds.erase(std::unique(holds.begin(), holds.end()), holds.end());
        for (double hold : holds) {
          if (hold <= 0.0 || hold >= finishes.s) break;
          auto trial = waits[y];
          trial[step] += hold;
          const Timeline candidate =
              timeline_of(*models[y]->model, paths[y].sequence, PathSpec::closed_tour(),
                          paths[y].evaluation, trial);
          std::optional<double> next;  // y's first conflict with either neighbour now
          for (int other : {y - 1, y + 1}) {
            if (other < 0 || other >= n) continue;
            const auto& left = other < y ? paths[other].timeline : candidate;
            const auto& right = other < y ? candidate : paths[other].timeline;
            if (auto c = first_conflict(left, right, axis, w); c && (!next || c->time_s < *next))
              next = c->time_s;
          }
          if (!next || *next > current_end + hold + 1e-6) {
            finishes = {hold, y, step};
            break;
          }
          if (*next > conflict->time_s + 1e-6 && hold < later.s) later = {hold, y, step};
        }
      }
    }
    const Hold& chosen = finishes.nozzle >= 0 ? finishes : later;
    if (chosen.nozzle < 0) {
      out.status = {PlanStatus::Code::kCollision,
                    "no wait moves the conflict of nozzles " + std::to_string(pair + 1) + " and " +
                        std::to_string(pair + 2) + " at t = " + seconds(conflict->time_s)};
      return out;
    }
    waits[chosen.nozzle][chosen.step] += chosen.s;
    auto rebuilt = build_paths(ctx, s.cut, {s.works[chosen.nozzle]}, {cycles[chosen.nozzle]},
                               {waits[chosen.nozzle]});
    rebuilt[0].nozzle = chosen.nozzle;
    paths[chosen.nozzle] = std::move(rebuilt[0]);
    if (paths[chosen.nozzle].finish_s > one_after_another_s) {
      out.status = {PlanStatus::Code::kCollision,
                    "waits would make the stage longer than the nozzles' work done one after "
                    "another"};
      return out;
    }
  }
  out.status = stop_status(ctx, "placing waits");
  if (out.status) out.status = {PlanStatus::Code::kSearchExhausted, "400 waits did not suffice"};
  return out;
}

}  // namespace

MethodResult delay_method(const StageContext& ctx) {
  const int n = ctx.options.nozzles;
  const RailAxis axis = ctx.options.rail_axis;
  const double w = ctx.options.gantry_width_m;
  const Sections& s = sections_of(ctx);
  const int vertices = static_cast<int>(s.cut.layer.points.size());
  // Where a nozzle may rest while its neighbours work anywhere in their sections: a
  // gantry width clear of each neighbouring section. Start each tour there (nearest the
  // middle of that interval), so a nozzle holding at its start, or finished there, is
  // out of its neighbours' way.
  std::vector<int> cycles(n, 0);
  std::vector<char> rests_clear(n, 1);
  for (int k = 0; k < n; ++k) {
    const double lo = k > 0 ? s.works[k].from_m + w : -std::numeric_limits<double>::infinity();
    const double hi = k + 1 < n ? s.works[k].to_m - w : std::numeric_limits<double>::infinity();
    // Inside the interval first; then, between two ends, nearest its middle, and at an
    // end of the rails, as far from the one neighbour as possible.
    const double target = std::isfinite(lo) && std::isfinite(hi) ? 0.5 * (lo + hi)
                          : std::isfinite(lo)                    ? s.works[k].to_m
                                                                 : s.works[k].from_m;
    std::pair<double, double> best{std::numeric_limits<double>::infinity(), 0.0};
    for (std::size_t c = 0; c < s.works[k].working.size(); ++c) {
      const Step& step = s.works[k].working[c];
      const auto& seg = s.cut.layer.segments[step.segment];
      const double r =
          rail_coordinate(step.reversed ? s.cut.layer.end_m(seg) : s.cut.layer.start_m(seg), axis);
      const std::pair<double, double> score{std::max({0.0, lo - r, r - hi}), std::abs(r - target)};
      if (score < best) {
        best = score;
        cycles[k] = static_cast<int>(c);
        rests_clear[k] = score.first <= 1e-9;
      }
    }
  }

  // The alternatives; the fastest collision-free one is returned.
  std::optional<MethodResult> fastest;
  auto consider = [&](MethodResult result, std::string what) {
    if (!result.status) return;
    if (!fastest || stage_time_s(result.paths) < stage_time_s(fastest->paths)) {
      if (!what.empty()) result.detail = std::move(what);
      fastest = std::move(result);
    }
  };
  if (PlanStatus late = stop_status(ctx, "iterative dividing"); !late) {
    MethodResult out;
    out.status = std::move(late);
    out.vertices = vertices;
    return out;
  }

  // 1. Waits.
  consider(with_waits(ctx, s, cycles), "");

  // 2. Turns: even-numbered nozzles work while odd ones hold at their start points, then
  //    the other way round. Safe when every holding nozzle rests a gantry width clear of
  //    its working neighbours' sections (the tours start there when they can).
  if (std::all_of(rests_clear.begin(), rests_clear.end(), [](char c) { return c != 0; })) {
    const auto alone = build_paths(ctx, s.cut, s.works, cycles);
    std::vector<std::vector<double>> turn(n);
    double even_finish = 0.0;
    for (int k = 0; k < n; k += 2) even_finish = std::max(even_finish, alone[k].busy_s);
    for (int k = 0; k < n; ++k) {
      turn[k].assign(s.works[k].working.size(), 0.0);
      if (k % 2 == 1 && !turn[k].empty()) turn[k][0] = even_finish;
    }
    consider(checked(ctx, build_paths(ctx, s.cut, s.works, cycles, turn)),
             "delay (odd nozzles wait for even ones: " + seconds(even_finish) + ")");
  }

  // 3. One nozzle builds the stage alone, on its single-nozzle tour of the uncut walls
  //    (planned as a single nozzle would plan it); the others park clear of the layout at
  //    the ends of the rails.
  {
    const CutLayer whole = cut_layer(ctx.layer, axis, {});
    NozzleWork all;
    all.from_m = ctx.from_m;
    all.to_m = ctx.to_m;
    all.section_segments.resize(whole.layer.segments.size());
    std::iota(all.section_segments.begin(), all.section_segments.end(), 0);
    bool planned = false;
    for (int j = 0; j < n; ++j) {
      std::vector<NozzleWork> works(n);
      bool fits = true;
      for (int k = 0; k < n; ++k) {
        if (k == j) continue;
        // Left of the worker: pack against the left end of the rails; right: the right end.
        const double at = k < j ? ctx.rail_min_m + k * w : ctx.rail_max_m - (n - 1 - k) * w;
        works[k].from_m = works[k].to_m = at;
        if ((k < j && at > ctx.from_m - w) || (k > j && at < ctx.to_m + w)) fits = false;
      }
      if (!fits) continue;
      if (!planned) {
        if (ctx.stop.should_stop()) break;
        PlanOptions o = ctx.options.planning;
        o.algorithm = Algorithm::kCcTsp;
        o.path = PathSpec::closed_tour();
        o.waypoints = false;  // only the order is kept
        o.time_limit_s = std::max(0.05, std::min(o.time_limit_s, ctx.stop.remaining_s()));
        all.working = plan_layer(whole.layer, ctx.machine, o).sequence;
        planned = true;
      }
      works[j] = all;
      MethodResult alone = checked(ctx, build_paths(ctx, whole, works, std::vector<int>(n, 0)));
      if (alone.status) {
        consider(std::move(alone),
                 "delay (nozzle " + std::to_string(j + 1) + " alone, the others parked)");
        break;
      }
    }
  }
  if (fastest) {
    fastest->vertices = vertices;
    return std::move(*fastest);
  }
  MethodResult out;
  out.vertices = vertices;
  out.status = stop_status(ctx, "the delay method");
  if (out.status)
    out.status = {PlanStatus::Code::kCollision,
                  "no waits resolve the conflicts, no turns are safe (a nozzle cannot rest a "
                  "gantry width clear of its neighbours' sections), and the rails leave no room "
                  "to park"};
  return out;
}

}  // namespace ccbuild::planner::detail
