#pragma once
// Plausible ranges of every number in building and plan files, and limits on counts, in
// SI. A value outside them is a typo or an attack, not a building: it is an input error
// naming the field and the range (in the file's own unit). docs/formats.md lists them.

#include <cstdint>

#include "ccbuild/common/format.hpp"

namespace ccbuild::floors::limits {

/// Coordinates of plan vertices: within 100 km of the plan's origin.
inline const Range kCoordinate_m = Range::closed(-100'000.0, 100'000.0);
/// Walls must be longer than this: layers merge points this close into one and drop
/// pieces this short (slice.hpp), so such a wall would vanish from every layer.
inline constexpr double kMinWallLength_m = 1e-3;
/// Wall thickness, when given.
inline const Range kWallThickness_m = Range::above(0.0, 5.0);
/// A wall's volume as its model states it (`model_volume:`, m³ in the file for metres).
inline const Range kWallVolume_m3 = Range::above(0.0, 1'000'000.0);
/// Openings and anchors: along a wall (their fit on the wall is checked separately).
inline const Range kAlongWall_m = Range::closed(0.0, 200'000.0);
inline const Range kOpeningWidth_m = Range::above(0.0, 200'000.0);
/// Sill and head, above the floor's base.
inline const Range kOpeningHeight_m = Range::closed(0.0, 100.0);
/// A wall's top, above the floor's base (`top:`), and the points that shape it.
inline const Range kWallTop_m = Range::above(0.0, 100.0);
inline constexpr std::size_t kMaxWallTopPoints = 1000;
/// A floor's height: of its walls (floor to floor without a slab).
inline const Range kFloorHeight_m = Range::above(0.0, 100.0);
/// A floor's level (its storey's elevation in the model): within 10 km of the model's datum.
inline const Range kLevel_m = Range::closed(-10'000.0, 10'000.0);
/// The slab on a floor's walls, up to the next floor's base.
inline const Range kSlabThickness_m = Range::closed(0.0, 10.0);
/// Layer height: printed layers are millimetres to centimetres thick.
inline const Range kLayerHeight_m = Range::closed(0.001, 1.0);
/// The slab stage between floors: up to 30 days.
inline const Range kSlabStage_s = Range::closed(0.0, 30 * 86'400.0);
/// Lintels: a precast element's depth, its bearing on each side, the time to set one.
inline const Range kLintelHeight_m = Range::closed(0.0, 3.0);
inline const Range kLintelBearing_m = Range::closed(0.0, 2.0);
inline const Range kLintelPlace_s = Range::above(0.0, 8 * 3600.0);
/// A crew: people on one task.
inline const Range kCrew = Range::closed(0.0, 100.0);
/// Slabs: formwork and reinforcement time, the pour's rate (m³/h in the file), the
/// strength that lets the next floor start.
inline const Range kSlabSetup_s = Range::closed(0.0, 30 * 86'400.0);
inline const Range kPourRate_m3_s = Range::above(0.1 / 3600.0, 500.0 / 3600.0);
inline const Range kSlabReady_mpa = Range::above(0.0, 100.0);

/// A site's rotation, degrees in the file.
inline const Range kSiteRotation_rad = Range::closed(-2 * 3.141592653589793, 2 * 3.141592653589793);

/// Ids of vertices and walls: 1 to this.
inline constexpr std::int64_t kMaxId = 999'999'999;
inline constexpr int kMaxFloors = 500;
inline constexpr std::size_t kMaxVertices = 200'000;
inline constexpr std::size_t kMaxWalls = 100'000;
/// Names in a print spec's `wall_types` or `exclude_materials`.
inline constexpr std::size_t kMaxPrintNames = 100;
inline constexpr std::size_t kMaxOpenings = 100'000;
inline constexpr std::size_t kMaxAnchors = 10'000;  ///< per floor
/// Layers of a whole building (floors x ceil(height / layer height)).
inline constexpr long kMaxLayers = 100'000;

}  // namespace ccbuild::floors::limits
