#pragma once
// Sends a schedule's jobs to the machines and sees them done (docs/dispatch.md). Each
// machine gets its jobs one at a time, in order: a job and its path chunks, then its
// acknowledgement, then its completion. Jobs with the same planned start (a layer's
// deposits on several gantries) are released together, once every earlier job is done,
// with a common start: planned, plus the delay the run has built up. A job not
// acknowledged in time is sent again, and so is one not done in time (a machine
// acknowledges a job it has seen again and never runs it twice). A fault is met by its
// kind's policy (policy_of): retry the job, re-plan the rest of the layer, ignore a
// rejected message, or stop safely (every machine paused, nothing more sent). Every
// change of a job's state and every fault is written to the journal (SQLite, WAL,
// synchronous) before it is acted on, so that a dispatcher restarted on the same journal
// sends no completed job again, loses none, and rebuilds the same recovery jobs. Not
// thread-safe: step() and the bus run in one thread.

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "ccbuild/dispatch/dispatch_jobs.hpp"
#include "ccbuild/dispatch/replan.hpp"
#include "ccbuild/floors/material.hpp"
#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/rules/age_clock.hpp"
#include "ccbuild/wire/bus.hpp"
#include "ccbuild_lcm/ccbuild_status_t.hpp"

struct sqlite3;

namespace ccbuild::dispatch {

/// One job's row in the journal.
/// A job's last state in the journal: sent, acknowledged, refused by its machine, done,
/// ended on a clog or a missed pin (recovered), or failed (the run stopped).
enum class JobState { kSent, kAcked, kRefused, kDone, kClogged, kPinMissed, kFailed };
/// The journal's word for it: "sent", "acked", "refused", "done", "clogged", "pin-missed",
/// "failed" (what its table holds, and outside readers of the journal read).
std::string to_string(JobState state);
std::optional<JobState> job_state_named(const std::string& word);

struct JournalRow {
  std::string machine_id;
  JobState state = JobState::kSent;
  double started_s = 0.0, finished_s = 0.0;  ///< schedule s, once it ended
  int stopped_at = -1;                       ///< waypoints done when it ended on a fault
};

/// What a machine stopped for (docs/dispatch.md); the numbers are the journal's and the
/// wire's codes. kNone: a stop of the dispatcher's own.
enum class FaultKind : std::int8_t {
  kNone = 0,
  kJointLimit = 1,
  kVelocityLimit = 2,
  kPathMismatch = 3,
  kOutOfOrder = 4,
  kColdJoint = 5,
  kTooEarly = 6,
  kAnchorTooYoung = 7,
  kPinMissed = 8,
  kPumpClog = 9,
  kAxisStalled = 10,
  kMalformed = 11,
};

/// A fault as the dispatcher met it.
/// What the dispatcher does about a fault (docs/dispatch.md, "Faults").
enum class FaultPolicy { kRetry, kReplanLayer, kIgnore, kStop };
/// "retry", "re-plan the rest of the layer", "ignore", "stop": the journal's words.
std::string to_string(FaultPolicy policy);
/// The policy the journal names `text`; kStop for words it does not know (the safe side).
FaultPolicy fault_policy_named(const std::string& text);

struct FaultRecord {
  std::string machine_id;
  std::int64_t job_id = 0;
  FaultKind kind = FaultKind::kNone;
  std::string message;
  FaultPolicy policy = FaultPolicy::kStop;  ///< what was done
};

/// The dispatch journal: each job's last state, and every fault and what was done.
class Journal {
 public:
  /// Opens or creates the journal at `path` (":memory:" for none on disk) for the schedule
  /// whose canonical JSON has the SHA-256 `schedule_sha256` (empty: any). A new journal
  /// records it; an existing one must have recorded the same. Throws InputError (field
  /// `--journal`) naming the file when SQLite cannot open it, it is not a journal, it
  /// belongs to another schedule, or it holds jobs but names no schedule.
  explicit Journal(const std::filesystem::path& path, const std::string& schedule_sha256 = "");
  ~Journal();
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  /// Records a job's state (durably, before the caller acts on it).
  void record(std::int64_t job_id, const JournalRow& row);
  void record(std::int64_t job_id, const std::string& machine_id, JobState state) {
    record(job_id, JournalRow{machine_id, state});
  }
  /// Records a fault and the policy applied (durably, before it is applied).
  void record_fault(const FaultRecord& fault);
  /// Every job recorded.
  std::map<std::int64_t, JournalRow> rows() const;
  /// The state of every job recorded.
  std::map<std::int64_t, JobState> states() const;
  std::vector<FaultRecord> faults() const;
  /// Records a re-plan (durably, before it is applied).
  void record_replan(const Replan& replan);
  /// Every re-plan recorded, in order.
  std::vector<Replan> replans() const;
  /// Records written, and the wall-clock seconds they took (each synced to disk).
  long writes() const { return writes_; }
  double write_s() const { return write_s_; }

