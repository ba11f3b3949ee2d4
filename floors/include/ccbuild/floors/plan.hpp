#pragma once
// A floor plan: vertices, straight walls between them, and openings (doors, windows)
// cut into walls. Three encodings load into the same model: YAML, JSON and the plain
// table text of the papers' examples. All lengths in the model are metres.

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "ccbuild/floors/beads.hpp"
#include "ccbuild/floors/units.hpp"

namespace ccbuild {
class Field;
}

namespace ccbuild::floors {

/// Where an element was written, so later checks can point at it.
struct SourceRef {
  std::string file;
  int line = 0;      ///< 1-based, 0 when unknown
  std::string path;  ///< field path such as `walls[3]`, empty for the table format
};

struct Vertex {
  std::int64_t id = 0;
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  SourceRef source;
};

struct Wall {
  std::int64_t id = 0;
  std::int64_t start_vertex = 0;
  std::int64_t end_vertex = 0;
  std::optional<double> thickness_m;  ///< unset: the machine's nozzle width
  SourceRef source;
  /// The IFC GlobalId of the element it was imported from (`guid:` in plan files); empty
  /// for walls not imported from an IFC model.
  std::string global_id{};
  /// The concrete its model says it takes (`model_volume:`, the file's unit cubed): the
  /// element's own quantity (IFC Qto_WallBaseQuantities NetVolume), shared among the plan
  /// walls and floors it became, m³. Unset when the model states none.
  std::optional<double> model_volume_m3{};
  /// Where the wall stops, above its floor's base (`top:` in plan files): points (offset
  /// from its start along it, top), linear between them and level beyond the first and the
  /// last, so that one point is a wall of one height (a knee wall, a parapet) and three a
  /// gable. Empty: the floor's full height. The wall is absent from every layer whose
  /// mid-height is at or above its top there (wall_gaps_above).
  std::vector<std::pair<double, double>> top_m{};
};

/// A top given as points (Wall::top_m, non-empty, offsets increasing) at `s_m` along its
/// wall: linear between the points, level beyond the first and the last.
double top_at(const std::vector<std::pair<double, double>>& top, double s_m);

/// The stretches of a wall of `length_m` whose top (Wall::top_m) is at or below `mid_m`:
/// where a layer of that mid-height leaves it out, m from its start, in order. Empty for a
/// wall without a top.
std::vector<std::pair<double, double>> wall_gaps_above(const Wall& wall, double length_m,
                                                       double mid_m);

/// A gap in a wall: absent from every layer whose mid-height lies in [sill, head).
/// A door has sill 0.
struct Opening {
  std::string id;  ///< optional name from the file ("W3"); empty when not given
  std::int64_t wall_id = 0;
  double offset_m = 0.0;  ///< from the wall's start vertex along the wall
  double width_m = 0.0;
  double sill_m = 0.0;  ///< above the floor's base
  double head_m = 0.0;  ///< above the floor's base
  SourceRef source;
  /// The IFC GlobalId of the opening element it was imported from (`guid:`); empty
  /// otherwise.
  std::string global_id{};
};

/// How an opening's lintel is made (`lintels:` in the building file); one kind for every
/// opening of a building. The lintel bears on the wall at the opening's head, `bearing_m`
/// past each side (clipped at the wall's ends, where a crossing wall carries it).
struct LintelSpec {
  enum class Type {
    /// A soffit form spans the opening at its head; the layers printed over it make the
    /// lintel (it is struck later, off the critical path).
    kFormwork,
    /// A precast element `height_m` deep: the wall over [head, head + height) is left out
    /// across the opening and both bearings, where the element lies.
    kPrecast,
  };
  Type type = Type::kFormwork;
  double height_m = 0.0;    ///< precast only
  double bearing_m = 0.15;  ///< on each side
  double place_s = 1800.0;  ///< to set one lintel (and its form), s
  int crew = 2;             ///< people who set it (0 when the machine's arm does)
  bool by_arm = false;      ///< set by the machine's arm: no crew needed
};
std::string to_string(LintelSpec::Type type);

struct FloorPlan {
  std::vector<Vertex> vertices;
  std::vector<Wall> walls;
  std::vector<Opening> openings;
  std::string source_file;
  LengthUnit units = LengthUnit::kMeter;  ///< the unit the file used: messages speak it
  /// How walls thicker than one bead are sliced (set from the machine by a project;
  /// bead width 0: one pass per wall).
  BeadSpec beads;
  /// The building's lintels (set by the building reader; a plan alone has formwork ones).
  LintelSpec lintel;

