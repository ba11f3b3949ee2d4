#pragma once
// Equivalent age at 20 °C as a function of the schedule's time: the one statement of the
// maturity method's bookkeeping (ASTM C1074), for the scheduler, the schedule's
// re-checks, the dispatcher's re-plans and the simulated machines' refusals. The site's
// weather makes it (schedule/conditions.hpp); without weather it is the clock itself.

#include <string>
#include <vector>

namespace ccbuild::rules {

/// Piecewise linear: from each breakpoint's time on, equivalent age accrues at its rate
/// (equivalent seconds per second), up to the next; before the first at the first's rate,
/// after the last at the last's. No breakpoint: real time (rate 1).
class AgeClock {
 public:
  struct Breakpoint {
    double t_s = 0.0;  ///< schedule time
    double e_s = 0.0;  ///< equivalent seconds accrued from the schedule's start
    double rate = 1.0;
  };
  AgeClock() = default;
  /// Breakpoints in time order (not checked here: the caller makes them so).
  explicit AgeClock(std::vector<Breakpoint> breakpoints) : points_(std::move(breakpoints)) {}

  bool real_time() const { return points_.empty(); }
  const std::vector<Breakpoint>& breakpoints() const { return points_; }
  /// Equivalent seconds accrued from 0 to `t_s`.
  double at(double t_s) const;
  /// The equivalent age at `to_s` of concrete placed at `from_s`, s.
  double age(double from_s, double to_s) const { return at(to_s) - at(from_s); }
  /// The earliest time at which concrete placed at `from_s` is `age_s` old; +infinity
  /// when it never is (a rate of 0 for ever).
  double after(double from_s, double age_s) const;

  /// As text, one breakpoint a line ("t_s e_s rate", 17 digits), for a machine's
  /// command line; and back. parse throws std::invalid_argument naming the line.
  std::string text() const;
  static AgeClock parse(const std::string& text);

 private:
  std::vector<Breakpoint> points_;
};

}  // namespace ccbuild::rules
