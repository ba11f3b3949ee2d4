#include "ccbuild/dispatch/site_clock.hpp"

#include <algorithm>
#include <cmath>

#include "ccbuild/common/input_error.hpp"
#include "ccbuild_lcm/ccbuild_clock_t.hpp"
#include "ccbuild_lcm/ccbuild_status_t.hpp"

namespace ccbuild::dispatch {

SiteClock::SiteClock(wire::Bus& bus, SiteClockOptions options)
    : bus_(bus), options_(std::move(options)), repeat_in_s_(options_.repeat_after_s) {
  for (const auto& m : options_.machines) {
    instants_[m];
    heard_[m] = false;
    bus_.subscribe<ccbuild_lcm::ccbuild_status_t>(
        wire::channel("STATUS", m), [this](const ccbuild_lcm::ccbuild_status_t& s) {
          const auto it = instants_.find(s.machine_id);
          if (it == instants_.end()) return;  // another machine's name on its channel
          MachineInstant& i = it->second;
          // An answer to an older tick (reordered, repeated) adds nothing.
          if (heard_[s.machine_id] && s.tick < i.tick) return;
          heard_[s.machine_id] = true;
          using S = ccbuild_lcm::ccbuild_status_t;
          i = {s.tick,
               s.sim_time_s,
               s.x_m,
               s.y_m,
               s.current_job_id != 0,
               s.state == S::PAUSED || s.state == S::ABORTED,
               s.current_job_id,
               s.started_s,
               s.idle_until_s};
          if (tick_ == 0) now_s_ = std::max(now_s_, s.sim_time_s);
        });
  }
}

bool SiteClock::behind(const std::string& machine, const MachineInstant& i) const {
  return !heard_.at(machine) || i.tick < tick_;
}

bool SiteClock::answered() const {
  for (const auto& [m, i] : instants_)
    if (behind(m, i)) return false;
  return true;
}

std::vector<std::string> SiteClock::waiting_for() const {
  std::vector<std::string> out;
  for (const auto& [m, i] : instants_)
    if (behind(m, i)) out.push_back(m);
  return out;
}

void SiteClock::advance_to(double t_s) {
  CCBUILD_CHECK(t_s >= now_s_, "site clock: time goes back");
  now_s_ = t_s;
  ++tick_;
  waited_s_ = 0.0;
  attempt_ = 0;
  repeat_in_s_ = options_.repeat_after_s;
  publish();
}

void SiteClock::step(double real_dt_s) {
  if (tick_ == 0 || answered()) return;
  waited_s_ += real_dt_s;
  repeat_in_s_ -= real_dt_s;
  if (repeat_in_s_ > 0.0) return;
  // The tick again (each machine answers a repeat with its status again), waiting twice
  // as long before the next repeat.
  ++repeats_;
  ++attempt_;
  repeat_in_s_ = std::min(options_.repeat_after_s * std::ldexp(1.0, std::min(attempt_, 20)),
                          options_.repeat_max_s);
  publish();
}

void SiteClock::poll() {
  if (tick_ == 0) return;
  ++repeats_;
  publish();
}

void SiteClock::publish() {
  // Each tick goes out in copies (a LAN loses one message in many; answering a copy twice
  // costs nothing), each its own message for the machines' replay check.
  for (int copy = 0; copy < options_.copies; ++copy) {
    ccbuild_lcm::ccbuild_clock_t c;
    c.utime = wire::utime_now();
    c.seq = ++seq_;
    c.tick = tick_;
    c.sim_time_s = now_s_;
    bus_.publish(wire::kClockChannel, c);
  }
}

}  // namespace ccbuild::dispatch
