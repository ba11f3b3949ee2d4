// ccbuild validate FILE: load and check a building (with its profiles) or one plan, and
// print what it holds.

#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "ccbuild/floors/quantities.hpp"
#include "ccbuild/orchestrator/layer_summary.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace ccbuild::cli {
namespace {

struct ValidateOptions {
  std::string file;
  bool json = false;
  InputOptions input;
};

void run_validate(const ValidateOptions& options, int& exit_code) {
  // Opening checks everything: the files, the profiles, and that the machine reaches it.
  const orchestrator::Project project = open_input(options.file, options.input);
  const floors::Building& b = project.building;
  const machine::MachineModel& machine = project.machine_model();
  const floors::Envelope space = floors::envelope(b);
  const Eigen::Vector2d extent = space.size_m();
  const double top_m = space.top_m;
  const orchestrator::BuildingSummary summary = orchestrator::summarize_building(b);
  int walls = 0, openings = 0, anchors = 0;
  for (const auto& f : summary.floors) {
    walls += f.wall_count;
    openings += f.opening_count;
    anchors += f.anchor_count;
  }
  // The walls' concrete as this machine lays them, against the model's own quantities
  // (imported models only: a building that states no volume prints none of this).
  bool modelled = false;
  for (const auto& f : b.floors)
    for (const auto& w : f.plan.walls) modelled = modelled || w.model_volume_m3.has_value();
  std::vector<floors::FloorQuantities> quantities;
  if (modelled)
    for (const auto& f : b.floors)
      quantities.push_back(floors::floor_quantities(f, b.layer_height_m, machine.nozzle_width_m));
  const double reach_x = machine.x.max_m - machine.x.min_m;
  const double reach_y = machine.y.max_m - machine.y.min_m;
  const double reach_z = machine.z.max_m - machine.z.min_m;

  if (options.json) {
    nlohmann::ordered_json out;
    out["file"] = options.file;
    out["kind"] = project.is_building ? "building" : "plan";
    out["valid"] = true;
    out["name"] = b.name;
    out["units"] = floors::to_string(project.file_unit);
    out["shown_in"] = floors::to_string(b.units);
    out["layer_height_m"] = b.layer_height_m;
    out["material"] = {{"name", project.material.name}, {"origin", project.material_origin}};
    out["machine"] = {{"name", machine.name},
                      {"origin", project.machine_origin},
                      {"reach_m", {reach_x, reach_y, reach_z}}};
    out["extent_m"] = {extent.x(), extent.y(), top_m};
    const schedule::Placement& placed = project.placement;
    out["placement"] = {{"how", placed.how},
                        {"origin_m", {placed.origin_m.x(), placed.origin_m.y()}},
                        {"rotation_deg", placed.rotation_rad * 180.0 / M_PI},
                        {"min_m", {space.min_m.x(), space.min_m.y()}},
                        {"max_m", {space.max_m.x(), space.max_m.y()}}};
    out["import_notes"] = b.import_notes;
    if (b.print.stated) {
      out["print"] = {{"thin_walls", b.print.refuse_thin_walls ? "refuse" : "leave-out"}};
      if (!b.print.wall_types.empty()) {
        out["print"]["wall_types"] = b.print.wall_types;
        out["print"]["exclude_materials"] = b.print.excluded_materials;
      }
    }
    out["left_out"] = nlohmann::ordered_json::array();
    for (const auto& w : b.left_out)
      out["left_out"].push_back(
          {{"floor", w.floor},
           {"wall", w.wall_id},
           {"thickness_m", w.thickness_m},
           {"narrowest_bead_m", w.narrowest_m},
           {"guid", w.global_id},
           {"text", floors::left_out_text(b.floors[w.floor].name, w, b.units)}});
    out["floors"] = nlohmann::ordered_json::array();
    for (const auto& f : summary.floors) {
      out["floors"].push_back({{"floor", f.floor_index},
                               {"name", f.name},
                               {"height_m", f.height_m},
                               {"base_elevation_m", f.base_elevation_m},
                               {"wall_count", f.wall_count},
                               {"opening_count", f.opening_count},
                               {"anchor_count", f.anchor_count},
                               {"layer_count", f.layer_count},
                               {"distinct_geometry_count", f.distinct_geometries}});
      if (modelled) {
        const floors::FloorQuantities& q = quantities[out["floors"].size() - 1];
        auto& row = out["floors"].back();
        row["printed_m3"] = q.printed_m3;
        row["model_volume_m3"] = q.model_m3 ? nlohmann::ordered_json(*q.model_m3) : nullptr;
        row["printed_modelled_m3"] = q.printed_modelled_m3;
        row["model_volume_off"] = q.off();
      }
    }
    out["totals"] = {{"floor_count", summary.floors.size()},
                     {"wall_count", walls},
                     {"opening_count", openings},
                     {"anchor_count", anchors},
                     {"layer_count", summary.total_layers},
                     {"distinct_geometry_count", summary.distinct_geometries}};
    std::cout << out.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
    exit_code = kExitOk;
    return;
  }

  auto L = [&](double m) { return project.length(m, 2); };
  std::cout << options.file << ": valid " << (project.is_building ? "building" : "plan") << "\n";
  if (!b.name.empty()) std::cout << printf_string("  %-10s %s\n", "name", b.name.c_str());
  std::cout << printf_string(
      "  %-10s %s in the file, metres inside%s\n", "units",
      floors::to_string(project.file_unit).c_str(),
      b.units == project.file_unit ? "" : (", shown in " + floors::to_string(b.units)).c_str());
  std::cout << printf_string("  %-10s %s\n", "layer", project.length(b.layer_height_m).c_str());
  std::cout << printf_string("  %-10s %s\n", "material", project.material_origin.c_str());
  std::cout << printf_string("  %-10s %s\n", "machine", project.machine_origin.c_str());
  std::cout << printf_string("  %-10s %s x %s, %s tall; the machine reaches %s x %s x %s\n", "size",
                             L(extent.x()).c_str(), L(extent.y()).c_str(), L(top_m).c_str(),
                             L(reach_x).c_str(), L(reach_y).c_str(), L(reach_z).c_str());
  {
    const schedule::Placement& placed = project.placement;
    std::cout << printf_string(
        "  %-10s %s: x %s to %s, y %s to %s on the machine (travel x %s to %s, y %s to %s)",
        "placed", placed.how.c_str(), L(space.min_m.x()).c_str(), L(space.max_m.x()).c_str(),
        L(space.min_m.y()).c_str(), L(space.max_m.y()).c_str(), L(machine.x.min_m).c_str(),
        L(machine.x.max_m).c_str(), L(machine.y.min_m).c_str(), L(machine.y.max_m).c_str());
    if (placed.how != "as drawn")
      std::cout << printf_string("; plan origin at (%s, %s), turned %.1f deg",
                                 L(placed.origin_m.x()).c_str(), L(placed.origin_m.y()).c_str(),
                                 placed.rotation_rad * 180.0 / M_PI);
    std::cout << "\n";
  }
  {
    // How the walls are printed (floors::wall_beads): one pass, two skins, or skins and fill.
    const floors::BeadSpec spec = orchestrator::bead_spec(machine, b);
    const double narrowest_m = spec.narrowest_m, widest_m = spec.widest_m;
    int one_pass = 0, two_skins = 0, filled = 0;
    for (const auto& f : b.floors)
      for (const auto& w : f.plan.walls) {
        const floors::WallPrint how = w.thickness_m ? floors::wall_beads(*w.thickness_m, spec).how
                                                    : floors::WallPrint::kOnePass;
        (how == floors::WallPrint::kSkinsAndFill ? filled
         : how == floors::WallPrint::kTwoSkins   ? two_skins
                                                 : one_pass)++;
      }
    std::cout << printf_string("  %-10s %d in one pass (beads %s%s%s)", "walls", one_pass,
                               L(narrowest_m).c_str(), narrowest_m == widest_m ? "" : " to ",
                               narrowest_m == widest_m ? "" : L(widest_m).c_str());
    if (two_skins > 0) std::cout << printf_string(", %d as two skins of half the wall", two_skins);
    if (filled > 0)
      std::cout << printf_string(", %d as two skins of %s and %s (wall_pattern: %s)", filled,
                                 L(machine.nozzle_width_m).c_str(),
                                 b.wall_pattern == floors::WallPattern::kSolid   ? "a poured core"
                                 : b.wall_pattern == floors::WallPattern::kSkins ? "a cavity"
                                                                                 : "a zig-zag tie",
                                 floors::wall_pattern_name(b.wall_pattern));
    std::cout << "\n";
  }
  if (b.print.stated) {
    const auto list = [](const std::vector<std::string>& names) {
      std::string text;
      for (const auto& name : names) text += (text.empty() ? "" : ", ") + name;
      return text;
    };
    std::cout << "  print      walls thinner than the narrowest bead "
              << (b.print.refuse_thin_walls ? "refused" : "left out for the crew");
    if (!b.print.wall_types.empty())
      std::cout << "; the model's " << list(b.print.wall_types) << " read as walls"
                << (b.print.excluded_materials.empty()
                        ? ", whatever their materials"
                        : ", but not those all of whose materials' names hold one of: " +
                              list(b.print.excluded_materials));
    std::cout << "\n";
  }
  for (const auto& note : b.import_notes) std::cout << "  import     " << note << "\n";
  for (const auto& w : b.left_out)
    std::cout << "  left out   " << floors::left_out_text(b.floors[w.floor].name, w, b.units)
              << "\n";
  std::cout << "\n"
            << printf_string("  %-5s  %-16s  %12s  %6s  %9s  %8s  %7s  %11s\n", "floor", "name",
                             "height", "walls", "openings", "anchors", "layers", "geometries");
  for (const auto& f : summary.floors) {
    std::cout << printf_string("  %-5d  %-16s  %12s  %6d  %9d  %8d  %7d  %11d\n", f.floor_index,
                               f.name.c_str(), project.length(f.height_m).c_str(), f.wall_count,
                               f.opening_count, f.anchor_count, f.layer_count,
                               f.distinct_geometries);
  }
  std::cout << "  (openings: doors and windows; anchors: the points a climbing machine's pins go "
               "into, listed in the file (0: placed by rule on solid wall); geometries: the "
               "floor's distinct layer outlines, each planned once)\n";
  std::cout << "\n"
            << printf_string(
                   "  total: %zu floor(s), %d walls, %d openings, %d layers, %d distinct layer "
                   "geometries\n",
                   summary.floors.size(), walls, openings, summary.total_layers,
                   summary.distinct_geometries);
  for (std::size_t k = 0; k < quantities.size(); ++k)
    std::cout << "  quantities " << floors::quantities_text(b.floors[k].name, quantities[k])
              << "\n";
  exit_code = kExitOk;
}

}  // namespace

