// ccbuild dry-run BUILDING|SCHEDULE.json: runs a schedule against simulated machines over
// LCM, exactly as the jobs would go to hardware: one `ccbuild-sim` process per gantry
// (or machines already on the bus with --external), the dispatcher and its journal here.

#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <set>

#include "ccbuild/common/input_error.hpp"
#include "ccbuild/orchestrator/dispatcher.hpp"
#include "ccbuild/orchestrator/schedule.hpp"
#include "ccbuild/orchestrator/schedule_diff.hpp"
#include "ccbuild/orchestrator/schedule_json.hpp"
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
  double retry_after_s = 1.0;
  bool external = false;
  double timeout_s = 600.0;
};

/// --inject "drop=0.1,duplicate=0.1,reorder=0.1": each fault and its probability.
/// Throws InputError (field --inject) for anything else.
std::vector<std::pair<std::string, double>> injected(const std::string& text) {
  std::vector<std::pair<std::string, double>> out;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t end = std::min(text.find(',', at), text.size());
    const std::string item = text.substr(at, end - at);
    const std::size_t eq = item.find('=');
    const std::string name = item.substr(0, eq);
    char* stop = nullptr;
    const double p = eq == std::string::npos ? -1 : std::strtod(item.c_str() + eq + 1, &stop);
    if ((name != "drop" && name != "duplicate" && name != "reorder") || eq == std::string::npos ||
        *stop != '\0' || !(p >= 0.0 && p <= 0.9))
      throw InputError("", 0, "--inject",
                       "expected drop=P, duplicate=P or reorder=P (P from 0 to 0.9), "
                       "comma-separated; got '" +
                           item + "'");
    out.emplace_back(name, p);
    at = end + 1;
  }
  return out;
}

/// The simulated machines, one process each; stopped (SIGTERM) when this goes.
class Machines {
 public:
  Machines(const std::set<std::string>& ids, const DryRunOptions& o, const fs::path& state_dir) {
    const fs::path sim = fs::read_symlink("/proc/self/exe").parent_path() / "ccbuild-sim";
    if (!fs::exists(sim))
      throw InputError(sim.string(), 0, "", "ccbuild-sim not found beside ccbuild (build it)");
    for (const auto& id : ids) {
      const std::string state = (state_dir / (id + ".state")).string();
      const std::string speed = std::to_string(o.speed);
      std::vector<std::string> args = {"ccbuild-sim",
                                       "--machine-id",
                                       id,
                                       "--lcm-url",
                                       o.lcm_url,
                                       "--speed",
                                       speed,
                                       "--state",
                                       state,
                                       "--seed",
                                       std::to_string(o.seed)};
      for (const auto& [name, p] : injected(o.inject)) {
        args.push_back("--" + name);
        args.push_back(std::to_string(p));
      }
      const pid_t pid = ::fork();
      CCBUILD_CHECK(pid >= 0, "fork failed");
      if (pid == 0) {
        ::prctl(PR_SET_PDEATHSIG, SIGTERM);  // never outlive the dry-run
        std::vector<char*> argv;
        for (auto& a : args) argv.push_back(a.data());
        argv.push_back(nullptr);
        ::execv(sim.c_str(), argv.data());
        ::_exit(127);
      }
      pids_.push_back(pid);
    }
  }
  ~Machines() {
    for (pid_t pid : pids_) ::kill(pid, SIGTERM);
    for (pid_t pid : pids_) ::waitpid(pid, nullptr, 0);
  }

 private:
  std::vector<pid_t> pids_;
};

std::string duration(double s) {
  if (s >= 2 * 86400.0) return printf_string("%.2f d", s / 86400.0);
  if (s >= 2 * 3600.0) return printf_string("%.2f h", s / 3600.0);
  return printf_string("%.1f s", s);
}

