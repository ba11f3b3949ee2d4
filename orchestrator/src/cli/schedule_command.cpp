// ccbuild schedule BUILDING: the whole building, every layer planned and timed, with its
// waits, nozzle counts, pipes, climbs and slabs; a text summary and the schedule JSON.

#include <iostream>
#include <map>
#include <memory>
#include <thread>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/quantities.hpp"
#include "ccbuild/report/report.hpp"
#include "ccbuild/rules/crew.hpp"
#include "ccbuild/schedule/schedule.hpp"
#include "ccbuild/schedule/schedule_json.hpp"
#include "ccbuild/schedule/site.hpp"
#include "ccbuild/schedule/what_if.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "export_files.hpp"

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

// 1970-01-01, day 0, was a Thursday.

/// The unit of a column: the one its largest value is read in.
template <typename T, typename Seconds>
TimeUnit column_unit(const T& rows, Seconds seconds_of) {
  double largest_s = 0.0;
  for (const auto& r : rows) largest_s = std::max(largest_s, std::abs(seconds_of(r)));
  return time_unit_for(largest_s);
}

void run_schedule(const ScheduleCommandOptions& o, int& exit_code) {
  const orchestrator::Project project = open_input(o.file, o.input);
  const auto inputs = project.files_read();
  OutputClaims outputs(inputs);  // every output checked before any planning
  if (!o.output.empty()) outputs.claim_file("--output", o.output, o.force);
  if (!o.report.empty()) outputs.claim_file("--report", o.report, o.force);
  std::vector<std::string> export_formats_given;
  for (const std::string& file : o.exports) {
    const std::string format = export_format_of(file, "--export");
    if (export_needs_dates(format) && !project.calendar)
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
      exported.push_back(write_export(doc, {}, export_formats_given[k], o.exports[k], outputs));
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

  std::cout << printf_string("%s on %s: %zu layers, %zu distinct plans, %s\n", o.file.c_str(),
                             project.machine_origin.c_str(), s.layers.size(), s.plans.size(),
                             s.feasible ? "feasible" : "NOT feasible");
  if (!s.feasible) std::cout << "not feasible: " << s.infeasibility->message << "\n";
  // Times of day on a site calendar, else time from the start.
  const schedule::SiteCalendar* calendar = project.calendar.get();
  const auto when = [calendar](double t_s) { return schedule::time_text(calendar, t_s); };
  if (calendar) {
    const schedule::SiteProgramme& p = calendar->programme();
    std::cout << printf_string(
        "site: from %s (%s, %s); working hours %s; %zu holiday%s; printing %s, pipes %s\n",
        calendar->local_text(0.0).c_str(), p.time_zone.c_str(),
        calendar->timestamp(0.0).substr(19).c_str(), calendar->week_text().c_str(),
        p.holidays.size(), p.holidays.size() == 1 ? "" : "s",
        p.printing_attended ? "attended" : "unattended",
        p.pipes_need_crew ? "by the crew" : "unattended");
    if (project.conditions)
      std::cout << "weather: " << project.conditions->source << "; concrete ages are equivalent "
                << "ages at 20 °C (" << project.material.maturity.name() << ")\n";
  }
  struct FloorLine {
    int layers = 0, max_nozzles = 0, waits = 0;
    double start_s = 1e300, end_s = 0, wait_s = 0;
    std::map<std::string, double> reasons;
  };
  std::map<int, FloorLine> floors;
  for (const auto& l : s.layers) {
    FloorLine& f = floors[l.floor];
    f.layers += 1;
    f.max_nozzles = std::max(f.max_nozzles, l.nozzles);
    f.start_s = std::min(f.start_s, l.start_s);
    f.end_s = std::max(f.end_s, l.end_s);
    if (l.wait_before_s > 0) {
      f.waits += 1;
      f.wait_s += l.wait_before_s;
      for (const auto& r : l.wait_reasons) f.reasons[schedule::to_string(r.kind)] += 1;
    }
  }
  int width = 5;  // the widest time in the start and end columns ("day 10 02:03" is 12)
  for (const auto& [floor, f] : floors)
    width = std::max(
        {width, static_cast<int>(when(f.start_s).size()), static_cast<int>(when(f.end_s).size())});
  const TimeUnit waited_unit =
      column_unit(floors, [](const auto& entry) { return entry.second.wait_s; });
  std::cout << printf_string("floor  layers  nozzles  %-*s  %-*s  waits  %10s  why\n", width,
                             "start", width, "end", "waited");
  for (const auto& [floor, f] : floors) {
    std::string why;
    for (const auto& [kind, n] : f.reasons)
      why += (why.empty() ? "" : ", ") + printf_string("%s x%.0f", kind.c_str(), n);
    std::cout << printf_string("%5d  %6d  %7d  %-*s  %-*s  %5d  %10s  %s\n", floor, f.layers,
                               f.max_nozzles, width, when(f.start_s).c_str(), width,
                               when(f.end_s).c_str(), f.waits,
                               duration_in(f.wait_s, waited_unit).c_str(), why.c_str());
  }
  std::cout << "  (nozzles: the most a layer of the floor uses; waits: how many of its layers "
               "waited before they started, waited: those waits summed, why: the reasons and "
               "how many layers waited for each, a layer may wait for several)\n";
  if (!s.days.empty()) {
    std::cout << printf_string("%zu working days with printing:\n", s.days.size());
    const TimeUnit printing_unit =
        column_unit(s.days, [](const schedule::WorkDay& d) { return d.printing_s; });
    for (const auto& d : s.days)
      std::cout << printf_string(
          "  %s %s  %3d layer%s, %s printing, %s, %d deliver%s, "
          "%.1f crew person-hours: %s\n",
          schedule::weekday_names()[schedule::weekday_of(*schedule::parse_local_date(d.date))],
          d.date.c_str(), d.layers, d.layers == 1 ? " " : "s",
          duration_in(d.printing_s, printing_unit).c_str(),
          floors::volume_text(d.concrete_m3, project.building.units).c_str(), d.deliveries,
          d.deliveries == 1 ? "y" : "ies", d.crew_h, d.detail.c_str());
  }
  std::vector<const schedule::Event*> climbs;
  for (const auto& e : s.events)
    if (e.kind == schedule::Event::Kind::kClimb) climbs.push_back(&e);
  const TimeUnit climb_wait_unit =
      column_unit(climbs, [](const schedule::Event* e) { return e->climb->wait_before_s; });
  const TimeUnit climb_motion_unit =
      column_unit(climbs, [](const schedule::Event* e) { return e->climb->plan.duration_s; });
  for (const schedule::Event* e : climbs) {
    const auto& c = *e->climb;
    // Each cause with the time it was the binding one (a night, then the wind, ...).
    std::string why;
    std::vector<schedule::WaitKind> told;
    for (const auto& r : c.wait_reasons) {
      if (std::find(told.begin(), told.end(), r.kind) != told.end()) continue;
      told.push_back(r.kind);
      const double bound_s = schedule::binding_s(c.wait_reasons, r.kind);
      if (bound_s <= 0.0) continue;
      why += (why.empty() ? "" : ", ") + schedule::to_string(r.kind) + " " +
             duration_in(bound_s, climb_wait_unit);  // the wait's column, one unit
    }
    std::cout << printf_string(
        "climb %d -> %d after floor %d layer %d: starts at %s after a wait of %s%s, %s of "
        "motion\n",
        c.from_stage, c.to_stage, e->floor, e->layer, when(e->start_s).c_str(),
        duration_in(c.wait_before_s, climb_wait_unit).c_str(),
        why.empty() ? "" : (" (" + why + ")").c_str(),
        duration_in(c.plan.duration_s, climb_motion_unit).c_str());
  }
  // The climb critical path: what each climb waited for, and the changes that shorten it.
  const auto waits = schedule::anchor_waits(project, s);
  double anchor_wait_s = 0.0;
  for (const auto& w : waits) anchor_wait_s += w.wait_s;
  if (!o.what_if.empty() && !waits.empty()) {
    std::cout << printf_string(
        "anchors: each climb waits for its latest pipe to reach %.1f MPa (%s after casting)\n",
        waits.front().required_mpa,
        duration_text(waits.front().strong_s - waits.front().cast_s).c_str());
    const TimeUnit waited_unit =
        column_unit(waits, [](const schedule::AnchorWait& w) { return w.wait_s; });
    for (const auto& w : waits)
      std::cout << printf_string(
          "  climb %d -> %d: pipe %s cast at %s (floor %d layer %d), strong at %s; the build "
          "was ready at %s and waited %s\n",
          w.from_stage, w.to_stage, w.anchor.c_str(), when(w.cast_s).c_str(), w.cast_floor,
          w.cast_layer, when(w.strong_s).c_str(), when(w.ready_s).c_str(),
          duration_in(w.wait_s, waited_unit).c_str());
  }
  if (anchor_wait_s > 0.0 && s.totals.makespan_s > 0.0) {
    std::cout << printf_string(
        "anchor waits: %s of the %s (%.0f%%)", duration_text(anchor_wait_s).c_str(),
        duration_text(s.totals.makespan_s).c_str(), 100.0 * anchor_wait_s / s.totals.makespan_s);
    if (o.what_if.empty())
      std::cout << "; `--what-if anchors` computes the changes that would shorten them";
    std::cout << "\n";
  }
  if (!o.what_if.empty()) {
    if (changes.empty())
      std::cout << (anchor_wait_s > 0.0
                        ? "what-if anchors: no change the profiles allow gives a feasible "
                          "schedule\n"
                        : "what-if anchors: no climb waits for its anchors; nothing to shorten\n");
    else
      std::cout << "what-if anchors (each change scheduled in full):\n";
    const TimeUnit makespan_unit =
        column_unit(changes, [](const schedule::AnchorWhatIf& w) { return w.makespan_s; });
    const TimeUnit change_unit = column_unit(changes, [&](const schedule::AnchorWhatIf& w) {
      return s.totals.makespan_s - w.makespan_s;
    });
    const TimeUnit waits_unit =
        column_unit(changes, [](const schedule::AnchorWhatIf& w) { return w.anchor_waits_s; });
    for (const auto& w : changes)
      std::cout << printf_string(
          "  %s: %s (%.0f s), %s%s, anchor waits %s\n", w.change.c_str(),
          duration_in(w.makespan_s, makespan_unit).c_str(), w.makespan_s,
          w.makespan_s <= s.totals.makespan_s ? "-" : "+",
          duration_in(std::abs(s.totals.makespan_s - w.makespan_s), change_unit).c_str(),
          duration_in(w.anchor_waits_s, waits_unit).c_str());
  }
  const auto& t = s.totals;
  std::cout << printf_string(
      "total: %s from the first layer to the last%s (machine busy %s: layers, moves, pipes, "
      "purges, climbs); summed over the nozzles: deposition %s, airtime %s; waits %s, climbs "
      "%s, slabs %s, pipes %s, purges %s, lintels %s, joints %s\n",
      duration_text(t.makespan_s).c_str(),
      calendar ? (", finished " + calendar->local_text(t.makespan_s)).c_str() : "",
      duration_text(t.machine_s).c_str(), duration_text(t.deposition_s).c_str(),
      duration_text(t.airtime_s).c_str(), duration_text(t.waits_s).c_str(),
      duration_text(t.climbs_s).c_str(), duration_text(t.slabs_s).c_str(),
      duration_text(t.pipes_s).c_str(), duration_text(t.purges_s).c_str(),
      duration_text(t.lintels_s).c_str(), duration_text(t.joints_s).c_str());
  {
    // Crew tasks: how many of each kind, and the person-hours they take.
    std::map<std::string, std::pair<int, double>> by_kind;  // count, person-hours
    double slab_m3 = 0.0;
    for (const auto& e : s.events) {
      if (e.kind == schedule::Event::Kind::kPour) slab_m3 += e.concrete_m3;
      if (e.crew == 0) continue;
      auto& [count, hours] = by_kind[schedule::to_string(e.kind)];
      ++count;
      hours += rules::person_hours(e.crew, e.end_s - e.start_s);
    }
    std::string kinds;
    for (const auto& [kind, v] : by_kind)
      kinds += printf_string("%s%d %s%s %.1f h", kinds.empty() ? "" : ", ", v.first, kind.c_str(),
                             v.first == 1 ? "" : "s", v.second);
    if (!by_kind.empty())
      std::cout << printf_string(
          "crew: %.1f person-hours (%s)%s\n", t.crew_h, kinds.c_str(),
          slab_m3 > 0.0
              ? ("; slabs poured: " + floors::volume_text(slab_m3, project.building.units)).c_str()
              : "");
  }
  {
    // Quantities: concrete per floor and in all, the pump's peak, the deliveries.
    std::map<int, double> per_floor;
    double peak_m3_s = 0.0;
    for (const auto& l : s.layers) {
      per_floor[l.floor] += l.concrete_m3;
      peak_m3_s = std::max(peak_m3_s, l.peak_flow_m3_s);
    }
    const floors::LengthUnit unit = project.building.units;
    std::string floors_text;
    for (const auto& [floor, m3] : per_floor)
      floors_text += printf_string("%sfloor %d %.2f", floors_text.empty() ? "" : ", ", floor,
                                   floors::volume_in(m3, unit));
    auto per_hour = [unit](double m3_s) { return floors::flow_text(m3_s, unit, 2); };
    std::cout << printf_string(
        "concrete: %s (%s); the nozzles draw at most %s%s; %zu deliveries of %s\n",
        floors::volume_text(t.concrete_m3, unit).c_str(), floors_text.c_str(),
        per_hour(peak_m3_s).c_str(),
        project.machine->pump_capacity_m3_s
            ? (" (the pump: " + per_hour(*project.machine->pump_capacity_m3_s) + ")").c_str()
            : "",
        s.deliveries.size(), floors::volume_text(project.material.delivery_batch_m3, unit).c_str());
    // Against the model's own wall volumes, where the building was imported with them.
    for (std::size_t f = 0; f < s.quantities.size(); ++f)
      if (s.quantities[f].model_m3)
        std::cout << "quantities: "
                  << floors::quantities_text(project.building.floors[f].name, s.quantities[f])
                  << "\n";
  }
  // Said whether or not the run is quiet: the crew has these walls to build.
  for (const auto& w : project.building.left_out)
    std::cerr << "left out: "
              << floors::left_out_text(project.building.floors[w.floor].name, w,
                                       project.building.units)
              << "\n";
  if (!o.no_compare) {
    // The other objective, scheduled in full, for comparison.
    schedule::ScheduleOptions other = options;
    other.objective = options.objective == schedule::Objective::kShortest
                          ? schedule::Objective::kFewestNozzles
                          : schedule::Objective::kShortest;
    // One nozzle: both objectives choose the same count for every layer.
    const bool same = project.machine->nozzles == 1;
    if (other.progress && !same)
      other.progress("scheduling again with --objective " + to_string(other.objective) +
                     ", to compare");
    other.progress = nullptr;
    const schedule::Schedule alt = same ? s : schedule::build_schedule(project, other);
    const auto most_nozzles = [](const schedule::Schedule& x) {
      int n = 0;
      for (const auto& l : x.layers) n = std::max(n, l.nozzles);
      return n;
    };
    const auto line = [&](const schedule::Schedule& x, schedule::Objective which) {
      return printf_string("%s %s%s (up to %d nozzle%s)", to_string(which).c_str(),
                           duration_text(x.totals.makespan_s).c_str(),
                           x.feasible ? "" : ", NOT feasible", most_nozzles(x),
                           most_nozzles(x) == 1 ? "" : "s");
    };
    std::cout << "objectives: " << line(s, options.objective) << " (this schedule); "
              << line(alt, other.objective) << "\n";
  }
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
