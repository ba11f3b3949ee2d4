#pragma once
// A whole building: floors stacked one on another, each with its plan, height, openings
// and the anchor points where climbing pipes are embedded; plus the layer height and
// references to the material and machine profiles.

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "ccbuild/common/document.hpp"
#include "ccbuild/floors/material.hpp"
#include "ccbuild/floors/plan.hpp"
#include "ccbuild/floors/units.hpp"

namespace ccbuild::floors {

/// A vertical anchor pipe embedded in a wall, `offset_m` from the wall's start vertex.
struct AnchorPoint {
  std::string id;
  std::int64_t wall_id = 0;
  double offset_m = 0.0;
  SourceRef source;
};

struct Floor {
  std::string name;
  int index = 0;          ///< 0 = ground floor
  double height_m = 0.0;  ///< floor-to-floor height
  /// The slab placed on its walls: from their top to the next floor's base (`slab` in the
  /// file, 0 by default). Not printed; the floors above stand on it.
  double slab_m = 0.0;
  double base_elevation_m = 0.0;  ///< sum of the heights and slabs below
  /// Its level in the model (`level`: its storey's elevation), when stated; the floor
  /// under it then runs up to it under its slab (docs/formats.md, Floors).
  std::optional<double> level_m;
  FloorPlan plan;  ///< includes the floor's own openings
  std::vector<AnchorPoint> anchors;
  SourceRef source;
};

/// What the machine prints of a building (`print:`; docs/formats.md, "What is printed").
struct PrintSpec {
  /// `thin_walls`: a wall thinner than the machine's narrowest bead is left out and said,
  /// for the crew to build (`leave-out`, the default), or stops the run (`refuse`).
  bool refuse_thin_walls = false;
  /// `wall_types` and `exclude_materials`: which of a model's elements were read as walls
  /// and whose materials kept them out of the print (IFC: as `ccbuild import` chose them,
  /// or a model named directly was read with). Empty when the building does not say.
  std::vector<std::string> wall_types, excluded_materials;
  /// The building states a print spec (`print:`, or a model named directly): the schedule
  /// records it.
  bool stated = false;
};

/// A wall the print spec left out of what the machine prints, for the crew to build.
struct LeftOutWall {
  int floor = 0;
  std::int64_t wall_id = 0;
  double thickness_m = 0.0;
  double narrowest_m = 0.0;  ///< the machine's narrowest bead, m
  std::string global_id;     ///< its model element's GlobalId; empty for other plans
  SourceRef source;
};

/// One line on a left-out wall, in `unit`: which, how thick, why, and where it was read.
std::string left_out_text(const std::string& floor_name, const LeftOutWall& wall, LengthUnit unit);

/// Where a building stands in the machine's frame (`site:` in the building file). Plan
/// coordinates are turned by `rotation_rad` (anticlockwise) about the plan's origin, then
/// moved by the origin: `origin_m` as given, or, with `centre`, so that the footprint's
/// bounding box sits in the middle of the machine's x and y travel. Without a site (or
/// with neither), plan coordinates are the machine's.
struct Site {
  std::optional<Eigen::Vector2d> origin_m;  ///< `origin: [x, y]`, in the file's unit
  double rotation_rad = 0.0;                ///< `rotation_deg`, in degrees in the file
  bool centre = false;                      ///< `place: centre`
  SourceRef source;
  /// Whether any placement key was given (a site may hold only its programme).
  bool places = false;
  /// The site's other keys (its programme: start, calendar, crews, weather), with their
  /// lines, for the schedule to read; unset when there are none.
  std::optional<Document> programme;
};
/// The keys of `site:` that place the building.
inline const std::vector<std::string> kSitePlacementKeys = {"origin", "rotation_deg", "place"};

/// The slabs poured on each floor's walls and the roof on the top floor's (`slabs:` in
/// the building file): formwork and reinforcement, the pour, then curing until the slab's
/// concrete carries the next floor's walls. Its area is the convex hull of the floor's
/// plan (an L-shaped floor's is overstated).
struct SlabSpec {
  double thickness_m = 0.2;             ///< every floor's `slab` where it gives none
  double setup_s = 4 * 3600.0;          ///< formwork and reinforcement, s
  double pour_rate_m3_s = 20.0 / 3600;  ///< the pour's placing rate
  double ready_mpa = 5.0;  ///< the strength at which the next floor's walls start on it
  /// Its concrete (EN 1992-1-1 §3.1.2), C30/37 with a class N cement by default.
  En1992Strength concrete{38.0, 0.25, "N", 0.0};
  int crew = 4;      ///< people who set up and pour
  bool roof = true;  ///< a roof slab on the top floor
};

/// The area a floor's slab covers: the convex hull of its plan's vertices, m².
double slab_area_m2(const Floor& floor);

struct Building {
  std::string name;
  std::string source_file;
  LengthUnit units = LengthUnit::kMeter;  ///< as the file said; the model is in metres
  double layer_height_m = 0.0;
  /// Between two floors: the slab stage (placing and curing the slab before the next
  /// floor's walls start on it), s; `slab_stage_h` in the file, 8 h by default.
  double slab_stage_s = 8 * 3600.0;
  /// Slabs poured and cured by a strength rule (`slabs:`; not with `slab_stage_h`);
  /// unset: the fixed slab stage.
  std::optional<SlabSpec> slabs;
  /// How every opening's lintel is made (`lintels:`); also in every floor's plan.
  LintelSpec lintels;
  std::vector<Floor> floors;
  /// resolved against the building file's folder; empty when the building names none (the
  /// flags' or the bundled profile is used)
  std::filesystem::path material_profile;
  std::filesystem::path machine_profile;
  SourceRef material_source;
  SourceRef machine_source;
  std::optional<Site> site;
  /// Between the two skins of a wall thicker than one bead (`wall_pattern:`).
  WallPattern wall_pattern = WallPattern::kSolid;
  /// Where a climbing machine climbs (`climbs:`): between floors (`between-floors`, the
  /// default: a stage that would end part-way up a floor ends at the floor below's top,
  /// when that still prints something), or wherever its legs and reach allow
  /// (`within-storey`: fewer climbs, but a climb's wait for its anchors then holds up a
  /// storey's layers part-way).
  bool climbs_within_storey = false;
  /// What the importers of drawn plans left out, and why (empty for plans in ccbuild's
  /// own formats).
  std::vector<std::string> import_notes;
  PrintSpec print;
  /// The walls leave_out_thin_walls took out of the floors' plans, in floor and wall order.
  std::vector<LeftOutWall> left_out;
  /// Every file read to build this model (the building file and its plans), so that no
  /// output is ever written over one of them.
  std::vector<std::filesystem::path> files_read;
};

/// The space a building takes: its footprint's bounding box over every floor's vertices,
/// and the top of its top floor, m.
struct Envelope {
  Eigen::Vector2d min_m = Eigen::Vector2d::Zero(), max_m = Eigen::Vector2d::Zero();
  double top_m = 0.0;
  /// Width along x and y (0 for a building without vertices).
  Eigen::Vector2d size_m() const { return (max_m - min_m).cwiseMax(Eigen::Vector2d::Zero()); }
};
Envelope envelope(const Building& building);

/// Takes every wall thinner than the narrowest bead of `beads` (wall_beads says kTooThin)
/// out of its floor's plan, with its openings and the ends no printed wall uses (so that
/// the building's extent, placement and slab are the printed walls'), into
/// `building.left_out`; nothing when the print spec refuses thin walls (the fit check then
/// names them). Throws InputError, at the wall, when an anchor of the floor stands on it or
/// when it is the floor's last wall.
void leave_out_thin_walls(Building& building, const BeadSpec& beads);

/// Turns every floor plan's vertices by `rotation_rad` about the plan's origin, then
/// moves them by `origin_m`: p -> R p + origin (walls, openings and anchors go along,
/// being placed along walls).
void place_building(Building& building, double rotation_rad, const Eigen::Vector2d& origin_m);

/// A floor's plan drawn in another format (`plan: {dxf: FILE, ...}`), as an importer read it.
struct ImportedPlan {
  FloorPlan plan;
  std::vector<std::string> notes;  ///< what was left out, and why
  std::filesystem::path file;      ///< the drawing read
};
/// Reads such a plan: `plan` is the floor's `plan:` map, `base` the building file's folder,
/// `unit` the building's. Given by the caller (ccbuild::import's read_drawing), so that
/// floors links no format library; without one, a drawn plan is refused.
using DrawingReader = std::function<ImportedPlan(
    const Field& plan, const std::filesystem::path& base, LengthUnit unit)>;

/// Loads and validates a building file (YAML or JSON) and the plans it references
/// (paths relative to the building file). Does not open the material and machine
/// profiles; their owners load them (load_material_profile, machine::load_machine).
/// Every number is checked against its plausible range (limits.hpp) and the building's
/// layers against limits::kMaxLayers. Throws InputError naming file, line and field for
/// every problem found.
Building load_building(const std::filesystem::path& path, const DrawingReader& drawings = {});

/// A user's FILE: a building (its root has `floors:`), or a single floor plan.
struct BuildingOrPlan {
  bool is_building = false;
  Building building;  ///< when is_building
  FloorPlan plan;     ///< otherwise: read and not yet validated against a floor height
};

/// Reads and parses `path` once and loads whatever it is. A plan's lengths are in its own
/// `units` key when it has one, else in `plan_unit`. Throws InputError.
BuildingOrPlan load_building_or_plan(const std::filesystem::path& path, LengthUnit plan_unit,
                                     const DrawingReader& drawings = {});

/// A building of one floor holding `plan`, for tools that work on a single plan: checks
/// the heights (metres) against their ranges (InputError on field `floor_height` or
/// `layer_height`, in the plan's unit) and validates the plan under that floor height.
Building building_from_plan(FloorPlan plan, std::string name, double floor_height_m,
                            double layer_height_m);

}  // namespace ccbuild::floors
