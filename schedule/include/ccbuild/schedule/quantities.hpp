#pragma once
// Concrete quantities of a schedule: each layer's volume (its pieces' length x bead width
// x layer height; a one-pass wall's bead is the nozzle's width), the peak flow its nozzles
// draw together (what the pump must deliver), and the deliveries the material's batch
// size makes of the consumption over time (truck k is due when the concrete used reaches
// k batches). SI units inside: m³, m³/s, s.

#include <vector>

#include "ccbuild/floors/slice.hpp"
#include "ccbuild/planner/timeline.hpp"
#include "ccbuild/schedule/schedule.hpp"

namespace ccbuild::schedule {

/// The volume of a layer's wall pieces, m³: length x width (a piece's bead width, else
/// `nozzle_width_m`) x `height_m`.
double layer_volume_m3(const floors::Layer& layer, double nozzle_width_m, double height_m);

/// The most concrete the nozzles of a plan deposit at once, m³/s: the sum, at each moment,
/// of every extruding nozzle's speed x its bead's width x `height_m`.
double peak_flow_m3_s(const std::vector<std::vector<planner::Waypoint>>& nozzles,
                      const floors::Layer& layer, double nozzle_width_m, double height_m);

/// The deliveries of `batch_m3` each (the last one the rest) for the layers' concrete,
/// consumed evenly over each layer from its start to its end: delivery k is due when the
/// concrete used reaches k batches (the first at the first layer's start).
std::vector<Delivery> deliveries_of(const std::vector<ScheduledLayer>& layers, double batch_m3);

}  // namespace ccbuild::schedule
