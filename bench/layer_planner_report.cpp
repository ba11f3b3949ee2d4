// Single-nozzle planner report: CC-TSP against nearest point and the original order,
// the gap to the lower bound, the gap to the exact optimum where it can be computed,
// and solve times, over generated floor plans of increasing size.
//
//   build/bench/bench_layer_planner --sizes 10,100,1000,5000 --seeds 5

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <string>
#include <vector>

#include "ccbuild/floors/generate.hpp"
#include "ccbuild/floors/slice.hpp"
#include "ccbuild/planner/lower_bound.hpp"
#include "ccbuild/planner/plan_layer.hpp"
#include "stats.hpp"

using namespace ccbuild;
using planner::Algorithm;

namespace {

using bench::max_of;
using bench::mean;
using bench::median;

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("Benchmark report of the single-nozzle layer planner on generated floor plans");
  std::vector<int> sizes{10, 20, 50, 100, 200, 500, 1000, 2000, 5000};
  int seeds = 5;
  std::string metric = "euclidean", objective = "distance";
  double time_limit = 60.0;
  bool per_layout = false;
  int planner_seeds = 1;
  std::string bound = "connected";
  app.add_option("--sizes", sizes, "Wall pieces per layer")->delimiter(',');
  app.add_option("--seeds", seeds, "Layouts per size");
  app.add_option("--metric", metric)->check(CLI::IsMember({"euclidean", "rectilinear"}));
  app.add_option("--objective", objective)->check(CLI::IsMember({"distance", "time"}));
  app.add_option("--time-limit", time_limit, "Per cc-tsp run, s");
  app.add_flag("--per-layout", per_layout, "Also print one line per layout");
  app.add_option("--planner-seeds", planner_seeds,
                 "Also run cc-tsp with this many seeds and report how far apart their results are");
  app.add_option("--bound", bound,
                 "Lower bound cc-tsp reports and stops at (the baselines use matching, so their "
                 "times are the heuristics')")
      ->check(CLI::IsMember({"connected", "matching"}));
  CLI11_PARSE(app, argc, argv);
  const planner::BoundKind bound_kind = *planner::parse_bound(bound);

  const machine::MachineModel machine = machine::MachineModel::defaults();
  std::printf(
      "| walls | layouts | saved vs nearest | saved vs original | gap to bound (mean / max) | gap "
      "to exact | "
      "cc-tsp solve s (median / max) | of which bound s | nearest s |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (int size : sizes) {
    std::vector<double> saved_nearest, saved_original, gap_bound, gap_exact, solve, bound_s,
        nearest_s, seed_spread;
    int walls = 0;
    for (int seed = 1; seed <= seeds; ++seed) {
      const floors::Layer layer = floors::slice_plan_at(
          floors::generate_plan_with_segments(size, static_cast<std::uint64_t>(seed)), 1.0, 2.0);
      walls += static_cast<int>(layer.segments.size());
      auto run = [&](Algorithm algorithm, std::uint64_t planner_seed = 1) {
        planner::PlanOptions o;
        o.algorithm = algorithm;
        o.metric = *planner::parse_metric(metric);
        o.objective = *planner::parse_objective(objective);
        o.time_limit_s = time_limit;
        o.seed = planner_seed;
        o.bound = algorithm == Algorithm::kCcTsp ? bound_kind : planner::BoundKind::kMatching;
        return planner::plan_layer(layer, machine, o);
      };
      auto value = [&](const planner::LayerPlan& p) {
        return objective == "distance" ? p.evaluation.airtime_distance_m : p.evaluation.airtime_s;
      };
      const auto cc = run(Algorithm::kCcTsp);
      const auto nearest = run(Algorithm::kNearest);
      const auto original = run(Algorithm::kOriginal);
      saved_nearest.push_back(100.0 * (1.0 - value(cc) / value(nearest)));
      saved_original.push_back(100.0 * (1.0 - value(cc) / value(original)));
      gap_bound.push_back(100.0 * cc.gap());
      solve.push_back(cc.solve_s);
      nearest_s.push_back(nearest.solve_s);
      {
        // solve_s includes the bound; time it alone to show its share.
        const planner::StopCondition clock;
        planner::airtime_lower_bound(layer, *planner::parse_metric(metric),
                                     planner::PathSpec::closed_tour(), bound_kind, clock);
        bound_s.push_back(clock.elapsed_s());
      }
      if (planner_seeds > 1) {
        double lo = value(cc), hi = value(cc);
        for (int k = 2; k <= planner_seeds; ++k) {
          const double v = value(run(Algorithm::kCcTsp, static_cast<std::uint64_t>(k)));
          lo = std::min(lo, v);
          hi = std::max(hi, v);
        }
        seed_spread.push_back(100.0 * (hi / lo - 1.0));
      }
      if (static_cast<int>(layer.segments.size()) <= 14) {
        const auto exact = run(Algorithm::kExact);
        gap_exact.push_back(100.0 * (value(cc) / value(exact) - 1.0));
      }
      if (per_layout)
        std::fprintf(stderr,
                     "  size %d seed %d: %zu walls, cc %.3f, nearest %.3f, original %.3f, bound "
                     "%.3f, %.3f s, %s\n",
                     size, seed, layer.segments.size(), value(cc), value(nearest), value(original),
                     cc.lower_bound_m, cc.solve_s, planner::to_string(cc.stop).c_str());
    }
    char exact[64] = "—";
    if (!gap_exact.empty())
      std::snprintf(exact, sizeof exact, "%.2f%% (%zu)", max_of(gap_exact), gap_exact.size());
    std::printf(
        "| %d | %d | %.1f%% | %.1f%% | %.2f%% / %.2f%% | %s | %.3f / %.3f | %.3f | %.3f |\n",
        walls / seeds, seeds, mean(saved_nearest), mean(saved_original), mean(gap_bound),
        max_of(gap_bound), exact, median(solve), max_of(solve), median(bound_s), median(nearest_s));
    if (!seed_spread.empty())
      std::printf("|   | spread of %d cc-tsp seeds per layout: mean %.3f%%, max %.3f%% |\n",
                  planner_seeds, mean(seed_spread), max_of(seed_spread));
    std::fflush(stdout);
  }
  return 0;
}
