// ccbuild-sim: one simulated machine as its own process, on the LCM bus at --lcm-url,
// answering the jobs for --machine-id (docs/dispatch.md). Runs until SIGTERM or SIGINT.

#include <CLI/CLI.hpp>
#include <chrono>
#include <csignal>
#include <iostream>

#include "ccbuild/common/input_error.hpp"
#include "ccbuild/machine/bus.hpp"
#include "ccbuild/machine/sim_machine.hpp"

namespace {
volatile std::sig_atomic_t stop_requested = 0;
extern "C" void on_stop(int) {
  stop_requested = 1;
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app(
      "ccbuild-sim: a simulated Contour Crafting machine on the LCM bus. It takes the jobs "
      "for its machine id as a real machine would, runs them on its own clock at --speed "
      "(idle time passes at once), keeps its own record of the jobs it ran in --state (read "
      "back when it restarts), acknowledges a job it has seen again without running it "
      "twice, and refuses jobs out of order or with paths that do not add up (a fault). "
      "`ccbuild dry-run` starts one per gantry.\n"
      "Example: ccbuild-sim --machine-id gantry-1 --state gantry-1.state",
      "ccbuild-sim");
  ccbuild::machine::SimOptions options;
  std::string url = "udpm://239.255.76.67:7667?ttl=0";
  std::string state;
  app.add_option("--machine-id", options.machine_id, "The machine it is")->capture_default_str();
  app.add_option("--lcm-url", url, "LCM provider URL (ttl=0: this host only)")
      ->capture_default_str();
  app.add_option("--speed", options.speed, "Simulated seconds per real second while busy")
      ->check(CLI::Range(1.0, 1e9))
      ->capture_default_str();
  app.add_option("--status-period", options.status_period_s, "Status every this many simulated s")
      ->check(CLI::Range(0.001, 86400.0))
      ->capture_default_str();
  app.add_option("--state", state, "Its record of the jobs it ran (appended; read at start)");
  app.add_option("--drop", options.drop, "Injected: the probability a message is lost")
      ->check(CLI::Range(0.0, 0.9));
  app.add_option("--duplicate", options.duplicate, "Injected: ... that one is handled twice")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--reorder", options.reorder, "Injected: ... that one is held behind the next")
      ->check(CLI::Range(0.0, 0.9));
  app.add_option("--seed", options.seed, "Seed of the injected faults")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  options.state_file = state;
  try {
    ccbuild::machine::Bus bus(url);
    ccbuild::machine::SimMachine sim(bus, options);
    std::signal(SIGTERM, on_stop);
    std::signal(SIGINT, on_stop);
    auto last = std::chrono::steady_clock::now();
    while (!stop_requested) {
      bus.handle(1);
      const auto now = std::chrono::steady_clock::now();
      sim.step(std::chrono::duration<double>(now - last).count());
      last = now;
    }
    std::cerr << "ccbuild-sim " << options.machine_id << ": stopped after " << sim.executed().size()
              << " jobs\n";
    return 0;
  } catch (const ccbuild::InputError& e) {
    std::cerr << "ccbuild-sim: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "ccbuild-sim: internal error: " << e.what() << "\n";
    return 3;
  }
}
