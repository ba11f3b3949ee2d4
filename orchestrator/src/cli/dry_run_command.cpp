// ccbuild dry-run BUILDING|SCHEDULE.json: runs a schedule against simulated machines over
// LCM, exactly as the jobs would go to hardware: one `ccbuild-sim` process per gantry
// (or machines already on the bus with --external), the dispatcher and its journal here.

#include <unistd.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <tuple>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/common/document.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/common/sha256.hpp"
#include "ccbuild/dispatch/dispatcher.hpp"
#include "ccbuild/dispatch/run_inputs.hpp"
#include "ccbuild/dispatch/run_report.hpp"
#include "ccbuild/dispatch/site_run.hpp"
#include "ccbuild/dispatch/site_watchdog.hpp"
#include "ccbuild/dispatch/supervisor.hpp"
#include "ccbuild/floors/material.hpp"
#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/machine/sim_limits.hpp"
#include "ccbuild/machine/sim_machine.hpp"
#include "ccbuild/schedule/conditions.hpp"
#include "ccbuild/schedule/schedule.hpp"
#include "ccbuild/schedule/schedule_json.hpp"
#include "ccbuild_lcm/ccbuild_job_t.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace ccbuild::cli {
namespace {
namespace fs = std::filesystem;

struct DryRunOptions {
  std::string file;
  InputOptions input;
  std::string lcm_url = "udpm://239.255.76.67:7667?ttl=0";
  double speed = 10'000.0;
  std::string journal;
  std::string state_dir;
  std::string log;
  std::string inject;  ///< "drop=0.1,duplicate=0.1,reorder=0.1"
  std::uint64_t seed = 1;
  double retry_after_s = 0.02;
  bool external = false;
  double timeout_s = 600.0;
  double status_period_s = 0.0;  ///< 0: chosen from the speed
  bool own_clock = false;        ///< machines on their own clocks (as hardware), no site clock
  bool by_layer = false;         ///< the summary layer by layer, not floor by floor
  bool no_watchdog = false;
  bool force = false;
  bool allow_infeasible = false;
  bool no_replan = false;  ///< send every job at its planned start plus the delay, as planned
};

/// The machine profile a schedule was made with: the building's (when FILE is one), else
/// --machine (which must be one of the files the schedule recorded), else the profile file
/// the schedule recorded (inputs.machine.profile), else (an older schedule) the recorded
/// file that loads as the machine it names. The recorded files were checked against their
/// SHA-256 already.
std::string machine_profile(const schedule::ScheduleDocument& schedule, const DryRunOptions& o,
                            const std::optional<orchestrator::Project>& project) {
  if (project) return project->machine->source_file;
  if (!o.input.machine.empty()) {
    const std::string sum = sha256_file_hex(o.input.machine);
    for (const auto& f : schedule.inputs.files)
      if (f.sha256 == sum) return o.input.machine;
    throw InputError(o.input.machine, 0, "--machine",
                     "is not among the files the schedule " + o.file +
                         " was made from; a schedule runs on its own machine");
  }
  // The profile the schedule recorded; a schedule from before it did: by its name.
  if (!schedule.inputs.machine.profile.empty()) return schedule.inputs.machine.profile;
  const std::string& name = schedule.inputs.machine.name;
  for (const auto& f : schedule.inputs.files) {
    const fs::path path = f.path;
    if (path.extension() != ".yaml" && path.extension() != ".json") continue;
    try {
      if (machine::load_machine(path).name == name) return path.string();
    } catch (const InputError&) {
    }
  }
  throw InputError(o.file, 0, "/inputs/machine/name",
                   "the machine profile '" + name +
                       "' is not among the schedule's files here; name it with --machine");
}

/// Where `profile` is a family, or the building was opened with one: the member fitted
/// to the schedule's building, as the schedule recorded it (the building where it stood),
/// written to a temporary folder. Empty otherwise.
dispatch::FittedMachineFolder fitted_machine(const schedule::ScheduleDocument& schedule,
                                             const DryRunOptions& o,
                                             const std::optional<orchestrator::Project>& project,
                                             const std::string& profile) {
  std::shared_ptr<const climb::FitResult> fit = project ? project->fit : nullptr;
  std::error_code ec;
  if (!fit && fs::is_regular_file(profile, ec) && machine::load_machine_profile(profile).family) {
    orchestrator::ProjectOptions again = project_options(o.input);
    again.machine_profile = profile;
    again.rotation_deg = schedule.inputs.placement.rotation_rad * 180.0 / M_PI;
    fit = orchestrator::open_project(schedule.inputs.building, again).fit;
  }
  if (!fit) return {};
  return dispatch::FittedMachineFolder::write(*fit, schedule.inputs.machine, profile, o.file);
}

/// The site clock's resolution: the rail guard's finest step, schedule s.
constexpr double kSiteStatusPeriod_s = 0.02;

void run_dry_run(const DryRunOptions& o, int& exit_code) {
  namespace lim = machine::sim_limits;
  const dispatch::InjectedFaults inject =
      dispatch::parse_injected(o.inject);  // its grammar, before any work
  // A schedule file read back and checked (its input files unchanged: the machines run
  // from them); a building scheduled first.
  schedule::ScheduleDocument schedule;
  std::optional<orchestrator::Project> project;
  OutputClaims outputs;
  if (fs::path(o.file).extension() == ".json") {
    schedule::ReadScheduleOptions read;
    read.inputs = schedule::RecordedInputCheck::kRefuseChangedOrMissing;
    schedule = schedule::read_schedule(o.file, read).document;
    outputs.add_input(o.file);
  } else {
    project = open_input(o.file, o.input);
    schedule::ScheduleOptions options;
    schedule::Schedule made = schedule::build_schedule(*project, options);
    schedule = {schedule::recorded_inputs(*project, options, &made), std::move(made)};
  }
  for (const auto& f : schedule.inputs.files) outputs.add_input(f.path);
  if (!o.input.machine.empty()) outputs.add_input(o.input.machine);
  if (!o.input.material.empty()) outputs.add_input(o.input.material);
  const schedule::RecordedMachine& machine_rec = schedule.inputs.machine;
  const floors::MaterialProfile& material = schedule.inputs.material;
  const floors::LengthUnit unit = shown_unit(o.input, schedule.inputs.units);
  auto L = [unit](double m) { return floors::length_text(m, unit); };
  if (!schedule.schedule.feasible && !o.allow_infeasible)
    throw InputError(o.file, 0, project ? "" : "/feasible",
                     "the schedule is not feasible (" + schedule.schedule.infeasibility->message +
                         "); its machines would be sent work that breaks the material's "
                         "constraints. Fix it first, or pass --allow-infeasible to see where "
                         "the machines stop it");
  // The schedule's identity, for the journal and the machines' records: the SHA-256 of
  // its JSON as `ccbuild schedule -o` writes it (the same for the building and its file).
  const std::string schedule_sha256 =
      sha256_hex(schedule::schedule_json(schedule.inputs, schedule.schedule)
                     .dump(1, ' ', false, nlohmann::json::error_handler_t::replace) +
                 "\n");

  auto jobs = dispatch::jobs_of_schedule(schedule);
  std::vector<std::string> ids;  // in rail order
  for (int k = 0;; ++k) {
    const std::string id = dispatch::gantry_id(k);
    if (std::none_of(jobs.begin(), jobs.end(),
                     [&](const dispatch::DispatchJob& j) { return j.machine_id == id; }))
      break;
    ids.push_back(id);
  }
  dispatch::check_injected(inject, schedule, jobs, ids);
  std::string profile = machine_profile(schedule, o, project);
  // A machine fitted on the fly (a family given as the machine): the machines are the
  // member the schedule was made for, fitted again as it was (the building where it stood)
  // and written to a folder of the run's own, not the family.
  const dispatch::FittedMachineFolder fitted = fitted_machine(schedule, o, project, profile);
  if (!fitted.profile().empty()) profile = fitted.profile().string();
  const machine::RailAxis rail_axis = machine_rec.rail_axis;
  const double gantry_width_m = machine_rec.gantry_width_m;
  const double rail_speed_m_s = machine_rec.rail_speed_m_s();
  const bool climbing = machine_rec.climbing;
  // Statuses at a fixed rate of machine time, no more than 200 a real second, within what
  // the machines accept.
  // On the site clock: the watchdog's resolution, schedule s. On their own clocks: a
  // status every this much machine time, no more than 200 a real second.
  const double status_period_s =
      o.status_period_s > 0.0 ? o.status_period_s
      : o.own_clock           ? std::clamp(std::max(1.0, o.speed * 0.005), lim::kStatusPeriod_s.min,
                                           lim::kStatusPeriod_s.max)
                              : kSiteStatusPeriod_s;
  // Every value the machines will be given, checked as they will check it.
  const double anchor_age_s =
      climbing ? material.age_for_strength_s(machine_rec.anchor_strength_mpa) : 0.0;
  const struct {
    const char* what;
    double value;
    const Range& range;
  } passed[] = {
      {"--speed", o.speed, lim::kSpeed},
      {"--status-period", status_period_s, lim::kStatusPeriod_s},
      {"the material's min_layer_interval_s", material.min_layer_interval_s, lim::kMinInterval_s},
      {"the material's max_layer_interval_s", material.max_layer_interval_s, lim::kMaxInterval_s},
      {"the age at which anchors reach the anchor strength",
       std::isfinite(anchor_age_s) ? anchor_age_s : 0.0, lim::kAnchorMinAge_s}};
  for (const auto& p : passed)
    if (!p.range.contains(p.value))
      throw InputError(o.file, 0, p.what,
                       "the simulated machines accept " + p.range.describe("") + ", got " +
                           plain_number(p.value));
  // What a machine reads: its profile (it loads the same files again).
  if (!o.external) machine::load_machine(profile);

  // Outputs: never an input, never two on one file, never a device or FIFO replaced; the
  // journal and the machines' records belong to this schedule only.
  if (!o.log.empty()) outputs.claim_file("--log", o.log, o.force);
  if (!o.journal.empty())
    outputs.claim_read_write("--journal", o.journal, {"-wal", "-shm", "-journal"});
  if (!o.state_dir.empty()) {
    outputs.claim_folder("--state-dir", o.state_dir);
    for (const auto& id : ids)
      outputs.claim_read_write("--state-dir", fs::path(o.state_dir) / (id + ".state"));
    outputs.claim_file("--state-dir", fs::path(o.state_dir) / "schedule.sha256", true);
    dispatch::check_state_dir(o.state_dir, ids, schedule_sha256);
  }

  // The planned gap between gantries, and how far they can close between two statuses.
  const double margin_m = 2.0 * rail_speed_m_s * (status_period_s + o.speed * 0.02);
  double planned_gap_m = std::numeric_limits<double>::infinity();
  for (const auto& [key, plan] : schedule.schedule.plans)
    if (plan.nozzles > 1) planned_gap_m = std::min(planned_gap_m, plan.min_gap_m);
  const bool several = ids.size() > 1;
  // On the site clock the watchdog guards at any speed; on the machines' own clocks only
  // where statuses come often enough.
  const bool can_guard = several && (!o.own_clock || gantry_width_m + margin_m < planned_gap_m);
  const bool guard = can_guard && !o.no_watchdog;

  // The default journal and machine records live in a folder of this run's own, removed
  // however the run ends (it used to stay behind whenever --journal was given). One left
  // by a killed run with the same process id is cleared first: its machine records would
  // be read back as this run's.
  struct TemporaryFolder {
    fs::path path;
    ~TemporaryFolder() {
      std::error_code ec;
      if (!path.empty()) fs::remove_all(path, ec);
    }
  } temporary;
  if (o.journal.empty() || o.state_dir.empty()) {
    std::error_code ec;
    const fs::path tmp = fs::temp_directory_path(ec);
    if (ec) throw InputError("", 0, "TMPDIR", "no temporary folder: " + ec.message());
    temporary.path = tmp / ("ccbuild-dry-run-" + std::to_string(::getpid()));
    fs::remove_all(temporary.path, ec);
    dispatch::check_writable_folder(temporary.path, {}, "TMPDIR");
  }
  if (!o.state_dir.empty()) {
    std::vector<fs::path> records;
    for (const auto& id : ids) records.push_back(fs::path(o.state_dir) / (id + ".state"));
    dispatch::check_writable_folder(o.state_dir, records, "--state-dir");
  }
  if (!o.journal.empty())
    dispatch::check_writable_folder(fs::absolute(o.journal).parent_path(), {o.journal},
                                    "--journal");
  const fs::path& work = temporary.path;
  const fs::path journal_path = o.journal.empty() ? work / "journal.sqlite" : fs::path(o.journal);
  dispatch::Journal journal(journal_path, schedule_sha256);
  machine::Bus bus(o.lcm_url);
  // The log goes to a temporary file beside it, in place once the run ends.
  const bool log = !o.log.empty();
  if (log) bus.log_to(outputs.writing_path(o.log).string());
  long malformed = 0;
  bus.on_malformed([&](const std::string& channel, int size) {
    ++malformed;
    std::cerr << "dry-run: a message on " << channel << " (" << size
              << " bytes) did not decode: rejected\n";
  });
  std::unique_ptr<dispatch::MachineSupervisor> machines;
  const fs::path state_dir = o.state_dir.empty() ? work : fs::path(o.state_dir);
  // With site weather the material's window and the anchors' age are equivalent ages, as
  // the scheduler kept them: the dispatcher and the machines count them on its clock.
  rules::AgeClock age_clock;
  if (schedule.inputs.conditions)
    age_clock = schedule::EquivalentAge(*schedule.inputs.conditions, material.maturity).clock();
  const fs::path age_clock_file = work / "age-clock.txt";
  if (!age_clock.real_time()) write_file_atomically(age_clock_file, age_clock.text(), true);
  if (!o.state_dir.empty()) {
    fs::create_directories(state_dir);
    write_file_atomically(state_dir / "schedule.sha256", schedule_sha256 + "\n", true);
  }
  if (!o.external) {
    std::vector<std::string> common = {
        "--lcm-url",       o.lcm_url,
        "--speed",         printf_string("%.17g", o.speed),
        "--seed",          std::to_string(o.seed),
        "--status-period", printf_string("%.17g", status_period_s),
        "--machine",       profile,
        "--min-interval",  printf_string("%.17g", material.min_layer_interval_s),
        "--max-interval",  printf_string("%.17g", material.max_layer_interval_s)};
    if (o.own_clock) common.push_back("--own-clock");
    if (!age_clock.real_time())
      common.insert(common.end(), {"--age-clock", age_clock_file.string()});
    if (climbing) {
      common.push_back("--climbing");
      // The age at which the material reaches the anchor strength the climber needs.
      if (std::isfinite(anchor_age_s) && anchor_age_s > 0.0)
        common.insert(common.end(), {"--anchor-min-age", printf_string("%.17g", anchor_age_s)});
    }
    for (const auto& [name, p] : inject.network) {
      common.push_back("--" + name);
      common.push_back(printf_string("%.17g", p));
    }
    machines = std::make_unique<dispatch::MachineSupervisor>(
        fs::read_symlink("/proc/self/exe").parent_path() / "ccbuild-sim", ids,
        dispatch::parking_homes(jobs, ids, machine_rec), common, inject.flags(), state_dir);
  }
  dispatch::DispatchOptions d;
  d.speed = o.speed;
  d.ack_timeout_s = o.retry_after_s;
  // On the site clock every status says which job the machine last ended, so a job is
  // sent again for a lost DONE only when statuses are lost too (or the machine restarted).
  d.done_slack_s = o.own_clock ? std::max(0.25, 10.0 * o.retry_after_s) : 2.0;
  d.purge_s = machine_rec.purge_s;
  // The material's window, against which the rest of a late run is re-planned.
  if (!o.no_replan) {
    d.min_interval_s = material.min_layer_interval_s;
    d.max_interval_s = material.max_layer_interval_s;
    d.material = &material;  // waits may absorb delay as far as the layers below allow
    d.age_clock = age_clock;
  }
  d.joint_treatment_s = material.planned_joint.treatment_s;
  d.joint_min_age_s = material.planned_joint.min_age_s;
  if (several) {  // the rest of a clogged layer may need its neighbours out of the way
    d.gantry_width_m = gantry_width_m;
    d.rail_axis = rail_axis;
    d.travel_speed_m_s = machine_rec.travel_speed_m_s;
    d.rail_min_m = machine::rail_coordinate(machine_rec.x_min_m, machine_rec.y_min_m, rail_axis);
    d.rail_max_m = machine::rail_coordinate(machine_rec.x_max_m, machine_rec.y_max_m, rail_axis);
  }
  dispatch::Dispatcher dispatcher(bus, jobs, journal, d);
  std::optional<dispatch::SiteWatchdog> watchdog;
  if (several && o.own_clock) {
    dispatch::WatchdogOptions w;
    w.machines = ids;
    w.rail_axis = rail_axis;
    w.gantry_width_m = gantry_width_m;
    w.margin_m = guard ? margin_m : 0.0;
    w.max_span_s = can_guard ? 1e9 : 1.0;  // else only where both reported that closely
    watchdog.emplace(bus, w);
  }
  std::cerr << printf_string("dry-run: %zu jobs to %zu machine(s) at %.0fx over %s\n", jobs.size(),
                             ids.size(), o.speed, o.lcm_url.c_str());
  std::optional<dispatch::SiteRun> site;
  if (!o.own_clock) {
    dispatch::SiteRunOptions so;
    so.speed = o.speed;
    so.guard = guard;
    so.status_period_s = status_period_s;
    site.emplace(bus, dispatcher, ids, rail_axis, gantry_width_m, so);
  }
  if (several && guard && site)
    std::cerr << printf_string(
        "dry-run: site watchdog guarding the rails on the site clock: a step of it only where "
        "no two gantries can come closer than %s whatever each does along its path, in "
        "steps of %.3g s (two gantries close at most %s within one)\n",
        L(gantry_width_m).c_str(), status_period_s,
        L(site->guard().margin_m(rail_speed_m_s)).c_str());
  else if (several && guard)
    std::cerr << printf_string(
        "dry-run: site watchdog guarding the rails: every machine paused below %s (the "
        "gantry width %s plus %s the gantries can close between statuses every %.3g s "
        "of machine time)\n",
        L(gantry_width_m + margin_m).c_str(), L(gantry_width_m).c_str(), L(margin_m).c_str(),
        status_period_s);
  else if (several && o.no_watchdog)
    std::cerr << "dry-run: site watchdog off (--no-watchdog): gaps are measured, a collision "
                 "stops the run\n";
  else if (several)
    std::cerr << printf_string(
        "dry-run: site watchdog %s: at %.0fx the gantries can close %s between statuses, "
        "more than the plans leave (%s over the gantry width); gaps are measured where both "
        "reported within 1 s of machine time, a collision stops the run (guarding needs a "
        "lower --speed)\n",
        "cannot guard", o.speed, floors::length_text(margin_m, unit, 1).c_str(),
        L(planned_gap_m - gantry_width_m).c_str());
  std::vector<std::string> events;
  const auto started = std::chrono::steady_clock::now();
  auto last = started, last_line = started;
  while (!dispatcher.finished()) {
    bus.handle(1);
    const auto now = std::chrono::steady_clock::now();
    const double dt_s = std::chrono::duration<double>(now - last).count();
    last = now;
    dispatcher.step(dt_s);
    if (site)
      if (const auto why = site->step(dt_s)) {
        events.push_back(*why);
        std::cerr << "dry-run: " << *why << "\n";
      }
    if (watchdog)
      if (const auto why = watchdog->check(dt_s)) {
        events.push_back(*why);
        std::cerr << "dry-run: " << *why << "\n";
        dispatcher.stop(*why);  // guarding: before they touch; else: they collided
      }
    if (machines) {
      std::optional<std::string> given_up;
      for (const auto& said : machines->restart_ended(given_up)) {
        events.push_back(said);
        std::cerr << "dry-run: " << said << "\n";
      }
      if (given_up) {
        events.push_back(*given_up);
        std::cerr << "dry-run: " << *given_up << "\n";
        dispatcher.stop(*given_up);
      }
    }
    if (!bus.log_error().empty())
      throw InputError(o.log, 0, "--log",
                       "writing the LCM log failed: " + bus.log_error() + "; the run stopped");
    if (now - last_line > std::chrono::seconds(2)) {
      last_line = now;
      // Where the building is: the last layer begun, the site's date, and an estimate of
      // the real time left from the jobs done so far.
      int floor = -1, layer = -1;
      for (const auto& [id, span] : dispatcher.executed())
        if (const dispatch::DispatchJob* j = dispatcher.job(id);
            j && j->kind == dispatch::JobKind::kDeposit &&
            std::make_pair(j->floor, j->layer) > std::make_pair(floor, layer))
          floor = j->floor, layer = j->layer;
      const double site_s = site ? site->clock().now_s() : 0.0;
      const std::string when =
          schedule.inputs.calendar
              ? schedule.inputs.calendar->local_text(site_s)
              : "day " + std::to_string(static_cast<int>(site_s / 86400.0) + 1) +
                    printf_string(" %02d:%02d", static_cast<int>(std::fmod(site_s, 86400.0) / 3600),
                                  static_cast<int>(std::fmod(site_s, 3600.0) / 60));
      const double done = static_cast<double>(dispatcher.executed().size());
      const double elapsed_s = std::chrono::duration<double>(now - started).count();
      const double eta_s = done > 0 ? elapsed_s * (dispatcher.jobs().size() - done) / done : 0.0;
      std::cerr << printf_string(
          "dry-run: floor %d layer %d, %s of site time%s; %.0f of %zu jobs (%.0f%%), about %s "
          "left\n",
          floor, layer, when.c_str(),
          site
              ? printf_string(" (tick %lld, %ld sent again)",
                              static_cast<long long>(site->clock().tick()), site->clock().repeats())
                    .c_str()
              : "",
          done, dispatcher.jobs().size(),
          100.0 * done / std::max<std::size_t>(1, dispatcher.jobs().size()),
          duration_text(eta_s).c_str());
      // A machine heard but not answering the clock runs on a clock of its own (a real
      // machine, or ccbuild-sim --own-clock): say so rather than wait in silence.
      if (site && site->clock().waited_s() > 2.0)
        for (const auto& machine : site->clock().waiting_for())
          std::cerr << printf_string(
              "dry-run: %s has not answered the site clock's tick %lld for %.0f s (a machine on "
              "its own clock answers with tick 0: run such machines with `ccbuild dry-run "
              "--own-clock`)\n",
              machine.c_str(), static_cast<long long>(site->clock().tick()),
              site->clock().waited_s());
      for (const auto& [machine, silent_s] : dispatcher.silent(3.0))
        std::cerr << printf_string(
            "dry-run: %s not heard from %s\n", machine.c_str(),
            silent_s > 3.0 ? printf_string("for %.0f s", silent_s).c_str() : "yet");
      std::cerr << printf_string(
          "dry-run: %zu of %zu jobs done, %ld sent again, %ld faults, %.0f s behind schedule\n",
          dispatcher.executed().size(), dispatcher.jobs().size(), dispatcher.resent(),
          dispatcher.faults(), dispatcher.delay_s());
    }
    if (std::chrono::duration<double>(now - started).count() > o.timeout_s) break;
  }
  const double real_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  // The last words (pauses, statuses) land before the machines stop.
  for (auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(300);
       std::chrono::steady_clock::now() < end;)
    bus.handle(10);
  machines.reset();

  // Planned against executed, layer by layer.
  const dispatch::RunReport report = dispatch::report_of(dispatcher);
  const schedule::SiteCalendar* calendar = schedule.inputs.calendar.get();
  std::cout << printf_string(
      "%s: %zu of %zu jobs executed on %zu machine(s) in %.1f s (%.0fx), finished at %s of "
      "schedule time\n",
      o.file.c_str(), dispatcher.executed().size(), dispatcher.jobs().size(), ids.size(), real_s,
      o.speed, schedule::time_text(calendar, report.finished_s, true).c_str());
  // Every time to the second, as a date on a site calendar, else as "day 3 07:05:09".
  const auto at = [calendar](double t_s) {
    return std::isfinite(t_s) ? schedule::time_text(calendar, t_s, true) : std::string("-");
  };
  const int width = calendar ? 23 : 15;
  if (o.by_layer) {
    std::cout << "by layer (planned start, planned end: the schedule's; started, ended: when the "
                 "layer's jobs started and the last of them ended; deviation: started less planned "
                 "start)\n";
    std::cout << printf_string("layer               %-*s  %-*s  deviation   %-*s  ended\n", width,
                               "planned start", width, "started", width, "planned end");
    for (const auto& l : report.layers)
      std::cout << printf_string("%-18s  %-*s  %-*s  %-10s  %-*s  %s\n",
                                 printf_string("floor %d layer %d", l.floor, l.layer).c_str(),
                                 width, at(l.planned_start_s).c_str(), width,
                                 l.ran() ? at(l.started_s).c_str() : "not run",
                                 l.ran() ? printf_string("%+.1f s", l.deviation_s()).c_str() : "-",
                                 width, at(l.planned_end_s).c_str(), at(l.ended_s).c_str());
  } else {
    std::cout << "by floor (--by-layer for every layer; planned start, planned end: the "
                 "schedule's; started, ended: when the floor's first layer started and its last "
                 "ended; off: its layers started over 1 s late or early; not run: its layers never "
                 "started; worst: its worst start deviation)\n";
    std::cout << printf_string("floor  layers  %-*s  %-*s  %-*s  %-*s  off   not run  worst\n",
                               width, "planned start", width, "started", width, "planned end",
                               width, "ended");
    for (const auto& f : report.floors)
      std::cout << printf_string("%5d  %6d  %-*s  %-*s  %-*s  %-*s  %4d  %7d  %+.1f s\n", f.floor,
                                 f.layers, width, at(f.planned_start_s).c_str(), width,
                                 at(f.started_s).c_str(), width, at(f.planned_end_s).c_str(), width,
                                 at(f.ended_s).c_str(), f.off_plan, f.not_run, f.worst_s);
  }
  // The crew's and the climber's jobs: planned, and how many ran.
  if (!report.crew_and_climber.empty()) {
    std::string line;
    for (const auto& [what, c] : report.crew_and_climber)
      line +=
          printf_string("%s%s %d of %d", line.empty() ? "" : "; ", what.c_str(), c.ran, c.planned);
    std::cout << "climbs, pipes and slabs (ran of planned): " << line << "\n";
  }
  std::cout << printf_string(
      "deviations: %d of %zu layers started more than 1 s off their planned start (worst "
      "%+.1f s), %d not run; %.1f s behind schedule at the end; jobs sent again: %ld; malformed "
      "messages rejected here: %ld\n",
      report.off_plan, report.layers.size(), report.worst_s, report.not_run, dispatcher.delay_s(),
      dispatcher.resent(), malformed);
  std::cout << printf_string("faults: %ld\n", dispatcher.faults());
  for (const auto& f : dispatcher.fault_records())
    std::cout << printf_string(
        "  %s job %lld: %s: %s -> %s\n", f.machine_id.empty() ? "dispatcher" : f.machine_id.c_str(),
        static_cast<long long>(f.job_id), dispatch::fault_name(f.kind).c_str(), f.message.c_str(),
        f.policy.c_str());
  // The re-plans of a late run (each journalled before it was applied).
  const auto& replans = dispatcher.replans();
  std::cout << printf_string(
      "re-plans: %zu%s\n", replans.size(),
      o.no_replan ? " (--no-replan: sent as planned)"
      : replans.empty()
          ? ""
          : printf_string(" (%d absorbed delay, %d started later, %d on planned joints, their "
                          "treatments ran %d of %d)",
                          report.absorbed, report.later, report.planned_joints,
                          report.treatments_ran, report.planned_joints)
                .c_str());
  constexpr std::size_t kReplansListed = 10;
  for (std::size_t k = 0; k < replans.size() && k < kReplansListed; ++k)
    std::cout << printf_string("  job %lld: %s: %s\n", static_cast<long long>(replans[k].job_id),
                               replans[k].what.c_str(), replans[k].detail.c_str());
  if (replans.size() > kReplansListed)
    std::cout << printf_string("  ... %zu more (the journal's table replan has every one)\n",
                               replans.size() - kReplansListed);
  for (const auto& e : events) std::cout << "event: " << e << "\n";
  bool collided = false;
  if (site) collided = site->collided() || site->guard().smallest_gap_m() < gantry_width_m;
  if (site && several) {
    const dispatch::RailGuard& rail_guard = site->guard();
    std::cout << printf_string(
        "gantry gaps: %ld measured at the site clock's %lld ticks, the smallest %s (gantry "
        "width %s)%s; %s\n",
        rail_guard.gaps_measured(), static_cast<long long>(site->clock().tick()),
        L(rail_guard.smallest_gap_m()).c_str(), L(gantry_width_m).c_str(),
        collided ? ": COLLISION" : "",
        guard ? printf_string("watchdog steps of %.3g s, within which two gantries close at most "
                              "%s",
                              status_period_s, L(rail_guard.margin_m(rail_speed_m_s)).c_str())
                    .c_str()
              : "no watchdog (--no-watchdog): steps of up to 0.5 s, unguarded");
  }
  if (site)
    std::cout << printf_string("site clock: %lld ticks, %ld sent again\n",
                               static_cast<long long>(site->clock().tick()),
                               site->clock().repeats());
  if (watchdog) {
    collided = watchdog->smallest_gap_m() < gantry_width_m;
    std::cout << printf_string(
        "gantry gaps: %ld measured from the machines' statuses%s, the smallest %s (gantry "
        "width %s)%s\n",
        watchdog->gaps_measured(), can_guard ? "" : " (only where both reported within 1 s)",
        L(watchdog->smallest_gap_m()).c_str(), L(gantry_width_m).c_str(),
        collided ? ": COLLISION" : "");
  }
  // The default journal goes with the temporary folder: say so rather than print a path
  // that is gone when the run ends.
  const std::string journal_where =
      o.journal.empty() ? "temporary (--journal FILE keeps one, and resumes from it)"
                        : journal_path.string();
  std::cout << printf_string("journal: %s, %ld writes in %.2f s (%.1f%% of the run)\n",
                             journal_where.c_str(), journal.writes(), journal.write_s(),
                             real_s > 0 ? 100.0 * journal.write_s() / real_s : 0.0);
  if (log) {
    if (!bus.close_log())
      throw InputError(o.log, 0, "--log", "writing the LCM log failed: " + bus.log_error());
    outputs.commit();
    std::cout << printf_string(
        "LCM log: %s, %ld messages, %.0f a second (lcm-logplayer replays it)\n", o.log.c_str(),
        bus.logged(), real_s > 0 ? bus.logged() / real_s : 0.0);
  }
  const bool complete = dispatcher.finished() && !dispatcher.stopped();
  if (dispatcher.stopped())
    std::cout << "STOPPED safely: " << *dispatcher.stopped() << "\n";
  else if (!complete)
    std::cout << "NOT complete: timed out after " << duration_text(o.timeout_s) << "\n";
  if (!schedule.schedule.feasible)
    std::cout << "the schedule itself is NOT feasible: " << schedule.schedule.infeasibility->message
              << "\n";
  exit_code = complete && !collided && schedule.schedule.feasible ? kExitOk : kExitNo;
  std::cout << (exit_code == kExitOk ? "completed within its constraints\n"
                                     : "NOT completed within its constraints\n");
}

}  // namespace

