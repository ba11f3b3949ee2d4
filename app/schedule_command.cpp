// ccbuild schedule BUILDING: the whole building, every layer planned and timed, with its
// waits, nozzle counts, pipes, climbs and slabs; a text summary and the schedule JSON.

#include <iostream>
#include <map>
#include <memory>
#include <thread>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/quantities.hpp"
#include "ccbuild/report/exports.hpp"
#include "ccbuild/report/report.hpp"
#include "ccbuild/report/schedule_text.hpp"
#include "ccbuild/rules/crew.hpp"
#include "ccbuild/schedule/schedule.hpp"
#include "ccbuild/schedule/schedule_json.hpp"
#include "ccbuild/schedule/what_if.hpp"
#include "ccbuild/site/site.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace ccbuild::cli {
namespace {

struct ScheduleCommandOptions {
  std::string file;
  InputOptions input;
  std::string output;
  std::string report;
  bool force = false;
  std::uint64_t seed = 1;
  int jobs = 0;
  double layer_time_limit_s = 60.0;
  bool quiet = false;
  bool no_compare = false;  ///< no "objectives:" line (the other objective not scheduled)
  bool path_digests = false;
  std::string what_if;  ///< "anchors" or empty
  std::string objective = "fewest-nozzles";
  std::vector<std::string> exports;  ///< files, their format by extension
};

void run_schedule(const ScheduleCommandOptions& o, int& exit_code) {
  const schedule::Project project = open_input(o.file, o.input);
  const auto inputs = project.files_read();
  OutputClaims outputs(inputs);  // every output checked before any planning
  if (!o.output.empty()) outputs.claim_file("--output", o.output, o.force);
  if (!o.report.empty()) outputs.claim_file("--report", o.report, o.force);
  std::vector<std::string> export_formats_given;
  for (const std::string& file : o.exports) {
    const std::string format = report::export_format_of(file, "--export");
    if (report::export_needs_dates(format) && !project.calendar)
      throw InputError("", 0, "--export",
                       "'" + file + "': " + format +
                           " needs dates, and the building has no site calendar: schedule it "
                           "with --site FILE, or export its schedule later with `ccbuild export "
                           "SCHEDULE.json -o " +
                           file + " --start 2027-03-01T07:00`");
    outputs.claim_file("--export", file, o.force);
    export_formats_given.push_back(format);
  }
  schedule::ScheduleOptions options;
  options.seed = o.seed;
  options.jobs = o.jobs;
  options.layer_time_limit_s = o.layer_time_limit_s;
  options.objective = o.objective == "shortest" ? schedule::Objective::kShortest
                                                : schedule::Objective::kFewestNozzles;
  if (!o.quiet) options.progress = [](const std::string& line) { std::cerr << line << "\n"; };
  // The comparison of objectives and the what-ifs take the plans and climbs this one made.
  options.memo = schedule::make_plan_memo();
  const schedule::Schedule s = schedule::build_schedule(project, options);
  std::vector<schedule::AnchorWhatIf> changes;
  if (!o.what_if.empty()) {
    // The bundled rapid-hardening mix, when the config folder is there.
    std::optional<floors::MaterialProfile> rapid;
    const std::filesystem::path rapid_file =
        std::filesystem::path(CCBUILD_CONFIG_DIR) / "materials/rapid-anchor-mix.yaml";
    std::error_code ec;
    if (std::filesystem::exists(rapid_file, ec)) rapid = floors::load_material_profile(rapid_file);
    if (options.progress) options.progress("what-if anchors: scheduling each change in full");
    changes = schedule::anchor_what_ifs(project, s, options, rapid ? &*rapid : nullptr);
  }
  std::vector<std::string> exported;
  if (!o.output.empty() || !o.report.empty() || !o.exports.empty()) {
    const schedule::ScheduleDocument doc{schedule::recorded_inputs(project, options, &s), s};
    for (std::size_t k = 0; k < o.exports.size(); ++k)
      exported.push_back(
          report::write_export(doc, {}, export_formats_given[k], o.exports[k], outputs));
    if (!o.output.empty())
      outputs.write(o.output,
                    schedule::schedule_json(doc.inputs, s, {o.path_digests})
                            .dump(1, ' ', false, nlohmann::json::error_handler_t::replace) +
                        "\n");
    if (!o.report.empty()) {
      report::ReportOptions report_options;
      report_options.anchor_what_ifs = changes;
      outputs.write(o.report, report::schedule_report_html(doc, report_options));
    }
    outputs.commit();  // all of them, or none when one could not be written
  }
  exit_code = s.feasible ? kExitOk : kExitNo;

  report::ScheduleTextOptions text;
  text.file = o.file;
  text.what_if = !o.what_if.empty();
  text.changes = &changes;
  report::write_schedule_text(std::cout, project, s, text);
  // Said whether or not the run is quiet: the crew has these walls to build.
  for (const auto& w : project.building.left_out)
    std::cerr << "left out: "
              << floors::left_out_text(project.building.floors[w.floor].name, w,
                                       project.building.units)
              << "\n";
  if (!o.no_compare) report::write_objectives_line(std::cout, project, s, options);
  for (const auto& w : s.warnings) std::cout << "warning: " << w << "\n";
  std::cout << printf_string(
      "computed in %.1f s: %.1f s planning %d layer plans, %.1f s planning climbs, %.1f s the "
      "rest\n",
      s.layer_planning_s + s.climb_planning_s + s.bookkeeping_s, s.layer_planning_s,
      s.plans_computed, s.climb_planning_s, s.bookkeeping_s);
  if (!o.output.empty()) std::cout << "schedule written to " << o.output << "\n";
  if (!o.report.empty()) std::cout << "report written to " << o.report << "\n";
  for (const std::string& line : exported) std::cout << line << "\n";
}

}  // namespace