void run_dry_run(const DryRunOptions& o, int& exit_code) {
  // A schedule file as it is; a building scheduled first.
  nlohmann::json schedule;
  if (fs::path(o.file).extension() == ".json") {
    schedule = orchestrator::read_schedule_file(o.file);
  } else {
    const orchestrator::Project project = open_input(o.file, o.input);
    orchestrator::ScheduleOptions options;
    schedule = orchestrator::schedule_json(project, options,
                                           orchestrator::build_schedule(project, options));
  }
  injected(o.inject);  // checked before anything starts
  auto jobs = orchestrator::jobs_of_schedule(schedule);
  std::set<std::string> ids;
  for (const auto& j : jobs) ids.insert(j.job.machine_id);
  const fs::path work =
      fs::temp_directory_path() / ("ccbuild-dry-run-" + std::to_string(::getpid()));
  fs::create_directories(work);
  const fs::path journal_path = o.journal.empty() ? work / "journal.sqlite" : fs::path(o.journal);
  orchestrator::Journal journal(journal_path);
  machine::Bus bus(o.lcm_url);
  if (!o.log.empty()) bus.log_to(o.log);
  long malformed = 0;
  bus.on_malformed([&](const std::string& channel, int size) {
    ++malformed;
    std::cerr << "dry-run: a message on " << channel << " (" << size
              << " bytes) did not decode: rejected\n";
  });
  std::unique_ptr<Machines> machines;
  const fs::path state_dir = o.state_dir.empty() ? work : fs::path(o.state_dir);
  if (!o.state_dir.empty()) fs::create_directories(state_dir);
  if (!o.external) machines = std::make_unique<Machines>(ids, o, state_dir);
  orchestrator::DispatchOptions d;
  d.speed = o.speed;
  d.ack_timeout_s = o.retry_after_s;
  d.done_slack_s = 2.0 * o.retry_after_s;
  orchestrator::Dispatcher dispatcher(bus, jobs, journal, d);
  std::cerr << printf_string("dry-run: %zu jobs to %zu machine(s) at %.0fx over %s\n", jobs.size(),
                             ids.size(), o.speed, o.lcm_url.c_str());
  const auto started = std::chrono::steady_clock::now();
  auto last = started, last_line = started;
  while (!dispatcher.finished()) {
    bus.handle(1);
    const auto now = std::chrono::steady_clock::now();
    dispatcher.step(std::chrono::duration<double>(now - last).count());
    last = now;
    if (now - last_line > std::chrono::seconds(2)) {
      last_line = now;
      std::cerr << printf_string("dry-run: %zu of %zu jobs done, %ld sent again, %ld faults\n",
                                 dispatcher.executed().size(), jobs.size(), dispatcher.resent(),
                                 dispatcher.faults());
    }
    if (std::chrono::duration<double>(now - started).count() > o.timeout_s) break;
  }
  const double real_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  machines.reset();
  // Planned against executed.
  double latest_s = 0.0, worst_late_s = 0.0;
  long late = 0;
  for (const auto& j : jobs) {
    const auto it = dispatcher.executed().find(j.job.job_id);
    if (it == dispatcher.executed().end()) continue;
    const double late_s = it->second.first - j.job.start_s;
    latest_s = std::max(latest_s, it->second.second);
    if (late_s > 1.0) ++late;
    worst_late_s = std::max(worst_late_s, late_s);
  }
  const bool complete = dispatcher.finished();
  std::cout << printf_string(
      "%s: %zu of %zu jobs executed on %zu machine(s) in %.1f s (%.0fx), finished at %s of "
      "schedule time\n",
      o.file.c_str(), dispatcher.executed().size(), jobs.size(), ids.size(), real_s, o.speed,
      duration(latest_s).c_str());
  std::cout << printf_string(
      "deviations: %ld jobs started more than 1 s after their planned start (worst %s); %ld "
      "sent again; %ld faults; %ld malformed messages rejected\n",
      late, duration(worst_late_s).c_str(), dispatcher.resent(), dispatcher.faults(), malformed);
  std::cout << printf_string("journal: %s, %ld writes in %.2f s (%.1f%% of the run)\n",
                             journal_path.string().c_str(), journal.writes(), journal.write_s(),
                             real_s > 0 ? 100.0 * journal.write_s() / real_s : 0.0);
  if (!o.log.empty())
    std::cout << printf_string(
        "LCM log: %s, %ld messages, %.0f a second (lcm-logplayer replays it)\n", o.log.c_str(),
        bus.logged(), real_s > 0 ? bus.logged() / real_s : 0.0);
  exit_code = complete && dispatcher.faults() == 0 ? kExitOk : kExitNo;
  if (!complete) std::cout << "NOT complete: timed out after " << duration(o.timeout_s) << "\n";
  if (o.journal.empty()) {
    std::error_code ec;
    fs::remove_all(work, ec);
  }
}

}  // namespace

void add_dry_run_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<DryRunOptions>();
  CLI::App* command = app.add_subcommand(
      "dry-run",
      "Run a schedule against simulated machines over LCM, as it would go to hardware: one "
      "ccbuild-sim process per gantry (or machines already on the bus with --external), "
      "each job sent with its path in chunks under 64 kB, acknowledged and completed, sent "
      "again when an answer is late (a machine never runs a job twice), every step written "
      "to the SQLite journal first (--journal: a dry-run restarted on it goes on where it "
      "stopped). Ends with planned against executed. Exit 0 when every job ran without a "
      "fault, 1 otherwise. Run it in a network namespace of its own (docs/dispatch.md). "
      "Work in progress (issue 13): no site watchdog, machine faults or common layer starts "
      "yet.\n"
      "Examples:\n"
      "  ccbuild dry-run config/buildings/house.yaml\n"
      "  ccbuild dry-run house.schedule.json --speed 100000 --journal house.journal");
  command->add_option("FILE", o->file, "A building, or a schedule JSON")->required();
  command->add_option("--lcm-url", o->lcm_url, "LCM provider URL (ttl=0: this host only)")
      ->capture_default_str();
  command->add_option("--speed", o->speed, "Simulated seconds per real second")
      ->check(number_in(Range::closed(1.0, 1e9), ""))
      ->capture_default_str();
  command->add_option("--journal", o->journal, "Keep the journal here (and resume from it)");
  command->add_option("--state-dir", o->state_dir,
                      "Where the simulated machines keep their records (<machine>.state: the "
                      "jobs each ran), kept after the run; default: a temporary folder");
  command->add_option("--log", o->log,
                      "Write the whole conversation as an LCM log (lcm-logger's format) here");
  command->add_option("--inject", o->inject,
                      "Network faults the simulated machines inject into what they receive and "
                      "send: drop=P, duplicate=P, reorder=P (probabilities per message)");
  command->add_option("--seed", o->seed, "Seed of the injected faults")
      ->check(unsigned_integer())
      ->capture_default_str();
  command
      ->add_option("--retry-after", o->retry_after_s,
                   "Send a job again when not acknowledged within this many real seconds "
                   "(or not done within its expected time plus twice this)")
      ->check(number_in(Range::above(0.0, 600.0), "s"))
      ->capture_default_str();
  command->add_flag("--external", o->external, "Use machines already on the bus");
  command->add_option("--timeout", o->timeout_s, "Give up after this many real seconds")
      ->check(number_in(Range::above(0.0, 86400.0), "s"))
      ->capture_default_str();
  add_input_options(*command, o->input);
  command->callback([o, &exit_code] { run_dry_run(*o, exit_code); });
}

}  // namespace ccbuild::cli
