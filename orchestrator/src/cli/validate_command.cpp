// ccbuild validate FILE: load and check a building (with its profiles) or one plan, and
// print what it holds.

#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/material.hpp"
#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/orchestrator/layer_summary.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace ccbuild::cli {
namespace {

struct ValidateOptions {
  std::string file;
  bool json = false;
  PlanInputOptions plan;
};

void run_validate(const ValidateOptions& options, int& exit_code) {
  const LoadedInput input = load_input(options.file, options.plan);
  const floors::Building& b = input.building;
  std::optional<floors::MaterialProfile> material;
  std::optional<machine::MachineModel> machine;
  if (input.is_building) {
    material = floors::load_material_profile(b.material_profile);
    machine = machine::load_machine(b.machine_profile);
  }
  // The building must fit inside the machine's reach (its extent against the URDF axis
  // ranges; where the site origin lies is not modelled, so lengths are compared).
  Eigen::Vector2d lo(1e18, 1e18), hi(-1e18, -1e18);
  for (const auto& floor : b.floors)
    for (const auto& v : floor.plan.vertices) {
      lo = lo.cwiseMin(v.position_m);
      hi = hi.cwiseMax(v.position_m);
    }
  const Eigen::Vector2d extent = hi - lo;
  if (machine) {
    const double reach_x = machine->x.max_m - machine->x.min_m,
                 reach_y = machine->y.max_m - machine->y.min_m;
    if (extent.x() > reach_x || extent.y() > reach_y)
      throw InputError(
          b.machine_profile.string(), 0, "",
          printf_string("the building is %.2f m x %.2f m but the machine reaches %.2f m x %.2f m",
                        extent.x(), extent.y(), reach_x, reach_y));
  }
  const orchestrator::BuildingSummary summary = orchestrator::summarize_building(b);
  int walls = 0, openings = 0, anchors = 0;
  for (const auto& f : summary.floors) {
    walls += f.wall_count;
    openings += f.opening_count;
    anchors += f.anchor_count;
  }

  if (options.json) {
    nlohmann::ordered_json out;
    out["file"] = options.file;
    out["kind"] = input.is_building ? "building" : "plan";
    out["valid"] = true;
    out["name"] = b.name;
    out["units"] = floors::to_string(b.units);
    out["layer_height_m"] = b.layer_height_m;
    if (material)
      out["material"] = {{"name", material->name}, {"file", b.material_profile.string()}};
    if (machine) out["machine"] = {{"name", machine->name}, {"file", b.machine_profile.string()}};
    out["extent_m"] = {extent.x(), extent.y()};
    out["floors"] = nlohmann::ordered_json::array();
    for (const auto& f : summary.floors) {
      out["floors"].push_back({{"index", f.floor_index},
                               {"name", f.name},
                               {"height_m", f.height_m},
                               {"walls", f.wall_count},
                               {"openings", f.opening_count},
                               {"anchors", f.anchor_count},
                               {"layers", f.layer_count},
                               {"distinct_geometries", f.distinct_geometries}});
    }
    out["totals"] = {{"floors", summary.floors.size()},
                     {"walls", walls},
                     {"openings", openings},
                     {"anchors", anchors},
                     {"layers", summary.total_layers},
                     {"distinct_geometries", summary.distinct_geometries}};
    std::cout << out.dump(2) << "\n";
    exit_code = kExitOk;
    return;
  }

  std::cout << options.file << ": valid " << (input.is_building ? "building" : "plan") << "\n";
  if (!b.name.empty()) std::cout << printf_string("  %-10s %s\n", "name", b.name.c_str());
  std::cout << printf_string("  %-10s %s in the file, metres inside\n", "units",
                             floors::to_string(b.units).c_str());
  std::cout << printf_string("  %-10s %.3f m\n", "layer", b.layer_height_m);
  if (material)
    std::cout << printf_string("  %-10s %s (%s)\n", "material", material->name.c_str(),
                               b.material_profile.c_str());
  if (machine)
    std::cout << printf_string(
        "  %-10s %s (%s); the building's %.2f m x %.2f m is within its %.2f m x %.2f m reach\n",
        "machine", machine->name.c_str(), b.machine_profile.c_str(), extent.x(), extent.y(),
        machine->x.max_m - machine->x.min_m, machine->y.max_m - machine->y.min_m);
  else
    std::cout << printf_string("  %-10s %.2f m x %.2f m\n", "extent", extent.x(), extent.y());
  std::cout << "\n"
            << printf_string("  %-5s %-16s %9s %6s %9s %8s %7s %11s\n", "floor", "name", "height",
                             "walls", "openings", "anchors", "layers", "geometries");
  for (const auto& f : summary.floors) {
    std::cout << printf_string("  %-5d %-16s %7.3f m %6d %9d %8d %7d %11d\n", f.floor_index,
                               f.name.c_str(), f.height_m, f.wall_count, f.opening_count,
                               f.anchor_count, f.layer_count, f.distinct_geometries);
  }
  std::cout << "\n"
            << printf_string(
                   "  total: %zu floor(s), %d walls, %d openings, %d layers, %d distinct layer "
                   "geometries\n",
                   summary.floors.size(), walls, openings, summary.total_layers,
                   summary.distinct_geometries);
  exit_code = kExitOk;
}

}  // namespace

void add_validate_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<ValidateOptions>();
  CLI::App* command = app.add_subcommand(
      "validate",
      "Check a building file (and the material and machine profiles it names) or a single floor "
      "plan, and summarise it.\n"
      "Every problem found is reported with its file, line and field; the exit code is 2 when "
      "anything is wrong.\n"
      "Examples:\n"
      "  ccbuild validate config/buildings/house.yaml\n"
      "  ccbuild validate plan.txt --units ft --floor-height 10 --layer-height 0.5");
  command
      ->add_option("FILE", options->file,
                   "Building file (YAML/JSON with `floors:`) or floor plan "
                   "(YAML, JSON or the table text format)")
      ->required();
  command->add_flag("--json", options->json, "Print the summary as one JSON object");
  add_plan_input_options(*command, options->plan);
  command->callback([options, &exit_code] { run_validate(*options, exit_code); });
}

}  // namespace ccbuild::cli
