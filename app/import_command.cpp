// ccbuild import DRAWING.dxf|MODEL.ifc -o building.yaml: a DXF floor plan or an IFC model as
// a building a user can review and edit: the building file, and its plans in ccbuild's own
// YAML beside it.

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <tuple>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/limits.hpp"
#include "ccbuild/floors/print_names.hpp"
#include "ccbuild/floors/quantities.hpp"
#include "ccbuild/import/building_files.hpp"
#include "ccbuild/import/dxf.hpp"
#include "ccbuild/import/ifc.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace ccbuild::cli {
namespace {
namespace fs = std::filesystem;

struct ImportOptions {
  std::string drawing;
  std::string output;
  std::vector<std::string> wall_layers, door_layers, window_layers;
  std::string wall_lines = "faces";
  std::string unit;
  int floors = 1;
  double floor_height_m = 3.0;
  double layer_height_m = 0.1;
  std::string machine, material;
  std::vector<std::string> wall_types, excluded_materials;  ///< IFC; empty: the defaults
  bool no_material_filter = false;
  bool gap_openings = false;  ///< DXF: gaps in wall lines as doors and windows
  double max_gap_m = 3.0;
  double door_head_m = 2.1, window_sill_m = 0.9, window_head_m = 2.1;  ///< DXF defaults
  std::vector<std::string> layer_heights;  ///< DXF: LAYER=SILL:HEAD, either may be empty
  bool force = false;
};

/// A YAML comment's text: one line whatever `text` holds (yaml_escaped, without quotes).
std::string comment(const std::string& text) {
  return yaml_escaped(text);
}

/// A path a building file names (its plans, its profiles): YAML text holds only UTF-8, so a
/// path that is not cannot be named. Throws InputError on `flag`.
void check_nameable(const std::string& path, const char* flag) {
  bool exact = true;
  yaml_escaped(path, &exact);
  if (!exact)
    throw InputError("", 0, flag,
                     "'" + comment(path) +
                         "' is not UTF-8 text: a YAML building file cannot name it; rename it");
}

/// `target` as a path relative to `folder` (both made absolute first).
std::string relative_to(const fs::path& target, const fs::path& folder) {
  return fs::absolute(target)
      .lexically_normal()
      .lexically_relative(fs::absolute(folder).lexically_normal())
      .generic_string();
}

/// An IFC model: the building file, and one plan file per distinct storey plan beside it.
void run_ifc_import(const ImportOptions& o, const fs::path& machine, const fs::path& material) {
  const fs::path out(o.output);
  const fs::path folder = out.has_parent_path() ? out.parent_path() : fs::path(".");
  // The flags are held to the building file's rule for `print:`, which they are written into.
  using Fault = std::string (*)(const std::string&);
  for (const auto& [flag, names, fault_of] :
       {std::tuple{"--wall-types", &o.wall_types, Fault{floors::wall_type_name_fault}},
        std::tuple{"--exclude-materials", &o.excluded_materials,
                   Fault{floors::excluded_material_name_fault}}}) {
    if (names->size() > floors::limits::kMaxPrintNames)
      throw InputError("", 0, flag,
                       printf_string("expected at most %zu names, got %zu",
                                     floors::limits::kMaxPrintNames, names->size()));
    for (const auto& name : *names)
      if (const std::string fault = fault_of(name); !fault.empty())
        throw InputError("", 0, flag, fault);
  }
  import::IfcOptions options;
  if (!o.wall_types.empty()) options.wall_types = o.wall_types;
  if (!o.excluded_materials.empty()) options.excluded_materials = o.excluded_materials;
  if (o.no_material_filter) options.excluded_materials.clear();
  options.layer_height_m = o.layer_height_m;
  const import::IfcImport read = import::read_ifc_building(o.drawing, options);
  const floors::Building& b = read.building;
  const import::BuildingFiles files = import::ifc_building_files(
      read, o.drawing, {out, relative_to(machine, folder), relative_to(material, folder)});
  OutputClaims outputs({o.drawing, machine, material});
  outputs.claim_file("--output", out, o.force);
  const std::string mark = import::plan_file_mark(out);
  for (const auto& p : files.plan_paths)
    outputs.claim_derived("--output (its plans)", p, out, o.force, mark);
  for (std::size_t d = 0; d < files.plans.size(); ++d)
    outputs.write(files.plan_paths[d], files.plans[d]);
  outputs.write(out, files.building);
  outputs.commit();

  for (const auto& note : read.notes) std::cerr << "import: note: " << comment(note) << "\n";
  std::size_t walls = 0, openings = 0;
  for (const auto& f : b.floors) {
    walls += f.plan.walls.size();
    openings += f.plan.openings.size();
  }
  std::cout << printf_string(
      "%s: %zu floors, %zu walls, %zu openings (%s)\nwritten: %s and %zu "
      "plan file%s beside it\n",
      o.drawing.c_str(), b.floors.size(), walls, openings, read.schema.c_str(),
      out.string().c_str(), files.plans.size(), files.plans.size() == 1 ? "" : "s");
  for (const auto& q : files.quantities) std::cout << "quantities: " << q << "\n";
}

/// --layer-heights items, LAYER=SILL:HEAD in metres (either may be left empty, not both).
/// Throws InputError (field --layer-heights) naming the item and what was expected.
std::map<std::string, import::DxfOptions::Heights> layer_heights(
    const std::vector<std::string>& items) {
  std::map<std::string, import::DxfOptions::Heights> out;
  for (const std::string& item : items) {
    const auto refuse = [&](const std::string& why) {
      throw InputError("", 0, "--layer-heights", "'" + echoed(item) + "': " + why);
    };
    const auto eq = item.rfind('=');
    if (eq == std::string::npos || eq == 0)
      refuse(
          "expected LAYER=SILL:HEAD in metres (A-GLAZ-HIGH=1.5:2.1; A-DOOR=:2.4 for a head "
          "only)");
    const std::string heights = item.substr(eq + 1);
    const auto colon = heights.find(':');
    if (colon == std::string::npos)
      refuse("expected SILL:HEAD after the '=' (either may be empty)");
    import::DxfOptions::Heights h;
    const auto number = [&](const std::string& text, const char* what) -> std::optional<double> {
      if (text.empty()) return std::nullopt;
      std::size_t used = 0;
      double value = 0.0;
      try {
        value = std::stod(text, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != text.size() || !floors::limits::kOpeningHeight_m.contains(value))
        refuse(std::string("its ") + what + " '" + echoed(text) + "' is not a height in metres (" +
               floors::limits::kOpeningHeight_m.describe("m") + ")");
      return value;
    };
    h.sill_m = number(heights.substr(0, colon), "sill");
    h.head_m = number(heights.substr(colon + 1), "head");
    if (!h.sill_m && !h.head_m) refuse("give the layer's sill, its head or both");
    if (!out.emplace(item.substr(0, eq), h).second) refuse("the layer is given twice");
  }
  return out;
}

void run_import(const ImportOptions& o, int& exit_code) {
  const fs::path out(o.output);
  const fs::path folder = out.has_parent_path() ? out.parent_path() : fs::path(".");
  const fs::path plan_path = import::dxf_plan_path(out);
  std::error_code ec;
  if (!fs::is_regular_file(o.drawing, ec)) throw InputError(o.drawing, 0, "", "file not found");
  const fs::path machine = o.machine.empty()
                               ? fs::path(CCBUILD_CONFIG_DIR) / "machines/cc-gantry.yaml"
                               : fs::path(o.machine);
  const fs::path material = o.material.empty()
                                ? fs::path(CCBUILD_CONFIG_DIR) / "materials/standard-mix.yaml"
                                : fs::path(o.material);
  // The building names its plans (beside it) and profiles: each must be YAML text.
  check_nameable(out.filename().string(), "--output");
  check_nameable(relative_to(machine, folder), "--machine");
  check_nameable(relative_to(material, folder), "--material");
  if (import::is_ifc_path(o.drawing)) {
    for (const auto& [given, flag] :
         {std::pair{!o.wall_layers.empty(), "--wall-layers"},
          std::pair{!o.door_layers.empty(), "--door-layers"},
          std::pair{!o.window_layers.empty(), "--window-layers"},
          std::pair{!o.unit.empty(), "--unit"}, std::pair{o.floors != 1, "--floors"},
          std::pair{o.gap_openings, "--gap-openings"},
          std::pair{!o.layer_heights.empty(), "--layer-heights"}})
      if (given)
        throw InputError("", 0, flag,
                         "is for DXF drawings; an IFC model says its storeys, walls and unit");
    run_ifc_import(o, machine, material);
    exit_code = kExitOk;
    return;
  }
  if (!o.wall_types.empty() || !o.excluded_materials.empty() || o.no_material_filter)
    throw InputError("", 0, "--wall-types",
                     "--wall-types and --exclude-materials are for IFC models");
  if (o.wall_layers.empty())
    throw InputError("", 0, "--wall-layers", "a DXF drawing needs --wall-layers (its wall layers)");
  OutputClaims outputs({o.drawing, machine, material});
  outputs.claim_file("--output", out, o.force);
  const std::string mark = import::plan_file_mark(out);
  outputs.claim_derived("--output (its plan)", plan_path, out, o.force, mark);

  import::DxfOptions d;
  d.wall_layers = o.wall_layers;
  d.door_layers = o.door_layers;
  d.window_layers = o.window_layers;
  d.wall_lines = o.wall_lines == "faces" ? import::DxfOptions::WallLines::kFaces
                                         : import::DxfOptions::WallLines::kCentrelines;
  if (!o.unit.empty()) d.metres_per_unit = import::unit_metres(o.unit);
  d.gap_openings = o.gap_openings;
  d.max_gap_m = o.max_gap_m;
  d.door_head_m = o.door_head_m;
  d.window_sill_m = o.window_sill_m;
  d.window_head_m = o.window_head_m;
  d.layer_heights = layer_heights(o.layer_heights);
  for (const auto& [layer, heights] : d.layer_heights) {
    const auto lower = [](std::string text) {
      for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      return text;
    };
    const auto same = [&](const std::string& name) { return lower(name) == lower(layer); };
    if (std::none_of(o.door_layers.begin(), o.door_layers.end(), same) &&
        std::none_of(o.window_layers.begin(), o.window_layers.end(), same))
      throw InputError("", 0, "--layer-heights",
                       "layer '" + echoed(layer) +
                           "' is not among --door-layers or --window-layers; sill and head are "
                           "given for the layers whose blocks are doors or windows");
  }
  const import::DxfPlan read = import::read_dxf_plan(o.drawing, d);
  floors::validate_plan(read.plan, o.floor_height_m, "the imported plan");

  const import::BuildingFiles files = import::dxf_building_files(
      read, o.drawing, {out, relative_to(machine, folder), relative_to(material, folder)}, o.floors,
      o.floor_height_m, o.layer_height_m);
  outputs.write(plan_path, files.plans.front());
  outputs.write(out, files.building);
  outputs.commit();

  for (const auto& note : read.notes) std::cerr << "import: note: " << comment(note) << "\n";
  int thick = 0;
  for (const auto& w : read.plan.walls) thick += w.thickness_m.has_value();
  std::cout << printf_string(
      "%s: %zu walls (%d with their drawn thickness), %zu openings, %zu vertices; left out: "
      "%zu (each said on stderr)\nwritten: %s (%d floor%s of %s m) and its plan %s\n",
      o.drawing.c_str(), read.plan.walls.size(), thick, read.plan.openings.size(),
      read.plan.vertices.size(), read.notes.size(), out.string().c_str(), o.floors,
      o.floors == 1 ? "" : "s", import::exact_text(o.floor_height_m).c_str(),
      plan_path.string().c_str());
  exit_code = kExitOk;
}

}  // namespace

void add_import_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ImportOptions>();
  CLI::App* command = app.add_subcommand(
      "import",
      "Turn an IFC model or a DXF floor plan into a building you can review, edit and "
      "schedule: the building file (-o) and, beside it, its plans in ccbuild's own YAML, every "
      "wall and opening commented with the element it came from.\n"
      "IFC (IFC4, IFC2X3; docs/formats.md, \"IFC models\"): every storey with walls is a floor "
      "(height: up to the slab over it, else the next storey), one plan file per distinct storey "
      "plan "
      "(<name>.1.plan.yaml, ...); walls of the types asked for (--wall-types) whose materials are "
      "printable (--exclude-materials) with their axis, thickness and openings; each keeps its "
      "GlobalId (guid:). Curtain walls, curved or sloped walls and what else cannot be printed is "
      "said on stderr, naming the element's GlobalId; nothing is guessed. Every command also "
      "takes the .ifc directly, with the default filters; both routes give the same schedule.\n"
      "DXF: the same plan repeats on every floor (--floors), in <name>.plan.yaml. Walls drawn as "
      "two face lines become one wall along their middle, as thick as they are apart "
      "(--wall-lines centrelines for plans drawn as centrelines); doors and windows are block "
      "inserts on their layers, or, with --gap-openings, gaps in the wall lines (a window where "
      "a line on a window layer lies in the gap, else a door). A building file can also name the "
      "drawing directly (plan: {dxf: "
      "...}); both give the same plan.\n"
      "Examples:\n"
      "  ccbuild import house.ifc -o house.yaml\n"
      "  ccbuild import house.ifc --wall-types IfcWall,IfcWallStandardCase,IfcWallElementedCase "
      "--exclude-materials glass -o house.yaml\n"
      "  ccbuild import ground.dxf --wall-layers A-WALL --door-layers A-DOOR -o house.yaml\n"
      "  ccbuild import ground.dxf --wall-layers A-WALL --door-layers A-DOOR --window-layers "
      "A-GLAZ,A-GLAZ-HIGH --layer-heights A-GLAZ-HIGH=1.5:2.1 -o house.yaml\n"
      "  ccbuild import plan.dxf --wall-layers WALLS --wall-lines centrelines --unit mm "
      "--floors 3 --floor-height 2.8 -o block.yaml");
  command->add_option("DRAWING", o->drawing, "The IFC model (.ifc) or DXF drawing")->required();
  command->add_option("-o,--output", o->output, "The building file to write (YAML)")
      ->required()
      ->check(output_path());
  command
      ->add_option("--wall-layers", o->wall_layers,
                   "DXF: layers holding the walls (any case; required for a drawing)")
      ->delimiter(',');
  command
      ->add_option("--wall-types", o->wall_types,
                   "IFC: element types read as walls (default IfcWall,IfcWallStandardCase; add "
                   "IfcWallElementedCase for stud walls)")
      ->delimiter(',');
  command
      ->add_option("--exclude-materials", o->excluded_materials,
                   "IFC: a wall all of whose materials' names contain one of these (any case) is "
                   "not printed (default glass,gypsum,plasterboard,drywall,timber,wood,stud,"
                   "insulation)")
      ->delimiter(',');
  command->add_flag("--no-material-filter", o->no_material_filter,
                    "IFC: print walls whatever their materials");
  command->add_option("--door-layers", o->door_layers, "Layers holding door block inserts")
      ->delimiter(',');
  command->add_option("--window-layers", o->window_layers, "Layers holding window block inserts")
      ->delimiter(',');
  command
      ->add_option("--wall-lines", o->wall_lines,
                   "How walls are drawn: faces (two lines a wall's thickness apart) or centrelines")
      ->check(CLI::IsMember({"faces", "centrelines"}))
      ->capture_default_str();
  command->add_flag("--gap-openings", o->gap_openings,
                    "DXF: a gap between two walls in line is a door, or a window where a line on "
                    "a window layer (glazing) lies in it");
  command
      ->add_option("--max-gap", o->max_gap_m,
                   "DXF: the widest gap read as an opening, m (with --gap-openings)")
      ->check(CLI::Range(0.01, 100.0))
      ->capture_default_str();
  command
      ->add_option("--door-head", o->door_head_m,
                   "DXF: a door's head, m, where its block has no HEAD attribute")
      ->check(number_in(floors::limits::kOpeningHeight_m, "m"))
      ->capture_default_str();
  command
      ->add_option("--window-sill", o->window_sill_m,
                   "DXF: a window's sill, m, where its block has no SILL attribute")
      ->check(number_in(floors::limits::kOpeningHeight_m, "m"))
      ->capture_default_str();
  command
      ->add_option("--window-head", o->window_head_m,
                   "DXF: a window's head, m, where its block has no HEAD attribute")
      ->check(number_in(floors::limits::kOpeningHeight_m, "m"))
      ->capture_default_str();
  command
      ->add_option("--layer-heights", o->layer_heights,
                   "DXF: a door or window layer's own sill and head, m, for its blocks without "
                   "SILL or HEAD attributes: LAYER=SILL:HEAD, either may be empty "
                   "(A-GLAZ-HIGH=1.5:2.1,A-DOOR-GARAGE=:2.4)")
      ->delimiter(',');
  command
      ->add_option("--unit", o->unit,
                   "The drawing's unit (default: its $INSUNITS): mm, cm, m, in, ft")
      ->check(CLI::IsMember({"mm", "cm", "m", "in", "ft"}));
  command->add_option("--floors", o->floors, "How many floors repeat the plan")
      ->check(CLI::Range(1, floors::limits::kMaxFloors))
      ->capture_default_str();
  command
      ->add_option(
          "--floor-height", o->floor_height_m,
          "Floor-to-floor height, m (" + floors::limits::kFloorHeight_m.describe("m") + ")")
      ->check(number_in(floors::limits::kFloorHeight_m, "m"))
      ->capture_default_str();
  command
      ->add_option("--layer-height", o->layer_height_m,
                   "Printed layer height, m (" + floors::limits::kLayerHeight_m.describe("m") + ")")
      ->check(number_in(floors::limits::kLayerHeight_m, "m"))
      ->capture_default_str();
  command->add_option("--machine", o->machine,
                      "Machine profile the building names (default: the bundled cc-gantry)");
  command->add_option("--material", o->material,
                      "Material profile the building names (default: the bundled standard mix)");
  command->add_flag("--force", o->force, "Replace the building and plan files if they exist");
  command->callback([o, &exit_code] { run_import(*o, exit_code); });
}

}  // namespace ccbuild::cli
