#include "ccbuild/sim/sim_machine.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "ccbuild/common/document.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/rules/tolerances.hpp"
#include "ccbuild/wire/path_chunks.hpp"
#include "ccbuild_lcm/ccbuild_ack_t.hpp"
#include "ccbuild_lcm/ccbuild_clock_t.hpp"
#include "ccbuild_lcm/ccbuild_command_t.hpp"
#include "ccbuild_lcm/ccbuild_done_t.hpp"
#include "ccbuild_lcm/ccbuild_fault_t.hpp"
#include "ccbuild_lcm/ccbuild_progress_t.hpp"
#include "ccbuild_lcm/ccbuild_status_t.hpp"

namespace ccbuild::sim {
namespace {
using ccbuild_lcm::ccbuild_fault_t;
using ccbuild_lcm::ccbuild_job_t;

constexpr double kIntervalSlack_s = 1e-3;
constexpr std::int64_t kReplayAge_us = 120'000'000;  ///< older than the newest by this: a replay
constexpr std::size_t kSeenKept = 8192;

/// One line of the machine's log on stderr, in one write (machines share the terminal).
void say(const std::string& line) {
  std::fwrite(line.data(), 1, line.size(), stderr);
}

using rules::kStatedRounding;

/// The fault a job ended on, as the record words it and as the wire codes it.
std::int8_t fault_code(const std::string& word) {
  return word == "clog"         ? ccbuild_fault_t::PUMP_CLOG
         : word == "pin-missed" ? ccbuild_fault_t::PIN_MISSED
                                : 0;
}

}  // namespace

std::vector<RecordedJob> read_machine_record(const std::filesystem::path& path) {
  const std::string text = read_text_file(path);  // regular, within the size limit
  std::vector<RecordedJob> out;
  std::istringstream lines(text);
  std::string line;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    if (line.empty()) continue;
    const auto bad = [&](const std::string& expected) {
      return InputError(path.string(), number, "",
                        expected + ", got '" +
                            (line.size() > 200 ? line.substr(0, 200) + "..." : line) +
                            "' (a machine's record is written by ccbuild-sim; this one is not)");
    };
    std::istringstream words(line);
    RecordedJob r;
    if (!(words >> r.job_id >> r.start_s >> r.end_s >> r.at[0] >> r.at[1] >> r.at[2] >> r.at[3]))
      throw bad("expected 'job_id start_s end_s x_m y_m z_m heading_rad [fault waypoints_done]'");
    const bool finite =
        std::isfinite(r.start_s) && std::isfinite(r.end_s) &&
        std::all_of(r.at.begin(), r.at.end(), [](double v) { return std::isfinite(v); });
    if (r.job_id <= 0 || !finite || r.end_s < r.start_s || r.start_s < 0.0)
      throw bad("expected a positive job id and finite times, the end not before the start");
    if (words >> r.fault) {
      r.ok = false;
      if (r.fault != "clog" && r.fault != "pin-missed")
        throw bad("expected the fault 'clog' or 'pin-missed' after the position");
      if (!(words >> r.stopped_at) || r.stopped_at < 0)
        throw bad("expected the waypoints done after the fault");
    }
    std::string extra;
    if (words >> extra) throw bad("expected nothing more on the line");
    out.push_back(std::move(r));
  }
  return out;
}

