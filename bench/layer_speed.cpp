// Solve time of plan_layer (cc-tsp, default settings) on generated floor plans of 100,
// 1,000 and 5,000 walls, with Google Benchmark. Run pinned to one core:
//   taskset -c 0 build/bench/bench_layer_speed

#include <benchmark/benchmark.h>

#include "ccbuild/floors/generate.hpp"
#include "ccbuild/floors/slice.hpp"
#include "ccbuild/planner/plan_layer.hpp"

using namespace ccbuild;

static void BM_PlanLayer(benchmark::State& state) {
  const floors::Layer layer = floors::slice_plan_at(
      floors::generate_plan_with_segments(static_cast<int>(state.range(0)), 1), 1.0, 2.0);
  const machine::MachineModel machine = machine::MachineModel::defaults();
  planner::PlanOptions options;
  options.time_limit_s = 60.0;
  double gap = 0.0;
  for (auto _ : state) {
    const planner::LayerPlan plan = planner::plan_layer(layer, machine, options);
    gap = plan.gap();
    benchmark::DoNotOptimize(plan.evaluation.airtime_s);
  }
  state.counters["walls"] = static_cast<double>(layer.segments.size());
  state.counters["gap_pct"] = 100.0 * gap;
}
BENCHMARK(BM_PlanLayer)
    ->Arg(100)
    ->Arg(1000)
    ->Arg(5000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK_MAIN();
