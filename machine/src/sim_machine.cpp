#include "ccbuild/machine/sim_machine.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild_lcm/ccbuild_ack_t.hpp"
#include "ccbuild_lcm/ccbuild_command_t.hpp"
#include "ccbuild_lcm/ccbuild_done_t.hpp"
#include "ccbuild_lcm/ccbuild_fault_t.hpp"
#include "ccbuild_lcm/ccbuild_progress_t.hpp"
#include "ccbuild_lcm/ccbuild_status_t.hpp"

namespace ccbuild::machine {
SimMachine::SimMachine(Bus& bus, SimOptions options)
    : bus_(bus), options_(std::move(options)), rng_(options_.seed) {
  if (!options_.state_file.empty()) {
    std::ifstream in(options_.state_file);
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
      ++number;
      if (line.empty()) continue;
      std::istringstream words(line);
      std::int64_t job = 0;
      double start_s = 0.0, end_s = 0.0;
      if (!(words >> job >> start_s >> end_s) || job <= 0 || !std::isfinite(end_s))
        throw InputError(options_.state_file.string(), number, "",
                         "expected 'job_id start_s end_s', got '" + line + "'");
      done_[job] = {start_s, end_s};
      executed_.push_back(job);
      clock_s_ = std::max(clock_s_, end_s);
    }
  }
  const std::string id = options_.machine_id;
  bus_.subscribe<ccbuild_lcm::ccbuild_job_t>(
      channel("JOB", id),
      [this](const ccbuild_lcm::ccbuild_job_t& j) { arrive([this, j] { on_job(j); }); });
  bus_.subscribe<ccbuild_lcm::ccbuild_path_chunk_t>(
      channel("PATH", id),
      [this](const ccbuild_lcm::ccbuild_path_chunk_t& c) { arrive([this, c] { on_chunk(c); }); });
  bus_.subscribe<ccbuild_lcm::ccbuild_command_t>(channel("COMMAND", id),
                                                 [](const ccbuild_lcm::ccbuild_command_t&) {});
}

void SimMachine::arrive(std::function<void()> handle) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  if (u(rng_) < options_.drop) return;
  if (u(rng_) < options_.reorder) {
    held_.push_back(std::move(handle));
    return;
  }
  handle();
  if (u(rng_) < options_.duplicate) handle();
  // What was held back comes after this one.
  std::vector<std::function<void()>> held;
  held.swap(held_);
  for (auto& h : held) h();
}

bool SimMachine::lost() {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  return options_.drop > 0.0 && u(rng_) < options_.drop;
}

void SimMachine::on_job(const ccbuild_lcm::ccbuild_job_t& job) {
  if (job.machine_id != options_.machine_id) {
    fault(job.job_id, ccbuild_lcm::ccbuild_fault_t::MALFORMED,
          "a job for machine '" + job.machine_id + "' on " + options_.machine_id + "'s channel");
    return;
  }
  // Seen before: done, or running now. Say so again; never run it twice.
  if (const auto it = done_.find(job.job_id); it != done_.end()) {
    acknowledge(job.job_id, true, true, "");
    publish_done(job.job_id, it->second.first, it->second.second);
    return;
  }
  if (current_ && current_->job.job_id == job.job_id) {
    acknowledge(job.job_id, true, true, "");
    return;
  }
  if (!executed_.empty() && job.job_id < executed_.back()) {
    acknowledge(job.job_id, false, false, "older than the last job run");
    fault(
        job.job_id, ccbuild_lcm::ccbuild_fault_t::OUT_OF_ORDER,
        printf_string("job %lld arrived after job %lld was run", static_cast<long long>(job.job_id),
                      static_cast<long long>(executed_.back())));
    return;
  }
  if (job.chunk_count < 0 || job.point_count < 0 || !(job.duration_s >= 0.0)) {
    acknowledge(job.job_id, false, false, "negative counts or duration");
    fault(job.job_id, ccbuild_lcm::ccbuild_fault_t::MALFORMED, "negative counts or duration");
    return;
  }
  Received& r = received_[job.job_id];
  r.job = job;
  try_start();
}

void SimMachine::on_chunk(const ccbuild_lcm::ccbuild_path_chunk_t& chunk) {
  if (done_.count(chunk.job_id) || (current_ && current_->job.job_id == chunk.job_id)) return;
  Received& r = received_[chunk.job_id];
  r.chunks[chunk.chunk_index] = chunk;
  try_start();
}

