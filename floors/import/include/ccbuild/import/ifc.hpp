#pragma once
// A building read from an IFC model (IFC4 or IFC2X3, STEP text), through IFC++
// (docs/formats.md, "IFC models").
//
// Every building storey with walls becomes a floor, in order of elevation; a floor's height
// is the distance to the next storey's elevation (the top one's: to the storey above it,
// else its walls' height, else a default said in a note). Each wall of the types asked for
// (IfcWall and IfcWallStandardCase by default) contained in a storey becomes one or more
// straight walls of that floor: its axis (the 'Axis' representation, else the middle of its
// extruded body's footprint) moved to the middle of its material layer set, as thick as the
// layer set (else its body). A wall that spans several storeys is a wall of each floor it
// fills at least half of. Openings voiding a wall (IfcRelVoidsElement) become openings of the
// wall they cut: their extent along the wall and their sill and head above the floor, from
// the opening's placement and extruded body; the door or window filling one names it.
// Where walls meet (L, T, X) their axes, which architects often stop at the other wall's
// face, are extended or trimmed to meet. The whole placement chain (IfcLocalPlacement
// relative to relative, rotated by RefDirection) is followed; lengths are converted from the
// project's length unit (IfcSIUnit with a prefix, or a conversion-based unit such as the
// foot) to metres. The model keeps its own coordinates.
//
// What cannot be printed is left out and said, never guessed: curved or sloped walls,
// elements of other types (curtain walls) and of non-printable materials, walls without
// usable geometry, storeys without walls; the model's true north and map conversion are
// ignored and said. Every note names the element by IFC type, GlobalId and name.

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "ccbuild/floors/building.hpp"

namespace ccbuild::import {

/// Limits on the IFC models ccbuild reads (docs/formats.md lists them).
namespace ifc_limits {
/// Entities (`#n=...` lines) in one model: IFC++ holds each one in memory.
inline constexpr std::size_t kMaxEntities = 1'000'000;
/// Links followed from one placement to the placement it is relative to.
inline constexpr int kMaxPlacementDepth = 64;
/// Straight pieces of one wall's axis (a polyline): a wall that turns more often is no wall
/// (and each piece is measured against the wall's whole body).
inline constexpr std::size_t kMaxPiecesPerWall = 1000;
}  // namespace ifc_limits

struct IfcOptions {
  /// IFC types read as walls (case-insensitive, e.g. IfcWallElementedCase for stud walls).
  std::vector<std::string> wall_types = {"IfcWall", "IfcWallStandardCase"};
  /// A wall all of whose materials' names contain one of these (case-insensitive) is not
  /// printable and is left out; a wall without a material is kept.
  std::vector<std::string> excluded_materials = {"glass",  "gypsum", "plasterboard", "drywall",
                                                 "timber", "wood",   "stud",         "insulation"};
  /// Axis ends closer than this are one vertex, m.
  double join_tolerance_m = 0.001;
  /// An axis polyline whose points stray from a straight line by more than this is not
  /// one straight wall but several, m.
  double straightness_tolerance_m = 0.001;
  /// The top storey's height when nothing in the model says it, m.
  double default_storey_height_m = 3.0;
  /// The printed layer height of the building, m (IFC models do not say it).
  double layer_height_m = 0.1;
  /// Entities allowed in the model (tests lower it).
  std::size_t max_entities = ifc_limits::kMaxEntities;
};

struct IfcImport {
  /// Floors with their plans (validated), in metres; material and machine profiles unset.
  floors::Building building;
  std::vector<std::string> notes;  ///< what was left out or ignored, and why; then a summary
  std::string schema;              ///< as the file says: IFC4, IFC2X3
  double metres_per_unit = 1.0;    ///< the project's length unit
};

/// True for a path ending in `.ifc` (any case).
bool is_ifc_path(const std::filesystem::path& path);

/// Reads the IFC model at `path` (lengths in metres, the model's own plan coordinates).
/// Throws InputError naming the file (and the element by GlobalId, or the line) for a file
/// larger than common::limits::kMaxInputFileBytes, one that is not an IFC STEP file or is
/// truncated (no ENDSEC / END-ISO-10303-21), a schema other than IFC4 and IFC2X3, more than
/// `options.max_entities` entities, a number that is not finite anywhere IFC++ reads one,
/// a second DATA section or anything but END-ISO-10303-21 after the DATA section (with the
/// line), storeys at more than floors::limits::kMaxFloors elevations, a wall axis of more
/// than ifc_limits::kMaxPiecesPerWall pieces, a placement chain that
/// loops or is deeper than ifc_limits::kMaxPlacementDepth, what IFC++ reports as an error
/// while reading, a model without storeys or walls ccbuild can print, and plans that do not
/// validate (floors::validate_plan).
IfcImport read_ifc_building(const std::filesystem::path& path, const IfcOptions& options = {});

}  // namespace ccbuild::import
