#pragma once
// A floor plan read from a DXF drawing (docs/formats.md, "DXF drawings"), through dxflib.
//
// Walls are the LINE, LWPOLYLINE and POLYLINE entities on the wall layers, drawn either as
// centrelines or, the usual way, as two parallel face lines: face lines facing each other
// across at most `max_thickness_m` become one wall along their middle, as thick as they
// are apart, over the stretch where both run; where walls meet (L, T, X) their middles are
// extended to meet each other. Doors and windows are block INSERTs on their layers: the
// block's extent along its x axis, as inserted, is the opening, placed on the wall it
// lies on; with gap_openings, so is a gap in a wall's line. What cannot be read (a curved segment,
// a face line with no partner, an opening on no wall) is left out and said in `notes`, naming the
// entity's handle and where it is.

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ccbuild/floors/building.hpp"
#include "ccbuild/floors/plan.hpp"

namespace ccbuild::import {

struct DxfOptions {
  std::vector<std::string> wall_layers;  ///< layer names (case-insensitive); required
  std::vector<std::string> door_layers;
  std::vector<std::string> window_layers;
  enum class WallLines { kFaces, kCentrelines } wall_lines = WallLines::kFaces;
  /// Metres per drawing unit; unset: from the drawing's $INSUNITS (refused when unitless).
  std::optional<double> metres_per_unit;
  double max_thickness_m = 0.6;  ///< face lines further apart are not one wall
  /// A gap between two walls in line (same thickness, their free ends facing each other,
  /// at most `max_gap_m` apart) is an opening: a window when a line on a window layer
  /// lies in it (glazing), else a door; the two walls become one.
  bool gap_openings = false;
  double max_gap_m = 3.0;
  double door_head_m = 2.1;  ///< doors: sill 0
  double window_sill_m = 0.9, window_head_m = 2.1;
  /// A door or window layer's own sill and head, m, for its blocks that have no SILL or
  /// HEAD attribute (a high window layer, a garage door layer); unset: the kind's above.
  struct Heights {
    std::optional<double> sill_m, head_m;
  };
  std::map<std::string, Heights> layer_heights;  ///< by layer name (any case)
};

struct DxfPlan {
  floors::FloorPlan plan;          ///< not validated (floors::validate_plan does that)
  std::vector<std::string> notes;  ///< what was left out, and why
  double metres_per_unit = 1.0;    ///< as used
};

/// Reads `path`. Throws InputError naming the file (and the entity's handle) for a file
/// that is not a DXF drawing, larger than common::limits::kMaxInputFileBytes, a wall
/// layer the drawing does not have, no walls at all, an unknown unit, a coordinate that
/// is not a finite number or beyond floors::limits::kCoordinate_m, more walls than
/// floors::limits::kMaxWalls, more openings than floors::limits::kMaxOpenings, or face lines
/// crowding beyond any plan (then with the entity's line), a `layer_heights` layer that is
/// not a door or window layer, or an opening whose sill is not below its head (naming where
/// each came from). A face line drawn twice is read
/// once; the notes list at most limits::kMaxListed of each kind, then how many more.
DxfPlan read_dxf_plan(const std::filesystem::path& path, const DxfOptions& options);

/// A floor's `plan: {dxf: FILE, wall_layers: [...], door_layers: [...], window_layers:
/// [...], wall_lines: faces|centrelines, unit: mm, max_thickness, door_head, window_sill,
/// window_head, layer_heights: [{layer, sill, head}, ...]}` (lengths in the building's
/// `unit`; FILE relative to `base`), read with
/// read_dxf_plan: the floors::DrawingReader that commands give to load_building. Throws
/// InputError naming the building file's field, or the drawing.
floors::ImportedPlan read_drawing(const Field& plan, const std::filesystem::path& base,
                                  floors::LengthUnit unit);

/// Metres per unit of a DXF $INSUNITS code (1 in, 2 ft, 4 mm, 5 cm, 6 m, ...); nullopt for
/// 0 (unitless) and codes that are not lengths.
std::optional<double> insunits_metres(int code);

/// Metres per unit named in a file ("mm", "cm", "m", "in", "ft"); nullopt otherwise.
std::optional<double> unit_metres(const std::string& name);

}  // namespace ccbuild::import
