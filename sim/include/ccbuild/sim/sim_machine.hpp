#pragma once
// The simulated machine behind `ccbuild-sim` (docs/dispatch.md): it takes jobs over the
// bus as a real machine would, runs them on its own clock at a speed factor, follows their
// timed paths (its status reports where the nozzle is), and keeps its own record of what
// it ran, in a state file written before it says a job is done, so that a restarted
// machine knows what it has done. A job it has seen is acknowledged again and never run
// twice. It refuses, with a fault: a job older than the last one it ran (out of order), a
// path that does not add up, a path outside its axis ranges or stopper or faster than an
// axis's velocity limit (from its URDF), a layer that would cover its layer below too
// early or too late for the material's interval window (each piece end it deposited is
// kept), and a pin inserted into an anchor younger than the anchor strength needs. Idle time
// between jobs passes at once (a job starts at its planned start or when it arrives, whichever is
// later on the machine's clock). A message seen before (the same utime and seq) or older than two
// minutes is a replay: rejected and logged. Faults of the machine can be injected: a pump clog
// part-way through a layer, a pin that misses its pipe, a crash right after a job is recorded, a
// rail axis that stalls (the drive does not notice: the site watchdog must). Not thread-safe:
// step() and the bus run in one thread.

#include <array>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/rules/age_clock.hpp"
#include "ccbuild/wire/bus.hpp"
#include "ccbuild/wire/timed_path.hpp"
#include "ccbuild_lcm/ccbuild_job_t.hpp"
#include "ccbuild_lcm/ccbuild_path_chunk_t.hpp"
#include "ccbuild_lcm/ccbuild_status_t.hpp"

namespace ccbuild::sim {

struct SimOptions {
  std::string machine_id = "gantry-1";
  /// Follows the site clock (docs/dispatch.md): simulates up to each tick's time, no
  /// further, and answers every tick with a status for that instant, so that the statuses
  /// of all machines describe the same moment. False: its own clock, `speed` times real
  /// time, statuses every `status_period_s` of it, as real hardware runs.
  bool site_clock = false;
  /// On its own clock: simulated seconds per real second while a job runs.
  double speed = 10'000.0;
  /// On its own clock: status (the heartbeat) every this many simulated seconds, and four
  /// times a real second at least. On the site clock: the last status again four times a
  /// real second while no tick comes.
  double status_period_s = 60.0;
  /// The machine's own record: one line per job run ("job_id start_s end_s x_m y_m z_m
  /// heading_rad", where it ended, then the fault it ended on and the waypoints done, if
  /// any), appended and flushed to disk before the job is reported done. Empty: kept in
  /// memory only.
  std::filesystem::path state_file;
  /// Faults of the network, injected into what this machine receives and sends, each
  /// with its probability per message (seeded): a message lost, handled twice, held
  /// back behind the next ones, or held back for up to delay_max_s of real time.
  double drop = 0.0, duplicate = 0.0, reorder = 0.0, delay = 0.0;
  double delay_max_s = 0.5;
  std::uint64_t seed = 1;
  /// Where the nozzle is parked before its first job: x, y, z (m), heading (rad).
  std::array<double, 4> home{0.0, 0.0, 0.0, 0.0};

  /// Its axis ranges, stopper and velocity limits (load_machine: from its URDF); null:
  /// unchecked.
  std::shared_ptr<const machine::MachineModel> model;
  /// Whether nozzle heights are checked against the z range (not on a climbing machine,
  /// whose gantry climbs with the building).
  bool check_z_range = true;
  /// The material's interval window, s: a piece end may be covered this long after the
  /// same end on the layer below was deposited (by this machine), no sooner, no later.
  double min_interval_s = 0.0;
  double max_interval_s = std::numeric_limits<double>::infinity();
  /// With site weather: the concrete's equivalent age against schedule time, in which the
  /// window above and the anchors' age below are counted (empty: real time).
  rules::AgeClock age_clock;
  /// How old an anchor must be before a unit pins into it, s (the age at which the
  /// material reaches the machine's anchor strength): an insertion ("climb ...: insert
  /// U1") sooner after the unit's last pipe ("pipe A1 for unit U1") was placed is refused
  /// (anchor too young). 0: unchecked.
  double anchor_min_age_s = 0.0;

