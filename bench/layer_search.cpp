// The layer search against the search before issue 14 (2-opt and Or-opt) on generated
// floor plans: tour length against the baseline's and against the lower bound, the time
// each takes, and the time each needs to come within 0.5% of the best tour known.
//
//   taskset -c 0 build/bench/bench_layer_search --sizes 100,1000,5000 --seeds 5
//
// The best tour known is the best of every run made here, the long reference runs
// included (the Lin–Kernighan search given --reference-s seconds per layout).
// With --write-plans it only writes the layouts as plan files, for compare_builds.py to
// time another build (the planner before this issue, say) on the same layers.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "ccbuild/floors/generate.hpp"
#include "ccbuild/floors/slice.hpp"
#include "ccbuild/planner/lower_bound.hpp"
#include "ccbuild/planner/plan_layer.hpp"
#include "stats.hpp"

using namespace ccbuild;

namespace {

using bench::mean;
using bench::median;
using bench::min_of;

/// `count` straight segments 0.5 to 3 m long, scattered at random over a square with
/// about 4 m² per segment: no junctions, unlike a floor plan.
floors::Layer scattered_segments(int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double side_m = std::sqrt(4.0 * count);
  floors::Layer layer;
  layer.z_bottom_m = 1.0;
  layer.z_top_m = 1.02;
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector2d a(side_m * unit(rng), side_m * unit(rng));
    const double angle = 2.0 * M_PI * unit(rng), length = 0.5 + 2.5 * unit(rng);
    const Eigen::Vector2d b = a + length * Eigen::Vector2d(std::cos(angle), std::sin(angle));
    floors::LayerSegment s;
    s.wall_id = k + 1;
    s.start_point = static_cast<int>(layer.points.size());
    s.end_point = s.start_point + 1;
    s.length_m = length;
    layer.points.push_back(a);
    layer.points.push_back(b);
    layer.segments.push_back(s);
  }
  return layer;
}

/// The layer as a plan table (docs/formats.md): its points as vertices, its wall pieces
/// as walls, in their order, so `ccbuild plan-layer` plans the same items. Never
/// overwrites: the file must not exist.
void write_plan_table(const floors::Layer& layer, const std::string& path,
                      const std::string& what) {
  std::FILE* out = std::fopen(path.c_str(), "wx");
  if (!out) {
    std::fprintf(stderr, "bench_layer_search: cannot create %s (it exists, or no directory)\n",
                 path.c_str());
    std::exit(2);
  }
  std::fprintf(out, "# bench_layer_search: %s; %zu walls, metres\nvertices\n", what.c_str(),
               layer.segments.size());
  for (std::size_t p = 0; p < layer.points.size(); ++p)
    std::fprintf(out, "%zu %.17g %.17g\n", p + 1, layer.points[p].x(), layer.points[p].y());
  std::fprintf(out, "walls\n");
  for (std::size_t w = 0; w < layer.segments.size(); ++w)
    std::fprintf(out, "%zu %d %d\n", w + 1, layer.segments[w].start_point + 1,
                 layer.segments[w].end_point + 1);
  if (std::fclose(out) != 0) {
    std::fprintf(stderr, "bench_layer_search: cannot write %s\n", path.c_str());
    std::exit(2);
  }
}

