#pragma once
// A building as `ccbuild validate` shows it: what it holds (floors, walls, openings,
// anchors, layers, distinct geometries), its units, material, machine and placement, how
// its walls are printed, what the import noted or left out, and its concrete against the
// model's own quantities; as text or JSON (docs/json.md).

#include <optional>
#include <ostream>
#include <string>

#include "ccbuild/schedule/project.hpp"

namespace ccbuild::report {

/// Writes the summary of `project` (opened from `file`) to `out`, as JSON when `json`.
void write_building_summary(std::ostream& out, const schedule::Project& project,
                            const std::string& file, bool json);

/// The layers of `project` (one floor's when `floor` is set) as `ccbuild layers` shows
/// them: per floor, its runs of layers of one geometry (numbered across the building, as
/// the schedule's plan keys name them), with their walls, pieces and wall length.
void write_layers_summary(std::ostream& out, const schedule::Project& project,
                          const std::string& file, const std::optional<int>& floor, bool json);

}  // namespace ccbuild::report
