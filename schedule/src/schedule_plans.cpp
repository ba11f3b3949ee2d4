// The scheduler's plans: each distinct geometry at each nozzle count (in parallel), the
// plans that follow the order of the layer below, and their registration under the
// schedule's plan keys, labelled with each layer's own walls.

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <set>
#include <utility>

#include "ccbuild/common/input_error.hpp"
#include "ccbuild/common/sha256.hpp"
#include "ccbuild/planner/follow_below.hpp"
#include "ccbuild/planner/plan_nozzles.hpp"
#include "scheduler.hpp"

namespace ccbuild::schedule::detail {

/// Runs `tasks` on `jobs` threads; the calling thread reports progress as they finish.
void run_parallel(std::vector<std::function<void()>>& tasks, int jobs,
                  const std::function<void(int done, int total)>& on_done) {
  if (tasks.empty()) return;
  const int total = static_cast<int>(tasks.size());
  std::atomic<int> next{0};
  std::mutex mutex;
  std::condition_variable finished;
  int done = 0;
  std::exception_ptr failure;
  auto worker = [&] {
    for (int k; (k = next.fetch_add(1)) < total;) {
      try {
        tasks[k]();
      } catch (...) {
        std::lock_guard lock(mutex);
        if (!failure) failure = std::current_exception();
      }
      {
        std::lock_guard lock(mutex);
        ++done;
      }
      finished.notify_one();
    }
  };
  std::vector<std::thread> threads;
  for (int t = 0; t < std::max(1, std::min(jobs, total)); ++t) threads.emplace_back(worker);
  {
    std::unique_lock lock(mutex);
    int reported = 0;
    while (reported < total) {
      finished.wait(lock, [&] { return done > reported; });
      reported = done;
      lock.unlock();
      if (on_done) on_done(reported, total);
      lock.lock();
    }
  }
  for (auto& t : threads) t.join();
  if (failure) std::rethrow_exception(failure);
}

Planned Scheduler::plan(int geometry, int nozzles) const {
  const auto started = Clock::now();
  Planned out;
  const floors::Layer& layer = reps_[geometry];
  planner::LayerPlanRequest request;
  request.nozzles = nozzles;
  request.planning.objective = planner::Objective::kTime;
  // The time objective's search never reads the bound (it only proves distance tours
  // optimal), and no schedule records it: the connected bound's cutting planes were half
  // of planning a 3,280-wall layer (bench/README.md, issue 50). The matching bound is
  // what the multi-nozzle planner takes too.
  request.planning.bound = planner::BoundKind::kMatching;
  request.planning.seed = options_.seed;
  request.planning.time_limit_s = options_.layer_time_limit_s;
  request.planning.max_kicks = options_.max_kicks;
  request.multi.gantry_width_m = machine_.gantry_width_m;
  request.multi.rail_axis = machine_.rail_axis;
  request.multi.planning = request.planning;
  request.multi.message_unit = project_.building.units;
  // The multi-nozzle planner's one-nozzle reference and its comparison with the delay
  // method are only reported, never decided on, and a schedule shows neither: it gives the
  // reference the plan it already has (none when it has none), and skips the comparison
  // (together two thirds of a 2,840-wall layer's two-nozzle plan; bench/README.md, issue 50).
  request.multi.compare_with_delay = false;
  if (const Planned* single = single_plan(geometry); nozzles > 1 && single)
    request.multi.single_nozzle_time_s = single->layer_time_s;
  else
    request.multi.plan_single_nozzle_reference = false;
  try {
    const planner::LayerPlanResult result = planner::plan_layer_nozzles(layer, machine_, request);
    if (!result.status) {
      out.why_not = result.status.to_string();
    } else if (result.single) {
      const auto& p = *result.single;
      out.method = "cc-tsp";
      out.layer_time_s = p.evaluation.layer_time_s;
      out.deposition_s = p.evaluation.deposition_s;
      out.airtime_s = p.evaluation.airtime_s;
      out.max_idle_s = p.evaluation.max_idle_s;
      out.stopped_by_time = p.stop == planner::StopReason::kTimeLimit;
      out.waypoints.push_back(p.waypoints);
    } else {
      const auto& m = *result.multi;
      out.method = m.stages.empty() ? "" : planner::to_string(m.stages.front().method);
      out.layer_time_s = m.layer_time_s;
      out.min_gap_m = m.min_gap_m;
      out.waypoints.assign(nozzles, {});
      for (const auto& stage : m.stages)
        for (const auto& n : stage.nozzles) {
          out.deposition_s += n.evaluation.deposition_s;
          out.airtime_s += n.evaluation.airtime_s;
          auto& path = out.waypoints[n.nozzle];
          path.insert(path.end(), n.waypoints.begin(), n.waypoints.end());
        }
    }
    if (result.status) {
      out.max_idle_s = result.max_idle_s();
      if (result.idle_limit_violations() > 0)
        out.why_not = idle_limit_broken(out.max_idle_s);
      else if (auto crowded = no_room_to_park(out.waypoints, nozzles))
        out.why_not = *crowded;
      else
        out.usable = true;
    }
  } catch (const InputError& error) {
    // A nozzle count the rails cannot take: an answer for this count, not an input error.
    out.why_not = error.diagnostics().empty() ? error.what() : error.diagnostics()[0].message;
  }
  for (auto& path : out.waypoints) label_pieces(path, layer);
  out.planning_s = seconds_since(started);
  return out;
}

std::optional<std::string> Scheduler::no_room_to_park(
    const std::vector<std::vector<planner::Waypoint>>& waypoints, int nozzles) const {
  const int idle = machine_.nozzles - nozzles;
  if (idle <= 0) return std::nullopt;
  // The idle gantries wait beyond the working ones, at the far end of the rails: each a
  // gantry width from the next (the dispatcher parks them there).
  const machine::AxisLimits& rail =
      machine_.rail_axis == machine::RailAxis::kY ? machine_.y : machine_.x;
  double reach_m = -kInf;
  for (const auto& path : waypoints)
    for (const auto& w : path)
      reach_m = std::max(reach_m, machine::rail_coordinate(w.position_m.x(), w.position_m.y(),
                                                           machine_.rail_axis));
  const double room_m = rail.max_m - idle * machine_.gantry_width_m;
  if (reach_m <= room_m + 1e-6) return std::nullopt;
  return printf_string(
      "on %d of the machine's %d gantries the path reaches %.3f %s along the rails, where "
      "the %d idle one%s, parked at the far end (%.3f %s), leave%s room only up to %.3f %s",
      nozzles, machine_.nozzles, reach_m, "m", idle, idle == 1 ? "" : "s", rail.max_m, "m",
      idle == 1 ? "s" : "", room_m, "m");
}

void Scheduler::largest_first(std::vector<std::pair<int, int>>& keys) const {
  // The plans are independent, and a batch ends with its last plan: started last, a large
  // layer's plan ran alone on one core for 6 s of the 40 x 40 rooms benchmark's proof.
  std::stable_sort(keys.begin(), keys.end(), [&](const auto& a, const auto& b) {
    return reps_[a.first].segments.size() > reps_[b.first].segments.size();
  });
}

void Scheduler::plan_batch(const std::vector<std::pair<int, int>>& wanted,
                           const std::string& what) {
  std::vector<std::pair<int, int>> todo;
  for (const auto& w : wanted)
    if (!planned_.count(w) && !recall(w.first, w.second) &&
        std::find(todo.begin(), todo.end(), w) == todo.end())
      todo.push_back(w);
  if (todo.empty()) return;
  std::vector<Planned> results(todo.size());
  largest_first(todo);
  std::vector<std::function<void()>> tasks;
  for (std::size_t k = 0; k < todo.size(); ++k)
    tasks.push_back([&, k] { results[k] = plan(todo[k].first, todo[k].second); });
  const auto started = Clock::now();
  run_parallel(tasks, jobs_, [&](int done, int total) {
    progress(printf_string("%s: %d of %d planned (%.1f s)", what.c_str(), done, total,
                           seconds_since(started)));
  });
  for (std::size_t k = 0; k < todo.size(); ++k) {
    planned_[todo[k]] = std::move(results[k]);
    remember(todo[k].first, todo[k].second);
  }
  schedule_.layer_planning_s += seconds_since(started);
  schedule_.plans_computed += static_cast<int>(todo.size());
}

void Scheduler::set_memo_scopes() {
  // The building as its layers, in order: floor, layer, geometry label and hash, heights.
  const floors::Building& b = project_.building;
  std::string layers = printf_string("%d %.17g", static_cast<int>(b.units), b.layer_height_m);
  for (const auto& f : b.floors)
    layers += printf_string(" f%.17g,%.17g", f.base_elevation_m, f.height_m);
  for (const auto& sl : slices_)
    layers += printf_string(" %d,%d,%d,%llx", sl.floor, sl.layer.index, sl.geometry,
                            static_cast<unsigned long long>(sl.layer.geometry_hash));
  const std::string building = sha256_hex(layers);
  layer_scope_ = {project_.machine.get(), building, options_.seed, options_.layer_time_limit_s,
                  options_.max_kicks.value_or(-1)};
  climb_scope_ = {project_.climber.get(), building, options_.seed, options_.climb_time_limit_s};
  if (!options_.memo) return;
  auto& kept = options_.memo->kept;
  for (std::shared_ptr<const void> m : {std::shared_ptr<const void>(project_.machine),
                                        std::shared_ptr<const void>(project_.climber)})
    if (m && std::find(kept.begin(), kept.end(), m) == kept.end()) kept.push_back(m);
}

bool Scheduler::recall(int geometry, int nozzles) {
  if (!options_.memo) return false;
  const auto it = options_.memo->layers.find({layer_scope_, geometry, nozzles});
  if (it == options_.memo->layers.end()) return false;
  planned_[{geometry, nozzles}] = it->second;
  return true;
}

void Scheduler::remember(int geometry, int nozzles) {
  if (options_.memo)
    options_.memo->layers[{layer_scope_, geometry, nozzles}] = planned_.at({geometry, nozzles});
}

const Planned& Scheduler::planned(int geometry, int nozzles) {
  const auto key = std::make_pair(geometry, nozzles);
  if (!planned_.count(key))
    plan_batch({key}, printf_string("geometry G%d with %d nozzles", geometry + 1, nozzles));
  return planned_.at(key);
}

const Planned* Scheduler::single_plan(int geometry) const {
  const auto single = planned_.find({geometry, 1});
  return single == planned_.end() ? nullptr : &single->second;
}

std::vector<std::pair<int, int>> Scheduler::counts_past_one(int geometry) const {
  std::vector<std::pair<int, int>> out;
  for (int n = 2; n <= machine_.nozzles; ++n)
    if (n == machine_.nozzles ||
        share_could_fit(deposition_of(geometry), n, 0.0, material_.max_layer_interval_s))
      out.emplace_back(geometry, n);
  return out;
}

double Scheduler::deposition_of(int geometry) const {
  return planner::deposition_time_s(reps_[geometry], machine_);
}

int Scheduler::fewest_nozzles(int geometry, double between_s) {
  return fewest_fitting_count(
      machine_.nozzles, deposition_of(geometry), between_s, material_.max_layer_interval_s,
      [&](int n) {
        return planned_.count({geometry, n}) > 0;
      },
      [&](int n) { return count_plan(planned(geometry, n), between_s); });
}

CountPlan Scheduler::count_plan(const Planned& p, double between_s) const {
  CountPlan c;
  c.usable = p.usable;
  c.layer_time_s = p.layer_time_s;
  // The next layer like it starts after this one, its pipes and the move up.
  if (p.usable)
    c.interval_s = p.layer_time_s + between_s +
                   planner::layer_change_s(machine_, p.waypoints, p.waypoints,
                                           project_.building.layer_height_m);
  return c;
}

void Scheduler::plan_counts_ahead() {
  std::set<std::pair<int, double>> asked;  // (geometry, pipe time), in a stable order
  for (std::size_t i = 0; i < slices_.size(); ++i)
    asked.emplace(slices_[i].geometry, run_between_s_[i]);
  // Each round plans at least one more count of each geometry still asking, so a geometry
  // is done within the machine's counts; a count named again (never, by the rule above)
  // ends the rounds rather than asking for ever.
  for (int round = 0; round < machine_.nozzles; ++round) {
    std::vector<std::pair<int, int>> missing;
    for (const auto& [geometry, between_s] : asked)
      if (const auto n = next_count_to_plan(machine_.nozzles, deposition_of(geometry), between_s,
                                            material_.max_layer_interval_s,
                                            [&](int count) -> std::optional<CountPlan> {
                                              const auto it = planned_.find({geometry, count});
                                              if (it == planned_.end()) return std::nullopt;
                                              return count_plan(it->second, between_s);
                                            }))
        if (!planned_.count({geometry, *n})) missing.emplace_back(geometry, *n);
    if (missing.empty()) return;
    plan_batch(missing, "nozzle counts that could be the fastest");
  }
}

std::optional<int> next_count_to_plan(int max_count, double deposition_s, double between_s,
                                      double max_interval_s,
                                      const std::function<std::optional<CountPlan>(int)>& known) {
  // Up to the first count not known its path is the one it takes; past it, unknown.
  std::optional<int> missing;
  fewest_fitting_count(
      max_count, deposition_s, between_s, max_interval_s,
      [&](int n) { return known(n).has_value(); },
      [&](int n) {
        if (!missing) {
          if (auto p = known(n)) return *p;
          missing = n;
        }
        return CountPlan{};
      });
  return missing;
}

double deposition_share_s(double deposition_s, int nozzles) {
  return deposition_s / nozzles;
}

bool share_could_fit(double deposition_s, int nozzles, double between_s, double max_interval_s) {
  return deposition_share_s(deposition_s, nozzles) + between_s <= max_interval_s;
}

int fewest_fitting_count(int max_count, double deposition_s, double between_s,
                         double max_interval_s, const std::function<bool(int)>& have,
                         const std::function<CountPlan(int)>& plan) {
  int fastest = 1;
  double fastest_s = kInf;
  const auto faster = [&](int n, const CountPlan& p) {
    if (p.layer_time_s < fastest_s || (p.layer_time_s == fastest_s && n < fastest)) {
      fastest_s = p.layer_time_s;
      fastest = n;
    }
  };
  std::vector<int> unplanned;  // counts that cannot fit, left until none does
  for (int n = 1; n <= max_count; ++n) {
    if (!have(n) && !share_could_fit(deposition_s, n, between_s, max_interval_s)) {
      unplanned.push_back(n);
      continue;
    }
    const CountPlan p = plan(n);
    if (!p.usable) continue;
    if (p.interval_s <= max_interval_s) return n;
    faster(n, p);
  }
  // None fits: the fastest comes closest. The counts left, most first (the fastest as a
  // rule), are planned only where their share could beat it.
  for (auto n = unplanned.rbegin(); n != unplanned.rend(); ++n) {
    if (deposition_share_s(deposition_s, *n) > fastest_s) continue;
    const CountPlan p = plan(*n);
    if (p.usable) faster(*n, p);
  }
  return fastest;
}

std::string Scheduler::register_plan(const PlanKey& base_key, const Slice& slice, int nozzles,
                                     const Planned& p) {
  const std::string base = base_key.to_string();
  // Labelled with this layer's walls: layers of one geometry may name their walls
  // differently (different plans drawn alike); such a layer gets its own entry.
  std::vector<std::vector<planner::Waypoint>> paths = p.waypoints;
  for (auto& path : paths) label_pieces(path, slice.layer);
  auto same_labels = [&](const SchedulePlan& plan) {
    for (std::size_t n = 0; n < paths.size(); ++n)
      for (std::size_t k = 0; k < paths[n].size(); ++k)
        if (paths[n][k].wall != plan.waypoints[n][k].wall ||
            paths[n][k].piece != plan.waypoints[n][k].piece)
          return false;
    return true;
  };
  auto& variants = variants_[base];
  for (const auto& key : variants)
    if (same_labels(schedule_.plans.at(key))) return key;
  PlanKey variant = base_key;
  variant.relabelled = static_cast<int>(variants.size());
  const std::string key = variant.to_string();
  SchedulePlan plan;
  plan.key = key;
  plan.geometry = slice.geometry + 1;
  plan.nozzles = nozzles;
  plan.method = p.method;
  plan.z_top_m = slice.layer.z_top_m;
  plan.layer_time_s = p.layer_time_s;
  plan.min_gap_m = p.min_gap_m;
  plan.waypoints = std::move(paths);
  plan.layer = slice.layer;
  for (auto& path : plan.waypoints)  // drawn at this layer's height
    for (auto& w : path) w.z_m += slice.layer.z_top_m - reps_[slice.geometry].z_top_m;
  indexes_[key] = index_of(plan.waypoints);
  schedule_.plans[key] = std::move(plan);
  registered_[key] = &p;
  variants.push_back(key);
  return key;
}

std::string Scheduler::plan_key(const Slice& slice, int nozzles) {
  PlanKey key;
  key.geometry = slice.geometry + 1;
  key.nozzles = nozzles;
  return register_plan(key, slice, nozzles, planned(slice.geometry, nozzles));
}

const Planned& Scheduler::follow_plan(const Slice& slice, const std::string& below_key,
                                      bool hold_back) {
  const std::string base = follow_key(slice, below_key, hold_back).to_string();
  auto it = follow_.find(base);
  if (it != follow_.end()) return it->second;
  const auto started = Clock::now();
  // Each piece goes to the nozzle that deposited the wall under it, in the order and the
  // direction that nozzle did, so that every piece is covered about one layer time after
  // the one under it.
  const SchedulePlan& under = schedule_.plans.at(below_key);
  const int nozzles = static_cast<int>(under.waypoints.size());
  std::vector<DepositIndex> by_nozzle;
  for (const auto& path : under.waypoints) by_nozzle.push_back(index_of({path}));
  const floors::Layer& layer = slice.layer;
  struct Keyed {
    double t_s;
    int segment;
    bool reversed;
  };
  std::vector<std::vector<Keyed>> keyed(nozzles);
  for (int k = 0; k < static_cast<int>(layer.segments.size()); ++k) {
    const auto& seg = layer.segments[k];
    // The nozzle that passed either end first; a piece over an opening goes last.
    Keyed best{kInf, k, false};
    int owner = 0;
    for (int n = 0; n < nozzles; ++n) {
      double a_lo = kInf, a_hi = kInf, b_lo = kInf, b_hi = kInf;
      const bool at_a = by_nozzle[n].times_at(seg.wall_id, layer.start_m(seg), a_lo, a_hi);
      const bool at_b = by_nozzle[n].times_at(seg.wall_id, layer.end_m(seg), b_lo, b_hi);
      if (!at_a && !at_b) continue;
      const double t = std::min(at_a ? a_lo : kInf, at_b ? b_lo : kInf);
      if (t < best.t_s) {
        best = {t, k, at_a && at_b ? b_lo < a_lo : !at_a};
        owner = n;
      }
    }
    keyed[owner].push_back(best);
  }
  planner::FollowRequest request;
  request.hold_back = hold_back;
  for (int n = 0; n < nozzles; ++n) {
    std::stable_sort(keyed[n].begin(), keyed[n].end(),
                     [](const Keyed& x, const Keyed& y) { return x.t_s < y.t_s; });
    std::vector<planner::FollowStep> steps;
    for (const auto& k : keyed[n]) steps.push_back({k.segment, k.reversed});
    request.order.push_back(std::move(steps));
    request.parked_m.push_back(under.waypoints[n].empty() ? Eigen::Vector2d::Zero()
                                                          : under.waypoints[n].back().position_m);
  }
  planner::FollowPlan f = planner::plan_following(layer, machine_, request);
  Planned out;
  out.method = "follow-below";
  out.layer_time_s = f.layer_time_s;
  out.deposition_s = f.deposition_s;
  out.airtime_s = f.airtime_s;
  out.max_idle_s = f.max_idle_s;
  out.min_gap_m = f.min_gap_m;
  out.why_not = f.idle_limit_violations > 0 ? idle_limit_broken(f.violating_idle_s) : f.gap_broken;
  out.usable = f.usable();
  out.waypoints = std::move(f.waypoints);
  // Drawn at the geometry's first layer, like every other plan.
  for (auto& path : out.waypoints)
    for (auto& w : path) w.z_m += reps_[slice.geometry].z_top_m - layer.z_top_m;
  out.planning_s = seconds_since(started);
  schedule_.layer_planning_s += out.planning_s;
  return follow_.emplace(base, std::move(out)).first->second;
}

}  // namespace ccbuild::schedule::detail
