// The dispatch journal (SQLite): each job's last state, every fault and every re-plan
// (docs/dispatch.md, "The dispatcher and its journal").

#include <sqlite3.h>

#include <chrono>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/dispatch/dispatcher.hpp"

namespace ccbuild::dispatch {
namespace {
/// A statement, its parameters bound by the caller; finalized when it goes.
class Statement {
 public:
  Statement(sqlite3* db, const char* sql_text) {
    CCBUILD_CHECK(sqlite3_prepare_v2(db, sql_text, -1, &stmt_, nullptr) == SQLITE_OK,
                  "journal: " + std::string(sqlite3_errmsg(db)));
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  sqlite3_stmt* operator*() const { return stmt_; }

 private:
  sqlite3_stmt* stmt_ = nullptr;
};

/// Runs a prepared INSERT, counting it and the time since `started` in the journal's figures.
void step_write(sqlite3* db, sqlite3_stmt* s, std::chrono::steady_clock::time_point started,
                long& writes, double& write_s) {
  // A write that fails (a full disk, a file-size limit) stops the run as bad input does,
  // naming the journal: what was written before stays, and a resume starts from it.
  if (sqlite3_step(s) != SQLITE_DONE) {
    const char* file = sqlite3_db_filename(db, "main");
    throw InputError(file ? file : "", 0, "--journal",
                     "cannot write the journal: " + std::string(sqlite3_errmsg(db)) +
                         " (a full disk?); every step written before it is kept");
  }
  ++writes;
  write_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
}

std::string text(sqlite3_stmt* s, int column) {
  const auto* t = sqlite3_column_text(s, column);
  return t ? reinterpret_cast<const char*>(t) : "";
}
}  // namespace

Journal::Journal(const std::filesystem::path& path, const std::string& schedule_sha256)
    : path_(path.string()) {
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
      "NULL, state TEXT NOT NULL, started_s REAL NOT NULL, finished_s REAL NOT NULL, "
      "stopped_at INTEGER NOT NULL, utime INTEGER NOT NULL);"
      "CREATE TABLE IF NOT EXISTS fault (id INTEGER PRIMARY KEY AUTOINCREMENT, machine_id TEXT "
      "NOT NULL, job_id INTEGER NOT NULL, kind INTEGER NOT NULL, message TEXT NOT NULL, policy "
      "TEXT NOT NULL, utime INTEGER NOT NULL);"
      "CREATE TABLE IF NOT EXISTS meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);"
      "CREATE TABLE IF NOT EXISTS replan (id INTEGER PRIMARY KEY AUTOINCREMENT, job_id INTEGER "
      "NOT NULL, what TEXT NOT NULL, start_s REAL NOT NULL, delay_s REAL NOT NULL, duration_s "
      "REAL NOT NULL, "
      "treatment_job_id INTEGER NOT NULL, treatment_start_s REAL NOT NULL, "
      "treatment_s REAL NOT NULL, detail TEXT NOT NULL, utime INTEGER NOT NULL);"
      "SELECT job_id, machine_id, state, started_s, finished_s, stopped_at FROM job_state LIMIT 0;";
  char* error = nullptr;
  if (sqlite3_exec(db_, setup, nullptr, nullptr, &error) != SQLITE_OK) {
    const std::string why = error ? error : "unknown";
    sqlite3_free(error);
    sqlite3_close(db_);
    db_ = nullptr;
    throw InputError(path_, 0, "--journal", "not a ccbuild dispatch journal: " + why);
  }
  if (schedule_sha256.empty()) return;
  // Which schedule it belongs to: a journal resumes that schedule only.
  std::string recorded;
  long rows = 0;
  {
    Statement s(db_, "SELECT value FROM meta WHERE key = 'schedule_sha256'");
    if (sqlite3_step(*s) == SQLITE_ROW) recorded = text(*s, 0);
    Statement count(db_, "SELECT (SELECT COUNT(*) FROM job_state) + (SELECT COUNT(*) FROM fault)");
    if (sqlite3_step(*count) == SQLITE_ROW) rows = sqlite3_column_int64(*count, 0);
  }
  const auto refuse = [&](const std::string& why) {
    sqlite3_close(db_);
    db_ = nullptr;
    throw InputError(path_, 0, "--journal",
                     why +
                         "; a journal resumes only the schedule it was written for: give a new "
                         "--journal file (or remove this one to start over)");
  };
  if (!recorded.empty() && recorded != schedule_sha256)
    refuse("belongs to another schedule (SHA-256 " + recorded.substr(0, 12) +
           "...), not to this one (" + schedule_sha256.substr(0, 12) + "...)");
  if (recorded.empty() && rows > 0)
    refuse("holds " + std::to_string(rows) +
           " records but names no schedule (an older ccbuild wrote it)");
  if (recorded.empty()) {
    Statement s(db_, "INSERT INTO meta (key, value) VALUES ('schedule_sha256', ?1)");
    sqlite3_bind_text(*s, 1, schedule_sha256.c_str(), -1, SQLITE_TRANSIENT);
    CCBUILD_CHECK(sqlite3_step(*s) == SQLITE_DONE, "journal: " + std::string(sqlite3_errmsg(db_)));
  }
}

Journal::~Journal() {
  sqlite3_close(db_);
}

void Journal::record(std::int64_t job_id, const JournalRow& row) {
  const auto started = std::chrono::steady_clock::now();
  Statement s(db_,
              "INSERT INTO job_state (job_id, machine_id, state, started_s, finished_s, "
              "stopped_at, utime) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7) ON CONFLICT(job_id) DO "
              "UPDATE SET state = excluded.state, started_s = excluded.started_s, finished_s = "
              "excluded.finished_s, stopped_at = excluded.stopped_at, utime = excluded.utime");
  sqlite3_bind_int64(*s, 1, job_id);
  sqlite3_bind_text(*s, 2, row.machine_id.c_str(), -1, SQLITE_TRANSIENT);
  const std::string state = to_string(row.state);
  sqlite3_bind_text(*s, 3, state.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_double(*s, 4, row.started_s);
  sqlite3_bind_double(*s, 5, row.finished_s);
  sqlite3_bind_int(*s, 6, row.stopped_at);
  sqlite3_bind_int64(*s, 7, wire::utime_now());
  step_write(db_, *s, started, writes_, write_s_);
}

void Journal::record_fault(const FaultRecord& f) {
  const auto started = std::chrono::steady_clock::now();
  Statement s(db_,
              "INSERT INTO fault (machine_id, job_id, kind, message, policy, utime) VALUES (?1, "
              "?2, ?3, ?4, ?5, ?6)");
  sqlite3_bind_text(*s, 1, f.machine_id.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_int64(*s, 2, f.job_id);
  sqlite3_bind_int(*s, 3, static_cast<int>(f.kind));
  sqlite3_bind_text(*s, 4, f.message.c_str(), -1, SQLITE_TRANSIENT);
  const std::string policy = to_string(f.policy);
  sqlite3_bind_text(*s, 5, policy.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_int64(*s, 6, wire::utime_now());
  step_write(db_, *s, started, writes_, write_s_);
}

void Journal::record_replan(const Replan& r) {
  const auto started = std::chrono::steady_clock::now();
  Statement s(db_,
              "INSERT INTO replan (job_id, what, start_s, delay_s, duration_s, treatment_job_id, "
              "treatment_start_s, treatment_s, detail, utime) VALUES (?1, ?2, ?3, ?4, ?5, ?6, "
              "?7, ?8, ?9, ?10)");
  sqlite3_bind_int64(*s, 1, r.job_id);
  sqlite3_bind_text(*s, 2, r.what.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_double(*s, 3, r.start_s);
  sqlite3_bind_double(*s, 4, r.delay_s);
  sqlite3_bind_double(*s, 5, r.duration_s);
  sqlite3_bind_int64(*s, 6, r.treatment_job_id);
  sqlite3_bind_double(*s, 7, r.treatment_start_s);
  sqlite3_bind_double(*s, 8, r.treatment_s);
  sqlite3_bind_text(*s, 9, r.detail.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_int64(*s, 10, wire::utime_now());
  step_write(db_, *s, started, writes_, write_s_);
}

std::vector<Replan> Journal::replans() const {
  std::vector<Replan> out;
  Statement s(db_,
              "SELECT job_id, what, start_s, delay_s, duration_s, treatment_job_id, "
              "treatment_start_s, treatment_s, detail FROM replan ORDER BY id");
  while (sqlite3_step(*s) == SQLITE_ROW)
    out.push_back({sqlite3_column_int64(*s, 0), text(*s, 1), sqlite3_column_double(*s, 2),
                   sqlite3_column_double(*s, 3), sqlite3_column_double(*s, 4),
                   sqlite3_column_int64(*s, 5), sqlite3_column_double(*s, 6),
                   sqlite3_column_double(*s, 7), text(*s, 8)});
  return out;
}

std::map<std::int64_t, JournalRow> Journal::rows() const {
  std::map<std::int64_t, JournalRow> out;
  Statement s(db_,
              "SELECT job_id, machine_id, state, started_s, finished_s, stopped_at FROM job_state");
  while (sqlite3_step(*s) == SQLITE_ROW) {
    const std::int64_t id = sqlite3_column_int64(*s, 0);
    const std::string word = text(*s, 2);
    const auto state = job_state_named(word);
    if (!state)
      throw InputError(path_, 0, "job_state",
                       "job " + std::to_string(id) + " has the state '" + echoed(word) +
                           "', not one a dispatch journal records");
    out[id] = {text(*s, 1), *state, sqlite3_column_double(*s, 3), sqlite3_column_double(*s, 4),
               sqlite3_column_int(*s, 5)};
  }
  return out;
}

std::map<std::int64_t, JobState> Journal::states() const {
  std::map<std::int64_t, JobState> out;
  for (const auto& [id, row] : rows()) out[id] = row.state;
  return out;
}

std::vector<FaultRecord> Journal::faults() const {
  std::vector<FaultRecord> out;
  Statement s(db_, "SELECT machine_id, job_id, kind, message, policy FROM fault ORDER BY id");
  while (sqlite3_step(*s) == SQLITE_ROW)
    out.push_back({text(*s, 0), sqlite3_column_int64(*s, 1),
                   static_cast<FaultKind>(sqlite3_column_int(*s, 2)), text(*s, 3),
                   fault_policy_named(text(*s, 4))});
  return out;
}

}  // namespace ccbuild::dispatch
