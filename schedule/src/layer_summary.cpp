#include "ccbuild/schedule/layer_summary.hpp"

#include <set>

namespace ccbuild::schedule {

BuildingSummary summarize_building(const floors::Building& building,
                                   const floors::SliceOptions& options) {
  BuildingSummary summary;
  floors::GeometryNumbering numbering;
  for (const auto& floor : building.floors) {
    FloorSummary fs;
    fs.floor_index = floor.index;
    fs.name = floor.name;
    fs.height_m = floor.height_m;
    fs.base_elevation_m = floor.base_elevation_m;
    fs.wall_count = static_cast<int>(floor.plan.walls.size());
    fs.opening_count = static_cast<int>(floor.plan.openings.size());
    fs.anchor_count = static_cast<int>(floor.anchors.size());
    const auto layers = floors::slice_floor(floor, building.layer_height_m, options);
    fs.layer_count = static_cast<int>(layers.size());
    std::set<int> distinct;
    bool gap = false;  // a layer with no walls since the last run: the next starts anew
    for (const auto& layer : layers) {
      const int label = numbering.number(layer);
      if (label == 0) {  // no walls: nothing printed, no geometry (as the scheduler)
        gap = true;
        continue;
      }
      distinct.insert(label);
      if (!gap && !fs.runs.empty() && fs.runs.back().geometry_label == label) {
        fs.runs.back().last_layer = layer.index;
        continue;
      }
      gap = false;
      LayerRun run;
      run.first_layer = run.last_layer = layer.index;
      run.geometry_hash = layer.geometry_hash;
      run.geometry_label = label;
      std::set<std::int64_t> walls;
      for (const auto& s : layer.segments) walls.insert(s.wall_id);
      run.wall_count = static_cast<int>(walls.size());
      run.segment_count = static_cast<int>(layer.segments.size());
      run.wall_length_m = layer.total_length_m();
      fs.runs.push_back(run);
    }
    fs.distinct_geometries = static_cast<int>(distinct.size());
    summary.total_layers += fs.layer_count;
    summary.floors.push_back(std::move(fs));
  }
  summary.distinct_geometries = numbering.count();
  return summary;
}

}  // namespace ccbuild::schedule