std::optional<std::pair<std::int8_t, std::string>> limit_breach(const machine::MachineModel& m,
                                                                const wire::TimedPath& p,
                                                                bool check_z_range) {
  for (std::size_t k = 0; k < p.size(); ++k) {
    const auto outside = [&](const char* axis, double v, double lo, double hi) {
      return v < lo - 1e-9 || v > hi + 1e-9
                 ? std::optional(std::pair<std::int8_t, std::string>(
                       ccbuild_fault_t::JOINT_LIMIT,
                       printf_string("waypoint %zu: %s = %.4f outside [%.4f, %.4f]", k, axis, v, lo,
                                     hi)))
                 : std::nullopt;
    };
    if (auto b = outside("x", p.x_m[k], m.x.min_m, m.x.max_m)) return b;
    if (auto b = outside("y", p.y_m[k], m.y.min_m, m.y.max_m)) return b;
    if (check_z_range)
      if (auto b = outside("z", p.z_m[k], m.z.min_m, m.z.max_m)) return b;
    if (auto b = outside("heading (the stopper)", p.heading_rad[k], m.stopper_min_rad,
                         m.stopper_max_rad))
      return b;
    if (k == 0) continue;
    const double dt = p.t_s[k] - p.t_s[k - 1];
    const struct {
      const char* axis;
      double delta, limit;
    } moves[] = {{"x", p.x_m[k] - p.x_m[k - 1], m.x.speed_m_s},
                 {"y", p.y_m[k] - p.y_m[k - 1], m.y.speed_m_s},
                 {"z", p.z_m[k] - p.z_m[k - 1], m.z.speed_m_s},
                 {"heading", p.heading_rad[k] - p.heading_rad[k - 1], m.rotation_speed_rad_s}};
    for (const auto& move : moves) {
      // No move, once rounded: two ends one micro-unit apart differ by a hair over 1e-6
      // in doubles (1.570797 - 1.570796), and may share a time.
      if (std::abs(move.delta) <= kStatedRounding * (1.0 + 1e-9)) continue;
      if (dt < 0.0 || rules::faster_than(move.delta, dt, move.limit))
        return std::pair<std::int8_t, std::string>(
            ccbuild_fault_t::VELOCITY_LIMIT,
            printf_string("waypoints %zu-%zu: %s moves %.4f in %.4f s, over its limit of %.4f/s",
                          k - 1, k, move.axis, move.delta, dt, move.limit));
    }
  }
  return std::nullopt;
}

SimMachine::SimMachine(wire::Bus& bus, SimOptions options)
    : bus_(bus),
      options_(std::move(options)),
      position_(options_.home),
      pin_failures_left_(options_.pin_failures),
      rng_(options_.seed) {
  if (!options_.state_file.empty() && std::filesystem::exists(options_.state_file)) {
    for (const RecordedJob& r : read_machine_record(options_.state_file)) {
      done_[r.job_id] = {r.start_s, r.end_s, r.at, r.ok, r.stopped_at, r.fault};
      last_ended_ = {r.job_id, fault_code(r.fault), r.start_s, r.end_s, r.stopped_at};
      if (r.fault == "clog") clogged_once_ = true;
      executed_.push_back(r.job_id);
      position_ = r.at;
      clock_s_ = std::max(clock_s_, r.end_s);
    }
  }
  const std::string id = options_.machine_id;
  bus_.subscribe<ccbuild_lcm::ccbuild_job_t>(wire::channel("JOB", id),
                                             [this](const ccbuild_lcm::ccbuild_job_t& j) {
                                               if (!replayed("JOB", j.utime, j.seq))
                                                 arrive([this, j] { on_job(j); });
                                             });
  bus_.subscribe<ccbuild_lcm::ccbuild_path_chunk_t>(
      wire::channel("PATH", id), [this](const ccbuild_lcm::ccbuild_path_chunk_t& c) {
        if (!replayed("PATH", c.utime, c.seq)) arrive([this, c] { on_chunk(c); });
      });
  if (options_.site_clock)
    bus_.subscribe<ccbuild_lcm::ccbuild_clock_t>(
        wire::kClockChannel, [this](const ccbuild_lcm::ccbuild_clock_t& c) {
          if (!replayed("CLOCK", c.utime, c.seq))
            arrive([this, c] { on_clock(c.tick, c.sim_time_s); });
        });
  bus_.subscribe<ccbuild_lcm::ccbuild_command_t>(
      wire::channel("COMMAND", id), [this](const ccbuild_lcm::ccbuild_command_t& c) {
        if (c.machine_id != options_.machine_id) {
          say(std::string() + "ccbuild-sim " + options_.machine_id + ": rejected a command for '" +
              c.machine_id + "'\n");
          return;
        }
        if (!replayed("COMMAND", c.utime, c.seq)) on_command(c.command, c.reason);
      });
}

