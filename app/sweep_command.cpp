// ccbuild sweep FILE: the overhead-platform design study of paper 002 §5 (Tables 1 and
// 2): over numbers of nozzles, platform widths, gantry widths and rail orientations, which
// method found a collision-free plan, total construction and machine time, vertices.

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/slice.hpp"
#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/planner/multi_nozzle.hpp"
#include "ccbuild/planner/plan_layer.hpp"
#include "ccbuild/schedule/project.hpp"
#include "ccbuild/study/sweep.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace ccbuild::cli {
namespace {
namespace fs = std::filesystem;

struct SweepOptions {
  std::string file;
  InputOptions input;
  std::vector<int> nozzles{2, 3};
  std::vector<std::string> platform_widths{"40ft", "60ft"};
  std::vector<std::string> gantry_widths{"2.5ft", "5ft", "7.5ft", "10ft"};
  std::vector<std::string> rail_axes{"x", "y"};
  std::optional<int> floor;
  std::optional<int> layer;
  std::string objective = "time";
  std::uint64_t seed = 1;
  double time_limit_s = 30.0;
  std::string csv;
  bool json = false;
  bool force = false;
};

void run_sweep(const SweepOptions& o, int& exit_code) {
  const schedule::Project project = open_input(o.file, o.input);
  const auto inputs = project.files_read();
  OutputClaims outputs(inputs);
  if (!o.csv.empty()) outputs.claim_file("--csv", o.csv, o.force);
  const floors::LengthUnit unit = project.building.units;
  study::SweepGrid grid;
  grid.nozzles = o.nozzles;
  grid.rail_axes = o.rail_axes;
  for (const auto& t : o.platform_widths)
    grid.platform_widths_m.push_back(length_flag(t, "--platform-width", unit));
  for (const auto& t : o.gantry_widths)
    grid.gantry_widths_m.push_back(length_flag(t, "--gantry-width", unit));
  grid.floor = o.floor;
  grid.layer = o.layer;
  grid.planning.objective = *planner::parse_objective(o.objective);
  grid.planning.seed = o.seed;
  grid.planning.time_limit_s = o.time_limit_s;
  const study::SweepResult result = study::run_sweep(project, grid, std::cerr);
  const auto& rows = result.rows;
  if (!o.csv.empty()) outputs.write(o.csv, study::sweep_csv(result));
  outputs.commit();

  const bool any = std::any_of(rows.begin(), rows.end(),
                               [](const study::SweepRow& r) { return bool(r.status); });
  if (o.json) {
    std::cout << study::sweep_json(result, o.file)
                     .dump(2, ' ', false, nlohmann::json::error_handler_t::replace)
              << "\n";
  } else {
    const double per_unit = floors::meters_per(unit);
    const std::string u = floors::to_string(unit);
    std::cout << printf_string(
        "%s: %d layer(s), %zu distinct; times summed over all of them; methods per platform stage "
        "of the largest layer (A path cycling, B buffer zone path cycling, C auxiliary buffer "
        "zone, D delay, - none)\n",
        o.file.c_str(), result.layer_count, result.distinct_count);
    std::cout << printf_string("  %-13s %s\n", "machine", project.machine_origin.c_str());
    std::cout << printf_string("%-7s  %-5s  %10s  %10s  %-8s  %16s  %11s  %8s\n", "nozzles",
                               "rails", ("platform " + u).c_str(), ("gantry " + u).c_str(),
                               "methods", "construction min", "machine min", "vertices");
    auto width = [&](const std::optional<double>& v) {
      return v ? printf_string("%.1f", *v / per_unit) : std::string("-");
    };
    for (const auto& r : rows) {
      std::cout << printf_string(
          "%-7d  %-5s  %10s  %10s  %-8s  %16s  %11s  %8d\n", r.nozzles,
          r.rail_axis.empty() ? "-" : r.rail_axis.c_str(), width(r.platform_m).c_str(),
          width(r.gantry_m).c_str(), r.methods.c_str(),
          r.status ? printf_string("%.1f", r.construction_s / 60).c_str() : "none",
          r.status ? printf_string("%.1f", r.machine_s / 60).c_str() : "none", r.vertices);
    }
    std::cout << "  (rails: the axis the gantries run along; platform, gantry: their widths across "
                 "the rails; methods: the letters above, one per platform stage; construction: the "
                 "layers' times summed, the nozzles working together; machine: the nozzles' busy "
                 "times summed; vertices: "
                 "the largest layer's, after splitting walls at the platform's sections)\n";
    for (const auto& r : rows)
      if (!r.status)
        std::cout << printf_string("  %d nozzles, %s, platform %s, gantry %s: %s\n", r.nozzles,
                                   r.rail_axis.c_str(), width(r.platform_m).c_str(),
                                   width(r.gantry_m).c_str(), r.status.to_string().c_str());
  }
  if (!any) std::cerr << "ccbuild: no configuration has a collision-free plan\n";
  exit_code = any ? kExitOk : kExitNo;
}

}  // namespace

