// ccbuild validate FILE: load and check a building (with its profiles) or one plan, and
// print what it holds.

#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "ccbuild/report/building_text.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace ccbuild::cli {
namespace {

struct ValidateOptions {
  std::string file;
  bool json = false;
  InputOptions input;
};

void run_validate(const ValidateOptions& options, int& exit_code) {
  // Opening checks everything: the files, the profiles, and that the machine reaches it.
  const schedule::Project project = open_input(options.file, options.input);
  report::write_building_summary(std::cout, project, options.file, options.json);
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
      "anything is wrong, and with --json the problems are printed as JSON on stdout too.\n"
      "Besides the files themselves it checks that the machine can build the building: its "
      "footprint and height within the machine's reach, every vertex within its x and y travel "
      "where the building stands (its `site:`, or --place centre), and every wall printable as "
      "beads of the nozzle's width: one bead, or two skins and what the building's wall_pattern "
      "puts between them.\n"
      "Examples:\n"
      "  ccbuild validate config/buildings/house.yaml\n"
      "  ccbuild validate model.yaml --place centre --json\n"
      "  ccbuild validate plan.txt --units ft --floor-height 10 --layer-height 0.5");
  command
      ->add_option("FILE", options->file,
                   "Building file (YAML/JSON with `floors:`) or floor plan "
                   "(YAML, JSON or the table text format)")
      ->required();
  command->add_flag("--json", options->json,
                    "Print the summary (or the errors) as one JSON object");
  add_input_options(*command, options->input);
  command->callback([options, &exit_code] { run_validate(*options, exit_code); });
}

}  // namespace ccbuild::cli
