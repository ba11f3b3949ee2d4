#pragma once
// The site watchdog on the site clock (docs/dispatch.md, "One site clock"): before the
// clock moves on, it grants the longest step over which no two neighbouring gantries can
// come closer than the gantry width, whatever each does along its current job's path:
// follow it, or stop anywhere on it (a stalled axis, a pause) — and a gantry standing
// still stays where its status says. The step is halved until it is safe; when it would
// have to be shorter than a status period, every machine is paused before they touch. It also takes
// the gap between neighbours at every tick, from the statuses of that one instant.

#include <optional>
#include <string>
#include <vector>

#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/wire/timed_path.hpp"

namespace ccbuild::dispatch {

struct RailGuardOptions {
  std::vector<std::string> machines;  ///< the gantries in rail order
  machine::RailAxis rail_axis = machine::RailAxis::kX;
  double gantry_width_m = 1.5;
  double status_period_s = 0.02;  ///< the finest step, schedule s
};

/// What one gantry may do over the next step.
struct GantryMotion {
  double rail_now_m = 0.0;  ///< where it stands now, along the rails (its status)
  /// Its current job's path, if it has one and is not paused; null: it stands still.
  const wire::TimedPath* path = nullptr;
  double path_started_s = 0.0;  ///< when that path started (or starts), schedule s
};

class RailGuard {
 public:
  explicit RailGuard(RailGuardOptions options);

  /// The gaps between neighbours at `t_s`, from each gantry's rail position then (in rail
  /// order, as in options). Returns a description of a collision (a gap under the width).
  std::optional<std::string> measure(double t_s, const std::vector<double>& rail_m);
  /// The longest safe step from `t_s`: `want_s`, halved until no two neighbours' reaches
  /// over it come closer than the width. 0 when a step would have to be shorter than one
  /// status period (or `want_s`, when that is shorter); then `why` says which gantries,
  /// where.
  double safe_step(double t_s, double want_s, const std::vector<GantryMotion>& gantries,
                   std::string* why) const;

  double smallest_gap_m() const { return smallest_gap_m_; }
  long gaps_measured() const { return gaps_measured_; }
  /// How far two gantries at full rail speed `rail_speed_m_s` close within one status
  /// period: an upper bound on how much of the last safe gap a pause can take.
  double margin_m(double rail_speed_m_s) const {
    return 2.0 * rail_speed_m_s * options_.status_period_s;
  }
  const RailGuardOptions& options() const { return options_; }

 private:
  RailGuardOptions options_;
  double smallest_gap_m_;
  long gaps_measured_ = 0;
};

/// The rail positions a gantry can be at over [t_s, t_s + dt_s]: from where it stands to
/// wherever its path takes it within the step, as (lowest, highest), m.
std::pair<double, double> rail_reach(const GantryMotion& gantry, double t_s, double dt_s,
                                     machine::RailAxis axis);

}  // namespace ccbuild::dispatch