bool SimMachine::replayed(const std::string& kind, std::int64_t utime, std::int64_t seq) {
  const auto key = std::make_tuple(kind, utime, seq);
  const bool seen = seen_.count(key) > 0;
  const bool stale = utime < newest_utime_ - kReplayAge_us;
  if (seen || stale) {
    ++replays_;
    say(printf_string(
        "ccbuild-sim %s: rejected a replayed message on %s (utime %lld, seq %lld: %s)\n",
        options_.machine_id.c_str(), wire::channel(kind, options_.machine_id).c_str(),
        static_cast<long long>(utime), static_cast<long long>(seq),
        seen ? "seen before" : "over two minutes older than the newest"));
    return true;
  }
  seen_.insert(key);
  seen_order_.push_back(key);
  if (seen_order_.size() > kSeenKept) {
    seen_.erase(seen_order_.front());
    seen_order_.pop_front();
  }
  newest_utime_ = std::max(newest_utime_, utime);
  return false;
}

void SimMachine::arrive(std::function<void()> handle) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  if (u(rng_) < options_.drop) return;
  if (options_.delay > 0.0 && u(rng_) < options_.delay) {
    delayed_.emplace_back(real_s_ + u(rng_) * options_.delay_max_s, std::move(handle));
    return;
  }
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

void SimMachine::on_command(std::int8_t command, const std::string& reason) {
  using ccbuild_lcm::ccbuild_command_t;
  say("ccbuild-sim " + options_.machine_id + ": " +
      (command == ccbuild_command_t::PAUSE    ? "paused"
       : command == ccbuild_command_t::RESUME ? "resumed"
                                              : "aborted") +
      (reason.empty() ? "" : " (" + reason + ")") + "\n");
  if (command == ccbuild_command_t::PAUSE) paused_ = true;
  if (command == ccbuild_command_t::RESUME) paused_ = false;
  if (command == ccbuild_command_t::ABORT) {
    aborted_ = true;
    paused_ = true;
  }
  publish_status();
}

void SimMachine::on_job(const ccbuild_lcm::ccbuild_job_t& job) {
  if (job.machine_id != options_.machine_id) {
    fault(job.job_id, ccbuild_fault_t::MALFORMED,
          "a job for machine '" + job.machine_id + "' on " + options_.machine_id + "'s channel");
    return;
  }
  // Seen before: done, or running now. Say so again; never run it twice.
  if (const auto it = done_.find(job.job_id); it != done_.end()) {
    acknowledge(job.job_id, true, true, "");
    const Done& d = it->second;
    publish_done(job.job_id, d.start_s, d.end_s, d.ok, d.stopped_at, d.detail);
    return;
  }
  if (current_ && current_->job.job_id == job.job_id) {
    acknowledge(job.job_id, true, true, "");
    return;
  }
  if (aborted_) {
    acknowledge(job.job_id, false, false, "aborted: takes no more jobs");
    return;
  }
  if (!executed_.empty() && job.job_id < executed_.back()) {
    acknowledge(job.job_id, false, false, "older than the last job run");
    fault(
        job.job_id, ccbuild_fault_t::OUT_OF_ORDER,
        printf_string("job %lld arrived after job %lld was run", static_cast<long long>(job.job_id),
                      static_cast<long long>(executed_.back())));
    return;
  }
  if (job.chunk_count < 0 || job.point_count < 0 || !(job.duration_s >= 0.0) ||
      !std::isfinite(job.start_s)) {
    acknowledge(job.job_id, false, false, "negative counts or duration");
    fault(job.job_id, ccbuild_fault_t::MALFORMED, "negative counts or duration");
    return;
  }
  Received& r = received_[job.job_id];
  r.job = job;
  try_start();
}

void SimMachine::on_chunk(const ccbuild_lcm::ccbuild_path_chunk_t& chunk) {
  if (done_.count(chunk.job_id) || (current_ && current_->job.job_id == chunk.job_id)) return;
  if (chunk.machine_id != options_.machine_id || chunk.n < 0 ||
      chunk.n > ccbuild_lcm::ccbuild_path_chunk_t::MAX_POINTS) {
    fault(chunk.job_id, ccbuild_fault_t::MALFORMED,
          "a path chunk for '" + chunk.machine_id + "' with " + std::to_string(chunk.n) +
              " points on " + options_.machine_id + "'s channel");
    return;
  }
  Received& r = received_[chunk.job_id];
  r.chunks[chunk.chunk_index] = chunk;
  try_start();
}