struct Run {
  double value = 0.0;  ///< airtime distance (m) or airtime (s)
  double solve_s = 0.0;
  double search_s = 0.0;  ///< solve_s without the bound
  double bound_s = 0.0;
  double bound_m = 0.0;
  long kicks = 0;
  long last_improvement_kick = 0;
  std::string stop;
  /// (elapsed s, search cost) each time the best tour improved.
  std::vector<std::pair<double, double>> trace;
  /// The first time the search's cost came within `fraction` of `target`; NaN: never.
  double time_within(double target, double fraction) const {
    for (const auto& [t, cost] : trace)
      if (cost <= target * (1.0 + fraction)) return t;
    return NAN;
  }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app(
      "The layer search (Lin-Kernighan) against the 2-opt/Or-opt search before it, on "
      "generated floor plans");
  std::vector<int> sizes{100, 1000, 5000};
  int seeds = 5;
  std::string objective = "distance";
  double reference_s = 0.0;
  double time_limit_s = 60.0;
  long max_kicks = -1;
  bool per_layout = false;
  int bound_rounds = 0;
  std::string layout = "floor-plan";
  app.add_option("--sizes", sizes, "Walls per generated plan")->delimiter(',');
  app.add_option("--seeds", seeds, "Layouts per size");
  app.add_option("--objective", objective)->check(CLI::IsMember({"distance", "time"}));
  app.add_option("--reference-s", reference_s,
                 "Also run the Lin-Kernighan search this long per layout (anytime) for the "
                 "best tour known; 0: none");
  app.add_option("--time-limit", time_limit_s, "Limit of each default run, s");
  app.add_option("--max-kicks", max_kicks, "Kicks of the Lin-Kernighan runs (default: its own)");
  app.add_option("--layout", layout,
                 "floor-plan: generated plans (rooms, junctions, openings); scattered: random "
                 "segments")
      ->check(CLI::IsMember({"floor-plan", "scattered"}));
  app.add_option("--bound-rounds", bound_rounds,
                 "Also compute the connected bound with this many cutting-plane rounds (no "
                 "stall rule) and report the gaps against it; 0: the planner's bound only");
  app.add_flag("--per-layout", per_layout, "One line per layout on stderr");
  std::string write_plans;
  app.add_option("--write-plans", write_plans,
                 "Write each layout as a plan table (vertices and walls, metres) into this new "
                 "directory, plan-WALLS-SEED.txt, and plan nothing: to time `ccbuild "
                 "plan-layer` of another build on the same layers (bench/README.md)");
  CLI11_PARSE(app, argc, argv);

  auto make_layer = [&](int size, int seed) {
    const auto layout_seed = static_cast<std::uint64_t>(seed);
    return layout == "scattered"
               ? scattered_segments(size, layout_seed)
               : floors::slice_plan_at(floors::generate_plan_with_segments(size, layout_seed), 1.0,
                                       2.0);
  };
  if (!write_plans.empty()) {
    std::error_code error;
    if (!std::filesystem::create_directory(write_plans, error)) {
      std::fprintf(stderr, "bench_layer_search: --write-plans %s: %s\n", write_plans.c_str(),
                   error ? error.message().c_str() : "exists already (choose a new directory)");
      return 2;
    }
    for (int size : sizes)
      for (int seed = 1; seed <= seeds; ++seed) {
        const std::string path =
            write_plans + "/plan-" + std::to_string(size) + "-" + std::to_string(seed) + ".txt";
        write_plan_table(make_layer(size, seed), path,
                         layout + " layout, " + std::to_string(size) + " walls asked, seed " +
                             std::to_string(seed));
        std::printf("%s\n", path.c_str());
      }
    return 0;
  }