 private:
  void exec(const std::string& sql_text);
  sqlite3* db_ = nullptr;
  long writes_ = 0;
  double write_s_ = 0.0;
  std::string path_;
};

/// The policy for a fault kind: "retry" (a pin that missed: the same job again, up to
/// three times), "re-plan the rest of the layer" (a clog: purge, then the rest of the
/// path as a new job), "ignore" (a malformed or foreign message the machine rejected:
/// nothing ran), or "stop" (every other kind: pause every machine and send nothing more).
FaultPolicy policy_of(FaultKind kind);
/// The fault kind's name, e.g. "PUMP_CLOG" ("STOP" for kNone and unknown codes).
std::string fault_name(FaultKind kind);

struct DispatchOptions {
  /// Real seconds before a job not acknowledged is sent again; each repeat waits twice as
  /// long, up to retry_max_s.
  double ack_timeout_s = 0.02;
  double retry_max_s = 1.0;
  /// Beyond its expected real duration, before a job not reported done is sent again
  /// (doubling likewise).
  double done_slack_s = 0.25;
  double speed = 10'000.0;  ///< the machines' speed factor (for the expected duration)
  double purge_s = 120.0;   ///< clearing a clogged nozzle, before the rest of its layer
  int pin_attempts = 3;     ///< a pin insertion tried at most this often
  /// For the rest of a clogged layer on shared rails: gantries in the way are moved clear
  /// first (0: not checked).
  double gantry_width_m = 0.0;
  machine::RailAxis rail_axis = machine::RailAxis::kX;
  double rail_min_m = -1e9, rail_max_m = 1e9;  ///< the rail axis's range
  double travel_speed_m_s = 0.5;
  /// The material's window between a piece end and the one laid on it (s); deposits are
  /// re-planned against it from what the machines laid (max 0: not checked).
  double min_interval_s = 0.0, max_interval_s = 0.0;
  /// A planned joint's treatment (s), and the age (s) the layer below must have first.
  double joint_treatment_s = 1800.0, joint_min_age_s = 0.0;
  /// The mix, for the strength of the layers below: with it, a job that may absorb delay
  /// (DispatchJob::absorbs) takes up as much of it as the layers the machines laid can
  /// carry the next layer and its joints keep the minimum (null: never).
  const floors::MaterialProfile* material = nullptr;
  /// With site weather, the concrete's equivalent age against the schedule's time: the
  /// window above is then one of equivalent age, as the scheduler kept it (empty: real
  /// time).
  rules::AgeClock age_clock;
};

class Dispatcher {
 public:
  /// `jobs` in schedule order (by planned start, as jobs_of_schedule gives them). Jobs
  /// already "done" in `journal` are not sent again; the recovery jobs its faults made
  /// are made again. `bus` and `journal` must outlive the dispatcher. Throws
  /// InternalError when `jobs` are out of order.
  Dispatcher(wire::Bus& bus, std::vector<DispatchJob> jobs, Journal& journal,
             DispatchOptions options = {});

