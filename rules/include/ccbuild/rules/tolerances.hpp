#pragma once
// How far a stated move may seem to exceed a speed limit before it does: the one speed
// tolerance of the schedule's re-checks and of the simulated machine's refusals.

namespace ccbuild::rules {

/// Schedules state times, positions and headings rounded to micro-units (1 us, 1 um,
/// 1 urad; docs/schedule.md): each end of a move may be off by half of one.
inline constexpr double kStatedRounding = 1e-6;

/// Whether moving `delta` (m or rad, either sign) in `dt_s` is faster than `limit` (per
/// s) by more than the rounding of the move's ends explains: each end's position and
/// time may be off by `rounding` (m or rad, and s), and the product by a relative 1e-9 of
/// floating error. A move planned at exactly the limit stays within it once rounded.
bool faster_than(double delta, double dt_s, double limit, double rounding = kStatedRounding);

}  // namespace ccbuild::rules
