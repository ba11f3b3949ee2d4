#pragma once
// What changed between two schedules (schedule JSON, docs/schedule.md): feasibility,
// totals, per floor, the first differing layers and events, and the plans. A time
// differs when it moves by more than the tolerance; anything that is not a time (a
// nozzle count, a plan, a layer or event that is there in one schedule only) differs
// whenever it is not equal.

#include <string>
#include <vector>

#include "ccbuild/schedule/schedule_json.hpp"

namespace ccbuild::schedule {

struct DiffTolerance {
  double absolute_s = 0.0;  ///< a time may move by this much
  double relative = 0.0;    ///< ... or by this fraction of its old value, whichever is more
  /// Whether `new_value` is within the tolerance of the reference `old_value` (the
  /// relative part is a share of the reference). Unset values are equal to each other only.
  bool allows(std::optional<double> old_value, std::optional<double> new_value) const;
};

struct ScheduleDiff {
  std::vector<std::string> changes;  ///< beyond the tolerance, most important first
  std::vector<std::string> notes;    ///< within it, or not a change of the schedule (inputs)
  int differing_layers = 0, differing_events = 0, differing_plans = 0;
  bool differs() const { return !changes.empty(); }
};

/// Compares two schedules (as read_schedule gives them); `shown` bounds how many
/// differing layers, events and plans are listed one by one (all are counted). Plans are
/// compared by key: a plan in one schedule only, or whose timed paths or pieces differ,
/// is a change.
ScheduleDiff diff_schedules(const ScheduleDocument& old_schedule,
                            const ScheduleDocument& new_schedule, const DiffTolerance& tolerance,
                            int shown = 5);

}  // namespace ccbuild::schedule
