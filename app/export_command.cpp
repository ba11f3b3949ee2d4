// ccbuild export SCHEDULE.json --format csv -o FILE: the schedule for the tools a site
// plans in (docs/schedule.md, "Exports").

#include <cmath>
#include <iostream>
#include <map>
#include <memory>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/common/dates.hpp"
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
  std::optional<std::string> units;  ///< --units: shown instead of the building's
};

void run_export(const ExportCommandOptions& o, int& exit_code) {
  OutputClaims outputs({o.schedule});
  outputs.claim_file("--output", o.output, o.force);
  // A task list needs no tool paths: a regression golden (digests only) exports too.
  schedule::ReadSchedule schedule =
      read_schedule_for(o.schedule, o.allow_changed_inputs, true, "export");
  for (const auto& f : schedule.document.inputs.files) outputs.add_input(f.path);
  if (o.units) schedule.document.inputs.units = *o.units;
  const schedule::ScheduleDocument& document = schedule.document;
  report::ExportDates dates;
  if (!o.start.empty()) {
    if (document.inputs.calendar)
      throw InputError("", 0, "--start",
                       "the schedule has a site calendar (from " +
                           document.inputs.calendar->local_text(0.0) +
                           ") that dates every task; --start is for a schedule made without one");
    dates.start_local_s = report::parse_local_start(o.start, "--start");
    // Every date written lies in the years a date may name: the last one too.
    const long long last_s = days_from_civil(kLastDateYear, 12, 31) * 86400 + 86399;
    if (*dates.start_local_s + std::ceil(document.schedule.totals.makespan_s) > last_s)
      throw InputError("", 0, "--start",
                       "'" + o.start + "' with this schedule's " +
                           duration_text(document.schedule.totals.makespan_s) + " ends after " +
                           std::to_string(kLastDateYear) + "-12-31; start earlier");
  }
  const std::string written = report::write_export(document, dates, o.format, o.output, outputs);
  outputs.commit();
  std::cout << written << "\n";
  if (o.format == "csv" && !dates.dated(document))
    std::cout << "  no site calendar and no --start: the start and end columns are empty; give "
                 "--start 2027-03-01T07:00 to date them\n";
  exit_code = kExitOk;
}

}  // namespace

void add_export_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ExportCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "export",
      "Write a schedule (from `ccbuild schedule -o`) for the tools a site plans in.\n"
      "  csv: one row per task, in order of start: every layer (its nozzles and concrete), "
      "every wait (its reasons), pipe, lintel, planned joint's treatment, purge, slab formwork "
      "and pour, climb and each of its phases, and every concrete delivery; columns id, kind, "
      "floor, layer, start and end (local date and time), start_s, end_s and duration_s "
      "(schedule seconds), who (machine, crew), crew (people), concrete_m3, detail.\n"
      "  ical: an iCalendar file (RFC 5545) for a shared calendar: the crew's tasks (pipes, "
      "lintels, joint treatments, slab formwork and pours, climbs) and each floor's walls "
      "finished, in the site's time zone.\n"
      "  mspdi: an MS Project XML file (MS Project, ProjectLibre, GanttProject, Primavera, "
      "Planner): a summary task per floor, every task with its dates and duration, "
      "finish-to-start links in the order the site works, the working week and holidays.\n"
      "  days: the work packages by day, as text: for each day the layers printed, the "
      "concrete and its trucks, the crew's tasks with person-hours, the machine's, the waits "
      "and where printing stopped.\n"
      "Dates come from the schedule's site calendar, or for a schedule made without one from "
      "--start (ical, mspdi and days need one of them). The schedule is read back and checked "
      "first, "
      "as by `ccbuild report`.\n"
      "Examples:\n"
      "  ccbuild schedule config/buildings/tower.yaml --site "
      "config/sites/weekdays-berlin-2027.yaml -o tower.json\n"
      "  ccbuild export tower.json --format csv -o tower.csv\n"
      "  ccbuild export tower.json --format ical -o tower.ics\n"
      "  ccbuild export tower.json --format mspdi -o tower.xml\n"
      "  ccbuild export tower.json --format days -o tower-days.txt\n"
      "  ccbuild export house.json --format csv -o house.csv --start 2027-03-01T07:00");
  command->add_option("SCHEDULE", o->schedule, "A schedule JSON file")->required();
  command
      ->add_option(
          "--format", o->format,
          "What to write: csv (a task list), ical (a calendar), mspdi (MS Project XML), days "
          "(work packages by day)")
      ->check(CLI::IsMember(report::export_formats()))
      ->capture_default_str();
  command->add_option("-o,--output", o->output, "The file to write")
      ->required()
      ->check(output_path());
  command->add_option("--start", o->start,
                      "For a schedule made without a site calendar: the local date and time "
                      "its second 0 is (2027-03-01T07:00 or \"2027-03-01 07:00\")");
  command->add_flag("--force", o->force, "Overwrite an existing output file");
  add_shown_units_option(*command, o->units);
  command->add_flag("--allow-changed-inputs", o->allow_changed_inputs,
                    "Export a schedule whose input files changed since it was made");
  command->callback([o, &exit_code] { run_export(*o, exit_code); });
}

}  // namespace ccbuild::cli
