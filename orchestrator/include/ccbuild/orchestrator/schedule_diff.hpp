#pragma once
// What changed between two schedules (schedule JSON, docs/schedule.md): feasibility,
// totals, per floor, the first differing layers and events, and the plans. A time
// differs when it moves by more than the tolerance; anything that is not a time (a
// nozzle count, a plan, a layer or event that is there in one schedule only) differs
// whenever it is not equal.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace ccbuild::orchestrator {

struct DiffTolerance {
  double absolute_s = 0.0;  ///< a time may move by this much
  double relative = 0.0;    ///< ... or by this fraction of its old value, whichever is more
  bool allows(double old_value, double new_value) const;
};

struct ScheduleDiff {
  std::vector<std::string> changes;  ///< beyond the tolerance, most important first
  std::vector<std::string> notes;    ///< within it, or not a change of the schedule (inputs)
  int differing_layers = 0, differing_events = 0, differing_plans = 0;
  bool differs() const { return !changes.empty(); }
};

/// Reads a schedule JSON file. Throws InputError naming the file and, for a document that
/// is not a schedule, the field (format, schema_version, layers, ...).
nlohmann::json read_schedule_file(const std::filesystem::path& path);

/// Compares two schedules; `shown` bounds how many differing layers and events are
/// listed one by one (all are counted).
ScheduleDiff diff_schedules(const nlohmann::json& old_schedule, const nlohmann::json& new_schedule,
                            const DiffTolerance& tolerance, int shown = 5);

}  // namespace ccbuild::orchestrator