  /// Injected machine faults. The pump clogs part-way through the deposit of this layer
  /// (once):
  int clog_floor = -1, clog_layer = -1;
  /// The first this many pin insertions (climb phases "insert") miss their pipe.
  int pin_failures = 0;
  /// The process ends (exit code 70) right after the N-th job it ran is recorded, before
  /// it says so; 0: never.
  long crash_after_jobs = 0;
  /// From this schedule time on, the rail axis stays where it is while the job goes on
  /// (the drive does not notice); negative: never.
  double stall_at_s = -1.0;
};

/// One line of a simulated machine's record (its state file): a job it ran, when, where it
/// ended, and the fault it ended on, if any.
struct RecordedJob {
  std::int64_t job_id = 0;
  double start_s = 0.0, end_s = 0.0;             ///< schedule s
  std::array<double, 4> at{0.0, 0.0, 0.0, 0.0};  ///< x, y, z (m), heading (rad) at its end
  bool ok = true;
  std::string fault;    ///< "clog" or "pin-missed" when not ok
  int stopped_at = -1;  ///< waypoints done when it ended on a fault
};

/// Reads a machine's record (SimOptions::state_file). Throws InputError naming the file
/// and line when it is not a regular file, is larger than limits::kMaxInputFileBytes, or a
/// line is not "job_id start_s end_s x_m y_m z_m heading_rad [clog|pin-missed
/// waypoints_done]" with finite numbers, a positive job id and end_s not before start_s.
std::vector<RecordedJob> read_machine_record(const std::filesystem::path& path);

/// Why `path` breaks `model`'s limits (a fault kind and the words), or nothing: a
/// waypoint outside an axis range (z only when `check_z_range`) or the stopper is a
/// JOINT_LIMIT; a segment faster along an axis, or in heading, than its velocity limit
/// (beyond what rounding its ends to micro-units, as schedules do, explains) is a
/// VELOCITY_LIMIT.
std::optional<std::pair<std::int8_t, std::string>> limit_breach(const machine::MachineModel& model,
                                                                const wire::TimedPath& path,
                                                                bool check_z_range);

class SimMachine {
 public:
  /// Subscribes to its machine's channels on `bus` (which must outlive it) and reads its
  /// state file when there is one. Throws InputError naming the state file when it
  /// cannot be read or a line is not "job_id start_s end_s x y z heading [fault done]".
  SimMachine(wire::Bus& bus, SimOptions options);

  /// Lets `real_dt_s` seconds of real time pass: runs the current job on (or starts the
  /// next one), publishing progress, completion and status.
  void step(double real_dt_s);

  /// The jobs it ran, in order, from its own record.
  const std::vector<std::int64_t>& executed() const { return executed_; }
  double clock_s() const { return clock_s_; }
  bool busy() const { return current_.has_value(); }
  long faults() const { return faults_; }
  /// Messages rejected as replays (seen before, or too old).
  long replays_rejected() const { return replays_; }
  /// The nozzle's position now: x, y, z (m) and cumulative heading (rad).
  std::array<double, 4> position() const { return position_; }

 private:
  struct Received {
    ccbuild_lcm::ccbuild_job_t job;
    std::map<int, ccbuild_lcm::ccbuild_path_chunk_t> chunks;
    bool complete() const { return static_cast<int>(chunks.size()) == job.chunk_count; }
  };
  struct Running {
    ccbuild_lcm::ccbuild_job_t job;
    wire::TimedPath path;
    double started_s = 0.0;
    double elapsed_s = 0.0;
    double reported = 0.0;  ///< the fraction last published
    /// Injected: the job ends on this fault at stop_elapsed_s, with stop_point waypoints
    /// done.
    std::int8_t stop_fault = 0;
    double stop_elapsed_s = 0.0;
    int stop_point = -1;
    std::string stop_message;
  };