  const machine::MachineModel machine = machine::MachineModel::defaults();
  const bool distance = objective == "distance";
  std::printf(
      "| walls | layouts | today: gap, s (search s) | lk: gap, s (search s) | lk shorter than "
      "today, mean / min | today's room | best known: gap | to 0.5%% of best, s: today / lk | lk "
      "to today's tour, s |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (int size : sizes) {
    std::vector<double> gap_base, gap_lk, s_base, s_lk, search_base, search_lk, shorter, gap_best,
        room, reach_base, reach_lk, reach_today;
    int walls = 0;
    for (int seed = 1; seed <= seeds; ++seed) {
      const floors::Layer layer = make_layer(size, seed);
      walls += static_cast<int>(layer.segments.size());
      auto run = [&](planner::Neighbourhood neighbourhood, double limit_s,
                     std::optional<long> kicks) {
        Run r;
        planner::PlanOptions o;
        o.objective = distance ? planner::Objective::kDistance : planner::Objective::kTime;
        o.neighbourhood = neighbourhood;
        o.time_limit_s = limit_s;
        o.max_kicks = kicks;
        o.waypoints = false;
        o.on_progress = [&](const planner::SearchProgress& p) {
          if (p.polish) return;  // the search's trace; the polish is its own phase
          r.trace.emplace_back(p.elapsed_s, p.cost);
          r.last_improvement_kick = p.kicks;
        };
        const planner::LayerPlan plan = planner::plan_layer(layer, machine, o);
        r.value = distance ? plan.evaluation.airtime_distance_m : plan.evaluation.airtime_s;
        r.solve_s = plan.solve_s;
        r.search_s = plan.solve_s - plan.bound_s;
        r.bound_s = plan.bound_s;
        r.bound_m = plan.lower_bound_m;
        r.kicks = plan.kicks;
        r.stop = planner::to_string(plan.stop);
        return r;
      };
      const std::optional<long> lk_kicks =
          max_kicks >= 0 ? std::optional<long>(max_kicks) : std::nullopt;
      const Run base = run(planner::Neighbourhood::kTwoOptOrOpt, time_limit_s, lk_kicks);
      const Run lk = run(planner::Neighbourhood::kLinKernighan, time_limit_s, lk_kicks);
      double best = std::min(base.value, lk.value);
      if (reference_s > 0.0) {
        const Run ref = run(planner::Neighbourhood::kLinKernighan, reference_s,
                            std::numeric_limits<long>::max());
        best = std::min(best, ref.value);
      }
      double bound = base.bound_m;
      if (bound_rounds > 0) {
        planner::ConnectedBoundLimits limits;
        limits.max_rounds = bound_rounds;
        limits.stall_fraction = 0.0;
        const auto strong = planner::connected_airtime_bound(
            layer, planner::Metric::kEuclidean, planner::PathSpec::closed_tour(), limits);
        if (per_layout)
          std::fprintf(stderr, "  strong bound %.3f (%d rounds, %s)\n", strong.lower_bound_m,
                       strong.rounds, planner::to_string(strong.stopped_by).c_str());
        bound = std::max(bound, strong.lower_bound_m);
        room.push_back(100.0 * (1.0 - strong.lower_bound_m / base.value));
      }
      if (distance) {
        gap_base.push_back(100.0 * (base.value / bound - 1.0));
        gap_lk.push_back(100.0 * (lk.value / bound - 1.0));
        gap_best.push_back(100.0 * (best / bound - 1.0));
        // The traces are the search's cost, the same as airtime distance on closed tours.
      }
      // Search time: the traces' times since the call, without the bound's.
      reach_base.push_back(base.time_within(best, 0.005) - base.bound_s);
      reach_lk.push_back(lk.time_within(best, 0.005) - lk.bound_s);
      reach_today.push_back(lk.time_within(base.value, 0.0) - lk.bound_s);
      s_base.push_back(base.solve_s);
      s_lk.push_back(lk.solve_s);
      search_base.push_back(base.search_s);
      search_lk.push_back(lk.search_s);
      shorter.push_back(100.0 * (1.0 - lk.value / base.value));
      if (per_layout)
        std::fprintf(stderr,
                     "  %d walls seed %d: today %.3f (%.2f s, %ld kicks, last better %ld, %s), lk "
                     "%.3f (%.2f s, %ld kicks, last better %ld, %s), best %.3f, bound %.3f\n",
                     size, seed, base.value, base.solve_s, base.kicks, base.last_improvement_kick,
                     base.stop.c_str(), lk.value, lk.solve_s, lk.kicks, lk.last_improvement_kick,
                     lk.stop.c_str(), best, bound);
    }
    auto reach = [](const std::vector<double>& v) {
      const long never = std::count_if(v.begin(), v.end(), [](double x) { return std::isnan(x); });
      std::vector<double> got;
      for (double x : v)
        if (!std::isnan(x)) got.push_back(x);
      char text[64];
      if (got.empty())
        std::snprintf(text, sizeof text, "never");
      else if (never > 0)
        std::snprintf(text, sizeof text, "%.3f (%ld never)", median(got), never);
      else
        std::snprintf(text, sizeof text, "%.3f", median(got));
      return std::string(text);
    };
    char room_text[32] = "—";
    if (!room.empty()) std::snprintf(room_text, sizeof room_text, "%.3f%%", mean(room));
    std::printf(
        "| %d | %d | %.3f%%, %.3f s (%.3f) | %.3f%%, %.3f s (%.3f) | %.3f%% / %.3f%% | %s | %.3f%% "
        "| %s / %s | %s |\n",
        walls / seeds, seeds, mean(gap_base), median(s_base), median(search_base), mean(gap_lk),
        median(s_lk), median(search_lk), mean(shorter), min_of(shorter), room_text, mean(gap_best),
        reach(reach_base).c_str(), reach(reach_lk).c_str(), reach(reach_today).c_str());
    std::fflush(stdout);
  }
  return 0;
}
