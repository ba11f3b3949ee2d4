// Planning time and duration of every climb of a building on a climbing machine, over
// several seeds: the target is at most 1 s of planning per climb on one core.
// Run pinned to one core:
//   taskset -c 0 build/bench/bench_climb_planning --seeds 10

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "ccbuild/climb/climb.hpp"
#include "ccbuild/floors/building.hpp"
#include "ccbuild/machine/climbing_machine.hpp"

using namespace ccbuild;

namespace {

struct Figures {
  std::vector<double> values;
  void add(double v) { values.push_back(v); }
  double min() const { return *std::min_element(values.begin(), values.end()); }
  double max() const { return *std::max_element(values.begin(), values.end()); }
  double median() const {
    std::vector<double> v = values;
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
  }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app(
      "Plans every climb of a building on a climbing machine over several seeds and "
      "prints, per climb, the planning time (min / median / max) and the climb's "
      "duration; planning only, the stages are placed once.");
  std::string building_file = "config/buildings/apartment.yaml";
  std::string machine_file = "config/machines/cc-climber.yaml";
  int seeds = 10;
  app.add_option("--building", building_file, "Building file")->capture_default_str();
  app.add_option("--machine", machine_file, "Climbing machine profile")->capture_default_str();
  app.add_option("--seeds", seeds, "Seeds 1..N per climb")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  const floors::Building building = floors::load_building(building_file);
  const machine::MachineProfile profile = machine::load_machine_profile(machine_file);
  if (!profile.climbing) {
    std::fprintf(stderr, "%s is not a climbing machine\n", machine_file.c_str());
    return 2;
  }
  const machine::ClimbingMachine& m = *profile.climbing;
  const auto began = std::chrono::steady_clock::now();
  const climb::StagePlan stages = climb::climb_stages(building, m);
  const double stages_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  std::printf("%s on %s: %zu stages placed in %.3f s; %d seeds per climb\n", building_file.c_str(),
              machine_file.c_str(), stages.stages.size(), stages_s, seeds);
  std::printf("%-8s %9s %9s %9s %10s %8s %9s\n", "climb", "min_s", "median_s", "max_s", "climb_min",
              "lift_min", "feasible");
  Figures all;
  for (std::size_t k = 0; k + 1 < stages.stages.size(); ++k) {
    Figures planning;
    double duration_s = 0.0, lift_s = 0.0;
    int feasible = 0;
    for (int seed = 1; seed <= seeds; ++seed) {
      climb::ClimbOptions options;
      options.seed = static_cast<std::uint64_t>(seed);
      const climb::ClimbPlan plan =
          climb::plan_climb(m, building, stages.stages[k], stages.stages[k + 1], options);
      planning.add(plan.planning_s);
      all.add(plan.planning_s);
      if (!plan.status) continue;
      ++feasible;
      duration_s = plan.duration_s;
      lift_s = plan.phases.back().duration_s;
    }
    std::printf("%zu -> %zu %9.3f %9.3f %9.3f %10.1f %8.1f %5d/%d\n", k, k + 1, planning.min(),
                planning.median(), planning.max(), duration_s / 60.0, lift_s / 60.0, feasible,
                seeds);
  }
  if (!all.values.empty())
    std::printf("all      %9.3f %9.3f %9.3f\n", all.min(), all.median(), all.max());
  return 0;
}
