// ccbuild import DRAWING.dxf -o building.yaml: a DXF floor plan as a building a user can
// review and edit: the building file, and the plan in ccbuild's own YAML beside it.

#include <cstdlib>
#include <iostream>
#include <memory>

#include "ccbuild/common/atomic_file.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/limits.hpp"
#include "ccbuild/import/dxf.hpp"
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
  bool force = false;
};

/// The shortest text that reads back as exactly `value`, so that the plan written is the
/// plan read.
std::string exact(double value) {
  for (int digits = 6; digits <= 17; ++digits) {
    const std::string text = printf_string("%.*g", digits, value);
    if (std::strtod(text.c_str(), nullptr) == value) return text;
  }
  return printf_string("%.17g", value);
}

/// YAML's double-quoted scalar.
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string plan_yaml(const floors::FloorPlan& plan, const std::string& drawing) {
  std::string out = "# Imported by `ccbuild import` from " + drawing +
                    " (every wall and opening names\n# the drawing's entity it came from).\n"
                    "units: m\nvertices:\n";
  for (const auto& v : plan.vertices)
    out += printf_string("  - {id: %lld, x: %s, y: %s}\n", static_cast<long long>(v.id),
                         exact(v.position_m.x()).c_str(), exact(v.position_m.y()).c_str());
  out += "walls:\n";
  for (const auto& w : plan.walls) {
    out +=
        printf_string("  - {id: %lld, start: %lld, end: %lld", static_cast<long long>(w.id),
                      static_cast<long long>(w.start_vertex), static_cast<long long>(w.end_vertex));
    if (w.thickness_m) out += ", thickness: " + exact(*w.thickness_m);
    out += "}  # " + w.source.path + "\n";
  }
  if (!plan.openings.empty()) out += "openings:\n";
  for (const auto& o : plan.openings)
    out +=
        printf_string("  - {id: %s, wall: %lld, offset: %s, width: %s, sill: %s, head: %s}  # %s\n",
                      quoted(o.id).c_str(), static_cast<long long>(o.wall_id),
                      exact(o.offset_m).c_str(), exact(o.width_m).c_str(), exact(o.sill_m).c_str(),
                      exact(o.head_m).c_str(), o.source.path.c_str());
  return out;
}

/// `target` as a path relative to `folder` (both made absolute first).
std::string relative_to(const fs::path& target, const fs::path& folder) {
  return fs::absolute(target)
      .lexically_normal()
      .lexically_relative(fs::absolute(folder).lexically_normal())
      .generic_string();
}

void run_import(const ImportOptions& o, int& exit_code) {
  const fs::path out(o.output);
  const fs::path folder = out.has_parent_path() ? out.parent_path() : fs::path(".");
  const fs::path plan_path = folder / (out.stem().string() + ".plan.yaml");
  std::error_code ec;
  if (!fs::is_regular_file(o.drawing, ec)) throw InputError(o.drawing, 0, "", "file not found");
  const fs::path machine = o.machine.empty()
                               ? fs::path(CCBUILD_CONFIG_DIR) / "machines/cc-gantry.yaml"
                               : fs::path(o.machine);
  const fs::path material = o.material.empty()
                                ? fs::path(CCBUILD_CONFIG_DIR) / "materials/standard-mix.yaml"
                                : fs::path(o.material);
  OutputClaims outputs({o.drawing, machine, material});
  outputs.claim_file("--output", out, o.force);
  outputs.claim_file("--output (its plan)", plan_path, o.force);

  import::DxfOptions d;
  d.wall_layers = o.wall_layers;
  d.door_layers = o.door_layers;
  d.window_layers = o.window_layers;
  d.wall_lines = o.wall_lines == "faces" ? import::DxfOptions::WallLines::kFaces
                                         : import::DxfOptions::WallLines::kCentrelines;
  if (!o.unit.empty()) d.metres_per_unit = import::unit_metres(o.unit);
  const import::DxfPlan read = import::read_dxf_plan(o.drawing, d);
  floors::validate_plan(read.plan, o.floor_height_m, "the imported plan");

  std::string building = "# Imported by `ccbuild import` from " + o.drawing +
                         ": review it, then `ccbuild validate` it.\n";
  building += "name: " + quoted(out.stem().string()) +
              "\nunits: m\nlayer_height: " + exact(o.layer_height_m) +
              "\nmaterial: " + quoted(relative_to(material, folder)) +
              "\nmachine: " + quoted(relative_to(machine, folder)) + "\nfloors:\n";
  for (int k = 0; k < o.floors; ++k)
    building += printf_string("  - {name: %s, height: %s, plan: %s}\n",
                              quoted(k == 0 ? "ground" : "floor " + std::to_string(k)).c_str(),
                              exact(o.floor_height_m).c_str(),
                              quoted(plan_path.filename().string()).c_str());
  write_file_atomically(plan_path, plan_yaml(read.plan, o.drawing), o.force, {o.drawing});
  write_file_atomically(out, building, o.force, {o.drawing});

  for (const auto& note : read.notes) std::cerr << "import: note: " << note << "\n";
  int thick = 0;
  for (const auto& w : read.plan.walls) thick += w.thickness_m.has_value();
  std::cout << printf_string(
      "%s: %zu walls (%d with their drawn thickness), %zu openings, %zu vertices; left out: "
      "%zu (each said on stderr)\nwritten: %s (%d floor%s of %s m) and its plan %s\n",
      o.drawing.c_str(), read.plan.walls.size(), thick, read.plan.openings.size(),
      read.plan.vertices.size(), read.notes.size(), out.string().c_str(), o.floors,
      o.floors == 1 ? "" : "s", exact(o.floor_height_m).c_str(), plan_path.string().c_str());
  exit_code = kExitOk;
}

}  // namespace

void add_import_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ImportOptions>();
  CLI::App* command = app.add_subcommand(
      "import",
      "Turn a DXF floor plan into a building you can review, edit and schedule: the building "
      "file (-o) and, beside it, the plan in ccbuild's own YAML (<name>.plan.yaml), every wall "
      "and opening commented with the drawing's entity it came from. The same plan repeats on "
      "every floor (--floors). Walls drawn as two face lines become one wall along their "
      "middle, as thick as they are apart (--wall-lines centrelines for plans drawn as "
      "centrelines); doors and windows are block inserts on their layers. What cannot be read "
      "is said on stderr, naming the entity (docs/formats.md, \"DXF drawings\"). A building "
      "file can also name the drawing directly (plan: {dxf: ...}); both give the same plan.\n"
      "Examples:\n"
      "  ccbuild import ground.dxf --wall-layers A-WALL --door-layers A-DOOR -o house.yaml\n"
      "  ccbuild import plan.dxf --wall-layers WALLS --wall-lines centrelines --unit mm "
      "--floors 3 --floor-height 2.8 -o block.yaml");
  command->add_option("DRAWING", o->drawing, "The DXF drawing")->required();
  command->add_option("-o,--output", o->output, "The building file to write (YAML)")
      ->required()
      ->check(output_path());
  command->add_option("--wall-layers", o->wall_layers, "Layers holding the walls (any case)")
      ->required()
      ->delimiter(',');
  command->add_option("--door-layers", o->door_layers, "Layers holding door block inserts")
      ->delimiter(',');
  command->add_option("--window-layers", o->window_layers, "Layers holding window block inserts")
      ->delimiter(',');
  command
      ->add_option("--wall-lines", o->wall_lines,
                   "How walls are drawn: faces (two lines a wall's thickness apart) or centrelines")
      ->check(CLI::IsMember({"faces", "centrelines"}))
      ->capture_default_str();
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