void add_sweep_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* command = app.add_subcommand(
      "sweep",
      "Design study of an overhead platform carrying several nozzles (as in paper 002, Tables 1 "
      "and 2): for "
      "every combination of nozzle count, rail orientation, platform width and gantry width, plan "
      "the layers "
      "with the automatic method and report which method succeeded in each platform stage, the "
      "total "
      "construction time (all layers), the total machine time (busy time of all nozzles) and the "
      "vertices "
      "after splitting. Progress goes to stderr. --nozzles 1 adds the one-nozzle baseline.\n"
      "Exit code 1 when no configuration has a collision-free plan.\n"
      "Lengths take a unit (40ft, 12m); bare numbers are in the file's unit.\n"
      "Examples:\n"
      "  ccbuild sweep config/buildings/apartment.yaml --floor 4 --csv study.csv\n"
      "  ccbuild sweep plan.txt --units ft --nozzles 2,3 --platform-width 40,60 --gantry-width "
      "2.5,5,7.5,10");
  command->add_option("FILE", o->file, "Building file or floor plan")->required();
  command->add_option("--nozzles", o->nozzles, "Nozzle counts; 1 adds the one-nozzle baseline row")
      ->delimiter(',')
      ->check(integer_in(1, planner::kMaxNozzles))
      ->capture_default_str();
  command->add_option("--platform-width", o->platform_widths, "Platform widths")
      ->delimiter(',')
      ->capture_default_str();
  command->add_option("--gantry-width", o->gantry_widths, "Gantry widths")
      ->delimiter(',')
      ->capture_default_str();
  command->add_option("--rail-axis", o->rail_axes, "Rail orientations: x, y")
      ->delimiter(',')
      ->check(CLI::IsMember({"x", "y"}))
      ->capture_default_str();
  command->add_option("--floor", o->floor, "Only this floor of a building")
      ->check(integer_in(0, 100000));
  command->add_option("--layer", o->layer, "Only this layer (of each floor selected)")
      ->check(integer_in(0, 10000000));
  command
      ->add_option("--objective", o->objective,
                   "What each section's tour minimises: time or distance")
      ->check(CLI::IsMember({"time", "distance"}))
      ->capture_default_str();
  command->add_option("--seed", o->seed, "Random seed")
      ->check(unsigned_integer())
      ->capture_default_str();
  command
      ->add_option("--time-limit", o->time_limit_s,
                   "Bound on each layer's planning in each configuration, s")
      ->check(number_in(Range::above(0.0, 86400.0), "s"))
      ->capture_default_str();
  command->add_option("--csv", o->csv, "Also write the table as CSV (SI units)")
      ->check(output_path());
  command->add_flag("--json", o->json, "Print the table as JSON");
  command->add_flag("--force", o->force, "Overwrite an existing --csv file");
  add_input_options(*command, o->input);
  command->callback([o, &exit_code] { run_sweep(*o, exit_code); });
}

}  // namespace ccbuild::cli
