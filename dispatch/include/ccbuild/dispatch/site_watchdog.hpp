#pragma once
// The site watchdog (docs/dispatch.md): from the machines' status messages it follows
// each gantry's position along the common rails and pauses every machine before two
// neighbours come closer than the gantry width. Gaps are taken at one moment of machine
// time (each machine's positions between its statuses interpolated), the latest moment
// both have reported. It acts at the gantry width plus a margin: what two gantries can
// close at full speed between two statuses and the pause reaching them. It also notices
// a machine whose heartbeat has stopped. Not thread-safe: check() and the bus run in one
// thread.

#include <deque>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/wire/bus.hpp"

namespace ccbuild::dispatch {

struct WatchdogOptions {
  std::vector<std::string> machines;  ///< the gantries in rail order
  machine::RailAxis rail_axis = machine::RailAxis::kX;
  double gantry_width_m = 1.5;
  double margin_m = 1.0;             ///< acted on below gantry_width_m + margin_m
  double heartbeat_timeout_s = 2.0;  ///< real seconds without a status: silent
  /// A position between two statuses further apart than this (machine time, s) is not
  /// guessed: the gap is measured only where both machines have reported that closely.
  double max_span_s = 1e9;
};

class SiteWatchdog {
 public:
  /// Subscribes to every machine's status on `bus` (which must outlive it).
  SiteWatchdog(wire::Bus& bus, WatchdogOptions options);

  /// Lets `real_dt_s` of real time pass and checks the gaps. Returns why every machine
  /// must be paused, the first time neighbours come closer than width plus margin.
  std::optional<std::string> check(double real_dt_s);
  /// The smallest gap between neighbours seen so far, m (infinite before two statuses).
  double smallest_gap_m() const { return smallest_gap_m_; }
  /// How many times a gap was measured.
  long gaps_measured() const { return gaps_measured_; }
  /// Machines silent for longer than the heartbeat timeout, now.
  std::vector<std::string> silent() const;

 private:
  /// A machine's status: its clock (schedule s) and nozzle position (m).
  void on_status(const std::string& machine_id, double sim_time_s, double x_m, double y_m);
  WatchdogOptions options_;
  struct Seen {
    std::deque<std::pair<double, double>> track;  ///< (machine time s, rail position m)
    double since_s = 0.0;                         ///< real seconds since the last status
    /// The rail position at machine time `t_s`, if the track reaches it.
    std::optional<double> rail_at(double t_s, double max_span_s) const;
  };
  std::map<std::string, Seen> seen_;
  double smallest_gap_m_;
  long gaps_measured_ = 0;
  bool tripped_ = false;
};

}  // namespace ccbuild::dispatch
