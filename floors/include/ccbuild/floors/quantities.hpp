#pragma once
// The concrete a floor's walls take as sliced, wall by wall, against the volume their model
// states (IFC BaseQuantities NetVolume, `model_volume:` in plan files). The one computation
// of it: `import`, `validate` and the schedule all print these numbers.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "ccbuild/floors/building.hpp"
#include "ccbuild/floors/slice.hpp"

namespace ccbuild::floors {

/// A floor whose printed volume differs from its model's by more than this share is
/// flagged (issue 50: within 3% of the model's NetVolume).
inline constexpr double kModelVolumeTolerance = 0.03;

/// The walls that came from one model element (by GlobalId; a wall without one is its own).
struct ElementVolume {
  std::string global_id;            ///< empty for a wall not imported
  std::vector<std::int64_t> walls;  ///< its plan walls, in plan order
  double printed_m3 = 0.0;          ///< what its walls' layers take
  std::optional<double> model_m3;   ///< what its model states, when it does
};

struct FloorQuantities {
  double printed_m3 = 0.0;  ///< every wall of the floor
  /// What the model states, summed over the walls that state it; unset when none does.
  std::optional<double> model_m3;
  double printed_modelled_m3 = 0.0;  ///< the printed volume of those same walls
  int walls_modelled = 0, walls_unmodelled = 0;
  std::vector<ElementVolume> elements;  ///< in order of first wall

  /// printed_modelled / model - 1, when the model states a volume.
  std::optional<double> difference() const;
  /// True when the difference is over kModelVolumeTolerance either way.
  bool off() const;
};

/// The floor's layers (slice_floor with `layer_height_m`) as concrete: each piece's length
/// x its bead's width x its layer's thickness. A piece sliced without beads is
/// `one_pass_width_m` wide (the machine's nozzle), or its wall's thickness where that is 0
/// (a building not yet on a machine: the wall as drawn).
FloorQuantities floor_quantities(const Floor& floor, double layer_height_m,
                                 double one_pass_width_m);
/// The same from the floor's layers as slice_floor gave them (layers without walls may be
/// left out): a caller that has sliced the floor does not slice it again.
FloorQuantities floor_quantities(const Floor& floor, const std::vector<const Layer*>& layers,
                                 double one_pass_width_m);

/// One line on a floor's quantities, m³ (`name` names the floor): "prints V m³ of walls",
/// and where the model states volumes "; the model's NetVolume of those N walls is M m³
/// (+d%)", then, when off, the elements that differ most (up to 3, by GlobalId).
std::string quantities_text(const std::string& name, const FloorQuantities& q);

}  // namespace ccbuild::floors
