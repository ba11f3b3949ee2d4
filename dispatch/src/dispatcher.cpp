#include "ccbuild/dispatch/dispatcher.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/dispatch/job_messages.hpp"
#include "ccbuild_lcm/ccbuild_ack_t.hpp"
#include "ccbuild_lcm/ccbuild_command_t.hpp"
#include "ccbuild_lcm/ccbuild_done_t.hpp"
#include "ccbuild_lcm/ccbuild_fault_t.hpp"
#include "ccbuild_lcm/ccbuild_status_t.hpp"

namespace ccbuild::dispatch {
namespace {
using ccbuild_lcm::ccbuild_fault_t;

// The journal keeps the wire's fault codes.
static_assert(static_cast<int>(FaultKind::kJointLimit) == ccbuild_fault_t::JOINT_LIMIT &&
              static_cast<int>(FaultKind::kVelocityLimit) == ccbuild_fault_t::VELOCITY_LIMIT &&
              static_cast<int>(FaultKind::kPathMismatch) == ccbuild_fault_t::PATH_MISMATCH &&
              static_cast<int>(FaultKind::kOutOfOrder) == ccbuild_fault_t::OUT_OF_ORDER &&
              static_cast<int>(FaultKind::kColdJoint) == ccbuild_fault_t::COLD_JOINT &&
              static_cast<int>(FaultKind::kTooEarly) == ccbuild_fault_t::TOO_EARLY &&
              static_cast<int>(FaultKind::kAnchorTooYoung) == ccbuild_fault_t::ANCHOR_TOO_YOUNG &&
              static_cast<int>(FaultKind::kPinMissed) == ccbuild_fault_t::PIN_MISSED &&
              static_cast<int>(FaultKind::kPumpClog) == ccbuild_fault_t::PUMP_CLOG &&
              static_cast<int>(FaultKind::kAxisStalled) == ccbuild_fault_t::AXIS_STALLED &&
              static_cast<int>(FaultKind::kMalformed) == ccbuild_fault_t::MALFORMED);

/// The path of `job` from waypoint `from` on, its times from there.
wire::TimedPath rest_of_path(const DispatchJob& job, int from, double& t0_s) {
  const wire::TimedPath& all = job.path;
  const int total = static_cast<int>(all.size());
  from = std::clamp(from, 0, std::max(0, total - 1));
  t0_s = total > 0 ? all.t_s[from] : 0.0;
  wire::TimedPath rest;
  for (int k = from; k < total; ++k)
    rest.push_back(all.t_s[k] - t0_s, all.x_m[k], all.y_m[k], all.z_m[k], all.heading_rad[k],
                   all.extruding[k], all.wall[k], all.piece[k]);
  return rest;
}
}  // namespace

std::string fault_name(FaultKind kind) {
  switch (static_cast<int>(kind)) {
    case ccbuild_fault_t::JOINT_LIMIT:
      return "JOINT_LIMIT";
    case ccbuild_fault_t::VELOCITY_LIMIT:
      return "VELOCITY_LIMIT";
    case ccbuild_fault_t::PATH_MISMATCH:
      return "PATH_MISMATCH";
    case ccbuild_fault_t::OUT_OF_ORDER:
      return "OUT_OF_ORDER";
    case ccbuild_fault_t::COLD_JOINT:
      return "COLD_JOINT";
    case ccbuild_fault_t::TOO_EARLY:
      return "TOO_EARLY";
    case ccbuild_fault_t::ANCHOR_TOO_YOUNG:
      return "ANCHOR_TOO_YOUNG";
    case ccbuild_fault_t::PIN_MISSED:
      return "PIN_MISSED";
    case ccbuild_fault_t::PUMP_CLOG:
      return "PUMP_CLOG";
    case ccbuild_fault_t::AXIS_STALLED:
      return "AXIS_STALLED";
    case ccbuild_fault_t::MALFORMED:
      return "MALFORMED";
    default:
      return "STOP";
  }
}

FaultPolicy policy_of(FaultKind kind) {
  switch (static_cast<int>(kind)) {
    case ccbuild_fault_t::PIN_MISSED:
      return FaultPolicy::kRetry;
    case ccbuild_fault_t::PUMP_CLOG:
      return FaultPolicy::kReplanLayer;
    case ccbuild_fault_t::MALFORMED:
      return FaultPolicy::kIgnore;
    default:
      return FaultPolicy::kStop;
  }
}

std::string to_string(FaultPolicy policy) {
  switch (policy) {
    case FaultPolicy::kRetry:
      return "retry";
    case FaultPolicy::kReplanLayer:
      return "re-plan the rest of the layer";
    case FaultPolicy::kIgnore:
      return "ignore";
    case FaultPolicy::kStop:
      break;
  }
  return "stop";
}

std::string to_string(JobState state) {
  switch (state) {
    case JobState::kSent:
      return "sent";
    case JobState::kAcked:
      return "acked";
    case JobState::kRefused:
      return "refused";
    case JobState::kDone:
      return "done";
    case JobState::kClogged:
      return "clogged";
    case JobState::kPinMissed:
      return "pin-missed";
    case JobState::kFailed:
      break;
  }
  return "failed";
}

std::optional<JobState> job_state_named(const std::string& word) {
  for (JobState s : {JobState::kSent, JobState::kAcked, JobState::kRefused, JobState::kDone,
                     JobState::kClogged, JobState::kPinMissed, JobState::kFailed})
    if (to_string(s) == word) return s;
  return std::nullopt;
}

FaultPolicy fault_policy_named(const std::string& text) {
  for (FaultPolicy p : {FaultPolicy::kRetry, FaultPolicy::kReplanLayer, FaultPolicy::kIgnore})
    if (to_string(p) == text) return p;
  return FaultPolicy::kStop;
}

Dispatcher::Dispatcher(wire::Bus& bus, std::vector<DispatchJob> jobs, Journal& journal,
                       DispatchOptions options)
    : bus_(bus), jobs_(std::move(jobs)), journal_(journal), options_(options) {
  schedule_jobs_ = jobs_.size();
  for (std::size_t k = 0; k < jobs_.size(); ++k) {
    CCBUILD_CHECK(k == 0 || jobs_[k - 1].start_s <= jobs_[k].start_s,
                  "dispatcher: jobs out of schedule order");
    origin_.push_back(k);
    index_of_[jobs_[k].job_id] = k;
    queues_[jobs_[k].machine_id].jobs.push_back(k);
  }
  ended_.assign(jobs_.size(), false);
  for (int k = 0; queues_.count(gantry_id(k)); ++k) rail_number_[gantry_id(k)] = k + 1;
  after_layer_.assign(jobs_.size(), false);
  // Back where the journal left off: the jobs ended, and the recovery jobs they made (in
  // order, so that the same ones are made again).
  const auto rows = journal_.rows();
  const std::vector<Replan> journalled = journal_.replans();
  std::size_t applied = 0;
  while (applied < journalled.size() && index_of_.count(journalled[applied].job_id))
    apply(journalled[applied++]);
  for (std::size_t k = 0; k < jobs_.size(); ++k) {  // jobs_ grows as recoveries are made
    const auto it = rows.find(jobs_[k].job_id);
    if (it == rows.end()) continue;
    const JournalRow& row = it->second;
    if (row.state == JobState::kDone) {
      ended_[k] = true;
      executed_[jobs_[k].job_id] = {row.started_s, row.finished_s};
      record_laid(k, row);
    } else if (row.state == JobState::kClogged || row.state == JobState::kPinMissed) {
      ended_[k] = true;
      executed_[jobs_[k].job_id] = {row.started_s, row.finished_s};
      record_laid(k, row);
      if (!recover(k, row)) stopped_ = "the journal ends on a fault with no recovery left";
    }
    // The re-plans journalled, each once its job exists (a rest exists once its clog is
    // recovered from): the same starts and treatments as before the restart.
    while (applied < journalled.size() && index_of_.count(journalled[applied].job_id))
      apply(journalled[applied++]);
  }
  if (applied < journalled.size())
    stopped_ = "the journal re-plans job " + std::to_string(journalled[applied].job_id) +
               ", which this run does not have";
  // The delay: set by the last re-plan of a layer's start, then raised by
  // every job that ended after it (those planned from that start on).
  double since_s = -std::numeric_limits<double>::infinity();
  for (const Replan& r : replans_) {
    const std::size_t k = index_of_.at(r.job_id);
    if (origin_[k] != k) continue;  // a rest's start: the delay is not set by it
    delay_s_ = r.delay_s;
    since_s = jobs_[k].start_s;
  }
  for (const auto& [id, times] : executed_) {
    const std::size_t k = index_of_.at(id);
    const DispatchJob& o = jobs_[origin_[k]];
    const auto row = rows.find(id);
    if (row != rows.end() && row->second.state == JobState::kDone && o.start_s >= since_s)
      delay_s_ = std::max(delay_s_, times.second - (o.start_s + o.duration_s));
  }
  for (auto& [machine, q] : queues_)
    while (q.next < q.jobs.size() && ended_[q.jobs[q.next]]) ++q.next;
  for (const auto& f : journal_.faults()) fault_records_.push_back(f);
  for (const auto& [machine, q] : queues_) {
    // The edge: messages become the dispatcher's own terms here.
    bus_.subscribe<ccbuild_lcm::ccbuild_ack_t>(wire::channel("ACK", machine),
                                               [this](const ccbuild_lcm::ccbuild_ack_t& a) {
                                                 on_ack(a.machine_id, a.job_id, a.accepted);
                                               });
    bus_.subscribe<ccbuild_lcm::ccbuild_done_t>(
        wire::channel("DONE", machine), [this](const ccbuild_lcm::ccbuild_done_t& d) {
          on_done({d.machine_id, d.job_id, d.ok != 0, d.started_s, d.finished_s, d.stopped_at,
                   static_cast<FaultKind>(d.fault), d.detail});
        });
    bus_.subscribe<ccbuild_lcm::ccbuild_fault_t>(
        wire::channel("FAULT", machine), [this](const ccbuild_lcm::ccbuild_fault_t& f) {
          const auto kind = static_cast<FaultKind>(f.kind);
          on_fault({f.machine_id, f.job_id, kind, f.message, policy_of(kind)});
        });
    bus_.subscribe<ccbuild_lcm::ccbuild_status_t>(
        wire::channel("STATUS", machine),
        [this](const ccbuild_lcm::ccbuild_status_t& s) { on_status(s); });
  }
}

std::vector<std::pair<std::string, double>> Dispatcher::silent(double silence_s) const {
  std::vector<std::pair<std::string, double>> out;
  for (const auto& [machine, q] : queues_)
    if (!q.heard || q.silent_s > silence_s) out.emplace_back(machine, q.silent_s);
  return out;
}

bool Dispatcher::finished() const {
  if (stopped_) return true;
  for (const auto& [machine, q] : queues_)
    if (q.next < q.jobs.size()) return false;
  return true;
}

void Dispatcher::stop(const std::string& reason) {
  if (stopped_) return;
  journal_.record_fault({"", 0, FaultKind::kNone, reason, FaultPolicy::kStop});
  stopped_ = reason;
  for (const auto& [machine, q] : queues_) {
    ccbuild_lcm::ccbuild_command_t c;
    c.utime = wire::utime_now();
    c.machine_id = machine;
    c.seq = ++seq_;
    c.command = ccbuild_lcm::ccbuild_command_t::PAUSE;
    c.reason = reason;
    bus_.publish(wire::channel("COMMAND", machine), c);
  }
}

namespace {
/// The rail coordinate of waypoint k of a job's path.
double rail_at(const DispatchJob& d, machine::RailAxis axis, bool last) {
  const std::size_t k = last ? d.path.size() - 1 : 0;
  return machine::rail_coordinate(d.path.x_m[k], d.path.y_m[k], axis);
}
}  // namespace

bool Dispatcher::insert_after(std::size_t after, std::size_t origin, DispatchJob job,
                              bool after_layer, std::int64_t skip_ids) {
  // Recovery jobs take the ids after their origin's (ids go in tens).
  std::int64_t id = jobs_[origin].job_id;
  for (const auto& [other, k] : index_of_)
    if (origin_[k] == origin) id = std::max(id, other);
  id += 1 + skip_ids;
  if (id >= jobs_[origin].job_id + 10) return false;
  job.job_id = id;
  Queue& q = queues_[job.machine_id];
  const auto at = std::find(q.jobs.begin(), q.jobs.end(), after);
  // After `after` and after what was inserted after it already.
  auto to = at + 1;
  while (to != q.jobs.end() && origin_[*to] == origin && *to != origin) ++to;
  const std::size_t offset = static_cast<std::size_t>(to - q.jobs.begin());
  jobs_.push_back(std::move(job));
  origin_.push_back(origin);
  ended_.push_back(false);
  after_layer_.push_back(after_layer);
  index_of_[id] = jobs_.size() - 1;
  q.jobs.insert(q.jobs.begin() + static_cast<std::ptrdiff_t>(offset), jobs_.size() - 1);
  return true;
}

void Dispatcher::insert_before(std::size_t before, DispatchJob job) {
  Queue& q = queues_[jobs_[before].machine_id];
  const auto at = std::find(q.jobs.begin(), q.jobs.end(), before);
  const std::ptrdiff_t offset = at - q.jobs.begin();
  index_of_[job.job_id] = jobs_.size();
  jobs_.push_back(std::move(job));
  origin_.push_back(origin_[before]);
  ended_.push_back(false);
  after_layer_.push_back(false);
  q.jobs.insert(q.jobs.begin() + offset, jobs_.size() - 1);
}

bool Dispatcher::clearing_moves(std::size_t index, const DispatchJob& rest, double start_s,
                                std::vector<std::pair<std::size_t, DispatchJob>>& moves) const {
  if (options_.gantry_width_m <= 0.0 || rest.path.size() == 0) return true;
  const machine::RailAxis axis = options_.rail_axis;
  double lo = 1e300, hi = -1e300;
  for (std::size_t k = 0; k < rest.path.size(); ++k) {
    const double r = machine::rail_coordinate(rest.path.x_m[k], rest.path.y_m[k], axis);
    lo = std::min(lo, r);
    hi = std::max(hi, r);
  }
  // Where the layer's other gantries stand once their jobs of this layer are done.
  const double layer_start_s = jobs_[origin_[index]].start_s;
  const auto number = [this](const std::string& id) {
    const auto it = rail_number_.find(id);
    return it == rail_number_.end() ? 0 : it->second;
  };
  const int mine = number(jobs_[index].machine_id);
  std::map<int, std::size_t> others;  // gantry number -> its job of this layer
  for (std::size_t k = 0; k < jobs_.size(); ++k)
    if (origin_[k] == k && k != origin_[index] && jobs_[k].start_s == layer_start_s &&
        jobs_[k].path.size() > 0)
      others[number(jobs_[k].machine_id)] = k;
  auto move = [&](std::size_t k, double to_rail_m) {
    const DispatchJob& d = jobs_[k];
    const auto& c = d.path;
    const std::size_t last = c.size() - 1;
    DispatchJob m = d;
    m.kind = JobKind::kTravel;
    m.plan = "";
    m.start_s = start_s;
    const double from_m = machine::rail_coordinate(c.x_m[last], c.y_m[last], axis);
    m.duration_s = std::abs(to_rail_m - from_m) / options_.travel_speed_m_s;
    m.detail =
        printf_string("%s moves clear along the rails to %.3f m (the rest of job %lld)",
                      d.machine_id.c_str(), to_rail_m, static_cast<long long>(jobs_[index].job_id));
    const bool along_y = axis == machine::RailAxis::kY;
    const double to_x_m = along_y ? c.x_m[last] : to_rail_m;
    const double to_y_m = along_y ? to_rail_m : c.y_m[last];
    wire::TimedPath p;
    p.push_back(0.0, c.x_m[last], c.y_m[last], c.z_m[last], c.heading_rad[last], false, 0, 0);
    p.push_back(m.duration_s, to_x_m, to_y_m, c.z_m[last], c.heading_rad[last], false, 0, 0);
    m.path = std::move(p);
    moves.emplace_back(k, std::move(m));
  };
  // Up the rails from this gantry: each at least a gantry width past the one before.
  double need_m = hi + options_.gantry_width_m;
  for (auto it = others.upper_bound(mine); it != others.end(); ++it) {
    const double at_m = rail_at(jobs_[it->second], axis, true);
    if (at_m >= need_m) break;
    if (need_m > options_.rail_max_m) return false;
    move(it->second, need_m);
    need_m += options_.gantry_width_m;
  }
  need_m = lo - options_.gantry_width_m;
  for (auto it = std::make_reverse_iterator(others.lower_bound(mine)); it != others.rend(); ++it) {
    const double at_m = rail_at(jobs_[it->second], axis, true);
    if (at_m <= need_m) break;
    if (need_m < options_.rail_min_m) return false;
    move(it->second, need_m);
    need_m -= options_.gantry_width_m;
  }
  return true;
}

bool Dispatcher::recover(std::size_t index, const JournalRow& row) {
  const std::size_t origin = origin_[index];
  const DispatchJob ended = jobs_[index];
  if (row.state == JobState::kClogged) {
    DispatchJob purge = ended;
    purge.kind = JobKind::kPurge;
    purge.start_s = row.finished_s;
    purge.duration_s = options_.purge_s;
    purge.plan = "";
    purge.detail = "purge after the clog in job " + std::to_string(ended.job_id);
    purge.path = {};
    DispatchJob rest = ended;
    double t0_s = 0.0;
    rest.path = rest_of_path(ended, row.stopped_at, t0_s);
    rest.start_s = row.finished_s + options_.purge_s;
    rest.duration_s = ended.duration_s - t0_s;
    rest.detail = ended.detail + ", the rest from waypoint " + std::to_string(row.stopped_at) +
                  " (after a clog)";
    std::vector<std::pair<std::size_t, DispatchJob>> moves;
    if (!clearing_moves(index, rest, row.finished_s, moves)) return false;
    // The rest waits for the layer's other jobs and the moves: it runs alone.
    // (An id is left free before the rest, for a planned joint's treatment if it needs one.)
    if (!insert_after(index, origin, purge, false) || !insert_after(index, origin, rest, true, 1))
      return false;
    for (auto& [k, m] : moves)
      if (!insert_after(k, k, std::move(m), false)) return false;
    return true;
  }
  if (row.state == JobState::kPinMissed) {
    int attempts = 1;
    for (std::size_t k = 0; k < jobs_.size(); ++k) attempts += k != origin && origin_[k] == origin;
    if (attempts >= options_.pin_attempts) return false;
    DispatchJob again = ended;
    again.detail = jobs_[origin].detail + ", attempt " + std::to_string(attempts + 1);
    return insert_after(index, origin, std::move(again), false);
  }
  return false;
}

bool Dispatcher::released(std::size_t index) const {
  // Every job planned to start before this one's (its origin's) has ended, and so have
  // the jobs recovering from them: a layer's jobs go out together. A job that runs alone
  // also waits for every other job of its layer.
  const double start_s = jobs_[origin_[index]].start_s;
  const auto blocks = [&](std::size_t k) {
    if (ended_[k] || k == index) return false;
    const double other_s = jobs_[origin_[k]].start_s;
    return other_s < start_s || (after_layer_[index] && other_s == start_s);
  };
  // The schedule's jobs are in order of planned start: only those from the first one
  // still open up to this start can hold it; then the few recovery jobs.
  while (first_open_ < schedule_jobs_ && ended_[first_open_]) ++first_open_;
  for (std::size_t k = first_open_; k < schedule_jobs_ && jobs_[k].start_s <= start_s; ++k)
    if (blocks(k)) return false;
  for (std::size_t k = schedule_jobs_; k < jobs_.size(); ++k)
    if (blocks(k)) return false;
  return true;
}

void Dispatcher::send(std::size_t index) {
  DispatchJob d = jobs_[index];
  d.start_s = start_of(index);
  if (const auto shortened = duration_at_.find(index); shortened != duration_at_.end())
    d.duration_s = shortened->second;
  JobMessages m = messages_of(d);
  m.job.utime = wire::utime_now();
  m.job.seq = ++seq_;
  bus_.publish(wire::channel("JOB", d.machine_id), m.job);
  for (auto& c : m.chunks) {
    c.utime = m.job.utime;
    c.seq = ++seq_;
    bus_.publish(wire::channel("PATH", d.machine_id), c);
  }
}

Dispatcher::Queue* Dispatcher::queue_of(const std::string& machine_id, std::int64_t job_id) {
  const auto it = queues_.find(machine_id);
  if (it == queues_.end()) return nullptr;
  Queue& q = it->second;
  // Only the job in flight counts: a repeat about an earlier one is harmless and ignored.
  if (q.next >= q.jobs.size() || jobs_[q.jobs[q.next]].job_id != job_id) return nullptr;
  return &q;
}

void Dispatcher::on_status(const ccbuild_lcm::ccbuild_status_t& s) {
  const auto it = queues_.find(s.machine_id);
  if (it == queues_.end()) return;
  Queue& q = it->second;
  q.heard = true;
  q.silent_s = 0.0;
  if (q.next >= q.jobs.size() || q.wait == Queue::Wait::kSend || stopped_) return;
  const std::int64_t job_id = jobs_[q.jobs[q.next]].job_id;
  // What a lost ACK or DONE would have said, learnt from the status: the job in flight
  // is the machine's current one (accepted), or the last one it ended.
  if (s.last_job_id == job_id) {
    on_done({s.machine_id, job_id, s.last_fault == 0, s.last_started_s, s.last_finished_s,
             s.last_stopped_at, static_cast<FaultKind>(s.last_fault), "(from its status)"});
    return;
  }
  if (s.current_job_id == job_id && q.wait == Queue::Wait::kAck) on_ack(s.machine_id, job_id, true);
}

bool Dispatcher::awaiting_machines() const {
  if (stopped_) return false;
  for (const auto& [machine, q] : queues_) {
    if (q.next >= q.jobs.size() || !q.heard) continue;
    if (q.wait == Queue::Wait::kAck) return true;
    if (q.wait == Queue::Wait::kSend && released(q.jobs[q.next])) return true;
  }
  return false;
}

void Dispatcher::on_ack(const std::string& machine_id, std::int64_t job_id, bool accepted) {
  Queue* q = queue_of(machine_id, job_id);
  if (!q || q->wait != Queue::Wait::kAck || stopped_) return;
  if (!accepted) {
    journal_.record(job_id, machine_id, JobState::kRefused);
    q->wait = Queue::Wait::kSend;  // sent again after the timeout; its fault's policy rules
    return;
  }
  journal_.record(job_id, machine_id, JobState::kAcked);
  q->wait = Queue::Wait::kDone;
  q->waited_s = 0.0;
}

void Dispatcher::on_fault(const FaultRecord& record) {
  // Once per fault: a machine repeats a job's fault only with a new message.
  for (const auto& seen : fault_records_)
    if (seen.machine_id == record.machine_id && seen.job_id == record.job_id &&
        seen.kind == record.kind && seen.message == record.message)
      return;
  journal_.record_fault(record);
  fault_records_.push_back(record);
  if (record.policy == FaultPolicy::kStop)
    stop(record.machine_id + ": " + fault_name(record.kind) + ": " + record.message);
}

void Dispatcher::advance(Queue& q, std::size_t index, const JournalRow& row) {
  ended_[index] = true;
  executed_[jobs_[index].job_id] = {row.started_s, row.finished_s};
  record_laid(index, row);
  ++q.next;
  q.wait = Queue::Wait::kSend;
  q.waited_s = 0.0;
  q.attempts = 0;
}

void Dispatcher::on_done(const JobEnd& done) {
  Queue* q = queue_of(done.machine_id, done.job_id);
  if (!q) return;
  const std::size_t index = q->jobs[q->next];
  JournalRow row{done.machine_id, JobState::kDone, done.started_s, done.finished_s,
                 done.stopped_at};
  if (done.ok) {
    journal_.record(done.job_id, row);
    const DispatchJob& o = jobs_[origin_[index]];
    delay_s_ = std::max(delay_s_, done.finished_s - (o.start_s + o.duration_s));
    advance(*q, index, row);
    return;
  }
  // A clog and a missed pin have recoveries; any other fault fails the job.
  const std::optional<JobState> recoverable =
      done.fault == FaultKind::kPumpClog    ? std::optional(JobState::kClogged)
      : done.fault == FaultKind::kPinMissed ? std::optional(JobState::kPinMissed)
                                            : std::nullopt;
  if (!recoverable) {
    journal_.record(done.job_id, JournalRow{done.machine_id, JobState::kFailed, done.started_s,
                                            done.finished_s, done.stopped_at});
    advance(*q, index, row);
    stop(done.machine_id + ": job " + std::to_string(done.job_id) + " ended on " +
         fault_name(done.fault) + ": " + done.detail);
    return;
  }
  row.state = *recoverable;
  journal_.record(done.job_id, row);  // before the recovery jobs are made
  if (!recover(index, row)) {
    advance(*queue_of(done.machine_id, done.job_id), index, row);
    stop(done.machine_id + ": job " + std::to_string(done.job_id) + " (" + to_string(row.state) +
         "): no recovery left");
    return;
  }
  advance(*queue_of(done.machine_id, done.job_id), index, row);
}

void Dispatcher::step(double real_dt_s) {
  if (stopped_) return;
  for (auto& [machine, q] : queues_) {
    q.silent_s += real_dt_s;
    if (q.next >= q.jobs.size() || !q.heard) continue;  // nothing to a machine not heard
    const std::size_t index = q.jobs[q.next];
    const DispatchJob& job = jobs_[index];
    q.waited_s += real_dt_s;
    if (q.wait == Queue::Wait::kSend && !released(index)) {
      q.waited_s = 0.0;
      continue;
    }
    // Each time a job goes out again, its answer is waited for twice as long (up to
    // retry_max_s): a LAN answers in milliseconds, a busy machine later.
    const double backoff = std::ldexp(1.0, std::min(q.attempts, 20));
    const double ack_within_s = std::min(options_.ack_timeout_s * backoff, options_.retry_max_s);
    const double done_within_s =
        job.duration_s / options_.speed + std::min(options_.done_slack_s * backoff, 60.0);
    const bool due = q.wait == Queue::Wait::kSend ||
                     (q.wait == Queue::Wait::kAck && q.waited_s > ack_within_s) ||
                     (q.wait == Queue::Wait::kDone && q.waited_s > done_within_s);
    if (!due) continue;
    if (q.wait == Queue::Wait::kSend) {
      // The first time out: its start re-planned from what the machines did (which may
      // put a treatment before it, or stop the run).
      replan(index);
      if (stopped_) return;
      if (q.jobs[q.next] != index) {
        q.waited_s = 0.0;
        continue;  // the treatment goes first, at the next step
      }
    }
    if (q.wait != Queue::Wait::kSend) {
      ++resent_;
      ++q.attempts;
    } else {
      q.attempts = 0;
    }
    journal_.record(job.job_id, job.machine_id, JobState::kSent);  // before it goes out
    send(index);
    q.wait = q.wait == Queue::Wait::kDone ? Queue::Wait::kDone : Queue::Wait::kAck;
    q.waited_s = 0.0;
  }
}

}  // namespace ccbuild::dispatch
