// ccbuild sweep FILE: the overhead-platform design study of paper 002 §5 (Tables 1 and
// 2): over numbers of nozzles, platform widths, gantry widths and rail orientations, which
// method found a collision-free plan, total construction and machine time, vertices.

#include <cmath>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/slice.hpp"
#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/planner/multi_nozzle.hpp"
#include "ccbuild/planner/plan_layer.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace ccbuild::cli {
namespace {
namespace fs = std::filesystem;

struct SweepOptions {
  std::string file;
  PlanInputOptions plan;
  std::vector<int> nozzles{2, 3};
  std::vector<std::string> platform_widths{"40ft", "60ft"};
  std::vector<std::string> gantry_widths{"2.5ft", "5ft", "7.5ft", "10ft"};
  std::vector<std::string> rail_axes{"x", "y"};
  std::optional<int> floor;
  std::optional<int> layer;
  std::string machine;
  std::string objective = "time";
  std::uint64_t seed = 1;
  std::string csv;
  bool json = false;
  bool force = false;
};

char letter(planner::MultiMethod m) {
  switch (m) {
    case planner::MultiMethod::kPathCycling:
      return 'A';
    case planner::MultiMethod::kBufferZonePathCycling:
      return 'B';
    case planner::MultiMethod::kAuxBufferZone:
      return 'C';
    case planner::MultiMethod::kDelay:
      return 'D';
    case planner::MultiMethod::kGlobalPathCycling:
      return 'G';
    case planner::MultiMethod::kAuto:
      return '?';
  }
  return '?';
}

struct Row {
  int nozzles;
  std::string rail_axis;
  double platform_m, gantry_m;
  std::string methods;  // one letter per platform stage of the largest layer, '-' for none
  bool ok = true;
  std::string failure;
  double construction_s = 0.0, machine_s = 0.0;
  int vertices = 0;
};

void run_sweep(const SweepOptions& o, int& exit_code) {
  if (!o.csv.empty()) check_output_path(o.csv, o.force, {o.file});
  const LoadedInput input = load_input(o.file, o.plan);
  const floors::Building& b = input.building;
  const floors::LengthUnit unit = b.units;
  auto length = [&](const std::string& text, const char* flag) {
    const auto v = floors::parse_length_m(text, unit);
    if (!v || *v <= 0.0)
      throw InputError("", 0, flag,
                       "expected positive lengths such as 40ft or 12m, got '" + text + "'");
    return *v;
  };
  std::vector<double> platforms, gantries;
  for (const auto& t : o.platform_widths) platforms.push_back(length(t, "--platform-width"));
  for (const auto& t : o.gantry_widths) gantries.push_back(length(t, "--gantry-width"));
  for (int n : o.nozzles)
    if (n < 2) throw InputError("", 0, "--nozzles", "each count must be at least 2");
  for (const auto& a : o.rail_axes)
    if (a != "x" && a != "y")
      throw InputError("", 0, "--rail-axis", "expected x or y, got '" + a + "'");

  // The layers to plan: each distinct geometry once, weighted by how many layers share it.
  std::map<std::uint64_t, std::pair<floors::Layer, int>> distinct;
  for (const auto& floor : b.floors) {
    if (o.floor && floor.index != *o.floor) continue;
    const auto layers = input.is_building || o.layer
                            ? floors::slice_floor(floor, b.layer_height_m)
                            : std::vector<floors::Layer>{floors::plan_as_layer(floor.plan)};
    for (const auto& layer : layers) {
      if (o.layer && layer.index != *o.layer) continue;
      if (layer.segments.empty()) continue;
      auto [it, fresh] = distinct.try_emplace(layer.geometry_hash, layer, 0);
      ++it->second.second;
    }
  }
  if (distinct.empty()) throw InputError("", 0, "--floor/--layer", "select no layer with walls");
  const floors::Layer* largest = nullptr;
  for (const auto& [hash, entry] : distinct)
    if (!largest || entry.first.segments.size() > largest->segments.size()) largest = &entry.first;

  machine::MachineModel machine = machine::MachineModel::defaults();
  if (!o.machine.empty())
    machine = machine::load_machine(o.machine);
  else if (input.is_building)
    machine = machine::load_machine(b.machine_profile);

  // Each layer's single-nozzle time, once, for the comparison inside every plan.
  std::map<std::uint64_t, double> single_time;
  for (const auto& [hash, entry] : distinct) {
    planner::PlanOptions single;
    single.objective = *planner::parse_objective(o.objective);
    single.seed = o.seed;
    single_time[hash] = planner::plan_layer(entry.first, machine, single).evaluation.layer_time_s;
  }
  std::vector<Row> rows;
  const std::size_t total =
      o.nozzles.size() * o.rail_axes.size() * platforms.size() * gantries.size();
  std::size_t done = 0;
  for (int n : o.nozzles) {
    for (const auto& axis : o.rail_axes) {
      for (double platform : platforms) {
        for (double gantry : gantries) {
          Row row{n, axis, platform, gantry, "", true, "", 0.0, 0.0, 0};
          ++done;
          std::cerr << printf_string(
              "sweep: %zu/%zu  %d nozzles, %s rails, platform %.2f m, gantry %.2f m, %zu layer "
              "geometr%s\n",
              done, total, n, axis.c_str(), platform, gantry, distinct.size(),
              distinct.size() == 1 ? "y" : "ies");
          planner::MultiNozzleOptions m;
          m.nozzles = n;
          m.gantry_width_m = gantry;
          m.rail_axis = axis == "y" ? planner::RailAxis::kY : planner::RailAxis::kX;
          m.platform_width_m = platform;
          m.planning.objective = *planner::parse_objective(o.objective);
          m.planning.seed = o.seed;
          m.planning.max_kicks = 300;
          std::pair<int, int> failed_at{0, 0};
          try {
            for (const auto& [hash, entry] : distinct) {
              m.single_nozzle_time_s = single_time[hash];
              const auto plan = planner::plan_layer_multi(entry.first, machine, m);
              if (&entry.first == largest) {
                for (const auto& stage : plan.stages)
                  row.methods += stage.nozzles.empty() ? '-' : letter(stage.method);
                row.vertices = plan.vertex_count;
              }
              if (!plan.collision_free) {
                row.ok = false;
                // Name the layer (the lowest of those sharing its geometry) unless the
                // input was a single plan.
                const std::string where =
                    input.is_building
                        ? printf_string(
                              "floor %d layer %d%s: ", entry.first.floor_index, entry.first.index,
                              entry.second > 1
                                  ? printf_string(" (and %d more like it)", entry.second - 1)
                                        .c_str()
                                  : "")
                        : std::string();
                // Report the lowest failing layer, whatever the order of the geometries.
                const std::pair<int, int> at{entry.first.floor_index, entry.first.index};
                if (row.failure.empty() || at < failed_at) {
                  row.failure = where + plan.failure;
                  failed_at = at;
                }
                continue;
              }
              row.construction_s += plan.layer_time_s * entry.second;
              row.machine_s += plan.machine_time_s * entry.second;
            }
          } catch (const InputError& e) {
            row.ok = false;
            row.failure = e.first().message;
            row.methods = "-";
          }
          rows.push_back(row);
        }
      }
    }
  }

  const double per_unit = floors::meters_per(unit);
  const std::string u = floors::to_string(unit);
  std::ostringstream csv;
  csv << "nozzles,rail_axis,platform_width_m,gantry_width_m,methods,collision_free,construction_"
         "time_s,"
         "machine_time_s,vertices,failure\n";
  for (const auto& r : rows)
    csv << r.nozzles << "," << r.rail_axis << "," << r.platform_m << "," << r.gantry_m << ","
        << r.methods << "," << (r.ok ? "true" : "false") << "," << (r.ok ? r.construction_s : 0.0)
        << "," << (r.ok ? r.machine_s : 0.0) << "," << r.vertices << ",\"" << r.failure << "\"\n";
  if (!o.csv.empty()) write_file_atomically(o.csv, csv.str(), o.force, {o.file});

  if (o.json) {
    nlohmann::ordered_json out = nlohmann::ordered_json::array();
    for (const auto& r : rows)
      out.push_back({{"nozzles", r.nozzles},
                     {"rail_axis", r.rail_axis},
                     {"platform_width_m", r.platform_m},
                     {"gantry_width_m", r.gantry_m},
                     {"methods", r.methods},
                     {"collision_free", r.ok},
                     {"construction_time_s", r.ok ? r.construction_s : 0.0},
                     {"machine_time_s", r.ok ? r.machine_s : 0.0},
                     {"vertices", r.vertices},
                     {"failure", r.failure}});
    std::cout << out.dump(2) << "\n";
  } else {
    int layers = 0;
    for (const auto& [hash, entry] : distinct) layers += entry.second;
    std::cout << printf_string(
        "%s: %d layer(s), %zu distinct; times summed over all of them; methods per platform stage "
        "of the "
        "largest layer (A path cycling, B buffer zone path cycling, C auxiliary buffer zone, D "
        "delay, - none)\n",
        o.file.c_str(), layers, distinct.size());
    std::cout << printf_string("%-8s %-5s %10s %10s  %-8s %16s %16s %9s\n", "nozzles", "rails",
                               ("platform " + u).c_str(), ("gantry " + u).c_str(), "methods",
                               "construction min", "machine min", "vertices");
    for (const auto& r : rows) {
      std::cout << printf_string(
          "%-8d %-5s %10.1f %10.1f  %-8s %16s %16s %9d\n", r.nozzles, r.rail_axis.c_str(),
          r.platform_m / per_unit, r.gantry_m / per_unit, r.methods.c_str(),
          r.ok ? printf_string("%.1f", r.construction_s / 60).c_str() : "none",
          r.ok ? printf_string("%.1f", r.machine_s / 60).c_str() : "none", r.vertices);
    }
    for (const auto& r : rows)
      if (!r.ok)
        std::cout << printf_string("  %d nozzles, %s, platform %.1f, gantry %.1f: %s\n", r.nozzles,
                                   r.rail_axis.c_str(), r.platform_m / per_unit,
                                   r.gantry_m / per_unit, r.failure.c_str());
  }
  exit_code = kExitOk;
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
      "after splitting. Progress goes to stderr.\n"
      "Lengths take a unit (40ft, 12m); bare numbers are in the file's unit.\n"
      "Examples:\n"
      "  ccbuild sweep config/buildings/apartment.yaml --floor 4 --csv study.csv\n"
      "  ccbuild sweep plan.txt --units ft --nozzles 2,3 --platform-width 40,60 --gantry-width "
      "2.5,5,7.5,10");
  command->add_option("FILE", o->file, "Building file or floor plan")->required();
  command->add_option("--nozzles", o->nozzles, "Nozzle counts")
      ->delimiter(',')
      ->capture_default_str();
  command->add_option("--platform-width", o->platform_widths, "Platform widths")
      ->delimiter(',')
      ->capture_default_str();
  command->add_option("--gantry-width", o->gantry_widths, "Gantry widths")
      ->delimiter(',')
      ->capture_default_str();
  command->add_option("--rail-axis", o->rail_axes, "Rail orientations: x, y")
      ->delimiter(',')
      ->capture_default_str();
  command->add_option("--floor", o->floor, "Only this floor of a building");
  command->add_option("--layer", o->layer, "Only this layer (of each floor selected)");
  command
      ->add_option("--objective", o->objective,
                   "What each section's tour minimises: time or distance")
      ->check(CLI::IsMember({"time", "distance"}))
      ->capture_default_str();
  command->add_option("--seed", o->seed, "Random seed")->capture_default_str();
  command->add_option("--machine", o->machine, "Machine profile (default: the building's)");
  command->add_option("--csv", o->csv, "Also write the table as CSV (SI units)");
  command->add_flag("--json", o->json, "Print the table as JSON");
  command->add_flag("--force", o->force, "Overwrite an existing --csv file");
  add_plan_input_options(*command, o->plan);
  command->callback([o, &exit_code] { run_sweep(*o, exit_code); });
}

}  // namespace ccbuild::cli