  /// Lets `real_dt_s` seconds of real time pass: sends what is due, again what timed out.
  void step(double real_dt_s);
  /// Every job done (then stopped() is empty), or stopped safely.
  bool finished() const;
  /// A machine is about to be sent a job, or has not yet acknowledged one: the site
  /// clock holds until it has (so a job starts at the site time it was meant for).
  bool awaiting_machines() const;
  /// Stops safely: every machine paused, nothing more sent; the reason is journalled.
  void stop(const std::string& reason);
  /// Why it stopped, if it did.
  const std::optional<std::string>& stopped() const { return stopped_; }
  long resent() const { return resent_; }
  long faults() const { return static_cast<long>(fault_records_.size()); }
  const std::vector<FaultRecord>& fault_records() const { return fault_records_; }
  /// Completion as the machines reported it: job id -> (start, end), schedule seconds,
  /// including jobs done before a restart (from the journal).
  const std::map<std::int64_t, std::pair<double, double>>& executed() const { return executed_; }
  /// The job with id `job_id`, or null.
  const DispatchJob* job(std::int64_t job_id) const {
    const auto it = index_of_.find(job_id);
    return it == index_of_.end() ? nullptr : &jobs_[it->second];
  }
  /// The jobs, the schedule's and the recovery jobs made so far.
  const std::vector<DispatchJob>& jobs() const { return jobs_; }
  /// The schedule job that jobs()[index] is or recovers from.
  std::size_t origin_of(std::size_t index) const { return origin_[index]; }
  /// The delay the run has built up against the schedule, s.
  double delay_s() const { return delay_s_; }
  /// The re-plans made (and those a restart found in the journal), in order.
  const std::vector<Replan>& replans() const { return replans_; }
  /// Machines not heard from (no status) for longer than `silence_s` real seconds, or
  /// never, and for how long.
  std::vector<std::pair<std::string, double>> silent(double silence_s) const;

 private:
  struct Queue {
    std::vector<std::size_t> jobs;  ///< indices into jobs_, in order
    std::size_t next = 0;           ///< the job in flight (or next to send)
    enum class Wait { kSend, kAck, kDone } wait = Wait::kSend;
    double waited_s = 0.0;
    int attempts = 0;       ///< times the job in flight was sent again
    bool heard = false;     ///< a status has come from the machine
    double silent_s = 0.0;  ///< real seconds since its last status
  };
  /// A machine's word that a job ended (its DONE message, translated at the edge).
  struct JobEnd {
    std::string machine_id;
    std::int64_t job_id = 0;
    bool ok = false;
    double started_s = 0.0, finished_s = 0.0;  ///< schedule s
    int stopped_at = -1;                       ///< waypoints done when it ended on a fault
    FaultKind fault = FaultKind::kNone;        ///< the fault it ended on (not ok)
    std::string detail;                        ///< for people
  };
  void send(std::size_t index);
  void on_ack(const std::string& machine_id, std::int64_t job_id, bool accepted);
  /// A status: the machine is heard, and a lost ACK or DONE is learnt from it.
  void on_status(const ccbuild_lcm::ccbuild_status_t& status);
  void on_done(const JobEnd& done);
  void on_fault(const FaultRecord& fault);
  Queue* queue_of(const std::string& machine_id, std::int64_t job_id);
  /// After the job at `index` ended as `row`: the jobs that recover from it, inserted
  /// after it in its machine's queue (a purge and the rest of a clogged path, run once
  /// the layer's other jobs are done, with the gantries in its way moved clear first; a
  /// pin again). Returns false when there is no recovery (then the run stops).
  bool recover(std::size_t index, const JournalRow& row);
  /// Puts `job` after the job at `after` in its machine's queue, with the next id of
  /// `origin`'s range. Returns false when the range is full.
  /// `skip_ids` ids are left free before it (for a treatment that may come first).
  bool insert_after(std::size_t after, std::size_t origin, DispatchJob job, bool after_layer,
                    std::int64_t skip_ids = 0);
  /// Puts `job` (with its id) right before the job at `before` in that job's queue; it
  /// recovers from the same schedule job.
  void insert_before(std::size_t before, DispatchJob job);
  /// Moves that clear the rails for `rest` (the rest of a clogged path of the job at
  /// `index`): (job index whose machine moves, the move). Nothing when none is needed;
  /// false when a gantry cannot get out of the way.
  bool clearing_moves(std::size_t index, const DispatchJob& rest, double start_s,
                      std::vector<std::pair<std::size_t, DispatchJob>>& moves) const;
  /// The job ended (done, or recovered from): its machine moves on.
  void advance(Queue& q, std::size_t index, const JournalRow& row);
  bool released(std::size_t index) const;
  /// The start (schedule s) the job at `index` goes out with.
  double start_of(std::size_t index) const;
  /// Before the job at `index` goes out the first time: its start re-planned from what the
  /// machines did (docs/dispatch.md, "When the site runs late"): a deposit's against the
  /// piece ends below it (later, or on a planned joint with its treatment first).
  /// Journals and applies what it changes.
  void replan(std::size_t index);
  /// The start window of `deposits` (one layer's) over the piece ends their machines laid
  /// below them.
  StartWindow window_below(const std::vector<std::size_t>& deposits) const;
  /// The part of replan for a wait that may absorb delay: how far it can be shortened.
  void absorb(std::size_t index);
  /// The part of replan for crew work that may start once the work before it ended.
  void start_when_ready(std::size_t index);
  /// When every layer the machines laid can carry the layer of `deposit` (from the end of
  /// its last deposit, by the mix's strength curve): -inf when none was laid, +inf when
  /// one never can; `bound` names the layer that binds.
  double carried_from_s(const DispatchJob& deposit, std::string& bound) const;
  /// Journals and applies "absorbed": the job at `index` starts at `start_s`, lasts
  /// `duration_s`, and leaves the run `delay_s` behind.
  void record_absorbed(std::size_t index, double start_s, double duration_s, double delay_s,
                       std::string detail);
  /// Applies a re-plan (made now, or read from the journal on a restart).
  void apply(const Replan& replan);
  /// The jobs that start with the job at `index`: a schedule layer's deposits (else itself).
  std::vector<std::size_t> starting_with(std::size_t index) const;
  /// The piece ends the deposit at `index` laid, ended as `row`.
  void record_laid(std::size_t index, const JournalRow& row);

