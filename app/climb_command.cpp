// ccbuild climb BUILDING: where a climbing machine stands, stage after stage, and every
// climb between stages planned with OMPL against the walls built so far.

#include <iostream>
#include <memory>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/units.hpp"
#include "ccbuild/report/climb_report.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace ccbuild::cli {
namespace {

struct ClimbOptions {
  std::string file;
  InputOptions input;
  std::optional<int> floor;
  std::uint64_t seed = 1;
  double time_limit_s = 10.0;
  bool json = false;
  std::string svg;
  bool force = false;
};

void run_climb(const ClimbOptions& o, int& exit_code) {
  const schedule::Project project = open_input(o.file, o.input);
  const auto inputs = project.files_read();
  OutputClaims outputs(inputs);
  if (!o.svg.empty()) outputs.claim_file("--svg", o.svg, o.force);
  climb::ClimbOptions options;
  options.seed = o.seed;
  options.time_limit_s = o.time_limit_s;
  const schedule::ClimbReport report = schedule::plan_climbs(project, o.floor, options);
  const climb::ClimbStatus status = report.status();
  if (!o.svg.empty()) outputs.write(o.svg, report::climb_report_svg(project, report));
  outputs.commit();
  exit_code = status ? kExitOk : kExitNo;
  if (o.json) {
    std::cout << report::climb_report_json(project, report)
                     .dump(2, ' ', false, nlohmann::json::error_handler_t::replace)
              << "\n";
    return;
  }
  report::write_climb_text(std::cout, project, report, o.file, o.floor);
}

}  // namespace

void add_climb_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ClimbOptions>();
  CLI::App* command = app.add_subcommand(
      "climb",
      "Plan how a climbing machine climbs the building it prints (paper 000 section 7): the "
      "stages the platform stands at (as high as its legs allow, the next layer still in the "
      "nozzle's reach), the pipes each stage's pins go into (as low as the legs allow, so they "
      "cure while printing goes on), and every climb: park the gantry, then unit by unit "
      "balance (the gantry as counterweight), release, transit and insert the pin, then lift. "
      "Each motion is planned by OMPL against the walls built so far (FCL), within the URDF's "
      "limits and statically stable, and re-checked at a finer resolution.\n"
      "On a fixed gantry (a profile without `climbing:`) it says whether the building is within "
      "its reach: then no climbs are needed; otherwise exit code 2 says what is out of reach.\n"
      "Exit code 1 when a stage or a climb is not feasible (the reason is printed).\n"
      "Examples:\n"
      "  ccbuild climb config/buildings/apartment.yaml --machine config/machines/cc-climber.yaml\n"
      "  ccbuild climb config/buildings/apartment.yaml --machine config/machines/cc-climber.yaml "
      "--floor 3 --json\n"
      "  ccbuild climb building.yaml --svg climbs.svg");
  command->add_option("BUILDING", o->file, "Building file")->required();
  command
      ->add_option("--floor", o->floor,
                   "Only the climbs made while this floor is printed (those after a stage whose "
                   "last layer is on it); every stage is still listed")
      ->check(integer_in(0, 100000));
  command->add_option("--seed", o->seed, "Random seed: the same seed gives the same motions")
      ->check(unsigned_integer())
      ->capture_default_str();
  command->add_option("--time-limit", o->time_limit_s, "Planning time for each climb, s")
      ->check(number_in(Range::above(0.0, 3600.0), "s"))
      ->capture_default_str();
  command->add_flag("--json", o->json, "Print one JSON object (errors too)");
  command->add_option("--svg", o->svg, "Also draw the platform and pipes in plan and elevation")
      ->check(output_path());
  command->add_flag("--force", o->force,
                    "Overwrite an existing --svg file (never one this run reads)");
  add_input_options(*command, o->input);
  command->callback([o, &exit_code] { run_climb(*o, exit_code); });
}

}  // namespace ccbuild::cli
