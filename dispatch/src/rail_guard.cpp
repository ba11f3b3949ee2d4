#include "ccbuild/dispatch/rail_guard.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ccbuild/common/format.hpp"

namespace ccbuild::dispatch {
namespace {

/// The rail position of `path` at `t_s` from its start.
double rail_on_path(const wire::TimedPath& p, double t_s, machine::RailAxis axis) {
  const auto at = wire::position_at(p, t_s);
  return machine::rail_coordinate(at[0], at[1], axis);
}

}  // namespace

std::pair<double, double> rail_reach(const GantryMotion& g, double t_s, double dt_s,
                                     machine::RailAxis axis) {
  double lo = g.rail_now_m, hi = g.rail_now_m;
  if (!g.path || g.path->size() == 0) return {lo, hi};
  const wire::TimedPath& p = *g.path;
  const double from_s = std::max(0.0, t_s - g.path_started_s);
  const double to_s = std::min(p.t_s.back(), t_s + dt_s - g.path_started_s);
  if (to_s < from_s) return {lo, hi};
  const auto take = [&](double r) {
    lo = std::min(lo, r);
    hi = std::max(hi, r);
  };
  take(rail_on_path(p, from_s, axis));
  take(rail_on_path(p, to_s, axis));
  for (auto it = std::upper_bound(p.t_s.begin(), p.t_s.end(), from_s);
       it != p.t_s.end() && *it < to_s; ++it) {
    const std::size_t k = static_cast<std::size_t>(it - p.t_s.begin());
    take(machine::rail_coordinate(p.x_m[k], p.y_m[k], axis));
  }
  return {lo, hi};
}

RailGuard::RailGuard(RailGuardOptions options)
    : options_(std::move(options)), smallest_gap_m_(std::numeric_limits<double>::infinity()) {}

std::optional<std::string> RailGuard::measure(double t_s, const std::vector<double>& rail_m) {
  std::optional<std::string> collided;
  for (std::size_t k = 0; k + 1 < rail_m.size(); ++k) {
    const double gap_m = rail_m[k + 1] - rail_m[k];
    ++gaps_measured_;
    smallest_gap_m_ = std::min(smallest_gap_m_, gap_m);
    if (gap_m < options_.gantry_width_m && !collided)
      collided = printf_string(
          "gantries collided: at %.2f s of site time %s at %.3f m and %s at %.3f m on the "
          "rails are %.3f m apart, under the gantry width %.3f m",
          t_s, options_.machines[k].c_str(), rail_m[k], options_.machines[k + 1].c_str(),
          rail_m[k + 1], gap_m, options_.gantry_width_m);
  }
  return collided;
}

double RailGuard::safe_step(double t_s, double want_s, const std::vector<GantryMotion>& gantries,
                            std::string* why) const {
  const double period_s = options_.status_period_s;
  for (double dt_s = want_s;; dt_s /= 2.0) {
    bool safe = true;
    for (std::size_t k = 0; safe && k + 1 < gantries.size(); ++k) {
      const auto left = rail_reach(gantries[k], t_s, dt_s, options_.rail_axis);
      const auto right = rail_reach(gantries[k + 1], t_s, dt_s, options_.rail_axis);
      // The smallest gap either could leave: the right one at its lowest, the left at
      // its highest (a rounding's worth of slack: paths are stated to the micrometre).
      if (right.first - left.second < options_.gantry_width_m - 1e-6) {
        safe = false;
        if (why)
          *why = printf_string(
              "site watchdog: at %.2f s of site time %s (at %.3f m, reaching up to %.3f m "
              "within %.3g s) and %s (at %.3f m, down to %.3f m) could come closer than the "
              "gantry width %.3f m: every machine paused",
              t_s, options_.machines[k].c_str(), gantries[k].rail_now_m, left.second, dt_s,
              options_.machines[k + 1].c_str(), gantries[k + 1].rail_now_m, right.first,
              options_.gantry_width_m);
      }
    }
    if (safe) return dt_s;
    if (dt_s / 2.0 < period_s) return 0.0;  // not even one status period is safe
  }
}

}  // namespace ccbuild::dispatch