  const Vertex* find_vertex(std::int64_t id) const;
  const Wall* find_wall(std::int64_t id) const;
  /// Start and end points of a wall whose vertices exist (checked: aborts otherwise).
  Eigen::Vector2d wall_start_m(const Wall& wall) const;
  Eigen::Vector2d wall_end_m(const Wall& wall) const;
  double wall_length_m(const Wall& wall) const;
};

/// True when two plans hold the same vertices, walls and openings (in the same order,
/// lengths within `tolerance_m`); where they were read from is ignored.
bool same_model(const FloorPlan& a, const FloorPlan& b, double tolerance_m = 1e-9);

/// What an opening is in a layer whose mid-height is `mid_m` above the floor's base: open
/// in [sill, head); a precast lintel in [head, head + its height); else wall.
enum class OpeningState { kWall, kOpen, kLintel };
OpeningState opening_state(const Opening& opening, const LintelSpec& lintel, double mid_m);
/// The stretch of its wall that an opening leaves out in `state` (kOpen: the opening;
/// kLintel: with both bearings), m from the wall's start, clipped to [0, wall_length_m].
std::pair<double, double> opening_gap_m(const Opening& opening, const LintelSpec& lintel,
                                        OpeningState state, double wall_length_m);

enum class PlanFormat { kAuto, kYaml, kJson, kTable };

/// Guesses the encoding: `.json` is JSON, `.yaml`/`.yml` YAML; otherwise a file whose
/// first meaningful line is a section header (`vertices`, `walls`, `openings`) is the
/// table format, anything else YAML.
PlanFormat detect_plan_format(const std::filesystem::path& path, const std::string& text);

/// Loads and validates a plan file. Lengths in the file are in the file's own `units`
/// key when it has one (YAML/JSON), else in `default_unit`.
/// Throws InputError naming file, line and field for anything malformed or invalid.
FloorPlan load_plan(const std::filesystem::path& path, LengthUnit default_unit = LengthUnit::kMeter,
                    PlanFormat format = PlanFormat::kAuto);

/// Reads a plan from text already loaded from `path` (format kAuto: detect_plan_format).
/// Does not validate. Throws InputError naming file, line and field.
FloorPlan plan_from_text(const std::string& text, const std::filesystem::path& path,
                         LengthUnit default_unit, PlanFormat format = PlanFormat::kAuto);

/// Parses the table format (`vertices` lines `id x y`, then `walls` lines `id a b`,
/// optionally `openings` lines `wall offset width sill head`). Does not validate.
/// Throws InputError naming file and line.
FloorPlan parse_plan_table(const std::string& text, const std::string& file, LengthUnit unit);

/// Reads a plan from a YAML/JSON map (a plan file's root, or a building's inline plan).
/// Does not validate. Throws InputError naming file, line and field path.
FloorPlan read_plan(const Field& field, LengthUnit default_unit);

/// Checks a plan: ids unique, walls reference existing vertices and have length, no two
/// walls overlap collinearly, openings fit their wall and do not overlap, sill < head,
/// at least one wall. `floor_height_m`, when given, bounds opening heads.
/// Throws InputError listing every problem found.
void validate_plan(const FloorPlan& plan, std::optional<double> floor_height_m = std::nullopt,
                   const std::string& context = "");

}  // namespace ccbuild::floors
