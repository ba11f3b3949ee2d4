// Whole-building schedules: wall-clock time of `build_schedule` on an example building,
// over several runs, with the shares of layer planning, climb planning and bookkeeping,
// and the peak memory. The target: the ten-storey tower in at most 15 s on this
// machine's 2 cores, climbs included; on a site calendar with hourly weather, within 1.5
// times its time without. Run:
//   build/bench/bench_schedule --building config/buildings/tower.yaml --runs 5 --jobs 2
//   build/bench/bench_schedule --site config/sites/weekdays-berlin-2027-weather.yaml

#include <sys/resource.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "ccbuild/schedule/project.hpp"
#include "ccbuild/schedule/schedule.hpp"

using namespace ccbuild;

int main(int argc, char** argv) {
  CLI::App app(
      "Schedules a building several times and prints, per run, the wall-clock time and its "
      "shares (planning layers, planning climbs, the rest), then the median and worst.");
  std::string building_file = "config/buildings/tower.yaml";
  int runs = 5;
  int jobs = 2;
  std::string site_file;
  app.add_option("--building", building_file, "Building file")->capture_default_str();
  app.add_option("--site", site_file, "A site programme (calendar, weather) to schedule on");
  app.add_option("--runs", runs, "Runs")->check(CLI::Range(1, 100))->capture_default_str();
  app.add_option("--jobs", jobs, "Threads (0: every core)")
      ->check(CLI::Range(0, 64))
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  schedule::ProjectOptions project_options;
  project_options.site_file = site_file;
  const schedule::Project project = schedule::open_project(building_file, project_options);
  std::vector<double> totals;
  std::printf("%s%s%s, %d runs, --jobs %d\n", building_file.c_str(),
              site_file.empty() ? "" : " on ", site_file.c_str(), runs, jobs);
  std::printf("run  total_s  layers_s  climbs_s  rest_s  plans  layers  climbs  feasible\n");
  for (int r = 0; r < runs; ++r) {
    schedule::ScheduleOptions options;
    options.jobs = jobs;
    const auto t0 = std::chrono::steady_clock::now();
    const schedule::Schedule s = schedule::build_schedule(project, options);
    const double total_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    totals.push_back(total_s);
    int climbs = 0;
    for (const auto& e : s.events) climbs += e.kind == schedule::Event::Kind::kClimb;
    std::printf("%3d  %7.2f  %8.2f  %8.2f  %6.2f  %5d  %6zu  %6d  %s\n", r + 1, total_s,
                s.layer_planning_s, s.climb_planning_s, s.bookkeeping_s, s.plans_computed,
                s.layers.size(), climbs, s.feasible ? "yes" : "no");
  }
  std::sort(totals.begin(), totals.end());
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  std::printf("median %.2f s, worst %.2f s, peak memory %.0f MiB\n", totals[totals.size() / 2],
              totals.back(), usage.ru_maxrss / 1024.0);
  return 0;
}