void add_validate_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<ValidateOptions>();
  CLI::App* command = app.add_subcommand(
      "validate",
      "Check a building file (and the material and machine profiles it names) or a single floor "
      "plan, and summarise it.\n"
      "Every problem found is reported with its file, line and field; the exit code is 2 when "
      "anything is wrong, and with --json the problems are printed as JSON on stdout too.\n"
      "Besides the files themselves it checks that the machine can build the building: its "
      "footprint and height within the machine's reach, every vertex within its x and y travel "
      "where the building stands (its `site:`, or --place centre), and every wall printable as "
      "beads of the nozzle's width: one bead, or two skins and what the building's wall_pattern "
      "puts between them.\n"
      "Examples:\n"
      "  ccbuild validate config/buildings/house.yaml\n"
      "  ccbuild validate model.yaml --place centre --json\n"
      "  ccbuild validate plan.txt --units ft --floor-height 10 --layer-height 0.5");
  command
      ->add_option("FILE", options->file,
                   "Building file (YAML/JSON with `floors:`) or floor plan "
                   "(YAML, JSON or the table text format)")
      ->required();
  command->add_flag("--json", options->json,
                    "Print the summary (or the errors) as one JSON object");
  add_input_options(*command, options->input);
  command->callback([options, &exit_code] { run_validate(*options, exit_code); });
}

}  // namespace ccbuild::cli