std::optional<std::pair<std::int8_t, std::string>> SimMachine::refusal(
    const ccbuild_lcm::ccbuild_job_t& job, const wire::TimedPath& path, double start_s) const {
  if (options_.model)
    if (auto breach = limit_breach(*options_.model, path, options_.check_z_range)) return breach;
  // A pin into an anchor younger than the anchor strength needs.
  if (job.kind == ccbuild_job_t::CLIMB_PHASE && job.phase == ccbuild_job_t::INSERT &&
      options_.anchor_min_age_s > 0.0) {
    {  // the unit's last pipe, by the job's unit field
      const std::string& unit = job.unit;
      const auto pipe = pipes_.find(unit);
      const double age_s =
          pipe == pipes_.end() ? 0.0 : options_.age_clock.age(pipe->second, start_s);
      if (pipe != pipes_.end() && age_s < options_.anchor_min_age_s - 1e-3)
        return std::pair<std::int8_t, std::string>(
            ccbuild_fault_t::ANCHOR_TOO_YOUNG,
            printf_string("%s: unit %s's anchor is %.1f s old, it needs %.1f s to be strong "
                          "enough",
                          job.detail.c_str(), unit.c_str(), age_s, options_.anchor_min_age_s));
    }
  }
  if (job.kind != ccbuild_job_t::DEPOSIT || job.layer <= 0) return std::nullopt;
  // The interval rule (rules/intervals.hpp) against what this machine laid below.
  const auto below = deposited_.find({job.floor, job.layer - 1});
  if (below == deposited_.end()) return std::nullopt;
  rules::DepositIndex above;
  wire::add_deposits(above, path, start_s);
  const rules::IntervalOffsets offsets = rules::interval_offsets(above, below->second);
  for (const rules::IntervalOffsets::End& e : offsets.each) {
    const char* what = nullptr;
    std::int8_t kind = 0;
    double interval_s = 0.0;
    // In the concrete's (equivalent) age, as the schedule's window is.
    const double oldest_s = options_.age_clock.age(e.low_lo_s, e.up_hi_s);
    const double youngest_s = options_.age_clock.age(e.low_hi_s, e.up_lo_s);
    if (oldest_s > options_.max_interval_s + kIntervalSlack_s && !job.on_planned_joint) {
      what = "a cold joint: covered %.1f s after it was deposited, over the maximum %.1f s";
      kind = ccbuild_fault_t::COLD_JOINT;
      interval_s = oldest_s;
    } else if (youngest_s < options_.min_interval_s - kIntervalSlack_s) {
      what = "too early: covered %.1f s after it was deposited, under the minimum %.1f s";
      kind = ccbuild_fault_t::TOO_EARLY;
      interval_s = youngest_s;
    }
    if (!what) continue;
    return std::pair<std::int8_t, std::string>(
        kind, printf_string("floor %d layer %d, wall %lld at (%.3f, %.3f) m: ", job.floor,
                            job.layer, static_cast<long long>(e.at.wall), e.at.x_m, e.at.y_m) +
                  printf_string(what, interval_s,
                                kind == ccbuild_fault_t::COLD_JOINT ? options_.max_interval_s
                                                                    : options_.min_interval_s));
  }
  return std::nullopt;
}

