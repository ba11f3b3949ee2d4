#include "ccbuild/orchestrator/dispatcher.hpp"

#include <sqlite3.h>

#include <chrono>

#include "ccbuild/common/input_error.hpp"
#include "ccbuild_lcm/ccbuild_ack_t.hpp"
#include "ccbuild_lcm/ccbuild_done_t.hpp"
#include "ccbuild_lcm/ccbuild_fault_t.hpp"

namespace ccbuild::orchestrator {
Journal::Journal(const std::filesystem::path& path) : path_(path.string()) {
  if (sqlite3_open(path_.c_str(), &db_) != SQLITE_OK) {
    const std::string why = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    db_ = nullptr;
    throw InputError(path_, 0, "--journal", "SQLite cannot open it: " + why);
  }
  // Written before acted on: the write-ahead log, synced at every commit.
  const char* setup =
      "PRAGMA journal_mode=WAL; PRAGMA synchronous=FULL;"
      "CREATE TABLE IF NOT EXISTS job_state (job_id INTEGER PRIMARY KEY, machine_id TEXT NOT "
      "NULL, state TEXT NOT NULL, utime INTEGER NOT NULL);";
  char* error = nullptr;
  if (sqlite3_exec(db_, setup, nullptr, nullptr, &error) != SQLITE_OK) {
    const std::string why = error ? error : "unknown";
    sqlite3_free(error);
    sqlite3_close(db_);
    db_ = nullptr;
    throw InputError(path_, 0, "--journal", "not a ccbuild dispatch journal: " + why);
  }
}

Journal::~Journal() {
  sqlite3_close(db_);
}

void Journal::record(std::int64_t job_id, const std::string& machine_id, const std::string& state) {
  const auto started = std::chrono::steady_clock::now();
  sqlite3_stmt* stmt = nullptr;
  CCBUILD_CHECK(sqlite3_prepare_v2(db_,
                                   "INSERT INTO job_state (job_id, machine_id, state, utime) "
                                   "VALUES (?1, ?2, ?3, ?4) ON CONFLICT(job_id) DO UPDATE SET "
                                   "state = excluded.state, utime = excluded.utime",
                                   -1, &stmt, nullptr) == SQLITE_OK,
                "journal: " + std::string(sqlite3_errmsg(db_)));
  sqlite3_bind_int64(stmt, 1, job_id);
  sqlite3_bind_text(stmt, 2, machine_id.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(stmt, 3, state.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_int64(stmt, 4, machine::utime_now());
  const int status = sqlite3_step(stmt);
  sqlite3_finalize(stmt);
  CCBUILD_CHECK(status == SQLITE_DONE, "journal: " + std::string(sqlite3_errmsg(db_)));
  ++writes_;
  write_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
}

std::map<std::int64_t, std::string> Journal::states() const {
  std::map<std::int64_t, std::string> out;
  sqlite3_stmt* stmt = nullptr;
  CCBUILD_CHECK(sqlite3_prepare_v2(db_, "SELECT job_id, state FROM job_state", -1, &stmt,
                                   nullptr) == SQLITE_OK,
                "journal: " + std::string(sqlite3_errmsg(db_)));
  while (sqlite3_step(stmt) == SQLITE_ROW)
    out[sqlite3_column_int64(stmt, 0)] =
        reinterpret_cast<const char*>(sqlite3_column_text(stmt, 1));
  sqlite3_finalize(stmt);
  return out;
}

Dispatcher::Dispatcher(machine::Bus& bus, std::vector<DispatchJob> jobs, Journal& journal,
                       DispatchOptions options)
    : bus_(bus), jobs_(std::move(jobs)), journal_(journal), options_(options) {
  const auto states = journal_.states();
  for (std::size_t k = 0; k < jobs_.size(); ++k) {
    const auto& job = jobs_[k].job;
    Queue& q = queues_[job.machine_id];
    q.jobs.push_back(k);
    const auto it = states.find(job.job_id);
    if (it != states.end() && it->second == "done" && q.next + 1 == q.jobs.size()) ++q.next;
  }
  for (const auto& [machine, q] : queues_) {
    bus_.subscribe<ccbuild_lcm::ccbuild_ack_t>(
        machine::channel("ACK", machine),
        [this](const ccbuild_lcm::ccbuild_ack_t& a) { on_ack(a); });
    bus_.subscribe<ccbuild_lcm::ccbuild_done_t>(
        machine::channel("DONE", machine),
        [this](const ccbuild_lcm::ccbuild_done_t& d) { on_done(d); });
    bus_.subscribe<ccbuild_lcm::ccbuild_fault_t>(
        machine::channel("FAULT", machine),
        [this](const ccbuild_lcm::ccbuild_fault_t&) { ++faults_; });
  }
}

bool Dispatcher::finished() const {
  for (const auto& [machine, q] : queues_)
    if (q.next < q.jobs.size()) return false;
  return true;
}

void Dispatcher::send(std::size_t index) {
  DispatchJob& d = jobs_[index];
  d.job.utime = machine::utime_now();
  d.job.seq = ++seq_;
  bus_.publish(machine::channel("JOB", d.job.machine_id), d.job);
  for (auto& c : d.chunks) {
    c.utime = d.job.utime;
    c.seq = ++seq_;
    bus_.publish(machine::channel("PATH", d.job.machine_id), c);
  }
}

Dispatcher::Queue* Dispatcher::queue_of(const std::string& machine_id, std::int64_t job_id) {
  const auto it = queues_.find(machine_id);
  if (it == queues_.end()) return nullptr;
  Queue& q = it->second;
  // Only the job in flight counts: a repeat about an earlier one is harmless and ignored.
  if (q.next >= q.jobs.size() || jobs_[q.jobs[q.next]].job.job_id != job_id) return nullptr;
  return &q;
}

void Dispatcher::on_ack(const ccbuild_lcm::ccbuild_ack_t& ack) {
  Queue* q = queue_of(ack.machine_id, ack.job_id);
  if (!q || q->wait != Queue::Wait::kAck) return;
  if (!ack.accepted) {
    journal_.record(ack.job_id, ack.machine_id, "refused");
    q->wait = Queue::Wait::kSend;  // sent again after the timeout; a fault says why
    return;
  }
  journal_.record(ack.job_id, ack.machine_id, "acked");
  q->wait = Queue::Wait::kDone;
  q->waited_s = 0.0;
}

void Dispatcher::on_done(const ccbuild_lcm::ccbuild_done_t& done) {
  Queue* q = queue_of(done.machine_id, done.job_id);
  if (!q) return;
  journal_.record(done.job_id, done.machine_id, "done");
  executed_[done.job_id] = {done.started_s, done.finished_s};
  ++q->next;
  q->wait = Queue::Wait::kSend;
  q->waited_s = 0.0;
}

void Dispatcher::step(double real_dt_s) {
  for (auto& [machine, q] : queues_) {
    if (q.next >= q.jobs.size()) continue;
    const std::size_t index = q.jobs[q.next];
    const auto& job = jobs_[index].job;
    q.waited_s += real_dt_s;
    const double done_within_s = job.duration_s / options_.speed + options_.done_slack_s;
    const bool due = q.wait == Queue::Wait::kSend ||
                     (q.wait == Queue::Wait::kAck && q.waited_s > options_.ack_timeout_s) ||
                     (q.wait == Queue::Wait::kDone && q.waited_s > done_within_s);
    if (!due) continue;
    if (q.wait != Queue::Wait::kSend || q.waited_s > real_dt_s) ++resent_;
    journal_.record(job.job_id, job.machine_id, "sent");  // before it goes out
    send(index);
    q.wait = q.wait == Queue::Wait::kDone ? Queue::Wait::kDone : Queue::Wait::kAck;
    q.waited_s = 0.0;
  }
}

}  // namespace ccbuild::orchestrator
