#pragma once
// The schedule as JSON (docs/schedule.md, `schema_version` 1): the inputs (every file
// read with its SHA-256, the seed, the version), the layers, the plans with every
// nozzle's timed path, the events, the totals and whether it is feasible. The same
// inputs and seed give the same bytes: no wall-clock times, numbers rounded.

#include <nlohmann/json.hpp>

#include "ccbuild/orchestrator/project.hpp"
#include "ccbuild/orchestrator/schedule.hpp"

namespace ccbuild::orchestrator {

inline constexpr int kScheduleSchemaVersion = 1;
inline constexpr const char* kCcbuildVersion = "0.1.0";

/// Throws InputError when an input file cannot be read back for its checksum.
nlohmann::ordered_json schedule_json(const Project& project, const ScheduleOptions& options,
                                     const Schedule& schedule);

}  // namespace ccbuild::orchestrator