void SimMachine::try_start() {
  if (current_ || aborted_) return;
  // The lowest job whose job message and every chunk have arrived.
  for (auto it = received_.begin(); it != received_.end(); ++it) {
    Received& r = it->second;
    if (r.job.job_id == 0 || !r.complete()) continue;
    wire::TimedPath path;
    for (const auto& [index, c] : r.chunks)
      for (int k = 0; k < c.n; ++k) wire::append_waypoint(path, c, k);
    bool ordered = true;
    for (std::size_t k = 1; k < path.size(); ++k)
      ordered = ordered && path.t_s[k] >= path.t_s[k - 1] - 1e-9;
    const auto job = r.job;
    received_.erase(it);
    const double last_t = path.t_s.empty() ? 0.0 : path.t_s.back();
    if (static_cast<int>(path.size()) != job.point_count || !ordered ||
        (job.chunk_count > 0 && last_t > job.duration_s + 1e-6)) {
      acknowledge(job.job_id, false, false, "its path does not match the job");
      fault(job.job_id, ccbuild_fault_t::PATH_MISMATCH,
            printf_string("job %lld: %zu points of %d, times %s, path ends at %.3f s of %.3f s",
                          static_cast<long long>(job.job_id), path.size(), job.point_count,
                          ordered ? "increasing" : "going back", last_t, job.duration_s));
      return;
    }
    // On its own clock idle time passes at once; on the site clock the job waits for it.
    const double start_s = std::max(clock_s_, job.start_s);
    if (const auto why = refusal(job, path, start_s)) {
      acknowledge(job.job_id, false, false, why->second);
      fault(job.job_id, why->first, why->second);
      return;
    }
    if (!options_.site_clock) clock_s_ = start_s;
    // A wait or a slab stage is the machine idle: on its own clock its time passes at once.
    const bool idle = job.kind == ccbuild_job_t::WAIT || job.kind == ccbuild_job_t::SLAB;
    Running run;
    run.job = job;
    run.path = std::move(path);
    run.started_s = start_s;
    // Injected: a clog part-way through the layer, at the first extruding waypoint past
    // 40% of its time; a pin that misses its pipe at the end of its insertion.
    if (job.kind == ccbuild_job_t::DEPOSIT && job.floor == options_.clog_floor &&
        job.layer == options_.clog_layer && !clogged_once_) {
      for (std::size_t k = 1; k < run.path.size(); ++k)
        if (run.path.extruding[k] && run.path.t_s[k] >= 0.4 * job.duration_s) {
          run.stop_fault = ccbuild_fault_t::PUMP_CLOG;
          run.stop_elapsed_s = run.path.t_s[k];
          run.stop_point = static_cast<int>(k);
          run.stop_message =
              printf_string("the pump clogged at waypoint %zu of %zu, (%.3f, %.3f) m", k,
                            run.path.size(), run.path.x_m[k], run.path.y_m[k]);
          break;
        }
    }
    if (job.kind == ccbuild_job_t::CLIMB_PHASE && job.phase == ccbuild_job_t::INSERT &&
        pin_failures_left_ > 0) {
      --pin_failures_left_;
      run.stop_fault = ccbuild_fault_t::PIN_MISSED;
      run.stop_elapsed_s = job.duration_s;
      run.stop_point = 0;
      run.stop_message = "the pin did not find its pipe (" + job.detail + ")";
    }
    if (idle && !options_.site_clock) run.elapsed_s = job.duration_s;
    current_ = std::move(run);
    // On the site clock the dispatcher decides the next step from the statuses: the
    // status that says the job is current goes before its acknowledgement.
    if (options_.site_clock) publish_status();
    acknowledge(job.job_id, true, false, "");
    return;
  }
}

void SimMachine::follow(double elapsed_s) {
  const wire::TimedPath& p = current_->path;
  if (p.size() == 0) return;
  std::array<double, 4> at = position_at(p, elapsed_s);
  // A stalled rail axis stays where it stopped; the others follow the path.
  const int rail = options_.model && options_.model->rail_axis == machine::RailAxis::kY ? 1 : 0;
  if (stalled_rail_m_) at[rail] = *stalled_rail_m_;
  position_ = at;
}

void SimMachine::maybe_stall() {
  if (options_.stall_at_s < 0.0 || stalled_rail_m_ || clock_s_ < options_.stall_at_s) return;
  const int rail = options_.model && options_.model->rail_axis == machine::RailAxis::kY ? 1 : 0;
  stalled_rail_m_ = position_[rail];
  say(printf_string("ccbuild-sim %s: (injected) the rail axis stalled at %.3f m\n",
                    options_.machine_id.c_str(), *stalled_rail_m_));
}

void SimMachine::report_progress() {
  Running& run = *current_;
  const double fraction =
      run.job.duration_s > 0 ? std::min(1.0, run.elapsed_s / run.job.duration_s) : 1.0;
  // Progress in tenths, not at every step: the bus stays quiet.
  if (fraction >= run.reported + 0.1 || fraction >= 1.0) {
    run.reported = fraction;
    auto p = stamped<ccbuild_lcm::ccbuild_progress_t>();
    p.job_id = run.job.job_id;
    p.fraction = fraction;
    p.sim_time_s = clock_s_;
    send("PROGRESS", p);
  }
}

