// ccbuild export SCHEDULE.json --format csv -o FILE: the schedule for the tools a site
// plans in (docs/schedule.md, "Exports").

#include <iostream>
#include <memory>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/report/exports.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace ccbuild::cli {
namespace {

struct ExportCommandOptions {
  std::string schedule;
  std::string format = "csv";
  std::string output;
  std::string start;
  bool force = false;
  bool allow_changed_inputs = false;
};

void run_export(const ExportCommandOptions& o, int& exit_code) {
  OutputClaims outputs({o.schedule});
  outputs.claim_file("--output", o.output, o.force);
  // A task list needs no tool paths: a regression golden (digests only) exports too.
  const schedule::ReadSchedule schedule =
      read_schedule_for(o.schedule, o.allow_changed_inputs, true, "export");
  const schedule::ScheduleDocument& document = schedule.document;
  report::ExportDates dates;
  if (!o.start.empty()) {
    if (document.inputs.calendar)
      throw InputError("", 0, "--start",
                       "the schedule has a site calendar (from " +
                           document.inputs.calendar->local_text(0.0) +
                           ") that dates every task; --start is for a schedule made without one");
    dates.start_local_s = report::parse_local_start(o.start, "--start");
  }
  std::size_t rows = 0;
  const std::string text = report::tasks_csv(document, dates, &rows);
  write_file_atomically(o.output, text, o.force, {o.schedule});

  std::cout << printf_string("%zu tasks of %s written to %s as CSV%s\n", rows, o.schedule.c_str(),
                             o.output.c_str(),
                             document.inputs.calendar || dates.start_local_s
                                 ? ""
                                 : " (no site calendar and no --start: the start and end "
                                   "columns are empty; give --start 2027-03-01T07:00 to date "
                                   "them)");
  exit_code = kExitOk;
}

}  // namespace

void add_export_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ExportCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "export",
      "Write a schedule (from `ccbuild schedule -o`) for the tools a site plans in. csv: one "
      "row per task, in order of start: every layer (its nozzles and concrete), every wait "
      "(its reasons), pipe, lintel, planned joint's treatment, purge, slab formwork and pour, "
      "climb and each of its phases, and every concrete delivery; columns id, kind, floor, "
      "layer, start and end (local date and time), start_s, end_s and duration_s (schedule "
      "seconds), who (machine, crew), crew (people), concrete_m3, detail. Dates come from the "
      "schedule's site calendar, or for a schedule made without one from --start. The "
      "schedule is read back and checked first, as by `ccbuild report`.\n"
      "Examples:\n"
      "  ccbuild schedule config/buildings/tower.yaml --site "
      "config/sites/weekdays-berlin-2027.yaml -o tower.json\n"
      "  ccbuild export tower.json --format csv -o tower.csv\n"
      "  ccbuild export house.json --format csv -o house.csv --start 2027-03-01T07:00");
  command->add_option("SCHEDULE", o->schedule, "A schedule JSON file")->required();
  command->add_option("--format", o->format, "What to write: csv (a task list)")
      ->check(CLI::IsMember({"csv"}))
      ->capture_default_str();
  command->add_option("-o,--output", o->output, "The file to write")
      ->required()
      ->check(output_path());
  command->add_option("--start", o->start,
                      "For a schedule made without a site calendar: the local date and time "
                      "its second 0 is (2027-03-01T07:00 or \"2027-03-01 07:00\")");
  command->add_flag("--force", o->force, "Overwrite an existing output file");
  command->add_flag("--allow-changed-inputs", o->allow_changed_inputs,
                    "Export a schedule whose input files changed since it was made");
  command->callback([o, &exit_code] { run_export(*o, exit_code); });
}

}  // namespace ccbuild::cli
