#pragma once
// How close a schedule comes to the limits it keeps: two gantries to each other, a climb
// to a wall, a piece's interval to the material's maximum, a nozzle's idle spell to its
// limit. A schedule within every limit may still leave millimetres or seconds to spare;
// these warnings say where (docs/schedule.md, "Margins").

#include <string>
#include <vector>

#include "ccbuild/floors/material.hpp"
#include "ccbuild/floors/units.hpp"
#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/schedule/schedule.hpp"

namespace ccbuild::schedule {

/// Where a margin is tight enough to warn.
struct MarginThresholds {
  double gantry_clearance_m = 0.05;  ///< neighbouring gantries: centres apart minus width
  /// A climbing link's nearest approach to a wall (the bundled climber's links keep 40 mm
  /// where nothing forces them closer).
  double climb_clearance_m = 0.02;
  double interval_share = 0.9;  ///< a local interval over this share of the maximum
  double idle_share = 0.9;      ///< an idle (air) move over this share of its limit
};

/// The tight margins of `schedule` as warnings, each saying where, by how much, and the
/// threshold: one per plan whose gantries come closer than the threshold (with the layers
/// that use it), and one per other kind naming the closest case and how many there are.
/// A layer on a planned joint has no maximum interval. The machine's sizes in metres (mm
/// when small), places on the building in `unit`, the building's own.
std::vector<std::string> margin_warnings(const Schedule& schedule,
                                         const machine::MachineModel& machine,
                                         const floors::MaterialProfile& material,
                                         const MarginThresholds& thresholds = {},
                                         floors::LengthUnit unit = floors::LengthUnit::kMeter);

}  // namespace ccbuild::schedule