void SimMachine::step(double real_dt_s) {
  real_s_ += real_dt_s;
  if (!delayed_.empty()) {
    std::vector<std::function<void()>> due;
    for (auto it = delayed_.begin(); it != delayed_.end();)
      if (it->first <= real_s_) {
        due.push_back(std::move(it->second));
        it = delayed_.erase(it);
      } else {
        ++it;
      }
    for (auto& handle : due) handle();
  }
  real_since_status_s_ += real_dt_s;
  if (options_.site_clock) {
    // Time moves only with the site clock; the last status again is the heartbeat.
    if (real_since_status_s_ >= 0.25) republish_status();
    return;
  }
  maybe_stall();
  if (current_ && !paused_) {
    Running& run = *current_;
    run.elapsed_s += real_dt_s * options_.speed;
    const double end_s = run.stop_fault ? run.stop_elapsed_s : run.job.duration_s;
    clock_s_ = run.started_s + std::min(run.elapsed_s, end_s);
    follow(std::min(run.elapsed_s, end_s));
    report_progress();
    if (run.elapsed_s >= end_s) finish(run.stop_fault == 0);
  }
  // Status every status_period_s of the machine's clock, and while it waits at least
  // four times a real second: the heartbeat.
  if (clock_s_ - last_status_s_ >= options_.status_period_s || real_since_status_s_ >= 0.25)
    publish_status();
  if (!paused_) try_start();
}

void SimMachine::on_clock(std::int64_t tick, double sim_time_s) {
  // A tick answered before (repeated, or reordered behind a later one): the status again.
  if (tick <= last_tick_ || !std::isfinite(sim_time_s)) {
    republish_status();
    return;
  }
  advance_to(sim_time_s);
  last_tick_ = tick;
  publish_status();
}

void SimMachine::advance_to(double t_s) {
  for (;;) {
    if (!current_ && !paused_) try_start();
    if (!current_ || paused_) break;
    Running& run = *current_;
    const double from_s = std::max(clock_s_, run.started_s);
    if (from_s > t_s) break;  // it starts after this tick
    const double end_elapsed_s = run.stop_fault ? run.stop_elapsed_s : run.job.duration_s;
    // Up to the tick, or to the stall first.
    double to_s = t_s;
    if (options_.stall_at_s >= 0.0 && !stalled_rail_m_ && options_.stall_at_s > from_s)
      to_s = std::min(to_s, options_.stall_at_s);
    const double end_s = from_s + (end_elapsed_s - run.elapsed_s);
    if (end_s <= to_s) {
      run.elapsed_s = end_elapsed_s;
      clock_s_ = end_s;
      follow(run.elapsed_s);
      maybe_stall();
      report_progress();
      const bool faulted = run.stop_fault != 0;
      finish(!faulted);
      // A job that ended on a fault holds the machine's clock there, standing still, so
      // that what recovers from it (a purge, a pin again, the rest of the path) starts
      // from the fault, not from the tick.
      if (faulted) return;
      continue;
    }
    run.elapsed_s += to_s - from_s;
    clock_s_ = to_s;
    follow(run.elapsed_s);
    maybe_stall();
    report_progress();
    if (to_s >= t_s) break;
  }
  clock_s_ = std::max(clock_s_, t_s);
  maybe_stall();
}

