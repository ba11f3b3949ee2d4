#pragma once
// Sends a schedule's jobs to the machines and sees them done (docs/dispatch.md). Each
// machine gets its jobs one at a time, in order: a job and its path chunks, then its
// acknowledgement, then its completion. A job not acknowledged in time is sent again,
// and so is one not done in time (a machine acknowledges a job it has seen again and
// never runs it twice). Every change of a job's state is written to the journal (SQLite,
// WAL, synchronous) before it is acted on, so that a dispatcher restarted on the same
// journal sends no completed job again and loses none. Not thread-safe: step() and the
// bus run in one thread.

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "ccbuild/machine/bus.hpp"
#include "ccbuild/orchestrator/dispatch_jobs.hpp"
#include "ccbuild_lcm/ccbuild_ack_t.hpp"
#include "ccbuild_lcm/ccbuild_done_t.hpp"

struct sqlite3;

namespace ccbuild::orchestrator {

/// The dispatch journal: each job's last state ("sent", "acked", "done", "refused").
class Journal {
 public:
  /// Opens or creates the journal at `path` (":memory:" for none on disk). Throws
  /// InputError naming the file when SQLite cannot open it or it is not a journal.
  explicit Journal(const std::filesystem::path& path);
  ~Journal();
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  /// Records a job's state (durably, before the caller acts on it).
  void record(std::int64_t job_id, const std::string& machine_id, const std::string& state);
  /// The state of every job recorded.
  std::map<std::int64_t, std::string> states() const;
  /// Records written, and the wall-clock seconds they took (each synced to disk).
  long writes() const { return writes_; }
  double write_s() const { return write_s_; }

 private:
  sqlite3* db_ = nullptr;
  long writes_ = 0;
  double write_s_ = 0.0;
  std::string path_;
};

struct DispatchOptions {
  double ack_timeout_s = 1.0;  ///< real seconds before a job is sent again
  double done_slack_s = 2.0;   ///< beyond its expected real duration, before it is sent again
  double speed = 10'000.0;     ///< the machines' speed factor (for the expected duration)
};

class Dispatcher {
 public:
  /// Jobs already "done" in `journal` are not sent again. `bus` and `journal` must
  /// outlive the dispatcher.
  Dispatcher(machine::Bus& bus, std::vector<DispatchJob> jobs, Journal& journal,
             DispatchOptions options = {});

  /// Lets `real_dt_s` seconds of real time pass: sends what is due, again what timed out.
  void step(double real_dt_s);
  bool finished() const;
  long resent() const { return resent_; }
  long faults() const { return faults_; }
  /// Completion as the machines reported it: job id -> (start, end), schedule seconds.
  const std::map<std::int64_t, std::pair<double, double>>& executed() const { return executed_; }

 private:
  struct Queue {
    std::vector<std::size_t> jobs;  ///< indices into jobs_, in order
    std::size_t next = 0;           ///< the job in flight (or next to send)
    enum class Wait { kSend, kAck, kDone } wait = Wait::kSend;
    double waited_s = 0.0;
  };
  void send(std::size_t index);
  void on_ack(const ccbuild_lcm::ccbuild_ack_t& ack);
  void on_done(const ccbuild_lcm::ccbuild_done_t& done);
  Queue* queue_of(const std::string& machine_id, std::int64_t job_id);

  machine::Bus& bus_;
  std::vector<DispatchJob> jobs_;
  Journal& journal_;
  DispatchOptions options_;
  std::map<std::string, Queue> queues_;
  std::map<std::int64_t, std::pair<double, double>> executed_;
  std::int64_t seq_ = 0;
  long resent_ = 0, faults_ = 0;
};

}  // namespace ccbuild::orchestrator
