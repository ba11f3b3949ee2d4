#pragma once
// One site clock for a dry-run (docs/dispatch.md, "One site clock"). The dispatcher owns
// simulated time: it publishes a tick with the time up to which every simulated machine
// may run, and each machine answers with its status for that instant. The next tick goes
// out only once every machine has answered the last one, so the statuses describe the
// same moment whatever the speed factor, and nothing moves between a tick and the
// decision about the next (a pause lands before the machines move on). Each tick goes
// out twice; one not answered within a few milliseconds is sent again, waiting twice as
// long each time. Not thread-safe: step() and the bus run in one thread.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "ccbuild/wire/bus.hpp"

namespace ccbuild::dispatch {

/// A machine's status as it answered a tick (the terms the clock and the guard need).
struct MachineInstant {
  std::int64_t tick = 0;
  double sim_time_s = 0.0;  ///< schedule s
  double x_m = 0.0, y_m = 0.0;
  bool busy = false;  ///< a job is current (running, or waiting for its start)
  bool paused = false;
  std::int64_t current_job_id = 0;
  double started_s = 0.0;    ///< when the current job started or starts
  double idle_until_s = -1;  ///< when it next moves by itself; == sim_time_s while moving
};

struct SiteClockOptions {
  std::vector<std::string> machines;
  double repeat_after_s = 0.005;  ///< real s before an unanswered tick is sent again
  double repeat_max_s = 0.2;      ///< the wait doubles up to this, real s
  int copies = 2;                 ///< each tick is published this many times
};

class SiteClock {
 public:
  /// Subscribes to every machine's status on `bus` (which must outlive it).
  SiteClock(wire::Bus& bus, SiteClockOptions options);

  /// Every machine has answered the current tick (before the first: has been heard).
  bool answered() const;
  /// Whether the first tick went out.
  bool started() const { return tick_ > 0; }
  /// The site's time, schedule s (before the first tick: the latest clock a machine
  /// reported, so that a run resumed on the machines' records goes on from there).
  double now_s() const { return now_s_; }
  std::int64_t tick() const { return tick_; }
  /// Each machine's latest answer.
  const std::map<std::string, MachineInstant>& instants() const { return instants_; }
  /// Publishes the next tick at `t_s` (not before now_s()).
  void advance_to(double t_s);
  /// The current tick again, for every machine's status again (a status that says a job
  /// has become current may have been lost).
  void poll();
  /// Lets `real_dt_s` of real time pass: sends an unanswered tick again when due.
  void step(double real_dt_s);
  /// Machines that have not answered the current tick, and for how long (real s).
  std::vector<std::string> waiting_for() const;
  double waited_s() const { return waited_s_; }
  long ticks() const { return tick_; }
  long repeats() const { return repeats_; }

 private:
  void publish();
  /// Not heard yet, or its latest answer is to an earlier tick than the current one.
  bool behind(const std::string& machine, const MachineInstant& i) const;
  wire::Bus& bus_;
  SiteClockOptions options_;
  std::map<std::string, MachineInstant> instants_;
  std::map<std::string, bool> heard_;
  std::int64_t tick_ = 0, seq_ = 0;
  double now_s_ = 0.0;
  double waited_s_ = 0.0, repeat_in_s_ = 0.0;
  long repeats_ = 0;
  int attempt_ = 0;  ///< repeats of the current tick
};

}  // namespace ccbuild::dispatch
