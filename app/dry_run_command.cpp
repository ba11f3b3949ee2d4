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
#include "ccbuild/dispatch/dry_run.hpp"
#include "ccbuild/dispatch/run_inputs.hpp"
#include "ccbuild/floors/material.hpp"
#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/schedule/schedule.hpp"
#include "ccbuild/schedule/schedule_json.hpp"
#include "ccbuild/sim/sim_limits.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace ccbuild::cli {
namespace {
namespace fs = std::filesystem;

struct DryRunOptions {
  std::string file;
  InputOptions input;
  std::string inject;  ///< "drop=0.1,duplicate=0.1,reorder=0.1"
  bool allow_infeasible = false;
  dispatch::DryRunSettings run;  ///< the rest of the flags, as the session takes them
};

void run_dry_run(const DryRunOptions& o, int& exit_code) {
  dispatch::DryRunSettings settings = o.run;
  settings.inject = dispatch::parse_injected(o.inject);  // its grammar, before any work
  // A schedule file read back and checked (its input files unchanged: the machines run
  // from them); a building scheduled first.
  schedule::ScheduleDocument schedule;
  std::optional<schedule::Project> project;
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
  settings.unit = shown_unit(o.input, schedule.inputs.units);
  if (!schedule.schedule.feasible && !o.allow_infeasible)
    throw InputError(o.file, 0, project ? "" : "/feasible",
                     "the schedule is not feasible (" + schedule.schedule.infeasibility->message +
                         "); its machines would be sent work that breaks the material's "
                         "constraints. Fix it first, or pass --allow-infeasible to see where "
                         "the machines stop it");
  settings.machine_profile = dispatch::machine_profile_of(schedule, o.file, o.input.machine,
                                                          project ? &*project : nullptr);
  // A machine fitted on the fly (a family given as the machine): the machines are the
  // member the schedule was made for, fitted again as it was (the building where it stood)
  // and written to a folder of the run's own (removed with `fitted`), not the family.
  const dispatch::FittedMachineFolder fitted =
      dispatch::FittedMachineFolder::of(schedule, o.file, project ? &*project : nullptr,
                                        settings.machine_profile, project_options(o.input));
  if (!fitted.profile().empty()) settings.machine_profile = fitted.profile().string();
  settings.schedule_file = o.file;
  settings.sim_program = fs::read_symlink("/proc/self/exe").parent_path() / "ccbuild-sim";
  exit_code =
      dispatch::run_dry_run(schedule, settings, outputs, std::cout, std::cerr) ? kExitOk : kExitNo;
}

}  // namespace

void add_dry_run_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<DryRunOptions>();
  CLI::App* command = app.add_subcommand(
      "dry-run",
      "Run a schedule against simulated machines over LCM, as it would go to hardware: one "
      "ccbuild-sim process per gantry (or machines already on the bus with --external), "
      "each checking the jobs against its URDF's limits and the material's interval window. "
      "One site clock drives them all: the dispatcher publishes the time up to which the "
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
  command->add_option("--lcm-url", o->run.lcm_url, "LCM provider URL (ttl=0: this host only)")
      ->capture_default_str();
  command->add_option("--speed", o->run.speed, "Simulated seconds per real second")
      ->check(number_in(sim::limits::kSpeed, ""))
      ->capture_default_str();
  command
      ->add_option("--journal", o->run.journal,
                   "Keep the journal here (SQLite) and resume from it; it records the schedule "
                   "it belongs to, and another schedule's journal is refused")
      ->check(output_path());
  command
      ->add_option("--state-dir", o->run.state_dir,
                   "Where the simulated machines keep their records (<machine>.state: the "
                   "jobs each ran, and schedule.sha256: whose they are), kept after the run; "
                   "default: a temporary folder. Another schedule's records are refused")
      ->check(output_path());
  command
      ->add_option("--log", o->run.log,
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
  command->add_option("--seed", o->run.seed, "Seed of the injected faults")
      ->check(unsigned_integer())
      ->capture_default_str();
  command
      ->add_option("--retry-after", o->run.retry_after_s,
                   "Send a job again when not acknowledged within this many real seconds, "
                   "waiting twice as long after each repeat up to 1 s (a job not reported done "
                   "within its expected time plus ten times this, at least 0.25 s, likewise; "
                   "on the site clock a lost answer is also learnt from the next status)")
      ->check(number_in(Range::above(0.0, 600.0), "s"))
      ->capture_default_str();
  command->add_flag("--external", o->run.external, "Use machines already on the bus");
  command
      ->add_option("--status-period", o->run.status_period_s,
                   "On the site clock: the watchdog's finest step, seconds of site time "
                   "(default 0.02 s: paused when a step would have to be shorter). With "
                   "--own-clock: the machines' status every this many seconds of machine time "
                   "(default 1 s, or what keeps them under 200 a real second)")
      ->check(number_in(sim::limits::kStatusPeriod_s, "s"));
  command->add_flag(
      "--own-clock", o->run.own_clock,
      "Run the simulated machines on their own clocks, each at --speed in real time with "
      "statuses every --status-period of it, as real hardware runs (no site clock: the "
      "watchdog guards only where statuses come often enough)");
  command->add_flag("--by-layer", o->run.by_layer,
                    "The summary layer by layer (planned and actual start and end, deviation), "
                    "not floor by floor");
  command->add_flag("--no-watchdog", o->run.no_watchdog,
                    "Let gantries collide: the site watchdog only measures the gaps (to "
                    "show what it prevents)");
  command->add_flag("--force", o->run.force, "Overwrite the --log file when it exists");
  command->add_flag("--allow-infeasible", o->allow_infeasible,
                    "Run a schedule marked not feasible anyway, to see where its machines stop "
                    "it (with --no-replan) or how re-planning carries it (it never ends "
                    "'completed within its constraints': exit 1)");
  command->add_flag(
      "--no-replan", o->run.no_replan,
      "Send every deposit at its planned start plus the run's delay, as the schedule says, "
      "and let the machines refuse what breaks the material's window. By default a deposit "
      "is re-planned from the piece ends the machines laid: later where it would cover one "
      "too soon, on a planned joint (its treatment first) where no start keeps every joint "
      "within the maximum (docs/dispatch.md)");
  command->add_option("--timeout", o->run.timeout_s, "Give up after this many real seconds")
      ->check(number_in(Range::above(0.0, 86400.0), "s"))
      ->capture_default_str();
  add_input_options(*command, o->input);
  command->callback([o, &exit_code] { run_dry_run(*o, exit_code); });
}

}  // namespace ccbuild::cli
