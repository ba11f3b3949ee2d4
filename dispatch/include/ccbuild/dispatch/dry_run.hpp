#pragma once
// The dry-run session (docs/dispatch.md): a schedule's jobs run on one simulated machine
// per gantry (ccbuild-sim processes it starts, or machines already on the bus), with the
// dispatcher, its SQLite journal, the site clock and the rail watchdog here; then the
// summary of planned against executed. `ccbuild dry-run` parses the flags into
// DryRunSettings and calls run_dry_run.

#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/dispatch/run_inputs.hpp"
#include "ccbuild/floors/units.hpp"
#include "ccbuild/schedule/schedule_json.hpp"

namespace ccbuild::dispatch {

/// How a dry-run runs; each field is a flag of `ccbuild dry-run` (its --help says more).
struct DryRunSettings {
  std::string schedule_file;          ///< named in messages
  std::string machine_profile;        ///< what each machine loads (a fitted member's own)
  std::filesystem::path sim_program;  ///< ccbuild-sim
  floors::LengthUnit unit = floors::LengthUnit::kMeter;  ///< lengths in the text
  std::string lcm_url = "udpm://239.255.76.67:7667?ttl=0";
  double speed = 10'000.0;  ///< schedule seconds per real second
  std::string journal;      ///< empty: a temporary one
  std::string state_dir;    ///< the machines' records; empty: temporary
  std::string log;          ///< an LCM log of every message; empty: none
  InjectedFaults inject;
  std::uint64_t seed = 1;
  double retry_after_s = 0.02;   ///< real s before an unacknowledged job is sent again
  bool external = false;         ///< machines already on the bus: start none
  double timeout_s = 600.0;      ///< real s
  double status_period_s = 0.0;  ///< 0: chosen from the speed
  bool own_clock = false;        ///< machines on their own clocks, no site clock
  bool by_layer = false;         ///< the summary layer by layer
  bool no_watchdog = false;
  bool force = false;      ///< --log may replace a file
  bool no_replan = false;  ///< every job sent as planned plus the delay
};

/// Runs `schedule` (read back and checked, or just made) on its machines and writes the
/// progress to `err` and the summary to `out`. Outputs are claimed in `outputs` (never an
/// input, never a device). True when every job ran within its constraints with no
/// collision on a feasible schedule. Throws InputError (a flag's value the machines cannot
/// take, an output it may not write, a journal or records of another schedule).
bool run_dry_run(const schedule::ScheduleDocument& schedule, const DryRunSettings& settings,
                 OutputClaims& outputs, std::ostream& out, std::ostream& err);

}  // namespace ccbuild::dispatch
