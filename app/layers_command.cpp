// ccbuild layers FILE: per floor, the runs of layers that share one geometry.

#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/slice.hpp"
#include "ccbuild/report/building_text.hpp"
#include "ccbuild/schedule/layer_summary.hpp"
#include "ccbuild/schedule/project.hpp"
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
  const schedule::Project project = open_input(options.file, options.input);
  if (options.floor) schedule::check_floor(project, *options.floor);
  report::write_layers_summary(std::cout, project, options.file, options.floor, options.json);
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
