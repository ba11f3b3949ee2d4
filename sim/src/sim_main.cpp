// ccbuild-sim: one simulated machine as its own process, on the LCM bus at --lcm-url,
// answering the jobs for --machine-id (docs/dispatch.md). Runs until SIGTERM or SIGINT.

#include <CLI/CLI.hpp>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/sim/sim_limits.hpp"
#include "ccbuild/sim/sim_machine.hpp"
#include "ccbuild/wire/bus.hpp"

namespace {
namespace sim_limits = ccbuild::sim::limits;
volatile std::sig_atomic_t stop_requested = 0;

CLI::Range range(const ccbuild::Range& r) {
  return CLI::Range(r.min, r.max);
}
extern "C" void on_stop(int) {
  stop_requested = 1;
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app(
      "ccbuild-sim: a simulated Contour Crafting machine on the LCM bus. It takes the jobs "
      "for its machine id as a real machine would and runs them on the site clock "
      "(CCBUILD_CLOCK: it simulates up to each tick's time and answers with its status for "
      "that instant), or with --own-clock on its own clock at --speed (idle time passes at "
      "once), as real hardware runs. It keeps its own record of the jobs it ran in --state (read "
      "back when it restarts), acknowledges a job it has seen again without running it "
      "twice, and refuses jobs out of order, paths that do not add up or break its URDF's "
      "limits (--machine), and layers that would cover its layer below too early or too late "
      "(--min-interval, --max-interval), with a fault. Replayed messages are rejected. "
      "Machine faults can be injected (--clog-at, --pin-failures, --crash-after, --stall-at). "
      "`ccbuild dry-run` starts one per gantry.\n"
      "Example: ccbuild-sim --machine-id gantry-1 --state gantry-1.state",
      "ccbuild-sim");
  ccbuild::sim::SimOptions options;
  std::string url = "udpm://239.255.76.67:7667?ttl=0";
  std::string state;
  bool climbing = false, own_clock = false;
  app.add_option("--machine-id", options.machine_id, "The machine it is")->capture_default_str();
  app.add_option("--lcm-url", url, "LCM provider URL (ttl=0: this host only)")
      ->capture_default_str();
  app.add_flag("--own-clock", own_clock,
               "Run on its own clock at --speed, statuses every --status-period of it, and "
               "ignore the site clock (as real hardware)");
  app.add_option("--speed", options.speed,
                 "With --own-clock: simulated seconds per real second while busy")
      ->check(range(sim_limits::kSpeed))
      ->capture_default_str();
  app.add_option("--status-period", options.status_period_s,
                 "With --own-clock: status every this many simulated s")
      ->check(range(sim_limits::kStatusPeriod_s))
      ->capture_default_str();
  app.add_option("--state", state, "Its record of the jobs it ran (appended; read at start)");
  app.add_option("--drop", options.drop, "Injected: the probability a message is lost")
      ->check(range(sim_limits::kDrop));
  app.add_option("--duplicate", options.duplicate, "Injected: ... that one is handled twice")
      ->check(range(sim_limits::kDuplicate));
  app.add_option("--reorder", options.reorder, "Injected: ... that one is held behind the next")
      ->check(range(sim_limits::kReorder));
  app.add_option("--delay", options.delay,
                 "Injected: ... that one is held back for up to --delay-max real seconds")
      ->check(range(sim_limits::kDelay));
  app.add_option("--delay-max", options.delay_max_s, "The longest injected delay, real s")
      ->check(range(sim_limits::kDelayMax_s))
      ->capture_default_str();
  app.add_option("--seed", options.seed, "Seed of the injected faults")->capture_default_str();
  std::string profile, clog_at, age_clock;
  std::vector<double> home;
  app.add_option("--home", home,
                 "Where the nozzle is parked before its first job: X Y Z HEADING "
                 "(m, rad)")
      ->expected(4);
  app.add_option("--machine", profile,
                 "Its machine profile: axis ranges, stopper and velocity limits from the URDF "
                 "it names (paths outside them are refused); default: unchecked");
  app.add_flag("--climbing", climbing, "A climbing machine: nozzle heights not held to z range");
  app.add_option("--min-interval", options.min_interval_s,
                 "The material's minimum layer interval, s (a layer covering this machine's "
                 "layer below sooner is refused: too early)")
      ->check(range(sim_limits::kMinInterval_s));
  app.add_option("--max-interval", options.max_interval_s,
                 "... its maximum, s (covered later: a cold joint)")
      ->check(range(sim_limits::kMaxInterval_s));
  app.add_option("--age-clock", age_clock,
                 "A file of the concrete's equivalent age against schedule time, one "
                 "breakpoint a line: \"t_s e_s rate\" (the site's weather; ccbuild dry-run "
                 "writes it): the interval window and the anchors' age are then equivalent "
                 "ages; default: real time");
  app.add_option("--anchor-min-age", options.anchor_min_age_s,
                 "How old an anchor must be before a unit pins into it, s (a pin sooner after "
                 "the unit's last pipe is refused: anchor too young)")
      ->check(range(sim_limits::kAnchorMinAge_s));
  app.add_option("--clog-at", clog_at,
                 "Injected: the pump clogs part-way through this layer, FLOOR:LAYER (from 0)");
  app.add_option("--pin-failures", options.pin_failures,
                 "Injected: the first N pin insertions miss their pipe")
      ->check(CLI::Range(0, sim_limits::kMaxPinFailures));
  app.add_option("--crash-after", options.crash_after_jobs,
                 "Injected: the process ends (exit 70) right after recording its N-th job")
      ->check(CLI::Range(0L, sim_limits::kMaxCrashAfterJobs));
  app.add_option("--stall-at", options.stall_at_s,
                 "Injected: the rail axis stalls from this schedule time on, s (the drive does "
                 "not notice)")
      ->check(range(sim_limits::kStallAt_s));
  CLI11_PARSE(app, argc, argv);
  options.state_file = state;
  options.check_z_range = !climbing;
  options.site_clock = !own_clock;
  if (home.size() == 4) options.home = {home[0], home[1], home[2], home[3]};
  try {
    if (!clog_at.empty() &&
        !sim_limits::parse_floor_layer(clog_at, options.clog_floor, options.clog_layer))
      throw ccbuild::InputError(
          "", 0, "--clog-at",
          "expected FLOOR:LAYER (whole numbers from 0), got '" + ccbuild::echoed(clog_at) + "'");
    if (!profile.empty())
      options.model = std::make_shared<const ccbuild::machine::MachineModel>(
          ccbuild::machine::load_machine(profile));
    if (!age_clock.empty()) {
      std::ifstream in(age_clock);
      if (!in) throw ccbuild::InputError(age_clock, 0, "--age-clock", "cannot open the file");
      std::stringstream text;
      text << in.rdbuf();
      try {
        options.age_clock = ccbuild::rules::AgeClock::parse(text.str());
      } catch (const std::invalid_argument& e) {
        throw ccbuild::InputError(age_clock, 0, "--age-clock", e.what());
      }
    }
    ccbuild::wire::Bus bus(url);
    bus.on_malformed([&](const std::string& channel, int size) {
      std::cerr << "ccbuild-sim " << options.machine_id << ": rejected a message on " << channel
                << " (" << size << " bytes) that does not decode as its channel's type\n";
    });
    ccbuild::sim::SimMachine sim(bus, options);
    std::signal(SIGTERM, on_stop);
    std::signal(SIGINT, on_stop);
    auto last = std::chrono::steady_clock::now();
    while (!stop_requested) {
      bus.handle(1);
      const auto now = std::chrono::steady_clock::now();
      sim.step(std::chrono::duration<double>(now - last).count());
      last = now;
    }
    // One write, so that machines stopping together do not mix their lines.
    std::ostringstream said;
    said << "ccbuild-sim " << options.machine_id << ": stopped; " << sim.executed().size()
         << " jobs in its record, " << sim.replays_rejected() << " replayed and "
         << bus.malformed_count() << " malformed messages rejected\n";
    std::cerr << said.str() << std::flush;
    return 0;
  } catch (const ccbuild::InputError& e) {
    std::cerr << "ccbuild-sim: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "ccbuild-sim: internal error: " << e.what() << "\n";
    return 3;
  }
}
