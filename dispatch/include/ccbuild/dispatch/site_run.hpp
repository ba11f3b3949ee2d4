#pragma once
// A dispatch on one site clock (docs/dispatch.md, "One site clock"): the dispatcher, the
// site clock and, with several gantries, the rail guard, stepped together in one thread.
// Each step lets real time pass; once every machine has answered the last tick, the gaps
// are measured at that instant and the clock moves on: held while a machine is being
// given a job; jumping to the next moment something moves when nothing moves now;
// otherwise by the time that has passed at the speed factor, landing on the next planned
// end of a job and no further than the rail guard allows. When the guard cannot allow a
// status period, or a gap is under the gantry width, every machine is paused and the run
// stops. Runs until every job is done, it stops, or its termination condition says so
// (cancellation from another thread included, as OMPL's planners are stopped).

#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ccbuild/dispatch/dispatcher.hpp"
#include "ccbuild/dispatch/rail_guard.hpp"
#include "ccbuild/dispatch/site_clock.hpp"
#include "ccbuild/wire/bus.hpp"

namespace ccbuild::dispatch {

/// When a run gives up: a condition checked between steps, or cancel() from any thread
/// (OMPL's PlannerTerminationCondition in spirit).
class TerminationCondition {
 public:
  explicit TerminationCondition(std::function<bool()> condition = [] { return false; })
      : condition_(std::move(condition)), cancelled_(std::make_shared<std::atomic<bool>>(false)) {}
  /// After `real_s` seconds of real time from now.
  static TerminationCondition after_real_s(double real_s);
  bool operator()() const { return *cancelled_ || condition_(); }
  /// Stops the run at its next step; safe from another thread (copies share the flag).
  void cancel() const { *cancelled_ = true; }
  bool cancelled() const { return *cancelled_; }

 private:
  std::function<bool()> condition_;
  std::shared_ptr<std::atomic<bool>> cancelled_;
};

struct SiteRunOptions {
  double speed = 10'000.0;        ///< schedule seconds per real second while something moves
  bool guard = true;              ///< the rail guard limits the steps (several gantries)
  double status_period_s = 0.02;  ///< the guard's resolution, schedule s
  double max_step_s = 60.0;       ///< the longest step while something moves, schedule s
  double tick_every_s = 0.001;    ///< real s between ticks while something moves, at least
  double poll_after_s = 0.03;     ///< held this long (real s), every status is asked again
  double unguarded_step_s = 0.5;  ///< unguarded, short enough for statuses to show a contact
};

class SiteRun {
 public:
  /// `machines` in rail order. `bus` and `dispatcher` must outlive it. The guard acts only
  /// with several machines and options.guard; the gaps are measured with several.
  SiteRun(wire::Bus& bus, Dispatcher& dispatcher, const std::vector<std::string>& machines,
          machine::RailAxis rail_axis, double gantry_width_m, SiteRunOptions options);

  /// Lets `real_dt_s` of real time pass (the bus is handled by the caller). Returns why
  /// it stopped every machine, the first time it does.
  std::optional<std::string> step(double real_dt_s);
  /// Runs until the dispatcher has finished or `done` says so, handling the bus itself
  /// (1 ms at a time) on the real clock; `each` is called after every step.
  void run(const TerminationCondition& done, const std::function<void()>& each = {});

  const SiteClock& clock() const { return clock_; }
  const RailGuard& guard() const { return guard_; }
  /// A gap under the gantry width was measured.
  bool collided() const { return collided_; }
  /// What stopped the run (the guard, a collision), in order.
  const std::vector<std::string>& events() const { return events_; }

 private:
  /// The next tick's time, or a reason to stop; nothing: hold.
  std::optional<double> next_tick(std::optional<std::string>& stop);
  wire::Bus& bus_;
  Dispatcher& dispatcher_;
  SiteClock clock_;
  RailGuard guard_;
  SiteRunOptions options_;
  bool several_;
  double real_since_tick_s_ = 0.0, held_s_ = 0.0;
  std::int64_t measured_tick_ = 0;
  bool collided_ = false;
  std::vector<std::string> events_;
};

}  // namespace ccbuild::dispatch
