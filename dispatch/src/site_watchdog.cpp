#include "ccbuild/dispatch/site_watchdog.hpp"

#include "ccbuild_lcm/ccbuild_status_t.hpp"

#include <algorithm>
#include <limits>

#include "ccbuild/common/format.hpp"

namespace ccbuild::dispatch {

SiteWatchdog::SiteWatchdog(wire::Bus& bus, WatchdogOptions options)
    : options_(std::move(options)), smallest_gap_m_(std::numeric_limits<double>::infinity()) {
  for (const auto& m : options_.machines) {
    seen_[m];
    bus.subscribe<ccbuild_lcm::ccbuild_status_t>(
        wire::channel("STATUS", m), [this](const ccbuild_lcm::ccbuild_status_t& s) {
          on_status(s.machine_id, s.sim_time_s, s.x_m, s.y_m);  // the edge: the terms it needs
        });
  }
}

void SiteWatchdog::on_status(const std::string& machine_id, double sim_time_s, double x_m,
                             double y_m) {
  const auto it = seen_.find(machine_id);
  if (it == seen_.end()) return;  // another machine's status on its channel: not believed
  Seen& seen = it->second;
  seen.since_s = 0.0;
  // A status older than the last one (reordered, or repeated) adds nothing.
  if (!seen.track.empty() && sim_time_s < seen.track.back().first) return;
  seen.track.emplace_back(sim_time_s, machine::rail_coordinate(x_m, y_m, options_.rail_axis));
  if (seen.track.size() > 256) seen.track.pop_front();
}

std::optional<double> SiteWatchdog::Seen::rail_at(double t_s, double max_span_s) const {
  if (track.empty() || t_s < track.front().first || t_s > track.back().first) return std::nullopt;
  const auto after =
      std::lower_bound(track.begin(), track.end(), t_s,
                       [](const std::pair<double, double>& p, double t) { return p.first < t; });
  if (after == track.begin()) return after->second;
  const auto before = after - 1;
  const double span = after->first - before->first;
  if (span <= 0.0 || t_s == after->first) return after->second;
  if (span > max_span_s) return std::nullopt;
  return before->second + (after->second - before->second) * (t_s - before->first) / span;
}

std::optional<std::string> SiteWatchdog::check(double real_dt_s) {
  for (auto& [m, seen] : seen_) seen.since_s += real_dt_s;
  std::optional<std::string> why;
  for (std::size_t k = 0; k + 1 < options_.machines.size(); ++k) {
    const Seen& a = seen_[options_.machines[k]];
    const Seen& b = seen_[options_.machines[k + 1]];
    if (a.track.empty() || b.track.empty()) continue;
    const double t_s = std::min(a.track.back().first, b.track.back().first);
    const auto rail_a = a.rail_at(t_s, options_.max_span_s);
    const auto rail_b = b.rail_at(t_s, options_.max_span_s);
    if (!rail_a || !rail_b) continue;
    const double gap_m = *rail_b - *rail_a;
    ++gaps_measured_;
    smallest_gap_m_ = std::min(smallest_gap_m_, gap_m);
    if (!tripped_ && !why && gap_m < options_.gantry_width_m + options_.margin_m)
      why = options_.margin_m > 0.0
                ? printf_string(
                      "site watchdog: at %.1f s of machine time %s at %.3f m and %s at %.3f m on "
                      "the rails are %.3f m apart, under the gantry width %.3f m plus the margin "
                      "%.3f m: every machine paused",
                      t_s, options_.machines[k].c_str(), *rail_a, options_.machines[k + 1].c_str(),
                      *rail_b, gap_m, options_.gantry_width_m, options_.margin_m)
                : printf_string(
                      "gantries collided: at %.1f s of machine time %s at %.3f m and %s at %.3f "
                      "m on the rails are %.3f m apart, under the gantry width %.3f m: every "
                      "machine paused",
                      t_s, options_.machines[k].c_str(), *rail_a, options_.machines[k + 1].c_str(),
                      *rail_b, gap_m, options_.gantry_width_m);
  }
  if (why) tripped_ = true;
  return why;
}

std::vector<std::string> SiteWatchdog::silent() const {
  std::vector<std::string> out;
  for (const auto& [m, seen] : seen_)
    if (seen.since_s > options_.heartbeat_timeout_s) out.push_back(m);
  return out;
}

}  // namespace ccbuild::dispatch
