#pragma once
// The IFC importer's stages (ifc.hpp): the STEP text checked before IFC++ sees it
// (ifc_step.cpp), what the model holds read through IFC++ (ifc_model.cpp), and the floors
// made of it (ifc.cpp). Nothing of IFC++ leaks out of ifc_model.cpp.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "ccbuild/import/ifc.hpp"
#include "note_log.hpp"

namespace ccbuild::import::ifc {

using Notes = import::detail::NoteLog;

/// What the STEP text says about itself.
struct StepSummary {
  std::string schema;  ///< FILE_SCHEMA's first name, upper case
  std::size_t entities = 0;
};

/// Checks the text of an IFC STEP file before IFC++ reads it, the whole file as IFC++ reads
/// it (ifc_step.cpp): the ISO-10303-21 header, a schema IFC++ reads (IFC4, IFC2X3), one DATA
/// section of entities only, closed by ENDSEC, then only END-ISO-10303-21 (else truncated),
/// at most `max_entities` entities, every number finite. Throws InputError naming `file`
/// and the line.
StepSummary check_step_text(const std::string& text, const std::string& file,
                            std::size_t max_entities);

/// An element of the model, as notes name it: "IfcWall 2O2Fr$t4X7Zf8NOew3FNr2 'Wall-042'".
struct Element {
  std::string type, guid, name;
  std::string describe() const;
};

/// An opening through a wall: the corners of its body, in the model's frame, metres (z
/// corrected as the wall's, see FoundWall::z_shift_m).
struct FoundOpening {
  Element what;
  std::string filled_by;  ///< "IfcDoor 1hF... 'Front door'", empty when nothing fills it
  std::string label;      ///< a short name for the plan: the filler's, else the opening's
  std::vector<Eigen::Vector3d> corners_m;
};

/// A wall as read: straight pieces of its centreline in the model's plan, metres.
struct FoundWall {
  Element what;
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> pieces;
  double thickness_m = 0.0;
  std::optional<double> bottom_m, top_m;  ///< its body's extent in z, when it has one
  bool clipped = false;                   ///< its body is cut by something ccbuild does not read
  bool bounded_cut = false;  ///< cut by a polygonal bounded half-space (read as unbounded)
  std::optional<double> net_volume_m3;  ///< the model's own NetVolume of it
  /// Where its body stops along each piece (as `pieces`): points (m from the piece's start,
  /// z in the model's frame), linear between them, from the upper outline of its solids in
  /// the wall's elevation (a gable's slope, a step); empty where no solid says.
  std::vector<std::vector<std::pair<double, double>>> piece_tops;
  /// Its body as upright polygons, each with a depth: the body's volume between two
  /// heights is, over the polygons, the area between them times the depth. A solid
  /// extruded upwards is a rectangle as wide as its profile's area and as high as the
  /// extrusion; one extruded through the wall, its profile in elevation. Empty when a solid
  /// is cut (a gable under its roof) or there is no body: a share of the wall's NetVolume
  /// then goes by height.
  struct UprightPiece {
    std::vector<Eigen::Vector2d> hz;  ///< (horizontal m, z m in the model's frame)
    double depth_m = 0.0;
  };
  std::vector<UprightPiece> body_volume;
  std::vector<FoundOpening> openings;
};

/// The volume (m³) of a wall's body between heights `lo_m` and `hi_m` (the model's frame),
/// from FoundWall::body_volume; 0 when that is empty.
double body_volume_between_m3(const FoundWall& wall, double lo_m, double hi_m);

struct FoundStorey {
  Element what;
  double elevation_m = 0.0;
  int order = 0;  ///< position in the file, for a stable order
  std::vector<FoundWall> walls;
};

/// A slab (IfcSlab of PredefinedType FLOOR, BASESLAB or ROOF, or any slab an IfcRoof is made
/// of): its extent in z, in the model's frame, metres (z corrected as a wall's).
struct FoundSlab {
  Element what;
  std::string kind;   ///< "FLOOR", "BASESLAB", "ROOF"
  bool roof = false;  ///< PredefinedType ROOF, or part of an IfcRoof
  double bottom_m = 0.0, top_m = 0.0;
  double thickness_m = 0.0;  ///< its layer set's, else its extrusion's depth
  std::string storey;        ///< the storey containing it (or its roof)
};

/// What read_model found.
struct ModelContents {
  double metres_per_unit = 1.0;
  std::string building_name;
  std::vector<FoundStorey> storeys;
  std::vector<FoundSlab> slabs;  ///< in file order
  Notes notes;                   ///< elements left out or ignored, in file order
  int left_out = 0;              ///< elements left out (walls, curtain walls, openings)
};

/// Reads the checked STEP text with IFC++ and collects storeys, walls and openings.
/// Throws InputError naming `file` (and the element) for what IFC++ reports as an error,
/// a model without a project or storeys, a placement chain that loops or is too deep.
ModelContents read_model(std::string text, const std::string& file, const IfcOptions& options);

}  // namespace ccbuild::import::ifc
