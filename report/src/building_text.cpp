// A building's summary (building_text.hpp).

#include "ccbuild/report/building_text.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "ccbuild/common/format.hpp"
#include "ccbuild/floors/beads.hpp"
#include "ccbuild/floors/quantities.hpp"
#include "ccbuild/floors/slice.hpp"
#include "ccbuild/schedule/layer_summary.hpp"

namespace ccbuild::report {

void write_building_summary(std::ostream& out, const schedule::Project& project,
                            const std::string& file, bool json) {
  const floors::Building& b = project.building;
  const machine::MachineModel& machine = project.machine_model();
  const floors::Envelope space = floors::envelope(b);
  const Eigen::Vector2d extent = space.size_m();
  const double top_m = space.top_m;
  const schedule::BuildingSummary summary = schedule::summarize_building(b);
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

  if (json) {
    nlohmann::ordered_json doc;
    doc["file"] = file;
    doc["kind"] = project.is_building ? "building" : "plan";
    doc["valid"] = true;
    doc["name"] = b.name;
    doc["units"] = floors::to_string(project.file_unit);
    doc["shown_in"] = floors::to_string(b.units);
    doc["layer_height_m"] = b.layer_height_m;
    doc["material"] = {{"name", project.material.name}, {"origin", project.material_origin}};
    doc["machine"] = {{"name", machine.name},
                      {"origin", project.machine_origin},
                      {"reach_m", {reach_x, reach_y, reach_z}}};
    doc["extent_m"] = {extent.x(), extent.y(), top_m};
    const schedule::Placement& placed = project.placement;
    doc["placement"] = {{"how", to_string(placed.how)},
                        {"origin_m", {placed.origin_m.x(), placed.origin_m.y()}},
                        {"rotation_deg", placed.rotation_rad * 180.0 / M_PI},
                        {"min_m", {space.min_m.x(), space.min_m.y()}},
                        {"max_m", {space.max_m.x(), space.max_m.y()}}};
    doc["import_notes"] = b.import_notes;
    if (b.print.stated) {
      doc["print"] = {{"thin_walls", b.print.refuse_thin_walls ? "refuse" : "leave-out"}};
      if (!b.print.wall_types.empty()) {
        doc["print"]["wall_types"] = b.print.wall_types;
        doc["print"]["exclude_materials"] = b.print.excluded_materials;
      }
    }
    doc["left_out"] = nlohmann::ordered_json::array();
    for (const auto& w : b.left_out)
      doc["left_out"].push_back(
          {{"floor", w.floor},
           {"wall", w.wall_id},
           {"thickness_m", w.thickness_m},
           {"narrowest_bead_m", w.narrowest_m},
           {"guid", w.global_id},
           {"text", floors::left_out_text(b.floors[w.floor].name, w, b.units)}});
    doc["floors"] = nlohmann::ordered_json::array();
    for (const auto& f : summary.floors) {
      doc["floors"].push_back({{"floor", f.floor_index},
                               {"name", f.name},
                               {"height_m", f.height_m},
                               {"base_elevation_m", f.base_elevation_m},
                               {"wall_count", f.wall_count},
                               {"opening_count", f.opening_count},
                               {"anchor_count", f.anchor_count},
                               {"layer_count", f.layer_count},
                               {"distinct_geometry_count", f.distinct_geometries}});
      if (modelled) {
        const floors::FloorQuantities& q = quantities[doc["floors"].size() - 1];
        auto& row = doc["floors"].back();
        row["printed_m3"] = q.printed_m3;
        row["model_volume_m3"] = q.model_m3 ? nlohmann::ordered_json(*q.model_m3) : nullptr;
        row["printed_modelled_m3"] = q.printed_modelled_m3;
        row["model_volume_off"] = q.off();
      }
    }
    doc["totals"] = {{"floor_count", summary.floors.size()},
                     {"wall_count", walls},
                     {"opening_count", openings},
                     {"anchor_count", anchors},
                     {"layer_count", summary.total_layers},
                     {"distinct_geometry_count", summary.distinct_geometries}};
    out << doc.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
    return;
  }

  auto L = [&](double m) { return project.length(m, 2); };
  out << file << ": valid " << (project.is_building ? "building" : "plan") << "\n";
  if (!b.name.empty()) out << printf_string("  %-10s %s\n", "name", b.name.c_str());
  out << printf_string(
      "  %-10s %s in the file, metres inside%s\n", "units",
      floors::to_string(project.file_unit).c_str(),
      b.units == project.file_unit ? "" : (", shown in " + floors::to_string(b.units)).c_str());
  out << printf_string("  %-10s %s\n", "layer", project.length(b.layer_height_m).c_str());
  out << printf_string("  %-10s %s\n", "material", project.material_origin.c_str());
  out << printf_string("  %-10s %s\n", "machine", project.machine_origin.c_str());
  out << printf_string("  %-10s %s x %s, %s tall; the machine reaches %s x %s x %s\n", "size",
                       L(extent.x()).c_str(), L(extent.y()).c_str(), L(top_m).c_str(),
                       L(reach_x).c_str(), L(reach_y).c_str(), L(reach_z).c_str());
  {
    const schedule::Placement& placed = project.placement;
    out << printf_string(
        "  %-10s %s: x %s to %s, y %s to %s on the machine (travel x %s to %s, y %s to %s)",
        "placed", to_string(placed.how).c_str(), L(space.min_m.x()).c_str(),
        L(space.max_m.x()).c_str(), L(space.min_m.y()).c_str(), L(space.max_m.y()).c_str(),
        L(machine.x.min_m).c_str(), L(machine.x.max_m).c_str(), L(machine.y.min_m).c_str(),
        L(machine.y.max_m).c_str());
    if (placed.how != schedule::PlacedBy::kAsDrawn)
      out << printf_string("; plan origin at (%s, %s), turned %.1f deg",
                           L(placed.origin_m.x()).c_str(), L(placed.origin_m.y()).c_str(),
                           placed.rotation_rad * 180.0 / M_PI);
    out << "\n";
  }
  {
    // How the walls are printed (floors::wall_beads): one pass, two skins, or skins and fill.
    const floors::BeadSpec spec = schedule::bead_spec(machine, b);
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
    out << printf_string("  %-10s %d in one pass (beads %s%s%s)", "walls", one_pass,
                         L(narrowest_m).c_str(), narrowest_m == widest_m ? "" : " to ",
                         narrowest_m == widest_m ? "" : L(widest_m).c_str());
    if (two_skins > 0) out << printf_string(", %d as two skins of half the wall", two_skins);
    if (filled > 0)
      out << printf_string(", %d as two skins of %s and %s (wall_pattern: %s)", filled,
                           L(machine.nozzle_width_m).c_str(),
                           b.wall_pattern == floors::WallPattern::kSolid   ? "a poured core"
                           : b.wall_pattern == floors::WallPattern::kSkins ? "a cavity"
                                                                           : "a zig-zag tie",
                           floors::wall_pattern_name(b.wall_pattern));
    out << "\n";
  }
  if (b.print.stated) {
    const auto list = [](const std::vector<std::string>& names) {
      std::string text;
      for (const auto& name : names) text += (text.empty() ? "" : ", ") + name;
      return text;
    };
    out << "  print      walls thinner than the narrowest bead "
        << (b.print.refuse_thin_walls ? "refused" : "left out for the crew");
    if (!b.print.wall_types.empty())
      out << "; the model's " << list(b.print.wall_types) << " read as walls"
          << (b.print.excluded_materials.empty()
                  ? ", whatever their materials"
                  : ", but not those all of whose materials' names hold one of: " +
                        list(b.print.excluded_materials));
    out << "\n";
  }
  for (const auto& note : b.import_notes) out << "  import     " << note << "\n";
  for (const auto& w : b.left_out)
    out << "  left out   " << floors::left_out_text(b.floors[w.floor].name, w, b.units) << "\n";
  out << "\n"
      << printf_string("  %-5s  %-16s  %12s  %6s  %9s  %8s  %7s  %11s\n", "floor", "name", "height",
                       "walls", "openings", "anchors", "layers", "geometries");
  for (const auto& f : summary.floors) {
    out << printf_string("  %-5d  %-16s  %12s  %6d  %9d  %8d  %7d  %11d\n", f.floor_index,
                         f.name.c_str(), project.length(f.height_m).c_str(), f.wall_count,
                         f.opening_count, f.anchor_count, f.layer_count, f.distinct_geometries);
  }
  out << "  (openings: doors and windows; anchors: the points a climbing machine's pins go "
         "into, listed in the file (0: placed by rule on solid wall); geometries: the "
         "floor's distinct layer outlines, each planned once)\n";
  out << "\n"
      << printf_string(
             "  total: %zu floor(s), %d walls, %d openings, %d layers, %d distinct layer "
             "geometries\n",
             summary.floors.size(), walls, openings, summary.total_layers,
             summary.distinct_geometries);
  for (std::size_t k = 0; k < quantities.size(); ++k)
    out << "  quantities " << floors::quantities_text(b.floors[k].name, quantities[k]) << "\n";
}

void write_layers_summary(std::ostream& out, const schedule::Project& project,
                          const std::string& file, const std::optional<int>& floor, bool json) {
  const floors::Building& b = project.building;
  const schedule::BuildingSummary summary = schedule::summarize_building(b);

  if (json) {
    nlohmann::ordered_json doc;
    doc["file"] = file;
    doc["layer_height_m"] = b.layer_height_m;
    doc["distinct_geometry_count"] = summary.distinct_geometries;
    doc["floors"] = nlohmann::ordered_json::array();
    for (const auto& f : summary.floors) {
      if (floor && f.floor_index != *floor) continue;
      nlohmann::ordered_json floor = {{"floor", f.floor_index},
                                      {"name", f.name},
                                      {"height_m", f.height_m},
                                      {"base_elevation_m", f.base_elevation_m},
                                      {"layer_count", f.layer_count},
                                      {"distinct_geometry_count", f.distinct_geometries},
                                      {"runs", nlohmann::ordered_json::array()}};
      for (const auto& r : f.runs) {
        floor["runs"].push_back({{"first_layer", r.first_layer},
                                 {"last_layer", r.last_layer},
                                 {"geometry", "G" + std::to_string(r.geometry_label)},
                                 {"geometry_hash", floors::hash_to_hex(r.geometry_hash)},
                                 {"wall_count", r.wall_count},
                                 {"piece_count", r.segment_count},
                                 {"wall_length_m", r.wall_length_m}});
      }
      doc["floors"].push_back(floor);
    }
    out << doc.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
    return;
  }

  out << printf_string("%s: layers of %s, %d distinct geometries in all\n", file.c_str(),
                       project.length(b.layer_height_m).c_str(), summary.distinct_geometries);
  for (const auto& f : summary.floors) {
    if (floor && f.floor_index != *floor) continue;
    out << "\n"
        << printf_string("floor %d '%s': %s high from %s, %d layers, %d distinct geometries\n",
                         f.floor_index, f.name.c_str(), project.length(f.height_m).c_str(),
                         project.length(f.base_elevation_m).c_str(), f.layer_count,
                         f.distinct_geometries);
    out << printf_string("  %-13s %-9s %-16s %6s %7s %14s\n", "layers", "geometry", "hash", "walls",
                         "pieces", "wall length");
    for (const auto& r : f.runs) {
      const std::string range =
          r.first_layer == r.last_layer
              ? std::to_string(r.first_layer)
              : std::to_string(r.first_layer) + "-" + std::to_string(r.last_layer);
      out << printf_string("  %-13s G%-8d %-16s %6d %7d %14s\n", range.c_str(), r.geometry_label,
                           floors::hash_to_hex(r.geometry_hash).c_str(), r.wall_count,
                           r.segment_count, project.length(r.wall_length_m, 2).c_str());
    }
  }
  out << "\n  (geometry: numbered across the building, one per distinct outline, as the "
         "schedule's `geometry` and plan keys g<geometry>n<nozzles> name it; hash: its "
         "digest, equal for the same walls at the same coordinates; pieces: the walls' stretches "
         "between openings; wall length: the walls' centre lines summed)\n";
}

}  // namespace ccbuild::report
