#pragma once
// The simulated machine behind `ccbuild-sim` (docs/dispatch.md): it takes jobs over the
// bus as a real machine would, runs them on its own clock at a speed factor, and keeps
// its own record of what it ran, in a state file written before it says a job is done,
// so that a restarted machine knows what it has done. A job it has seen is acknowledged
// again and never run twice; a job older than the last one it ran is refused with a
// fault (out of order), as is a job whose path does not add up. Idle time between jobs
// passes at once (a job starts at its planned start or when it arrives, whichever is
// later on the machine's clock). Not thread-safe: step() and the bus run in one thread.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "ccbuild/machine/bus.hpp"
#include "ccbuild_lcm/ccbuild_job_t.hpp"
#include "ccbuild_lcm/ccbuild_path_chunk_t.hpp"

namespace ccbuild::machine {

struct SimOptions {
  std::string machine_id = "gantry-1";
  /// Simulated seconds per real second while a job runs.
  double speed = 10'000.0;
  /// Status (the heartbeat) every this many simulated seconds, and four times a real
  /// second at least.
  double status_period_s = 60.0;
  /// The machine's own record: one line per job done ("job_id start_s end_s"), appended
  /// and flushed to disk before the job is reported done. Empty: kept in memory only.
  std::filesystem::path state_file;
  /// Faults of the network, injected into what this machine receives and sends, each
  /// with its probability per message (seeded): a message lost, handled twice, or held
  /// back behind the next ones.
  double drop = 0.0, duplicate = 0.0, reorder = 0.0;
  std::uint64_t seed = 1;
};

class SimMachine {
 public:
  /// Subscribes to its machine's channels on `bus` (which must outlive it) and reads its
  /// state file when there is one. Throws InputError naming the state file when it
  /// cannot be read or a line is not "job_id start_s end_s".
  SimMachine(Bus& bus, SimOptions options);

  /// Lets `real_dt_s` seconds of real time pass: runs the current job on (or starts the
  /// next one), publishing progress, completion and status.
  void step(double real_dt_s);

  /// The jobs it ran, in order, from its own record.
  const std::vector<std::int64_t>& executed() const { return executed_; }
  double clock_s() const { return clock_s_; }
  bool busy() const { return current_.has_value(); }
  long faults() const { return faults_; }

 private:
  struct Received {
    ccbuild_lcm::ccbuild_job_t job;
    std::map<int, ccbuild_lcm::ccbuild_path_chunk_t> chunks;
    bool complete() const { return static_cast<int>(chunks.size()) == job.chunk_count; }
  };
  struct Running {
    ccbuild_lcm::ccbuild_job_t job;
    double started_s = 0.0;
    double elapsed_s = 0.0;
    double reported = 0.0;  ///< the fraction last published
  };

  void on_job(const ccbuild_lcm::ccbuild_job_t& job);
  void on_chunk(const ccbuild_lcm::ccbuild_path_chunk_t& chunk);
  void try_start();
  void acknowledge(std::int64_t job_id, bool accepted, bool duplicate, const std::string& reason);
  void fault(std::int64_t job_id, std::int8_t kind, const std::string& message);
  void finish();
  void publish_done(std::int64_t job_id, double started_s, double finished_s);
  void publish_status();
  std::int64_t next_seq() { return ++seq_; }
  /// Takes an incoming message through the injected network faults.
  void arrive(std::function<void()> handle);
  /// Whether an outgoing message is lost (injected).
  bool lost();
  template <class Message>
  void send(const std::string& kind, const Message& message) {
    if (!lost()) bus_.publish(channel(kind, options_.machine_id), message);
  }
  /// A message with its header filled in: utime, this machine, the next seq.
  template <class Message>
  Message stamped() {
    Message m;
    m.utime = utime_now();
    m.machine_id = options_.machine_id;
    m.seq = next_seq();
    return m;
  }

  Bus& bus_;
  SimOptions options_;
  std::map<std::int64_t, Received> received_;
  std::optional<Running> current_;
  std::vector<std::int64_t> executed_;
  std::map<std::int64_t, std::pair<double, double>> done_;  ///< job -> (start, end)
  double clock_s_ = 0.0;
  double last_status_s_ = -1e300;
  double real_since_status_s_ = 0.0;
  std::int64_t seq_ = 0;
  long faults_ = 0;
  std::mt19937_64 rng_;
  std::vector<std::function<void()>> held_;  ///< reordered: handled after the next ones
};

}  // namespace ccbuild::machine
