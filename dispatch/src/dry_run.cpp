// The dry-run session (dry_run.hpp): the machines started, the dispatcher, journal, site
// clock and watchdog run to the end, and the summary of planned against executed.

#include "ccbuild/dispatch/dry_run.hpp"

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
#include "ccbuild/common/format.hpp"
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
#include "ccbuild/schedule/schedule.hpp"
#include "ccbuild/schedule/schedule_json.hpp"
#include "ccbuild/sim/sim_limits.hpp"
#include "ccbuild/sim/sim_machine.hpp"
#include "ccbuild/site/conditions.hpp"
#include "ccbuild_lcm/ccbuild_job_t.hpp"

namespace ccbuild::dispatch {
namespace {
namespace fs = std::filesystem;

/// The site clock's resolution: the rail guard's finest step, schedule s.
constexpr double kSiteStatusPeriod_s = 0.02;

}  // namespace

bool run_dry_run(const schedule::ScheduleDocument& schedule, const DryRunSettings& o,
                 OutputClaims& outputs, std::ostream& out, std::ostream& err) {
  namespace lim = sim::limits;
  const InjectedFaults& inject = o.inject;
  const schedule::RecordedMachine& machine_rec = schedule.inputs.machine;
  const floors::MaterialProfile& material = schedule.inputs.material;
  const floors::LengthUnit unit = o.unit;
  auto L = [unit](double m) { return floors::length_text(m, unit); };
  // The schedule's identity, for the journal and the machines' records: the SHA-256 of
  // its JSON as `ccbuild schedule -o` writes it (the same for the building and its file).
  const std::string schedule_sha256 =
      sha256_hex(schedule::schedule_json(schedule.inputs, schedule.schedule)
                     .dump(1, ' ', false, nlohmann::json::error_handler_t::replace) +
                 "\n");

  auto jobs = jobs_of_schedule(schedule);
  std::vector<std::string> ids;  // in rail order
  for (int k = 0;; ++k) {
    const std::string id = gantry_id(k);
    if (std::none_of(jobs.begin(), jobs.end(),
                     [&](const DispatchJob& j) { return j.machine_id == id; }))
      break;
    ids.push_back(id);
  }
  check_injected(inject, schedule, jobs, ids);
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
      throw InputError(o.schedule_file, 0, p.what,
                       "the simulated machines accept " + p.range.describe("") + ", got " +
                           plain_number(p.value));
  // What a machine reads: its profile (it loads the same files again).
  if (!o.external) machine::load_machine(o.machine_profile);

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
    check_state_dir(o.state_dir, ids, schedule_sha256);
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
    check_writable_folder(temporary.path, {}, "TMPDIR");
  }
  if (!o.state_dir.empty()) {
    std::vector<fs::path> records;
    for (const auto& id : ids) records.push_back(fs::path(o.state_dir) / (id + ".state"));
    check_writable_folder(o.state_dir, records, "--state-dir");
  }
  if (!o.journal.empty())
    check_writable_folder(fs::absolute(o.journal).parent_path(), {o.journal}, "--journal");
  const fs::path& work = temporary.path;
  const fs::path journal_path = o.journal.empty() ? work / "journal.sqlite" : fs::path(o.journal);
  Journal journal(journal_path, schedule_sha256);
  wire::Bus bus(o.lcm_url);
  // The log goes to a temporary file beside it, in place once the run ends.
  const bool log = !o.log.empty();
  if (log) bus.log_to(outputs.writing_path(o.log).string());
  long malformed = 0;
  bus.on_malformed([&](const std::string& channel, int size) {
    ++malformed;
    err << "dry-run: a message on " << channel << " (" << size
        << " bytes) did not decode: rejected\n";
  });
  std::unique_ptr<MachineSupervisor> machines;
  const fs::path state_dir = o.state_dir.empty() ? work : fs::path(o.state_dir);
  // With site weather the material's window and the anchors' age are equivalent ages, as
  // the scheduler kept them: the dispatcher and the machines count them on its clock.
  rules::AgeClock age_clock;
  if (schedule.inputs.conditions)
    age_clock = site::EquivalentAge(*schedule.inputs.conditions, material.maturity).clock();
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
        "--machine",       o.machine_profile,
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
    machines = std::make_unique<MachineSupervisor>(o.sim_program, ids,
                                                   parking_homes(jobs, ids, machine_rec), common,
                                                   inject.flags(), state_dir);
  }
  DispatchOptions d;
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
  Dispatcher dispatcher(bus, jobs, journal, d);
  std::optional<SiteWatchdog> watchdog;
  if (several && o.own_clock) {
    WatchdogOptions w;
    w.machines = ids;
    w.rail_axis = rail_axis;
    w.gantry_width_m = gantry_width_m;
    w.margin_m = guard ? margin_m : 0.0;
    w.max_span_s = can_guard ? 1e9 : 1.0;  // else only where both reported that closely
    watchdog.emplace(bus, w);
  }
  err << printf_string("dry-run: %zu jobs to %zu machine(s) at %.0fx over %s\n", jobs.size(),
                       ids.size(), o.speed, o.lcm_url.c_str());
  std::optional<SiteRun> site;
  if (!o.own_clock) {
    SiteRunOptions so;
    so.speed = o.speed;
    so.guard = guard;
    so.status_period_s = status_period_s;
    site.emplace(bus, dispatcher, ids, rail_axis, gantry_width_m, so);
  }
  if (several && guard && site)
    err << printf_string(
        "dry-run: site watchdog guarding the rails on the site clock: a step of it only where "
        "no two gantries can come closer than %s whatever each does along its path, in "
        "steps of %.3g s (two gantries close at most %s within one)\n",
        L(gantry_width_m).c_str(), status_period_s,
        L(site->guard().margin_m(rail_speed_m_s)).c_str());
  else if (several && guard)
    err << printf_string(
        "dry-run: site watchdog guarding the rails: every machine paused below %s (the "
        "gantry width %s plus %s the gantries can close between statuses every %.3g s "
        "of machine time)\n",
        L(gantry_width_m + margin_m).c_str(), L(gantry_width_m).c_str(), L(margin_m).c_str(),
        status_period_s);
  else if (several && o.no_watchdog)
    err << "dry-run: site watchdog off (--no-watchdog): gaps are measured, a collision "
           "stops the run\n";
  else if (several)
    err << printf_string(
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
        err << "dry-run: " << *why << "\n";
      }
    if (watchdog)
      if (const auto why = watchdog->check(dt_s)) {
        events.push_back(*why);
        err << "dry-run: " << *why << "\n";
        dispatcher.stop(*why);  // guarding: before they touch; else: they collided
      }
    if (machines) {
      std::optional<std::string> given_up;
      for (const auto& said : machines->restart_ended(given_up)) {
        events.push_back(said);
        err << "dry-run: " << said << "\n";
      }
      if (given_up) {
        events.push_back(*given_up);
        err << "dry-run: " << *given_up << "\n";
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
        if (const DispatchJob* j = dispatcher.job(id);
            j && j->kind == JobKind::kDeposit &&
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
      err << printf_string(
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
          err << printf_string(
              "dry-run: %s has not answered the site clock's tick %lld for %.0f s (a machine on "
              "its own clock answers with tick 0: run such machines with `ccbuild dry-run "
              "--own-clock`)\n",
              machine.c_str(), static_cast<long long>(site->clock().tick()),
              site->clock().waited_s());
      for (const auto& [machine, silent_s] : dispatcher.silent(3.0))
        err << printf_string(
            "dry-run: %s not heard from %s\n", machine.c_str(),
            silent_s > 3.0 ? printf_string("for %.0f s", silent_s).c_str() : "yet");
      err << printf_string(
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
  const RunReport report = report_of(dispatcher);
  const site::SiteCalendar* calendar = schedule.inputs.calendar.get();
  out << printf_string(
      "%s: %zu of %zu jobs executed on %zu machine(s) in %.1f s (%.0fx), finished at %s of "
      "schedule time\n",
      o.schedule_file.c_str(), dispatcher.executed().size(), dispatcher.jobs().size(), ids.size(),
      real_s, o.speed, site::time_text(calendar, report.finished_s, true).c_str());
  // Every time to the second, as a date on a site calendar, else as "day 3 07:05:09".
  const auto at = [calendar](double t_s) {
    return std::isfinite(t_s) ? site::time_text(calendar, t_s, true) : std::string("-");
  };
  const int width = calendar ? 23 : 15;
  if (o.by_layer) {
    out << "by layer (planned start, planned end: the schedule's; started, ended: when the "
           "layer's jobs started and the last of them ended; deviation: started less planned "
           "start)\n";
    out << printf_string("layer               %-*s  %-*s  deviation   %-*s  ended\n", width,
                         "planned start", width, "started", width, "planned end");
    for (const auto& l : report.layers)
      out << printf_string("%-18s  %-*s  %-*s  %-10s  %-*s  %s\n",
                           printf_string("floor %d layer %d", l.floor, l.layer).c_str(), width,
                           at(l.planned_start_s).c_str(), width,
                           l.ran() ? at(l.started_s).c_str() : "not run",
                           l.ran() ? printf_string("%+.1f s", l.deviation_s()).c_str() : "-", width,
                           at(l.planned_end_s).c_str(), at(l.ended_s).c_str());
  } else {
    out << "by floor (--by-layer for every layer; planned start, planned end: the "
           "schedule's; started, ended: when the floor's first layer started and its last "
           "ended; off: its layers started over 1 s late or early; not run: its layers never "
           "started; worst: its worst start deviation)\n";
    out << printf_string("floor  layers  %-*s  %-*s  %-*s  %-*s  off   not run  worst\n", width,
                         "planned start", width, "started", width, "planned end", width, "ended");
    for (const auto& f : report.floors)
      out << printf_string("%5d  %6d  %-*s  %-*s  %-*s  %-*s  %4d  %7d  %+.1f s\n", f.floor,
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
    out << "climbs, pipes and slabs (ran of planned): " << line << "\n";
  }
  out << printf_string(
      "deviations: %d of %zu layers started more than 1 s off their planned start (worst "
      "%+.1f s), %d not run; %.1f s behind schedule at the end; jobs sent again: %ld; malformed "
      "messages rejected here: %ld\n",
      report.off_plan, report.layers.size(), report.worst_s, report.not_run, dispatcher.delay_s(),
      dispatcher.resent(), malformed);
  out << printf_string("faults: %ld\n", dispatcher.faults());
  for (const auto& f : dispatcher.fault_records())
    out << printf_string("  %s job %lld: %s: %s -> %s\n",
                         f.machine_id.empty() ? "dispatcher" : f.machine_id.c_str(),
                         static_cast<long long>(f.job_id), fault_name(f.kind).c_str(),
                         f.message.c_str(), to_string(f.policy).c_str());
  // The re-plans of a late run (each journalled before it was applied).
  const auto& replans = dispatcher.replans();
  out << printf_string(
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
    out << printf_string("  job %lld: %s: %s\n", static_cast<long long>(replans[k].job_id),
                         replans[k].what.c_str(), replans[k].detail.c_str());
  if (replans.size() > kReplansListed)
    out << printf_string("  ... %zu more (the journal's table replan has every one)\n",
                         replans.size() - kReplansListed);
  for (const auto& e : events) out << "event: " << e << "\n";
  bool collided = false;
  if (site) collided = site->collided() || site->guard().smallest_gap_m() < gantry_width_m;
  if (site && several) {
    const RailGuard& rail_guard = site->guard();
    out << printf_string(
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
    out << printf_string("site clock: %lld ticks, %ld sent again\n",
                         static_cast<long long>(site->clock().tick()), site->clock().repeats());
  if (watchdog) {
    collided = watchdog->smallest_gap_m() < gantry_width_m;
    out << printf_string(
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
  out << printf_string("journal: %s, %ld writes in %.2f s (%.1f%% of the run)\n",
                       journal_where.c_str(), journal.writes(), journal.write_s(),
                       real_s > 0 ? 100.0 * journal.write_s() / real_s : 0.0);
  if (log) {
    if (!bus.close_log())
      throw InputError(o.log, 0, "--log", "writing the LCM log failed: " + bus.log_error());
    outputs.commit();
    out << printf_string("LCM log: %s, %ld messages, %.0f a second (lcm-logplayer replays it)\n",
                         o.log.c_str(), bus.logged(), real_s > 0 ? bus.logged() / real_s : 0.0);
  }
  const bool complete = dispatcher.finished() && !dispatcher.stopped();
  if (dispatcher.stopped())
    out << "STOPPED safely: " << *dispatcher.stopped() << "\n";
  else if (!complete)
    out << "NOT complete: timed out after " << duration_text(o.timeout_s) << "\n";
  if (!schedule.schedule.feasible)
    out << "the schedule itself is NOT feasible: " << schedule.schedule.infeasibility->message
        << "\n";
  const bool ok = complete && !collided && schedule.schedule.feasible;
  out << (ok ? "completed within its constraints\n" : "NOT completed within its constraints\n");
  return ok;
}

}  // namespace ccbuild::dispatch