  void on_job(const ccbuild_lcm::ccbuild_job_t& job);
  /// A site clock tick: simulates up to `sim_time_s` and answers with a status.
  void on_clock(std::int64_t tick, double sim_time_s);
  /// Runs the current job (and the next ones that start) on to `t_s` of site time.
  void advance_to(double t_s);
  /// The injected stall, once the clock has reached it.
  void maybe_stall();
  /// Progress in tenths of the running job.
  void report_progress();
  void on_chunk(const ccbuild_lcm::ccbuild_path_chunk_t& chunk);
  void on_command(std::int8_t command, const std::string& reason);
  /// Whether a message with this header was seen before or is too old (then logged).
  bool replayed(const std::string& channel, std::int64_t utime, std::int64_t seq);
  void try_start();
  /// Why the machine refuses to start `job` with `path` at `start_s` (kind, words).
  std::optional<std::pair<std::int8_t, std::string>> refusal(const ccbuild_lcm::ccbuild_job_t& job,
                                                             const wire::TimedPath& path,
                                                             double start_s) const;
  void acknowledge(std::int64_t job_id, bool accepted, bool duplicate, const std::string& reason);
  void fault(std::int64_t job_id, std::int8_t kind, const std::string& message);
  /// Ends the current job (completed, or on its injected fault) and records it.
  void finish(bool completed);
  void publish_done(std::int64_t job_id, double started_s, double finished_s, bool ok,
                    int stopped_at, const std::string& detail);
  void publish_status();
  /// The last status again (a tick repeated, or the heartbeat on the site clock).
  void republish_status();
  void follow(double elapsed_s);
  std::int64_t next_seq() { return ++seq_; }
  /// Takes an incoming message through the injected network faults.
  void arrive(std::function<void()> handle);
  /// Whether an outgoing message is lost (injected).
  bool lost();
  template <class Message>
  void send(const std::string& kind, const Message& message) {
    if (!lost()) bus_.publish(wire::channel(kind, options_.machine_id), message);
  }
  /// A message with its header filled in: utime, this machine, the next seq.
  template <class Message>
  Message stamped() {
    Message m;
    m.utime = wire::utime_now();
    m.machine_id = options_.machine_id;
    m.seq = next_seq();
    return m;
  }

  struct Done {
    double start_s, end_s;
    std::array<double, 4> at;
    bool ok;
    int stopped_at;
    std::string detail;
  };

  wire::Bus& bus_;
  SimOptions options_;
  std::map<std::int64_t, Received> received_;
  std::optional<Running> current_;
  std::vector<std::int64_t> executed_;
  std::map<std::int64_t, Done> done_;
  /// When the last pipe of each climbing unit was placed (schedule s), by unit name.
  std::map<std::string, double> pipes_;
  /// Piece ends deposited per (floor, layer).
  std::map<std::pair<int, int>, rules::DepositIndex> deposited_;  ///< what it laid, site time
  double clock_s_ = 0.0;
  double last_status_s_ = -1e300;
  double real_since_status_s_ = 0.0;
  std::array<double, 4> position_{0.0, 0.0, 0.0, 0.0};
  bool paused_ = false, aborted_ = false, clogged_once_ = false;
  int pin_failures_left_ = 0;
  long jobs_run_here_ = 0;
  std::optional<double> stalled_rail_m_;
  std::int64_t seq_ = 0;
  long faults_ = 0, replays_ = 0;
  std::mt19937_64 rng_;
  std::vector<std::function<void()>> held_;  ///< reordered: handled after the next ones
  /// Delayed: handled once the real time passes the first.
  std::vector<std::pair<double, std::function<void()>>> delayed_;
  double real_s_ = 0.0;  ///< real seconds stepped
  /// Message headers seen (channel kind, utime, seq), the last few thousand.
  std::set<std::tuple<std::string, std::int64_t, std::int64_t>> seen_;
  std::deque<std::tuple<std::string, std::int64_t, std::int64_t>> seen_order_;
  std::int64_t newest_utime_ = 0;
  /// The site clock tick last answered (0: none yet).
  std::int64_t last_tick_ = 0;
  std::optional<ccbuild_lcm::ccbuild_status_t> last_status_;
  /// The last job it ended, repeated in every status.
  struct LastEnded {
    std::int64_t job_id = 0;
    std::int8_t fault = 0;
    double started_s = 0.0, finished_s = 0.0;
    int stopped_at = -1;
  } last_ended_;
};

}  // namespace ccbuild::sim
