// ccbuild layers FILE: per floor, the runs of layers that share one geometry.

#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/slice.hpp"
#include "ccbuild/orchestrator/layer_summary.hpp"
#include "ccbuild/orchestrator/project.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace ccbuild::cli {
namespace {

struct LayersOptions {
  std::string file;
  std::optional<int> floor;
  bool json = false;
  InputOptions input;
};

void run_layers(const LayersOptions& options, int& exit_code) {
  const orchestrator::Project project = open_input(options.file, options.input);
  const floors::Building& b = project.building;
  if (options.floor) orchestrator::check_floor(project, *options.floor);
  const orchestrator::BuildingSummary summary = orchestrator::summarize_building(b);

  if (options.json) {
    nlohmann::ordered_json out;
    out["file"] = options.file;
    out["layer_height_m"] = b.layer_height_m;
    out["distinct_geometry_count"] = summary.distinct_geometries;
    out["floors"] = nlohmann::ordered_json::array();
    for (const auto& f : summary.floors) {
      if (options.floor && f.floor_index != *options.floor) continue;
      nlohmann::ordered_json floor = {{"floor", f.floor_index},
                                      {"name", f.name},
                                      {"height_m", f.height_m},
                                      {"base_elevation_m", f.base_elevation_m},
                                      {"layer_count", f.layer_count},
                                      {"distinct_geometry_count", f.distinct_geometries},
                                      {"runs", nlohmann::ordered_json::array()}};
      for (const auto& r : f.runs) {
        floor["runs"].push_back({{"first_layer", r.first_layer},
                                 {"last_layer", r.last_layer},
                                 {"geometry", "G" + std::to_string(r.geometry_label)},
                                 {"geometry_hash", floors::hash_to_hex(r.geometry_hash)},
                                 {"wall_count", r.wall_count},
                                 {"piece_count", r.segment_count},
                                 {"wall_length_m", r.wall_length_m}});
      }
      out["floors"].push_back(floor);
    }
    std::cout << out.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
    exit_code = kExitOk;
    return;
  }

  std::cout << printf_string("%s: layers of %s, %d distinct geometries in all\n",
                             options.file.c_str(), project.length(b.layer_height_m).c_str(),
                             summary.distinct_geometries);
  for (const auto& f : summary.floors) {
    if (options.floor && f.floor_index != *options.floor) continue;
    std::cout << "\n"
              << printf_string(
                     "floor %d '%s': %s high from %s, %d layers, %d distinct geometries\n",
                     f.floor_index, f.name.c_str(), project.length(f.height_m).c_str(),
                     project.length(f.base_elevation_m).c_str(), f.layer_count,
                     f.distinct_geometries);
    std::cout << printf_string("  %-13s %-9s %-16s %6s %7s %14s\n", "layers", "geometry", "hash",
                               "walls", "pieces", "wall length");
    for (const auto& r : f.runs) {
      const std::string range =
          r.first_layer == r.last_layer
              ? std::to_string(r.first_layer)
              : std::to_string(r.first_layer) + "-" + std::to_string(r.last_layer);
      std::cout << printf_string("  %-13s G%-8d %-16s %6d %7d %14s\n", range.c_str(),
                                 r.geometry_label, floors::hash_to_hex(r.geometry_hash).c_str(),
                                 r.wall_count, r.segment_count,
                                 project.length(r.wall_length_m, 2).c_str());
    }
  }
  std::cout
      << "\n  (geometry: numbered across the building, one per distinct outline, as the "
         "schedule's `geometry` and plan keys g<geometry>n<nozzles> name it; hash: its "
         "digest, equal for the same walls at the same coordinates; pieces: the walls' stretches "
         "between openings; wall length: the walls' centre lines summed)\n";
  exit_code = kExitOk;
}

}  // namespace

void add_layers_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<LayersOptions>();
  CLI::App* command = app.add_subcommand(
      "layers",
      "Slice a building (or a plan) into layers and list, per floor, the runs of consecutive "
      "layers "
      "that share one geometry (G1, G2, ... are numbered across the building, so a label seen "
      "twice is the same geometry and is planned once).\n"
      "A wall cut by an opening counts once in `walls` and once per piece in `pieces`.\n"
      "Examples:\n"
      "  ccbuild layers config/buildings/apartment.yaml --floor 4\n"
      "  ccbuild layers config/buildings/house.yaml --json");
  command->add_option("FILE", options->file, "Building file or floor plan")->required();
  command->add_option("--floor", options->floor, "Only this floor (0 = ground)")
      ->check(integer_in(0, 100000));
  command->add_flag("--json", options->json, "Print one JSON object (errors too)");
  add_input_options(*command, options->input);
  command->callback([options, &exit_code] { run_layers(*options, exit_code); });
}

}  // namespace ccbuild::cli
