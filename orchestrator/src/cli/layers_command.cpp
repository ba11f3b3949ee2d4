// ccbuild layers FILE: per floor, the runs of layers that share one geometry.

#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/slice.hpp"
#include "ccbuild/orchestrator/layer_summary.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace ccbuild::cli {
namespace {

struct LayersOptions {
  std::string file;
  std::optional<int> floor;
  bool json = false;
  PlanInputOptions plan;
};

void run_layers(const LayersOptions& options, int& exit_code) {
  const LoadedInput input = load_input(options.file, options.plan);
  const floors::Building& b = input.building;
  if (options.floor && (*options.floor < 0 || *options.floor >= static_cast<int>(b.floors.size())))
    throw InputError("", 0, "--floor",
                     printf_string("no floor %d; %s has floors 0 to %zu", *options.floor,
                                   options.file.c_str(), b.floors.size() - 1));
  const orchestrator::BuildingSummary summary = orchestrator::summarize_building(b);

  if (options.json) {
    nlohmann::ordered_json out;
    out["file"] = options.file;
    out["layer_height_m"] = b.layer_height_m;
    out["distinct_geometries"] = summary.distinct_geometries;
    out["floors"] = nlohmann::ordered_json::array();
    for (const auto& f : summary.floors) {
      if (options.floor && f.floor_index != *options.floor) continue;
      nlohmann::ordered_json floor = {{"index", f.floor_index},
                                      {"name", f.name},
                                      {"height_m", f.height_m},
                                      {"base_elevation_m", f.base_elevation_m},
                                      {"layers", f.layer_count},
                                      {"distinct_geometries", f.distinct_geometries},
                                      {"runs", nlohmann::ordered_json::array()}};
      for (const auto& r : f.runs) {
        floor["runs"].push_back({{"first_layer", r.first_layer},
                                 {"last_layer", r.last_layer},
                                 {"geometry", "G" + std::to_string(r.geometry_label)},
                                 {"geometry_hash", floors::hash_to_hex(r.geometry_hash)},
                                 {"walls", r.wall_count},
                                 {"segments", r.segment_count},
                                 {"wall_length_m", r.wall_length_m}});
      }
      out["floors"].push_back(floor);
    }
    std::cout << out.dump(2) << "\n";
    exit_code = kExitOk;
    return;
  }

  std::cout << printf_string("%s: layers of %.3f m, %d distinct geometries in all\n",
                             options.file.c_str(), b.layer_height_m, summary.distinct_geometries);
  for (const auto& f : summary.floors) {
    if (options.floor && f.floor_index != *options.floor) continue;
    std::cout << "\n"
              << printf_string(
                     "floor %d '%s': %.3f m high from %.3f m, %d layers, %d distinct geometries\n",
                     f.floor_index, f.name.c_str(), f.height_m, f.base_elevation_m, f.layer_count,
                     f.distinct_geometries);
    std::cout << printf_string("  %-13s %-9s %-16s %6s %9s %12s\n", "layers", "geometry", "hash",
                               "walls", "segments", "wall length");
    for (const auto& r : f.runs) {
      const std::string range =
          r.first_layer == r.last_layer
              ? std::to_string(r.first_layer)
              : std::to_string(r.first_layer) + "-" + std::to_string(r.last_layer);
      std::cout << printf_string("  %-13s G%-8d %-16s %6d %9d %10.2f m\n", range.c_str(),
                                 r.geometry_label, floors::hash_to_hex(r.geometry_hash).c_str(),
                                 r.wall_count, r.segment_count, r.wall_length_m);
    }
  }
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
      "A wall cut by an opening counts once in `walls` and once per piece in `segments`.\n"
      "Examples:\n"
      "  ccbuild layers config/buildings/apartment.yaml --floor 4\n"
      "  ccbuild layers config/buildings/house.yaml --json");
  command->add_option("FILE", options->file, "Building file or floor plan")->required();
  command->add_option("--floor", options->floor, "Only this floor (0 = ground)");
  command->add_flag("--json", options->json, "Print one JSON object");
  add_plan_input_options(*command, options->plan);
  command->callback([options, &exit_code] { run_layers(*options, exit_code); });
}

}  // namespace ccbuild::cli
