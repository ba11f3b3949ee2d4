// The scheduler's preparation: the building sliced into its layers in build order, the
// distinct plans each layer needs, the climbs and where the anchor pipes go, and the pipe
// work that falls between the layers of a run. Split from schedule.cpp, which schedules
// the layers one by one.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <thread>
#include <unordered_map>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/schedule/json_blocks.hpp"
#include "ccbuild/schedule/quantities.hpp"
#include "scheduler.hpp"

namespace ccbuild::schedule {
namespace detail {

void Scheduler::prepare() {
  const floors::Building& b = project_.building;
  // Every layer with walls, bottom to top; geometries by first appearance (unless taken
  // from another scheduler of this building).
  floors::GeometryNumbering numbering;
  if (slices_.empty()) {
    // The floors sliced in parallel (their beads are most of it: 3 s for the 40 x 40 rooms
    // benchmark's two floors one after the other).
    std::vector<std::vector<floors::Layer>> sliced(b.floors.size());
    std::vector<std::function<void()>> tasks;
    for (std::size_t f = 0; f < b.floors.size(); ++f)
      tasks.push_back([&, f] { sliced[f] = floors::slice_floor(b.floors[f], b.layer_height_m); });
    run_parallel(tasks, jobs_, nullptr);
    for (std::size_t f = 0; f < b.floors.size(); ++f)
      for (auto& l : sliced[f]) {
        bool fresh = false;
        const int number = numbering.number(l, &fresh);
        if (number == 0) continue;  // no walls
        if (fresh) reps_.push_back(l);
        slices_.push_back({b.floors[f].index, std::move(l), number - 1});  // reps_'s index
      }
  }
  for (const auto& f : b.floors) {
    std::vector<const floors::Layer*> layers;
    for (const Slice& slice : slices_)
      if (slice.floor == f.index) layers.push_back(&slice.layer);
    schedule_.quantities.push_back(floors::floor_quantities(f, layers, machine_.nozzle_width_m));
  }
  if (slices_.empty())
    throw InputError(project_.file.string(), 0, "",
                     "nothing to print: no layer of any floor has a wall outside its openings");
  const int count = static_cast<int>(slices_.size());
  layer_end_s_.assign(count, 0.0);
  set_memo_scopes();
  yard_.emplace(machine::AxisSpeeds{machine_.x.speed_m_s, machine_.y.speed_m_s,
                                    machine_.z.speed_m_s, machine_.rotation_speed_rad_s},
                machine_.rail_axis,
                machine::rail_coordinate(machine_.x.max_m, machine_.y.max_m, machine_.rail_axis),
                machine_.nozzles, machine_.gantry_width_m);

  // Each opening's lintel goes in before the first layer of its floor whose mid-height is
  // at or over its head (the slicer's rule: that layer is no longer cut by the opening).
  // An opening whose head no printed layer of its floor reaches needs none: the slab
  // spans it.
  for (const auto& f : b.floors)
    for (const auto& o : f.plan.openings)
      for (int i = 0; i < count; ++i) {
        if (slices_[i].floor != f.index ||
            floors::layer_mid_m(f.height_m, b.layer_height_m, slices_[i].layer.index) < o.head_m)
          continue;
        if (i == 0) {
          // Under the building's first layer: no layer is ever cut by it.
          schedule_.warnings.push_back(
              printf_string("floor %d: opening %s has its head at %s, under the first layer's "
                            "mid-height: no layer leaves it open, and it gets no lintel",
                            f.index, o.id.c_str(), project_.length(o.head_m).c_str()));
          break;
        }
        LintelTask task;
        task.opening = !o.id.empty()
                           ? o.id
                           : printf_string("wall %lld at %s", static_cast<long long>(o.wall_id),
                                           project_.length(o.offset_m).c_str());
        task.wall = o.wall_id;
        task.offset_m = o.offset_m;
        task.width_m = o.width_m;
        const floors::Wall* wall = f.plan.find_wall(o.wall_id);
        const double length_m = wall ? f.plan.wall_length_m(*wall) : o.offset_m + o.width_m;
        std::tie(task.from_m, task.to_m) =
            floors::opening_gap_m(o, b.lintels, floors::OpeningState::kLintel, length_m);
        if (wall && length_m > 0.0) {
          const Eigen::Vector2d a = f.plan.wall_start_m(*wall);
          const Eigen::Vector2d along = (f.plan.wall_end_m(*wall) - a) / length_m;
          task.start_m = a + along * task.from_m;
          task.end_m = a + along * task.to_m;
        }
        task.sill_m = o.sill_m;
        task.head_m = o.head_m;
        task.head_z_m = f.base_elevation_m + o.head_m;
        task.type = b.lintels.type;
        task.height_m = b.lintels.height_m;
        task.by_arm = b.lintels.by_arm;
        lintels_before_[i].push_back(std::move(task));
        break;
      }

  // Climbing machine: stages (as `ccbuild climb` places them) and their climbs, planned
  // in parallel with the first layer plans.
  std::vector<double> climb_planning_s;
  if (project_.climber) {
    const climb::StagePlan stages = climb::climb_stages(b, *project_.climber);
    schedule_.stages = stages.stages;
    if (!stages.status) {
      Infeasibility inf;
      inf.kind = InfeasibilityKind::kClimb;
      inf.message = "the climbing machine's stages: " + stages.status.to_string();
      inf.fix = "anchor points the units can reach (see `ccbuild climb`)";
      fail(inf);
    }
  }
  const int climb_count = std::max(0, static_cast<int>(schedule_.stages.size()) - 1);
  climbs_.resize(climb_count);
  climb_planning_s.assign(climb_count, 0.0);
  {
    std::vector<std::function<void()>> tasks;
    std::vector<std::pair<int, int>> first;
    // One nozzle, except where it cannot fit: where its deposition alone is over the
    // maximum interval (every geometry of the 40 x 40 rooms benchmark, whose 12 one-nozzle
    // plans took a quarter of the run; bench/README.md) the geometry's counts for more
    // nozzles are planned at once. The count choice plans one nozzle where it could still
    // be the fastest. A geometry whose deposition alone is over the share that makes one
    // nozzle too slow (below) gets those counts with its one-nozzle plan: no plan is faster
    // than its deposition.
    for (int g = 0; g < static_cast<int>(reps_.size()); ++g) {
      const bool one_could_fit =
          machine_.nozzles == 1 ||
          share_could_fit(deposition_of(g), 1, 0.0, material_.max_layer_interval_s);
      std::vector<std::pair<int, int>> keys;
      if (one_could_fit) keys.emplace_back(g, 1);
      if (!one_could_fit ||
          deposition_of(g) > kTryMoreNozzlesShare * material_.max_layer_interval_s)
        for (const auto& key : counts_past_one(g)) keys.push_back(key);
      for (const auto& key : keys)
        if (!recall(key.first, key.second)) first.push_back(key);
    }
    largest_first(first);
    std::vector<Planned> results(first.size());
    for (std::size_t k = 0; k < first.size(); ++k)
      tasks.push_back([&, k] { results[k] = plan(first[k].first, first[k].second); });
    std::vector<int> climbs_planned;
    for (int c = 0; c < climb_count; ++c) {
      if (options_.memo)
        if (auto it = options_.memo->climbs.find({climb_scope_, c});
            it != options_.memo->climbs.end()) {
          climbs_[c] = it->second;
          continue;
        }
      climbs_planned.push_back(c);
      tasks.push_back([&, c] {
        const auto t0 = Clock::now();
        climb::ClimbOptions o;
        o.seed = options_.seed;
        o.time_limit_s = options_.climb_time_limit_s;
        climbs_[c] = climb::plan_climb(*project_.climber, b, schedule_.stages[c],
                                       schedule_.stages[c + 1], o);
        climb_planning_s[c] = seconds_since(t0);
      });
    }
    const auto t0 = Clock::now();
    if (!tasks.empty())
      run_parallel(tasks, jobs_, [&](int done, int total) {
        progress(
            printf_string("planning %zu layer plans and %zu climbs: %d of %d done "
                          "(%.1f s)",
                          first.size(), climbs_planned.size(), done, total, seconds_since(t0)));
      });
    for (std::size_t k = 0; k < first.size(); ++k) {
      planned_[first[k]] = std::move(results[k]);
      remember(first[k].first, first[k].second);
    }
    if (options_.memo)
      for (int c : climbs_planned) options_.memo->climbs[{climb_scope_, c}] = climbs_[c];
    schedule_.plans_computed += static_cast<int>(first.size());
    double climb_s = 0.0;
    for (double s : climb_planning_s) climb_s += s;
    // Wall-clock shares: the climbs' part of the batch by their summed time.
    const double batch_s = seconds_since(t0);
    double layer_sum_s = 0.0;
    for (const auto& k : first) layer_sum_s += planned_.at(k).planning_s;
    const double share = climb_s + layer_sum_s > 0 ? climb_s / (climb_s + layer_sum_s) : 0.0;
    schedule_.climb_planning_s += batch_s * share;
    schedule_.layer_planning_s += batch_s * (1.0 - share);
  }
  // Geometries whose one-nozzle plan is too slow or unusable: their counts for more (those
  // planned above are not planned again).
  {
    std::vector<std::pair<int, int>> more;
    for (int g = 0; g < static_cast<int>(reps_.size()); ++g) {
      const Planned* p = single_plan(g);
      if (p &&
          (!p->usable || p->layer_time_s > kTryMoreNozzlesShare * material_.max_layer_interval_s))
        for (const auto& key : counts_past_one(g)) more.push_back(key);
    }
    plan_batch(more, "layer geometries too slow for one nozzle");
  }
  for (const auto& [key, p] : planned_)
    if (p.stopped_by_time)
      schedule_.warnings.push_back(printf_string(
          "the plan of geometry G%d with %d nozzles stopped at its time limit of %.0f s: "
          "schedules may differ between machines of different speed",
          key.first + 1, key.second, options_.layer_time_limit_s));

  // Pipes cast after each layer, and the climb after each stage's last layer.
  for (std::size_t s = 0; s < schedule_.stages.size(); ++s) {
    const auto& st = schedule_.stages[s];
    for (const auto& a : st.anchors)
      if (a.floor >= 0) pipes_after_[{a.floor, a.layer}].push_back(a);
    if (static_cast<int>(s) < climb_count)
      climb_after_[{st.last.floor, st.last.layer}] = static_cast<int>(s);
  }

  std::vector<LayerOrder> order;
  order.reserve(slices_.size());
  for (const Slice& slice : slices_)
    order.push_back({slice.floor, slice.layer.index, slice.geometry});
  std::map<std::pair<int, int>, int> pipe_counts;
  for (const auto& [key, anchors] : pipes_after_)
    pipe_counts[key] = static_cast<int>(anchors.size());
  run_between_s_ = pipe_time_in_runs_s(order, pipe_counts,
                                       project_.climber ? project_.climber->pipe_embed_s : 0.0);
  plan_counts_ahead();
}

std::vector<double> pipe_time_in_runs_s(const std::vector<LayerOrder>& order,
                                        const std::map<std::pair<int, int>, int>& pipes_after,
                                        double pipe_s) {
  const int count = static_cast<int>(order.size());
  std::vector<double> out(order.size(), 0.0);
  for (int first = 0; first < count;) {
    int last = first;
    while (last + 1 < count && order[last + 1].floor == order[first].floor &&
           order[last + 1].geometry == order[first].geometry)
      ++last;
    double most_s = 0.0;
    for (int k = std::max(first, 1); k <= last; ++k)
      if (order[k - 1].floor == order[k].floor)
        if (auto it = pipes_after.find({order[k - 1].floor, order[k - 1].layer});
            it != pipes_after.end())
          most_s = std::max(most_s, it->second * pipe_s);
    std::fill(out.begin() + first, out.begin() + last + 1, most_s);
    first = last + 1;
  }
  return out;
}

}  // namespace detail
}  // namespace ccbuild::schedule
