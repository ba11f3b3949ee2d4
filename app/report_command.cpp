// ccbuild report SCHEDULE.json -o report.html: the schedule drawn in one self-contained
// HTML page (Gantt, intervals, strength, tool paths, 3-D playback).

#include <iostream>
#include <memory>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/report/report.hpp"
#include "ccbuild/schedule/schedule_diff.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace ccbuild::cli {
namespace {

struct ReportCommandOptions {
  std::string schedule;
  std::string output;
  bool force = false;
  bool allow_changed_inputs = false;
  std::optional<std::string> units;  ///< --units: shown instead of the building's
};

void run_report(const ReportCommandOptions& o, int& exit_code) {
  OutputClaims outputs({o.schedule});
  outputs.claim_file("--output", o.output, o.force);
  schedule::ReadSchedule schedule =
      read_schedule_for(o.schedule, o.allow_changed_inputs, false, "report");
  for (const auto& f : schedule.document.inputs.files) outputs.add_input(f.path);
  if (o.units) schedule.document.inputs.units = *o.units;
  report::ReportOptions options;
  options.notes = schedule.notes;
  const std::string html = report::schedule_report_html(schedule.document, options);
  outputs.write(o.output, html);
  outputs.commit();
  std::cout << printf_string(
      "report of %s written to %s (%.1f MB)%s\n", o.schedule.c_str(), o.output.c_str(),
      html.size() / 1e6,
      schedule.document.schedule.feasible ? "" : "; the schedule is NOT feasible");
  exit_code = kExitOk;
}

}  // namespace

void add_report_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ReportCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "report",
      "Draw a schedule (from `ccbuild schedule -o`) as one self-contained HTML page that any "
      "current browser opens without a network: a summary and its warnings (an infeasible "
      "schedule says so first, and where), a Gantt of the whole build (wheel to zoom, drag to "
      "pan, hover for what, when and why), each layer's intervals against the material's band "
      "and one layer's local intervals as a heat map on its plan, the anchors' strength at "
      "every climb and the buildability margin over time, every distinct plan's tool path with "
      "its gantries' x/t curves, and a 3-D playback of the build with a time slider. The schedule "
      "is read back and checked first (docs/schedule.md): a hand-edited one that breaks a rule "
      "is refused with the rule and the place, and so is one whose input files changed.\n"
      "Examples:\n"
      "  ccbuild schedule config/buildings/tower.yaml -o tower.json\n"
      "  ccbuild report tower.json -o tower.html\n"
      "  ccbuild schedule config/buildings/house.yaml --report house.html");
  command->add_option("SCHEDULE", o->schedule, "A schedule JSON file")->required();
  command->add_option("-o,--output", o->output, "The HTML file to write")
      ->required()
      ->check(output_path());
  command->add_flag("--force", o->force, "Overwrite an existing output file");
  add_shown_units_option(*command, o->units);
  command->add_flag("--allow-changed-inputs", o->allow_changed_inputs,
                    "Draw a schedule whose input files changed since it was made (the report "
                    "then says which); by default it is refused, being out of date");
  command->callback([o, &exit_code] { run_report(*o, exit_code); });
}

}  // namespace ccbuild::cli