void add_schedule_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ScheduleCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "schedule",
      "Schedule the whole building: every layer of every floor planned (each distinct layer "
      "geometry once, with the time objective) and timed, bottom to top. Each layer gets the "
      "fewest nozzles (up to the machine's `nozzles`) that keep every wall piece's interval to "
      "the layer below within the material's [min, max]; a layer waits when an interval would "
      "be too short or the layers below could not yet carry it (strength curve, safety factor), "
      "and a nozzle idle past its limit is purged. On a climbing machine: pipes cast between "
      "layers, climbs between floors once their anchors are strong enough. Between floors: the "
      "slab stage (`slab_stage_h`, 8 h by default).\n"
      "On a site programme (--site FILE or the building's `site:`): times in dates from its "
      "start in its time zone; attended printing, joint treatments, climbs and crew pipes in "
      "working hours (reason off-shift); printing stops at a layer's end and resumes on a "
      "planned joint; with weather, concrete ages in equivalent age at 20 degrees C, printing "
      "waits out the cold and climbs the wind. A summary per day follows the floors.\n"
      "Prints a summary per floor; -o writes the schedule JSON (docs/schedule.md), the same "
      "bytes for the same inputs and seed whatever --jobs. Progress goes to stderr. A layer "
      "plan is named g<geometry>n<nozzles> (g5n2: the fifth distinct layer outline, on two "
      "nozzles; `ccbuild layers` lists the outlines); margin warnings name what comes close to "
      "a limit and where, with the threshold they are warned under.\n"
      "Exit code 1 when the building cannot be built within its constraints: the summary (and "
      "the JSON, marked \"feasible\": false) says where, by how much, and the fix.\n"
      "Examples:\n"
      "  ccbuild schedule config/buildings/house.yaml -o house-schedule.json\n"
      "  ccbuild schedule config/buildings/tower.yaml -o tower.json --jobs 2\n"
      "  ccbuild schedule config/buildings/apartment.yaml --machine "
      "config/machines/cc-climber.yaml\n"
      "  ccbuild schedule config/buildings/tower.yaml --site "
      "config/sites/weekdays-berlin-2027-weather.yaml\n"
      "  ccbuild schedule config/buildings/tower.yaml --site "
      "config/sites/weekdays-berlin-2027.yaml -o tower.json --export tower.ics --export "
      "tower.xml");
  command->add_option("BUILDING", o->file, "Building file (or a lone plan)")->required();
  command->add_option("-o,--output", o->output, "Write the schedule JSON here")
      ->check(output_path());
  command
      ->add_option("--report", o->report,
                   "Also write the HTML report (as `ccbuild report` draws it)")
      ->check(output_path());
  command->add_flag("--force", o->force,
                    "Overwrite an existing -o or --report file (never one this run reads)");
  command->add_option("--seed", o->seed, "Random seed: the same seed gives the same schedule")
      ->check(unsigned_integer())
      ->capture_default_str();
  command
      ->add_option("--jobs", o->jobs,
                   "Threads planning layers and climbs (0: every core); the schedule does not "
                   "depend on it")
      ->check(integer_in(0, 256))
      ->capture_default_str();
  command
      ->add_option("--layer-time-limit", o->layer_time_limit_s,
                   "Planning time limit of each layer plan, s (plans normally end well before, "
                   "on their kick budget)")
      ->check(number_in(Range::above(0.0, 86400.0), "s"))
      ->capture_default_str();
  command->add_flag("--quiet", o->quiet, "No progress lines on stderr");
  command->add_flag("--no-compare", o->no_compare,
                    "Skip the \"objectives:\" line: the other objective is not scheduled for "
                    "comparison (it reuses this schedule's plans, but its own nozzle counts are "
                    "planned; a study, whose objective is an axis, runs with this)");
  command
      ->add_option("--export", o->exports,
                   "Also write the schedule for a site's tools, as `ccbuild export` does; the "
                   "extension says what: .csv (a task list), .ics (iCalendar), .xml (MS "
                   "Project XML), .txt (work packages by day). All but .csv need a site "
                   "calendar (--site or the building's site:). May be given several times")
      ->check(output_path());
  command->add_flag("--path-digests", o->path_digests,
                    "In -o, each nozzle's timed path as its digest (waypoint count and SHA-256) "
                    "instead of its waypoints: a schedule a fraction of the size that `diff` "
                    "compares exactly (the regression goldens); report and dry-run need the "
                    "paths and refuse it");
  command
      ->add_option("--what-if", o->what_if,
                   "anchors: print each climb's wait for its pipes to reach the anchor strength "
                   "(the climb critical path) and the changes that would shorten the waits, each "
                   "scheduled in full: pipes cast a storey earlier (the legs as much longer as "
                   "that needs), a lower anchor strength, two more units sharing the load")
      ->check(CLI::IsMember({"anchors"}));
  command
      ->add_option("--objective", o->objective,
                   "fewest-nozzles: each layer with the fewest nozzles that keep its intervals "
                   "(the default); shortest: each layer with the count that ends it earliest "
                   "(on a calendar, more nozzles may finish a floor within a shift instead of "
                   "stopping on a planned joint). The summary compares both, each scheduled "
                   "in full")
      ->check(CLI::IsMember({"fewest-nozzles", "shortest"}))
      ->capture_default_str();
  add_input_options(*command, o->input);
  command->callback([o, &exit_code] { run_schedule(*o, exit_code); });
}

}  // namespace ccbuild::cli