void SimMachine::finish(bool completed) {
  const Running run = std::move(*current_);
  current_.reset();
  const double end_s = run.started_s + (completed ? run.job.duration_s : run.stop_elapsed_s);
  const std::string fault_word = completed                                      ? ""
                                 : run.stop_fault == ccbuild_fault_t::PUMP_CLOG ? "clog"
                                                                                : "pin-missed";
  const int stopped_at = completed ? -1 : run.stop_point;
  // The record first: a machine that dies now still knows the job is done.
  if (!options_.state_file.empty()) {
    FILE* f = std::fopen(options_.state_file.c_str(), "a");
    // Not a crash to be restarted from: the machine cannot keep its record at all.
    if (f == nullptr)
      throw InputError(
          options_.state_file.string(), 0, "--state",
          std::string("cannot append to the machine's record: ") + std::strerror(errno));
    std::fprintf(f, "%lld %.17g %.17g %.17g %.17g %.17g %.17g",
                 static_cast<long long>(run.job.job_id), run.started_s, end_s, position_[0],
                 position_[1], position_[2], position_[3]);
    if (!completed) std::fprintf(f, " %s %d", fault_word.c_str(), stopped_at);
    std::fprintf(f, "\n");
    std::fflush(f);
    ::fsync(::fileno(f));
    std::fclose(f);
  }
  done_[run.job.job_id] = {run.started_s, end_s, position_, completed, stopped_at, fault_word};
  last_ended_ = {run.job.job_id, fault_code(fault_word), run.started_s, end_s, stopped_at};
  executed_.push_back(run.job.job_id);
  clock_s_ = end_s;
  if (run.stop_fault == ccbuild_fault_t::PUMP_CLOG) clogged_once_ = true;
  // The pipes it placed, for the anchors' age.
  if (run.job.kind == ccbuild_job_t::PIPE && completed && !run.job.unit.empty())
    pipes_[run.job.unit] = end_s;
  // What it laid, for the interval check of the layer above.
  if (run.job.kind == ccbuild_job_t::DEPOSIT) {
    wire::add_deposits(deposited_[{run.job.floor, run.job.layer}], run.path, run.started_s,
                       completed ? -1 : std::max(0, run.stop_point));
  }
  if (options_.crash_after_jobs > 0 && ++jobs_run_here_ == options_.crash_after_jobs) {
    say(std::string() + "ccbuild-sim " + options_.machine_id + ": (injected) crashed after " +
        std::to_string(jobs_run_here_) + " jobs\n");
    std::_Exit(70);
  }
  if (!completed) fault(run.job.job_id, run.stop_fault, run.stop_message);
  publish_done(run.job.job_id, run.started_s, end_s, completed, stopped_at, fault_word);
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
  say(std::string() + "ccbuild-sim " + options_.machine_id + ": fault: " + message + "\n");
  auto f = stamped<ccbuild_lcm::ccbuild_fault_t>();
  f.job_id = job_id;
  f.kind = kind;
  f.message = message;
  send("FAULT", f);
}

void SimMachine::publish_done(std::int64_t job_id, double started_s, double finished_s, bool ok,
                              int stopped_at, const std::string& detail) {
  auto d = stamped<ccbuild_lcm::ccbuild_done_t>();
  d.job_id = job_id;
  d.ok = ok;
  d.started_s = started_s;
  d.finished_s = finished_s;
  d.stopped_at = stopped_at;
  d.fault = fault_code(detail);
  d.detail = detail;
  send("DONE", d);
}

void SimMachine::publish_status() {
  using ccbuild_lcm::ccbuild_status_t;
  last_status_s_ = clock_s_;
  real_since_status_s_ = 0.0;
  auto s = stamped<ccbuild_status_t>();
  s.state = aborted_   ? ccbuild_status_t::ABORTED
            : paused_  ? ccbuild_status_t::PAUSED
            : current_ ? ccbuild_status_t::BUSY
                       : ccbuild_status_t::IDLE;
  s.current_job_id = current_ ? current_->job.job_id : 0;
  s.jobs_done = static_cast<std::int64_t>(executed_.size());
  s.sim_time_s = clock_s_;
  s.x_m = position_[0];
  s.y_m = position_[1];
  s.z_m = position_[2];
  s.heading_cumulative_rad = position_[3];
  s.pump_on = current_ && !paused_ && current_->job.kind == ccbuild_job_t::DEPOSIT &&
              current_->started_s <= clock_s_;
  s.tick = options_.site_clock ? last_tick_ : 0;
  s.started_s = current_ ? current_->started_s : 0.0;
  s.idle_until_s = -1.0;
  if (current_ && !paused_) {
    const Running& run = *current_;
    const bool idle = run.job.kind == ccbuild_job_t::WAIT || run.job.kind == ccbuild_job_t::SLAB;
    s.idle_until_s = run.started_s > clock_s_ ? run.started_s
                     : idle                   ? run.started_s + run.job.duration_s
                                              : clock_s_;
  }
  s.last_job_id = last_ended_.job_id;
  s.last_fault = last_ended_.fault;
  s.last_started_s = last_ended_.started_s;
  s.last_finished_s = last_ended_.finished_s;
  s.last_stopped_at = last_ended_.stopped_at;
  last_status_ = s;
  send("STATUS", s);
}

void SimMachine::republish_status() {
  if (!last_status_) {
    publish_status();
    return;
  }
  real_since_status_s_ = 0.0;
  auto s = *last_status_;
  s.utime = wire::utime_now();
  s.seq = next_seq();
  send("STATUS", s);
}

}  // namespace ccbuild::sim