void add_dry_run_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<DryRunOptions>();
  CLI::App* command = app.add_subcommand(
      "dry-run",
      "Run a schedule against simulated machines over LCM, as it would go to hardware: one "
      "ccbuild-sim process per gantry (or machines already on the bus with --external), "
      "each checking the jobs against its URDF's limits and the material's interval window. "
      "One site clock drives them all: the orchestrator publishes the time up to which the "
      "machines may run, each answers with its status for that instant, and the clock moves "
      "on (at --speed while something moves, at once over idle time) only once all have "
      "answered. A layer's jobs go out together with a common start; each job's path in "
      "chunks under 64 kB; acknowledged and completed, sent again when an answer is late "
      "(from 20 ms, doubling; a machine never runs a job twice); every step written to the "
      "SQLite journal first (--journal: a dry-run restarted on it goes on where it stopped). "
      "Faults meet their policy: a pin that missed is tried again, a clog is purged and the "
      "rest of its layer re-planned, anything else stops every machine safely. With several "
      "gantries the site watchdog lets the clock move on only where no two gantries can come "
      "closer than their width whatever each does along its path, and pauses them all before "
      "they touch, at any speed. Idle gantries park at the far end of the rails. A machine "
      "that crashes is started again on its own record (at most 10 times). Ends with planned "
      "against executed, floor by floor (--by-layer: layer by layer), every fault and what "
      "was done. Before anything starts, a schedule file is read back and checked (a "
      "hand-edited one that breaks a rule is refused with the place), its input files must "
      "be unchanged, a schedule marked not feasible is refused, every flag and fault is "
      "checked against what the machines accept and the schedule holds, and the journal and "
      "state folders must be writable (exit 2). Exit 0 when the building was completed "
      "within its constraints, 1 otherwise. Run it in a network namespace of its own "
      "(scripts/in-netns.sh; docs/dispatch.md).\n"
      "Examples:\n"
      "  ccbuild dry-run config/buildings/house.yaml\n"
      "  ccbuild dry-run house.schedule.json --speed 100000 --journal house.journal\n"
      "  ccbuild dry-run config/buildings/house.yaml --inject drop=0.1,clog=0:5 --seed 3\n"
      "  ccbuild dry-run twin.schedule.json --inject stall=gantry-1@75 --log twin.lcmlog");
  command->add_option("FILE", o->file, "A building, or a schedule JSON")->required();
  command->add_option("--lcm-url", o->lcm_url, "LCM provider URL (ttl=0: this host only)")
      ->capture_default_str();
  command->add_option("--speed", o->speed, "Simulated seconds per real second")
      ->check(number_in(machine::sim_limits::kSpeed, ""))
      ->capture_default_str();
  command
      ->add_option("--journal", o->journal,
                   "Keep the journal here (SQLite) and resume from it; it records the schedule "
                   "it belongs to, and another schedule's journal is refused")
      ->check(output_path());
  command
      ->add_option("--state-dir", o->state_dir,
                   "Where the simulated machines keep their records (<machine>.state: the "
                   "jobs each ran, and schedule.sha256: whose they are), kept after the run; "
                   "default: a temporary folder. Another schedule's records are refused")
      ->check(output_path());
  command
      ->add_option("--log", o->log,
                   "Write the whole conversation as an LCM log (lcm-logger's format) here, in "
                   "place when the run ends (or into a character device such as /dev/null); "
                   "never over an input, the journal or another output")
      ->check(output_path());
  command->add_option(
      "--inject", o->inject,
      "Faults to inject, comma-separated. Network (into what the machines "
      "receive and send, probabilities per message): drop=P, duplicate=P, "
      "reorder=P, delay=P (held up to 0.5 s). Machine (on gantry-1 unless MACHINE@ names another): "
      "clog=FLOOR:LAYER (the pump clogs part-way through that layer), pin=N "
      "(the first N pin insertions miss), crash=N (the process dies right "
      "after its N-th job), stall=SECONDS (the rail axis stalls from then on)");
  command->add_option("--seed", o->seed, "Seed of the injected faults")
      ->check(unsigned_integer())
      ->capture_default_str();
  command
      ->add_option("--retry-after", o->retry_after_s,
                   "Send a job again when not acknowledged within this many real seconds, "
                   "waiting twice as long after each repeat up to 1 s (a job not reported done "
                   "within its expected time plus ten times this, at least 0.25 s, likewise; "
                   "on the site clock a lost answer is also learnt from the next status)")
      ->check(number_in(Range::above(0.0, 600.0), "s"))
      ->capture_default_str();
  command->add_flag("--external", o->external, "Use machines already on the bus");
  command
      ->add_option("--status-period", o->status_period_s,
                   "On the site clock: the watchdog's finest step, seconds of site time "
                   "(default 0.02 s: paused when a step would have to be shorter). With "
                   "--own-clock: the machines' status every this many seconds of machine time "
                   "(default 1 s, or what keeps them under 200 a real second)")
      ->check(number_in(machine::sim_limits::kStatusPeriod_s, "s"));
  command->add_flag(
      "--own-clock", o->own_clock,
      "Run the simulated machines on their own clocks, each at --speed in real time with "
      "statuses every --status-period of it, as real hardware runs (no site clock: the "
      "watchdog guards only where statuses come often enough)");
  command->add_flag("--by-layer", o->by_layer,
                    "The summary layer by layer (planned and actual start and end, deviation), "
                    "not floor by floor");
  command->add_flag("--no-watchdog", o->no_watchdog,
                    "Let gantries collide: the site watchdog only measures the gaps (to "
                    "show what it prevents)");
  command->add_flag("--force", o->force, "Overwrite the --log file when it exists");
  command->add_flag("--allow-infeasible", o->allow_infeasible,
                    "Run a schedule marked not feasible anyway, to see where its machines stop "
                    "it (with --no-replan) or how re-planning carries it (it never ends "
                    "'completed within its constraints': exit 1)");
  command->add_flag(
      "--no-replan", o->no_replan,
      "Send every deposit at its planned start plus the run's delay, as the schedule says, "
      "and let the machines refuse what breaks the material's window. By default a deposit "
      "is re-planned from the piece ends the machines laid: later where it would cover one "
      "too soon, on a planned joint (its treatment first) where no start keeps every joint "
      "within the maximum (docs/dispatch.md)");
  command->add_option("--timeout", o->timeout_s, "Give up after this many real seconds")
      ->check(number_in(Range::above(0.0, 86400.0), "s"))
      ->capture_default_str();
  add_input_options(*command, o->input);
  command->callback([o, &exit_code] { run_dry_run(*o, exit_code); });
}

}  // namespace ccbuild::cli