void SimMachine::try_start() {
  if (current_) return;
  // The lowest job whose job message and every chunk have arrived.
  for (auto it = received_.begin(); it != received_.end(); ++it) {
    Received& r = it->second;
    if (r.job.job_id == 0 || !r.complete()) continue;
    int points = 0;
    double last_t = 0.0;
    bool ordered = true;
    for (const auto& [index, c] : r.chunks) {
      points += c.n;
      for (int k = 0; k < c.n; ++k) {
        ordered = ordered && c.t_s[k] >= last_t - 1e-9;
        last_t = c.t_s[k];
      }
    }
    const auto job = r.job;
    received_.erase(it);
    if (points != job.point_count || !ordered ||
        (job.chunk_count > 0 && last_t > job.duration_s + 1e-6)) {
      acknowledge(job.job_id, false, false, "its path does not match the job");
      fault(job.job_id, ccbuild_lcm::ccbuild_fault_t::PATH_MISMATCH,
            printf_string("job %lld: %d points of %d, times %s, path ends at %.3f s of %.3f s",
                          static_cast<long long>(job.job_id), points, job.point_count,
                          ordered ? "increasing" : "going back", last_t, job.duration_s));
      return;
    }
    acknowledge(job.job_id, true, false, "");
    clock_s_ = std::max(clock_s_, job.start_s);  // idle time passes at once
    current_ = Running{job, clock_s_, 0.0, 0.0};
    return;
  }
}

void SimMachine::step(double real_dt_s) {
  if (current_) {
    current_->elapsed_s += real_dt_s * options_.speed;
    clock_s_ = current_->started_s + std::min(current_->elapsed_s, current_->job.duration_s);
    const double fraction = current_->job.duration_s > 0
                                ? std::min(1.0, current_->elapsed_s / current_->job.duration_s)
                                : 1.0;
    // Progress in tenths, not at every step: the bus stays quiet.
    if (fraction >= current_->reported + 0.1 || fraction >= 1.0) {
      current_->reported = fraction;
      auto p = stamped<ccbuild_lcm::ccbuild_progress_t>();
      p.job_id = current_->job.job_id;
      p.fraction = fraction;
      p.sim_time_s = clock_s_;
      send("PROGRESS", p);
    }
    if (current_->elapsed_s >= current_->job.duration_s) finish();
  }
  // Status every status_period_s of the machine's clock, and while it waits at least
  // four times a real second: the heartbeat.
  real_since_status_s_ += real_dt_s;
  if (clock_s_ - last_status_s_ >= options_.status_period_s || real_since_status_s_ >= 0.25)
    publish_status();
  try_start();
}

void SimMachine::finish() {
  const Running run = *current_;
  const double end_s = run.started_s + run.job.duration_s;
  // The record first: a machine that dies now still knows the job is done.
  if (!options_.state_file.empty()) {
    FILE* f = std::fopen(options_.state_file.c_str(), "a");
    CCBUILD_CHECK(f != nullptr, "cannot append to " + options_.state_file.string());
    std::fprintf(f, "%lld %.6f %.6f\n", static_cast<long long>(run.job.job_id), run.started_s,
                 end_s);
    std::fflush(f);
    ::fsync(::fileno(f));
    std::fclose(f);
  }
  done_[run.job.job_id] = {run.started_s, end_s};
  executed_.push_back(run.job.job_id);
  current_.reset();
  clock_s_ = end_s;
  publish_done(run.job.job_id, run.started_s, end_s);
}

void SimMachine::acknowledge(std::int64_t job_id, bool accepted, bool duplicate,
                             const std::string& reason) {
  auto a = stamped<ccbuild_lcm::ccbuild_ack_t>();
  a.job_id = job_id;
  a.accepted = accepted;
  a.duplicate = duplicate;
  a.reason = reason;
  send("ACK", a);
}

void SimMachine::fault(std::int64_t job_id, std::int8_t kind, const std::string& message) {
  ++faults_;
  auto f = stamped<ccbuild_lcm::ccbuild_fault_t>();
  f.job_id = job_id;
  f.kind = kind;
  f.message = message;
  send("FAULT", f);
}

void SimMachine::publish_done(std::int64_t job_id, double started_s, double finished_s) {
  auto d = stamped<ccbuild_lcm::ccbuild_done_t>();
  d.job_id = job_id;
  d.ok = true;
  d.started_s = started_s;
  d.finished_s = finished_s;
  d.detail = "";
  send("DONE", d);
}

void SimMachine::publish_status() {
  last_status_s_ = clock_s_;
  real_since_status_s_ = 0.0;
  auto s = stamped<ccbuild_lcm::ccbuild_status_t>();
  s.state = current_ ? ccbuild_lcm::ccbuild_status_t::BUSY : ccbuild_lcm::ccbuild_status_t::IDLE;
  s.current_job_id = current_ ? current_->job.job_id : 0;
  s.jobs_done = static_cast<std::int64_t>(executed_.size());
  s.sim_time_s = clock_s_;
  s.x_m = s.y_m = s.z_m = 0.0;
  s.heading_cumulative_rad = 0.0;
  s.pump_on = current_ && current_->job.kind == ccbuild_lcm::ccbuild_job_t::DEPOSIT;
  send("STATUS", s);
}

}  // namespace ccbuild::machine
