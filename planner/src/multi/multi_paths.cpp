// Shared by the multi-nozzle methods: nozzle paths from the sections' work, the exact
// check of a candidate plan, and the search for compatible start points (path cycling).

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>

#include "ccbuild/common/format.hpp"
#include "multi_internal.hpp"

namespace ccbuild::planner::detail {
namespace {

Sequence rotated(const Sequence& tour, int by) {
  if (tour.empty()) return tour;
  Sequence out(tour.begin() + by, tour.end());
  out.insert(out.end(), tour.begin(), tour.begin() + by);
  return out;
}

Eigen::Vector2d park_point(const StageContext& ctx, double rail_at) {
  Eigen::Vector2d lo = ctx.layer.points.empty() ? Eigen::Vector2d::Zero() : ctx.layer.points[0],
                  hi = lo;
  for (const auto& p : ctx.layer.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return with_rail_coordinate(0.5 * (lo + hi), ctx.options.rail_axis, rail_at);
}

// When each step's wait begins, from the timing of the cost model.
std::vector<double> step_starts(const Evaluation& e, const Sequence& sequence,
                                const CostModel& model, const std::vector<double>& waits) {
  std::vector<double> starts;
  double t = 0.0;
  std::size_t move = 0;
  for (std::size_t k = 0; k < sequence.size(); ++k) {
    starts.push_back(t);
    if (k < waits.size()) t += waits[k];
    if (k > 0) t += e.moves[move++].time_s;
    t +=
        model.layer().segments[sequence[k].segment].length_m / model.machine().deposition_speed_m_s;
  }
  return starts;
}

}  // namespace

Sequence concatenated(const NozzleWork& work, int cycle) {
  Sequence out;
  for (const auto& block : work.fixed_blocks) out.insert(out.end(), block.begin(), block.end());
  const Sequence w = rotated(work.working, cycle);
  out.insert(out.end(), w.begin(), w.end());
  return out;
}

double stage_time_s(const std::vector<NozzlePath>& paths) {
  double t = 0.0;
  for (const auto& p : paths) t = std::max(t, p.finish_s);
  return t;
}
std::vector<NozzlePath> build_paths(const StageContext& ctx, const CutLayer& cut,
                                    const std::vector<NozzleWork>& works,
                                    const std::vector<int>& cycles,
                                    const std::vector<std::vector<double>>& waits) {
  std::vector<NozzlePath> paths;
  for (std::size_t k = 0; k < works.size(); ++k) {
    const NozzleWork& work = works[k];
    NozzlePath path;
    path.nozzle = static_cast<int>(k);
    path.section_from_m = work.from_m;
    path.section_to_m = work.to_m;
    path.start_offset = cycles.empty() ? 0 : cycles[k];
    SectionModel section(ctx, cut, work.section_segments);
    const Sequence full = concatenated(work, path.start_offset);
    for (std::size_t b = 0; b < work.fixed_blocks.size(); ++b)
      path.zones.insert(path.zones.end(), work.fixed_blocks[b].size(), work.fixed_names[b]);
    path.zones.insert(path.zones.end(), work.working.size(), "working");
    if (k < waits.size()) path.wait_before_step_s = waits[k];
    if (full.empty()) {
      path.timeline = parked_at(park_point(ctx, 0.5 * (work.from_m + work.to_m)));
    } else {
      path.sequence = section.local(full);
      path.evaluation = section.model->evaluate(path.sequence, PathSpec::closed_tour());
      path.timeline = timeline_of(*section.model, path.sequence, PathSpec::closed_tour(),
                                  path.wait_before_step_s);
      path.step_start_s =
          step_starts(path.evaluation, path.sequence, *section.model, path.wait_before_step_s);
    }
    path.layer = std::move(section.layer);  // the model is not used past this point
    path.finish_s = path.timeline.end_s();
    path.wait_s =
        std::accumulate(path.wait_before_step_s.begin(), path.wait_before_step_s.end(), 0.0);
    path.busy_s = path.finish_s - path.wait_s;
    paths.push_back(std::move(path));
  }
  return paths;
}

std::string verify(const StageContext& ctx, const std::vector<NozzlePath>& paths, double& min_gap) {
  const RailAxis axis = ctx.options.rail_axis;
  const double w = ctx.options.gantry_width_m;
  const int n = static_cast<int>(paths.size());
  min_gap = std::numeric_limits<double>::infinity();
  for (int k = 0; k + 1 < n; ++k) {
    min_gap = std::min(min_gap, min_gap_m(paths[k].timeline, paths[k + 1].timeline, axis));
    if (const auto c = first_conflict(paths[k].timeline, paths[k + 1].timeline, axis, w))
      return "nozzles " + std::to_string(k + 1) + " and " + std::to_string(k + 2) +
             " collide at t = " + seconds(c->time_s) + " (rail positions " +
             length(ctx.options, c->left_m) + " and " + length(ctx.options, c->right_m) + ")";
  }
  // Each gantry must stay where the others leave it room on the rails.
  for (int k = 0; k < n; ++k) {
    const double lo = ctx.rail_min_m + k * w, hi = ctx.rail_max_m - (n - 1 - k) * w;
    for (const auto& p : paths[k].timeline.positions()) {
      const double r = rail_coordinate(p, axis);
      if (r < lo - 1e-9 || r > hi + 1e-9)
        return "nozzle " + std::to_string(k + 1) + " would need rail position " +
               length(ctx.options, r) + ", outside its reach " + length(ctx.options, lo) + " to " +
               length(ctx.options, hi);
    }
  }
  return "";
}

PlanStatus stop_status(const StageContext& ctx, const std::string& during) {
  if (ctx.stop.cancelled()) return {PlanStatus::Code::kCancelled, "cancelled during " + during};
  if (ctx.stop.should_stop())
    return {PlanStatus::Code::kTimeLimit, "the time limit came during " + during};
  return PlanStatus();
}

CycleSearch compatible_cycles(const StageContext& ctx, const CutLayer& cut,
                              const std::vector<NozzleWork>& works) {
  const int n = static_cast<int>(works.size());
  std::vector<std::unique_ptr<SectionModel>> sections;
  std::vector<Sequence> prefix(n), working(n);
  std::vector<int> count(n);
  for (int k = 0; k < n; ++k) {
    sections.push_back(std::make_unique<SectionModel>(ctx, cut, works[k].section_segments));
    Sequence fixed;
    for (const auto& block : works[k].fixed_blocks)
      fixed.insert(fixed.end(), block.begin(), block.end());
    prefix[k] = sections[k]->local(fixed);
    working[k] = sections[k]->local(works[k].working);
    count[k] = std::max<int>(1, static_cast<int>(working[k].size()));
  }
  std::vector<std::map<int, Timeline>> cache(n);
  auto timeline = [&](int k, int c) -> const Timeline& {
    auto it = cache[k].find(c);
    if (it != cache[k].end()) return it->second;
    Sequence s = prefix[k];
    const Sequence w = rotated(working[k], c);
    s.insert(s.end(), w.begin(), w.end());
    Timeline t = s.empty() ? parked_at(park_point(ctx, 0.5 * (works[k].from_m + works[k].to_m)))
                           : timeline_of(*sections[k]->model, s, PathSpec::closed_tour());
    return cache[k].emplace(c, std::move(t)).first->second;
  };
  std::vector<std::vector<char>> dead(n);
  for (int k = 0; k < n; ++k) dead[k].assign(count[k], 0);
  std::vector<int> choice(n, 0);
  long checks = 0;
  bool out_of_budget = false, out_of_time = false;
  // Can nozzles k+1.. be placed, given nozzle k uses cycle c? Results depend only on
  // (k, c) because only neighbours can collide, so failures are remembered.
  std::function<bool(int, int)> extend = [&](int k, int c) -> bool {
    if (k == n - 1) return true;
    for (int c2 = 0; c2 < count[k + 1]; ++c2) {
      if (dead[k + 1][c2]) continue;
      if (++checks > ctx.options.max_cycle_checks) out_of_budget = true;
      if (checks % 16 == 0 && ctx.stop.should_stop()) out_of_time = true;
      if (out_of_budget || out_of_time) return false;
      if (first_conflict(timeline(k, c), timeline(k + 1, c2), ctx.options.rail_axis,
                         ctx.options.gantry_width_m))
        continue;
      if (extend(k + 1, c2)) {
        choice[k + 1] = c2;
        return true;
      }
      if (out_of_budget || out_of_time) return false;
    }
    dead[k][c] = 1;
    return false;
  };
  for (int c0 = 0; c0 < count[0] && !out_of_budget && !out_of_time; ++c0) {
    if (extend(0, c0)) {
      choice[0] = c0;
      return {PlanStatus(), choice};
    }
  }
  const std::string checked_pairs = std::to_string(checks) + " cycle pairs checked";
  if (out_of_time) return {stop_status(ctx, "path cycling (" + checked_pairs + ")"), {}};
  if (out_of_budget)
    return {{PlanStatus::Code::kSearchExhausted, "gave up after " + checked_pairs}, {}};
  return {{PlanStatus::Code::kCollision,
           "no combination of start points is collision-free (" + checked_pairs + ")"},
          {}};
}

MethodResult checked(const StageContext& ctx, std::vector<NozzlePath> paths) {
  MethodResult out;
  double gap = 0.0;
  const std::string problem = verify(ctx, paths, gap);
  if (!problem.empty()) {
    out.status = {PlanStatus::Code::kCollision, problem};
    return out;
  }
  out.paths = std::move(paths);
  return out;
}

}  // namespace ccbuild::planner::detail
