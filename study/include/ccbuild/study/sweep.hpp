#pragma once
// The overhead-platform design study of paper 002 §5 (Tables 1 and 2), behind `ccbuild
// sweep`: over numbers of nozzles, platform widths, gantry widths and rail orientations,
// which method found a collision-free plan for each distinct layer, the total
// construction and machine time, and the largest layer's vertices.

#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "ccbuild/planner/plan_layer.hpp"
#include "ccbuild/schedule/project.hpp"

namespace ccbuild::study {

/// The grid of a sweep; lengths in metres.
struct SweepGrid {
  std::vector<int> nozzles{2, 3};
  std::vector<double> platform_widths_m;
  std::vector<double> gantry_widths_m;
  std::vector<std::string> rail_axes{"x", "y"};  ///< each already a valid rail axis name
  std::optional<int> floor, layer;               ///< which layers; unset: all
  planner::PlanOptions planning;                 ///< objective, seed, time limit
};

/// One configuration of the grid (the one-nozzle baseline has no rails or widths).
struct SweepRow {
  int nozzles = 1;
  std::string rail_axis;                       ///< empty for the one-nozzle baseline
  std::optional<double> platform_m, gantry_m;  ///< unset for the baseline
  std::string methods;  ///< one letter per platform stage of the largest layer, '-' for none
  planner::PlanStatus status;
  double construction_s = 0.0, machine_s = 0.0;
  int vertices = 0;
};

struct SweepResult {
  std::vector<SweepRow> rows;
  int layer_count = 0;             ///< the layers the times are summed over
  std::size_t distinct_count = 0;  ///< the distinct geometries planned
};

/// Plans every configuration of `grid` on the project's distinct layers, one line per
/// configuration to `progress`. Throws InputError when the selection has no layer.
SweepResult run_sweep(const schedule::Project& project, const SweepGrid& grid,
                      std::ostream& progress);

/// The rows as CSV (lengths in metres, times in seconds).
std::string sweep_csv(const SweepResult& result);

/// The rows as JSON (`file` and the counts first).
nlohmann::ordered_json sweep_json(const SweepResult& result, const std::string& file);

}  // namespace ccbuild::study
