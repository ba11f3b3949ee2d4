#include "ccbuild/planner/plan_layer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

#include "cc_tsp.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/planner/timeline.hpp"
#include "search_internal.hpp"

namespace ccbuild::planner {

std::string to_string(Algorithm algorithm) {
  switch (algorithm) {
    case Algorithm::kCcTsp:
      return "cc-tsp";
    case Algorithm::kNearest:
      return "nearest";
    case Algorithm::kOriginal:
      return "original";
    case Algorithm::kExact:
      return "exact";
  }
  return "?";
}

std::optional<Algorithm> parse_algorithm(const std::string& text) {
  for (Algorithm a :
       {Algorithm::kCcTsp, Algorithm::kNearest, Algorithm::kOriginal, Algorithm::kExact})
    if (to_string(a) == text) return a;
  return std::nullopt;
}

std::string to_string(Neighbourhood neighbourhood) {
  return neighbourhood == Neighbourhood::kLinKernighan ? "lk" : "2opt-oropt";
}

std::optional<Neighbourhood> parse_neighbourhood(const std::string& text) {
  for (Neighbourhood n : {Neighbourhood::kLinKernighan, Neighbourhood::kTwoOptOrOpt})
    if (to_string(n) == text) return n;
  return std::nullopt;
}

std::string to_string(StopReason reason) {
  switch (reason) {
    case StopReason::kFinished:
      return "finished";
    case StopReason::kProvenOptimal:
      return "proven-optimal";
    case StopReason::kConverged:
      return "converged";
    case StopReason::kTimeLimit:
      return "time-limit";
    case StopReason::kCancelled:
      return "cancelled";
  }
  return "?";
}

Sequence map_sequence(const Sequence& sequence, const std::vector<floors::SegmentMatch>& matches) {
  Sequence out;
  out.reserve(sequence.size());
  for (const Step& step : sequence) {
    CCBUILD_CHECK(step.segment >= 0 && step.segment < static_cast<int>(matches.size()),
                  "a mapped step names a segment of the planned layer");
    const floors::SegmentMatch& m = matches[step.segment];
    out.push_back({m.segment, step.reversed != m.reversed});
  }
  return out;
}

double LayerPlan::gap() const {
  const double airtime = evaluation.airtime_distance_m;
  if (lower_bound_m <= 1e-12)
    return airtime <= 1e-9 ? 0.0 : std::numeric_limits<double>::quiet_NaN();
  return (airtime - lower_bound_m) / lower_bound_m;
}

namespace {

/// The default budget of the Lin–Kernighan search: kicks in all, and kicks in a row
/// without a better tour (see docs/planning.md, "When the search stops").
constexpr long kLinKernighanMaxKicks = 60'000;
constexpr long kLinKernighanStallKicks = 10'000;
/// The 2-opt/Or-opt search's kicks in a row without a better tour, at most: on layers of
/// thousands of walls (the time objective's large layers) a longer stall bought little
/// (bench/README.md, "40 x 40 rooms"); layers of up to 450 items stay under it.
constexpr long kTwoOptOrOptStallKicks = 10'000;
/// The exact-time polish's step evaluations on a large layer, at most (20,000 a wall up
/// to 2,000 walls): its descent gains less and less per step; on a 6,880-wall layer the
/// last 98 million steps of 138 million took 3.9 s and 0.065% of its layer time
/// (bench/README.md, "40 x 40 rooms").
constexpr long kLargePolishMaxSteps = 40'000'000;

struct Solved {
  Sequence sequence;
  long kicks = 0;
  std::optional<long> polish_kicks;  ///< unset: no exact-time polish ran
  StopReason reason = StopReason::kFinished;
};

// `proof_m`: an airtime distance no longer than this is optimal (LayerBound::proof_m);
// the distance objective stops there.
Solved solve_cc_tsp(const CostModel& model, const PathSpec& path, const PlanOptions& options,
                    double proof_m, const StopCondition& stop) {
  const auto& layer = model.layer();
  const int n = static_cast<int>(layer.segments.size());
  std::vector<int> rest;
  for (int s = 0; s < n; ++s)
    if (!path.first || s != path.first->segment) rest.push_back(s);
  Sequence prefix;
  Eigen::Vector2d start = path.start_m;
  std::optional<Eigen::Vector2d> heading;
  double fixed_distance = 0.0;
  if (path.first) {
    prefix.push_back(*path.first);
    fixed_distance = model.distance_m(path.start_m, model.step_start_m(*path.first));
    start = model.step_end_m(*path.first);
    heading = (start - model.step_start_m(*path.first)).normalized();
  }
  Solved out;
  out.sequence = prefix;
  if (rest.empty()) return out;

  const bool open = !path.closed;
  const Sequence initial = detail::euler_construction(model, rest, open, start, heading);
  detail::TourCosts costs(model, rest, options.objective, open, start, heading);
  costs.build_neighbours(options.objective == Objective::kTime ? 10 : 8);
  detail::SearchSettings settings;
  const long items = costs.item_count();
  settings.seed = options.seed;
  settings.neighbourhood = options.neighbourhood;
  settings.two_opt_before_lk = options.objective == Objective::kTime;
  const bool large = static_cast<std::size_t>(n) > detail::kExactPolishKicksMaxSegments;
  // The time objective on large layers: LK's tours were no faster in exact airtime on
  // 1,000-wall plans (after the polish's descent) and took twice as long to find
  // (bench/README.md), so these keep the 2-opt/Or-opt search.
  if (options.objective == Objective::kTime && large)
    settings.neighbourhood = Neighbourhood::kTwoOptOrOpt;
  // Under the time objective an anytime run's extra time goes to the exact-time polish
  // below: the symmetric search's costs only approximate the airtime, and searching
  // them until the limit left no time for the polish (on a 1,000-wall plan 2,419 s of
  // airtime after a 3 s limit, against 1,797 s on the default budget).
  const bool anytime_polish = options.anytime && options.objective == Objective::kTime;
  // The default budget. LK: kicks are local, so the work grows with the layer, but past
  // ~1,000 walls LK finds with fewer kicks what more would (on 5,000-wall plans 0.03%
  // shorter than the 2-opt/Or-opt search with its ~300,000, in about half its time; the
  // cap trades time for length smoothly, bench/README.md). The time objective uses LK on
  // layers of at most 200 walls only, whose budget is under the caps.
  long default_kicks = 2000 + 60 * items, default_stall_kicks = 1000 + 20 * items;
  if (settings.neighbourhood == Neighbourhood::kLinKernighan) {
    default_kicks = std::min(default_kicks, kLinKernighanMaxKicks);
    default_stall_kicks = std::min(default_stall_kicks, kLinKernighanStallKicks);
  } else {
    default_stall_kicks = std::min(default_stall_kicks, kTwoOptOrOptStallKicks);
  }
  if (options.max_kicks || (options.anytime && !anytime_polish)) {
    settings.max_kicks = settings.stall_kicks =
        options.max_kicks ? *options.max_kicks : std::numeric_limits<long>::max();
    // With no stall rule, a search stalled for a fifth of the default budget's stall
    // restarts from a varied Euler walk (ending after 0.3 of that stall without a better
    // tour) and merges what is better there into its best tour (docs/planning.md). In 2 s
    // on ten 1,000-wall plans: 0.166% shorter than without restarts; restarting after
    // the whole stall, 0.098% (bench/README.md). Distance and LK only: the time
    // objective's extra time goes to its polish.
    if (options.objective == Objective::kDistance &&
        settings.neighbourhood == Neighbourhood::kLinKernighan) {
      settings.restart_kicks = default_kicks;
      settings.restart_stall_kicks = default_stall_kicks / 5;
      settings.restart_own_stall_kicks = default_stall_kicks * 3 / 10;
      settings.restart_tour = [&](std::mt19937_64& rng) {
        return detail::tour_from_sequence(
            costs, detail::euler_construction(model, rest, open, start, heading, &rng));
      };
    }
  } else {
    settings.max_kicks = default_kicks;
    settings.stall_kicks = default_stall_kicks;
  }
  if (options.on_progress)
    settings.on_better = [&](long kicks, double cost) {
      options.on_progress(SearchProgress{stop.elapsed_s(), kicks, cost});
    };
  if (options.objective == Objective::kDistance) settings.target_cost = proof_m - fixed_distance;
  // Under the time objective the exact-time polish follows, and it is where lifts go:
  // a time limit that cut the search short used to leave it nothing (a 1,000-wall plan:
  // 2,348 s of airtime with 0.6 s, against 1,797 s on the default budget). The search
  // gets at most half of what is left; its default budget ends far sooner.
  const bool polish_follows = options.objective == Objective::kTime && options.exact_polish;
  const detail::SearchOutcome outcome =
      detail::chained_local_search(costs, detail::tour_from_sequence(costs, initial), settings,
                                   polish_follows ? stop.within(stop.remaining_s() / 2.0) : stop);
  out.kicks = outcome.kicks;
  out.reason = outcome.reason;
  for (const Step& step : detail::sequence_from_tour(costs, outcome.tour))
    out.sequence.push_back(step);

  if (polish_follows && !stop.should_stop()) {
    std::mt19937_64 rng(options.seed ^ 0x9E3779B97F4A7C15ULL);
    // Small layers get the whole neighbourhood and many kicks: the time landscape (stopper
    // winding, lifts) is rugged, and on layers the exact solver can check, 500 kicks
    // reached its optimum in 160 of 160 runs (8 layouts, both metrics, closed and open,
    // 5 seeds). Larger layers get a local window and a fixed budget; past 200 walls the
    // descent alone (on a 1,000-wall plan, 200 kicks after it found nothing in 5 s), with
    // room to finish it (11 and 7 million steps on two 1,000-wall plans, 68 million on a
    // 5,000-wall one).
    detail::ExactPolishSettings polish;
    const bool small = n <= 16;
    polish.window = small ? static_cast<std::size_t>(n) : 8;
    polish.max_kicks = options.polish_kicks ? *options.polish_kicks
                                            : (small   ? 500
                                               : large ? 0
                                                       : 20);
    polish.max_step_evaluations = small   ? 40'000'000
                                  : large ? std::min(20'000L * n, kLargePolishMaxSteps)
                                          : std::min<long>(4'000'000, 400L * n * n);
    if (options.on_progress)
      polish.on_better = [&](long kicks, double cost_s) {
        options.on_progress(SearchProgress{stop.elapsed_s(), kicks, cost_s, true});
      };
    if (anytime_polish) {  // until the time limit, unless polish_kicks bounds it
      if (!options.polish_kicks) polish.max_kicks = std::numeric_limits<long>::max();
      polish.max_step_evaluations = std::numeric_limits<long>::max();
      polish.local_kicks = large;
    }
    detail::ExactPolishOutcome polished =
        detail::improve_exact_time(model, out.sequence, path, prefix.size(), polish, rng, stop);
    out.sequence = std::move(polished.sequence);
    out.polish_kicks = polished.kicks;
    if (stop.should_stop()) out.reason = stop.reason();
  }
  if (path.closed && options.objective == Objective::kDistance) {
    // Any rotation of a closed tour has the same distance: start at the lowest segment.
    const auto first =
        std::min_element(out.sequence.begin(), out.sequence.end(),
                         [](const Step& a, const Step& b) { return a.segment < b.segment; });
    std::rotate(out.sequence.begin(), first, out.sequence.end());
  }
  return out;
}

}  // namespace

LayerPlan plan_layer(const floors::Layer& layer, const machine::MachineModel& machine,
                     const PlanOptions& options) {
  const StopCondition stop(options.time_limit_s, options.cancel);
  const int n = static_cast<int>(layer.segments.size());
  if (n == 0)
    throw InputError("", 0, "layer", "has no walls to plan (every wall is inside an opening?)");
  if (!(options.time_limit_s > 0.0) || std::isnan(options.time_limit_s))
    throw InputError("", 0, "PlanOptions::time_limit_s", "must be positive");
  if ((options.max_kicks && *options.max_kicks < 0) ||
      (options.polish_kicks && *options.polish_kicks < 0))
    throw InputError("", 0,
                     options.max_kicks && *options.max_kicks < 0 ? "PlanOptions::max_kicks"
                                                                 : "PlanOptions::polish_kicks",
                     "must be zero or more");
  const PathSpec& path = options.path;
  if (path.first) {
    if (path.closed)
      throw InputError("", 0, "PathSpec::first", "needs an open path (a start point)");
    if (path.first->segment < 0 || path.first->segment >= n)
      throw InputError("", 0, "PathSpec::first", "is not a wall of this layer");
  }
  if (options.algorithm == Algorithm::kExact && n > kExactMaxSegments)
    throw InputError("", 0, "PlanOptions::algorithm",
                     "exact handles layers of at most " + std::to_string(kExactMaxSegments) +
                         " walls; this layer has " + std::to_string(n) + " (use cc-tsp)");

  CostModel model(layer, machine, options.metric);
  LayerPlan plan;
  plan.algorithm = options.algorithm;
  plan.metric = options.metric;
  plan.objective = options.objective;
  plan.path = path;
  // The bound gets a third of the time limit at most, so a tight limit still leaves the
  // search most of it (the default limit is far beyond what the bound needs).
  const StopCondition bound_stop = stop.within(options.time_limit_s / 3.0);
  LayerBound bound = airtime_lower_bound(layer, options.metric, path, options.bound, bound_stop,
                                         options.connected_bound);
  plan.lower_bound_m = bound.distance_m;
  plan.bound_s = stop.elapsed_s();
  plan.lower_bound_source = bound.source();
  plan.odd_points = bound.odd_points;
  // Moved, not copied: with a kept certificate it holds every moat (after source()).
  plan.connected_bound = std::move(bound.connected);

  std::vector<int> all(n);
  std::iota(all.begin(), all.end(), 0);
  std::vector<int> rest;
  for (int s : all)
    if (!path.first || s != path.first->segment) rest.push_back(s);
  Sequence prefix;
  if (path.first) prefix.push_back(*path.first);

  switch (options.algorithm) {
    case Algorithm::kOriginal: {
      plan.sequence = prefix;
      for (const Step& s : detail::original_sequence(rest)) plan.sequence.push_back(s);
      break;
    }
    case Algorithm::kNearest: {
      plan.sequence = prefix;
      PathSpec from = path;
      if (path.first) from = PathSpec::open_from(model.step_end_m(*path.first));
      for (const Step& s : detail::nearest_sequence(model, rest, from)) plan.sequence.push_back(s);
      break;
    }
    case Algorithm::kCcTsp: {
      Solved solved = solve_cc_tsp(model, path, options, bound.proof_m(), stop);
      plan.sequence = std::move(solved.sequence);
      plan.kicks = solved.kicks;
      plan.polish_kicks = solved.polish_kicks;
      plan.stop = solved.reason;
      break;
    }
    case Algorithm::kExact: {
      // The heuristic only gives the exact search a first upper bound: on its default
      // budget, even when asked for an anytime run, or it would leave the exact search
      // no time.
      PlanOptions warm_start = options;
      warm_start.anytime = false;
      Solved solved = solve_cc_tsp(model, path, warm_start, bound.proof_m(), stop);
      plan.sequence = std::move(solved.sequence);
      plan.kicks = solved.kicks;
      plan.polish_kicks = solved.polish_kicks;
      const double upper = detail::exact_objective(model, plan.sequence, path, options.objective);
      const auto better =
          detail::exact_sequence(model, all, path, options.objective, upper - 1e-9, stop);
      if (better) plan.sequence = *better;
      plan.stop = stop.should_stop() ? stop.reason() : StopReason::kProvenOptimal;
      break;
    }
  }
  CCBUILD_CHECK(covers_every_segment_once(plan.sequence, layer.segments.size()),
                "the planned sequence deposits every wall exactly once");
  plan.evaluation = model.evaluate(plan.sequence, path);
  if (options.waypoints)
    plan.waypoints = waypoints_of(model, plan.sequence, path, plan.evaluation, layer.z_top_m);
  if (options.objective == Objective::kDistance &&
      plan.evaluation.airtime_distance_m <= bound.proof_m() + 1e-9)
    plan.stop = StopReason::kProvenOptimal;
  plan.solve_s = stop.elapsed_s();
  return plan;
}

LayerPlan time_sequence(const floors::Layer& layer, const machine::MachineModel& machine,
                        const Sequence& sequence, const PlanOptions& options) {
  CCBUILD_CHECK(covers_every_segment_once(sequence, layer.segments.size()),
                "a timed sequence deposits every wall exactly once");
  const CostModel model(layer, machine, options.metric);
  LayerPlan plan;
  plan.algorithm = options.algorithm;
  plan.metric = options.metric;
  plan.objective = options.objective;
  plan.path = options.path;
  plan.sequence = sequence;
  plan.evaluation = model.evaluate(plan.sequence, options.path);
  if (options.waypoints)
    plan.waypoints =
        waypoints_of(model, plan.sequence, options.path, plan.evaluation, layer.z_top_m);
  return plan;
}

}  // namespace ccbuild::planner
