#pragma once
// Summaries of a sliced building: which layers share a geometry, how much wall each has.
// Used by `ccbuild validate` and `ccbuild layers`, and later to plan each distinct
// layer geometry once.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "ccbuild/floors/building.hpp"
#include "ccbuild/floors/slice.hpp"

namespace ccbuild::schedule {

/// Consecutive layers of one floor with the same geometry.
struct LayerRun {
  int first_layer = 0;
  int last_layer = 0;
  std::uint64_t geometry_hash = 0;
  int geometry_label = 0;  ///< 1-based, numbered by first appearance in the building
  int wall_count = 0;      ///< distinct walls present
  int segment_count = 0;   ///< wall pieces (a wall cut by an opening counts twice)
  double wall_length_m = 0.0;
};

struct FloorSummary {
  int floor_index = 0;
  std::string name;
  double height_m = 0.0;
  double base_elevation_m = 0.0;
  int wall_count = 0;
  int opening_count = 0;
  int anchor_count = 0;
  int layer_count = 0;
  int distinct_geometries = 0;  ///< within this floor
  std::vector<LayerRun> runs;
};

struct BuildingSummary {
  std::vector<FloorSummary> floors;
  int total_layers = 0;
  int distinct_geometries = 0;  ///< across the whole building
};

/// Slices every floor and groups the layers into runs of identical geometry.
BuildingSummary summarize_building(const floors::Building& building,
                                   const floors::SliceOptions& options = {});

}  // namespace ccbuild::schedule
