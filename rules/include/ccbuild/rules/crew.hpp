#pragma once
// Site rules about crews, stated once.

namespace ccbuild::rules {

/// The person-hours of a task: its crew's size times its duration, h. Every total, day
/// and export of crew time adds these.
inline double person_hours(int crew, double duration_s) {
  return crew * duration_s / 3600.0;
}

}  // namespace ccbuild::rules
