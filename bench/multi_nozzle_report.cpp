// Multi-nozzle report: over generated layouts of increasing complexity, for 2 and 3
// nozzles and gantry widths of 2.5, 5, 7.5 and 10 ft, each method's success rate and the
// construction (layer) time it saves against one nozzle; then, for auto, which method it
// used and how often our delay method would have been faster than that.
//
//   build/bench/bench_multi_nozzle --layouts 50

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <string>
#include <vector>

#include "ccbuild/floors/generate.hpp"
#include "ccbuild/floors/slice.hpp"
#include "ccbuild/planner/multi_nozzle.hpp"

using namespace ccbuild;
using planner::MultiMethod;

int main(int argc, char** argv) {
  CLI::App app("Benchmark report of multi-nozzle planning on generated floor plans");
  int layouts = 50;
  int smallest = 20, largest = 500;
  std::vector<int> nozzle_counts{2, 3};
  std::vector<double> widths_ft{2.5, 5.0, 7.5, 10.0};
  std::string objective = "time";
  std::vector<std::string> method_names{
      "path-cycling", "global-path-cycling", "bz-path-cycling", "aux-buffer-zone", "delay", "auto"};
  app.add_option("--layouts", layouts, "Layouts, from --smallest to --largest walls");
  app.add_option("--smallest", smallest);
  app.add_option("--largest", largest);
  app.add_option("--nozzles", nozzle_counts)->delimiter(',');
  app.add_option("--gantry-width-ft", widths_ft)->delimiter(',');
  app.add_option("--objective", objective)->check(CLI::IsMember({"time", "distance"}));
  app.add_option("--methods", method_names, "Methods to run (default: all five, then auto)")
      ->delimiter(',');
  bool verbose = false;
  app.add_flag("--verbose", verbose, "One line per plan on stderr: method, outcome, saved");
  CLI11_PARSE(app, argc, argv);

  std::vector<MultiMethod> methods;
  for (const std::string& name : method_names) {
    const auto m = planner::parse_multi_method(name);
    if (!m) {
      std::fprintf(stderr, "unknown method %s\n", name.c_str());
      return 2;
    }
    methods.push_back(*m);
  }
  struct Tally {
    int tried = 0, succeeded = 0;
    std::vector<double> saved;
    double seconds = 0.0;  // planning time
    // auto only: which method it used (per stage), and how often delay would have been
    // faster than the papers' method it used (and by how much, % of auto's time).
    std::map<std::string, int> chosen;
    std::vector<double> delay_gain;
  };
  // (nozzles, width, method, big) -> tally; big: layouts of 100+ walls.
  std::map<std::tuple<int, double, int, bool>, Tally> tally;
  // The default machine with 100 m of rails, so that the largest layouts fit.
  machine::MachineModel machine = machine::MachineModel::defaults();
  machine.x.max_m = machine.x.min_m + 100.0;
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < layouts; ++i) {
    const int walls = layouts == 1 ? smallest : smallest + (largest - smallest) * i / (layouts - 1);
    const floors::Layer layer = floors::slice_plan_at(
        floors::generate_plan_with_segments(walls, static_cast<std::uint64_t>(i + 1)), 1.0, 2.0);
    const bool big = layer.segments.size() >= 100;
    planner::PlanOptions single;
    single.objective = *planner::parse_objective(objective);
    const double single_time = planner::plan_layer(layer, machine, single).evaluation.layer_time_s;
    for (int n : nozzle_counts) {
      for (double ft : widths_ft) {
        for (std::size_t m = 0; m < methods.size(); ++m) {
          planner::MultiNozzleOptions o;
          o.nozzles = n;
          o.gantry_width_m = ft * floors::kMetersPerFoot;
          o.method = methods[m];
          o.planning.objective = *planner::parse_objective(objective);
          o.planning.max_kicks = 300;
          o.single_nozzle_time_s = single_time;
          Tally& t = tally[{n, ft, static_cast<int>(m), big}];
          ++t.tried;
          try {
            const auto began = std::chrono::steady_clock::now();
            const planner::MultiNozzlePlan plan = planner::plan_layer_multi(layer, machine, o);
            t.seconds +=
                std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
            for (const auto& stage : plan.stages) {
              if (stage.nozzles.empty()) continue;
              ++t.chosen[planner::to_string(stage.method)];
              if (stage.faster_delay_s)
                t.delay_gain.push_back(100.0 * (1.0 - *stage.faster_delay_s / stage.time_s));
            }
            if (plan.status) {
              ++t.succeeded;
              t.saved.push_back(100.0 * (1.0 - plan.layer_time_s / plan.single_nozzle_time_s));
            }
            if (verbose) {
              const auto& stage = plan.stages.front();
              std::fprintf(stderr, "  %zu walls, %d nozzles, %.1f ft, %s: %s\n",
                           layer.segments.size(), n, ft, planner::to_string(methods[m]).c_str(),
                           plan.status
                               ? (stage.method_detail + ", saved " +
                                  std::to_string(100.0 * (1.0 - plan.layer_time_s /
                                                                    plan.single_nozzle_time_s)) +
                                  "%")
                                     .c_str()
                               : stage.attempts.back().to_string().c_str());
            }
          } catch (const std::exception& e) {
            std::fprintf(stderr, "layout %d: %s\n", i + 1, e.what());
          }
        }
      }
    }
    std::fprintf(stderr, "layout %d/%d (%zu walls) done, %.0f s\n", i + 1, layouts,
                 layer.segments.size(),
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  auto mean = [](const std::vector<double>& v) {
    return v.empty() ? NAN : std::accumulate(v.begin(), v.end(), 0.0) / v.size();
  };
  auto least = [](const std::vector<double>& v) {
    return v.empty() ? NAN : *std::min_element(v.begin(), v.end());
  };
  auto most = [](const std::vector<double>& v) {
    return v.empty() ? NAN : *std::max_element(v.begin(), v.end());
  };
  // Both size classes of one configuration and method together.
  auto merged = [&](int n, double ft, int m) {
    Tally all;
    for (bool b : {false, true}) {
      const Tally& t = tally[{n, ft, m, b}];
      all.tried += t.tried;
      all.succeeded += t.succeeded;
      all.saved.insert(all.saved.end(), t.saved.begin(), t.saved.end());
      all.seconds += t.seconds;
      for (const auto& [name, count] : t.chosen) all.chosen[name] += count;
      all.delay_gain.insert(all.delay_gain.end(), t.delay_gain.begin(), t.delay_gain.end());
    }
    return all;
  };
  std::printf(
      "| nozzles | gantry ft | method | success (all) | saved, mean / min (all) | success (100+ "
      "walls) | saved, mean / min (100+ walls) | s per plan |\n"
      "|---:|---:|---|---:|---:|---:|---:|---:|\n");
  for (int n : nozzle_counts) {
    for (double ft : widths_ft) {
      for (std::size_t m = 0; m < methods.size(); ++m) {
        const Tally all = merged(n, ft, static_cast<int>(m));
        const Tally& big = tally[{n, ft, static_cast<int>(m), true}];
        std::printf(
            "| %d | %.1f | %s | %d/%d | %.1f%% / %.1f%% | %d/%d | %.1f%% / %.1f%% | %.2f |\n", n,
            ft, planner::to_string(methods[m]).c_str(), all.succeeded, all.tried, mean(all.saved),
            least(all.saved), big.succeeded, big.tried, mean(big.saved), least(big.saved),
            all.tried ? all.seconds / all.tried : NAN);
      }
    }
  }
  const auto automatic = std::find(methods.begin(), methods.end(), MultiMethod::kAuto);
  if (automatic == methods.end()) return 0;
  const int a = static_cast<int>(automatic - methods.begin());
  std::printf(
      "\n| nozzles | gantry ft | auto used (all layouts) | delay faster than auto's plan | by, "
      "mean "
      "/ max |\n|---:|---:|---|---:|---:|\n");
  for (int n : nozzle_counts) {
    for (double ft : widths_ft) {
      const Tally all = merged(n, ft, a);
      std::string used;
      for (const auto& [name, count] : all.chosen)
        used += (used.empty() ? "" : ", ") + name + " " + std::to_string(count);
      std::printf("| %d | %.1f | %s | %zu/%d | %.1f%% / %.1f%% |\n", n, ft, used.c_str(),
                  all.delay_gain.size(), all.tried, mean(all.delay_gain), most(all.delay_gain));
    }
  }
  return 0;
}
