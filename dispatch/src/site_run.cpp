#include "ccbuild/dispatch/site_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace ccbuild::dispatch {

TerminationCondition TerminationCondition::after_real_s(double real_s) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(real_s);
  return TerminationCondition([until] { return std::chrono::steady_clock::now() >= until; });
}

SiteRun::SiteRun(wire::Bus& bus, Dispatcher& dispatcher, const std::vector<std::string>& machines,
                 machine::RailAxis rail_axis, double gantry_width_m, SiteRunOptions options)
    : bus_(bus),
      dispatcher_(dispatcher),
      clock_(bus, SiteClockOptions{machines}),
      guard_(RailGuardOptions{machines, rail_axis, gantry_width_m, options.status_period_s}),
      options_(options),
      several_(machines.size() > 1) {}

std::optional<std::string> SiteRun::step(double real_dt_s) {
  clock_.step(real_dt_s);
  real_since_tick_s_ += real_dt_s;
  if (!clock_.answered() || dispatcher_.stopped()) return std::nullopt;
  std::optional<std::string> stop;
  const std::optional<double> to_s = next_tick(stop);
  if (stop) {
    events_.push_back(*stop);
    dispatcher_.stop(*stop);
    return stop;
  }
  if (to_s) {
    clock_.advance_to(*to_s);
    real_since_tick_s_ = 0.0;
    held_s_ = 0.0;
  } else if ((held_s_ += real_dt_s) > options_.poll_after_s) {
    clock_.poll();  // a status may have been lost: every machine's again
    held_s_ = 0.0;
  }
  return std::nullopt;
}

std::optional<double> SiteRun::next_tick(std::optional<std::string>& stop) {
  const double now_s = clock_.now_s();
  if (!clock_.started()) return now_s;  // the first tick: where the machines' records leave them
  const auto& ids = guard_.options().machines;
  const machine::RailAxis axis = guard_.options().rail_axis;
  if (several_ && measured_tick_ != clock_.tick()) {
    measured_tick_ = clock_.tick();
    std::vector<double> rail_m;
    for (const auto& id : ids) {
      const auto& i = clock_.instants().at(id);
      rail_m.push_back(machine::rail_coordinate(i.x_m, i.y_m, axis));
    }
    if (auto collision = guard_.measure(now_s, rail_m)) {
      collided_ = true;
      stop = *collision;
      return std::nullopt;
    }
  }
  if (dispatcher_.awaiting_machines()) return std::nullopt;
  // Each tick lands on the next planned end of a job that moves, so that the next job can
  // start where the last one ended.
  bool moving = false;
  const double inf = std::numeric_limits<double>::infinity();
  double next_s = inf, end_s = inf;
  for (const auto& [id, i] : clock_.instants()) {
    if (!i.busy || i.paused || i.idle_until_s < 0.0) continue;
    if (i.idle_until_s <= now_s + 1e-9) {
      moving = true;
      if (const DispatchJob* job = dispatcher_.job(i.current_job_id))
        if (i.started_s + job->duration_s > now_s)
          end_s = std::min(end_s, i.started_s + job->duration_s);
    } else {
      next_s = std::min(next_s, i.idle_until_s);
    }
  }
  if (!moving) {  // nothing moves before then
    if (std::isfinite(next_s)) return next_s;
    return std::nullopt;
  }
  if (real_since_tick_s_ < options_.tick_every_s) return std::nullopt;
  const double want_s = std::min(options_.speed * real_since_tick_s_, options_.max_step_s);
  double step_s = std::min({want_s, end_s - now_s, next_s - now_s});
  if (step_s < options_.status_period_s && step_s < end_s - now_s && step_s < next_s - now_s)
    return std::nullopt;  // at low speeds, a status period at a time
  if (several_ && options_.guard) {
    std::vector<GantryMotion> motions;
    for (const auto& id : ids) {
      const auto& i = clock_.instants().at(id);
      GantryMotion m;
      m.rail_now_m = machine::rail_coordinate(i.x_m, i.y_m, axis);
      if (i.busy && !i.paused)
        if (const DispatchJob* job = dispatcher_.job(i.current_job_id); job && job->path.size()) {
          m.path = &job->path;
          m.path_started_s = i.started_s;
        }
      motions.push_back(m);
    }
    std::string why;
    step_s = guard_.safe_step(now_s, step_s, motions, &why);
    if (step_s <= 0.0) {
      stop = why;
      return std::nullopt;
    }
  } else if (several_) {
    step_s = std::min(step_s, options_.unguarded_step_s);
  }
  return now_s + step_s;
}

void SiteRun::run(const TerminationCondition& done, const std::function<void()>& each) {
  auto last = std::chrono::steady_clock::now();
  while (!dispatcher_.finished() && !done()) {
    bus_.handle(1);
    const auto now = std::chrono::steady_clock::now();
    const double dt_s = std::chrono::duration<double>(now - last).count();
    last = now;
    dispatcher_.step(dt_s);
    step(dt_s);
    if (each) each();
  }
}

}  // namespace ccbuild::dispatch