  wire::Bus& bus_;
  std::vector<DispatchJob> jobs_;
  /// Per job: the schedule job it stands for (itself, or the one a recovery job recovers).
  std::vector<std::size_t> origin_;
  std::vector<bool> ended_;             ///< per job: done, or ended and recovered from
  std::size_t schedule_jobs_ = 0;       ///< the schedule's jobs come first in jobs_
  mutable std::size_t first_open_ = 0;  ///< every schedule job before it has ended
  /// Per job: released only once every other job of its layer has ended.
  std::vector<bool> after_layer_;
  std::map<std::int64_t, std::size_t> index_of_;
  Journal& journal_;
  DispatchOptions options_;
  std::map<std::string, Queue> queues_;
  /// Each machine's number in rail order (gantry_id(k) is k + 1; 0 for another name).
  std::map<std::string, int> rail_number_;
  std::map<std::int64_t, std::pair<double, double>> executed_;
  std::vector<FaultRecord> fault_records_;
  std::optional<std::string> stopped_;
  double delay_s_ = 0.0;
  /// Piece ends laid, by (floor, layer, machine), as the machines reported their deposits.
  /// What the machines laid of each (floor, layer), in schedule time.
  std::map<std::pair<int, int>, rules::DepositIndex> laid_;
  /// Per (floor, layer) laid: its bottom (m) and when its last deposit ended (schedule s).
  std::map<std::pair<int, int>, std::pair<double, double>> layer_end_;
  std::set<std::int64_t> decided_;             ///< jobs whose start was re-planned, or needed none
  std::map<std::size_t, double> start_at_;     ///< re-planned starts of jobs that run alone
  std::map<std::size_t, double> duration_at_;  ///< re-planned lengths of shortened waits
  std::vector<Replan> replans_;
  std::int64_t seq_ = 0;
  long resent_ = 0;
};

}  // namespace ccbuild::dispatch
