// An imported building as files (building_files.hpp).

#include "ccbuild/import/building_files.hpp"

#include <cstdlib>

#include "ccbuild/common/format.hpp"
#include "ccbuild/floors/quantities.hpp"

namespace ccbuild::import {
namespace fs = std::filesystem;

std::string exact_text(double value) {
  for (int digits = 6; digits <= 17; ++digits) {
    const std::string text = printf_string("%.*g", digits, value);
    if (std::strtod(text.c_str(), nullptr) == value) return text;
  }
  return printf_string("%.17g", value);
}

std::string plan_yaml(const floors::FloorPlan& plan, const std::string& drawing,
                      const std::string& what) {
  std::string out = "# Imported by `ccbuild import` from " + yaml_escaped(drawing) +
                    " (every wall and opening names\n# " + yaml_escaped(what) +
                    " it came from).\nunits: m\nvertices:\n";
  for (const auto& v : plan.vertices)
    out +=
        printf_string("  - {id: %lld, x: %s, y: %s}\n", static_cast<long long>(v.id),
                      exact_text(v.position_m.x()).c_str(), exact_text(v.position_m.y()).c_str());
  out += "walls:\n";
  for (const auto& w : plan.walls) {
    out +=
        printf_string("  - {id: %lld, start: %lld, end: %lld", static_cast<long long>(w.id),
                      static_cast<long long>(w.start_vertex), static_cast<long long>(w.end_vertex));
    if (w.thickness_m) out += ", thickness: " + exact_text(*w.thickness_m);
    if (!w.global_id.empty()) out += ", guid: " + yaml_quoted(w.global_id);
    if (w.top_m.size() == 1 && w.top_m[0].first == 0.0) {
      out += ", top: " + exact_text(w.top_m[0].second);
    } else if (!w.top_m.empty()) {
      out += ", top: [";
      for (std::size_t k = 0; k < w.top_m.size(); ++k)
        out += (k ? ", [" : "[") + exact_text(w.top_m[k].first) + ", " +
               exact_text(w.top_m[k].second) + "]";
      out += "]";
    }
    if (w.model_volume_m3) out += ", model_volume: " + exact_text(*w.model_volume_m3);
    out += "}  # " + yaml_escaped(w.source.path) + "\n";
  }
  if (!plan.openings.empty()) out += "openings:\n";
  for (const auto& o : plan.openings)
    out += printf_string(
        "  - {id: %s, wall: %lld, offset: %s, width: %s, sill: %s, head: %s%s}  # "
        "%s\n",
        yaml_quoted(o.id).c_str(), static_cast<long long>(o.wall_id),
        exact_text(o.offset_m).c_str(), exact_text(o.width_m).c_str(), exact_text(o.sill_m).c_str(),
        exact_text(o.head_m).c_str(),
        o.global_id.empty() ? "" : (", guid: " + yaml_quoted(o.global_id)).c_str(),
        yaml_escaped(o.source.path).c_str());
  return out;
}

std::string plan_file_mark(const fs::path& building) {
  return "# ccbuild import: a plan file of " + yaml_escaped(building.filename().string());
}

BuildingFiles ifc_building_files(const IfcImport& read, const std::string& model,
                                 const BuildingFileNames& names) {
  BuildingFiles files;
  const fs::path& out = names.building;
  const fs::path folder = out.has_parent_path() ? out.parent_path() : fs::path(".");
  const floors::Building& b = read.building;
  // Floors with the same plan share its file.
  std::vector<std::size_t> plan_of(b.floors.size());
  std::vector<std::size_t> distinct;  // floor index of each plan file's first floor
  for (std::size_t k = 0; k < b.floors.size(); ++k) {
    plan_of[k] = distinct.size();
    for (std::size_t d = 0; d < distinct.size(); ++d)
      if (floors::same_model(b.floors[distinct[d]].plan, b.floors[k].plan, 0.0)) {
        plan_of[k] = d;
        break;
      }
    if (plan_of[k] == distinct.size()) distinct.push_back(k);
  }
  std::vector<fs::path>& plan_paths = files.plan_paths;
  for (std::size_t d = 0; d < distinct.size(); ++d)
    plan_paths.push_back(folder / (out.stem().string() + printf_string(".%zu.plan.yaml", d + 1)));
  std::string& building = files.building;
  building = "# Imported by `ccbuild import` from " + yaml_escaped(model) + " (" +
             yaml_escaped(read.schema) +
             "): review it, then `ccbuild validate` it.\n# What the import left out "
             "or ignored:\n";
  for (const auto& note : read.notes) building += "#   " + yaml_escaped(note) + "\n";
  // What the walls take as drawn (each as thick as the model says, before a machine lays
  // them as beads) against the model's own quantities.
  std::vector<std::string>& quantities = files.quantities;
  for (const auto& f : b.floors)
    quantities.push_back(
        floors::quantities_text(f.name, floors::floor_quantities(f, b.layer_height_m, 0.0)));
  building += "# Concrete of the walls as drawn, against the model's own quantities:\n";
  for (const auto& q : quantities) building += "#   " + yaml_escaped(q) + "\n";
  building += "name: " + yaml_quoted(b.name) +
              "\nunits: m\nlayer_height: " + exact_text(b.layer_height_m) +
              "\nmaterial: " + yaml_quoted(names.material) +
              "\nmachine: " + yaml_quoted(names.machine) + "\n";
  // What is printed, as chosen here: the schedule records it.
  const auto list_text = [](const std::vector<std::string>& list) {
    std::string text;
    for (const auto& name : list) text += (text.empty() ? "" : ", ") + yaml_quoted(name);
    return "[" + text + "]";
  };
  building += "print: {thin_walls: leave-out, wall_types: " + list_text(b.print.wall_types) +
              ",\n        exclude_materials: " + list_text(b.print.excluded_materials) + "}\n";
  building += "floors:\n";
  // Levels as the model states them; a floor under a level runs up to it under its slab, so
  // a slab added later fills the storey and moves no level (only the top floor's height).
  for (std::size_t k = 0; k < b.floors.size(); ++k) {
    const floors::Floor& f = b.floors[k];
    const bool to_level = k + 1 < b.floors.size() && b.floors[k + 1].level_m.has_value();
    std::string keys = "name: " + yaml_quoted(f.name);
    if (f.level_m) keys += ", level: " + exact_text(*f.level_m);
    if (!to_level) keys += ", height: " + exact_text(f.height_m);
    if (f.slab_m > 0.0) keys += ", slab: " + exact_text(f.slab_m);
    building +=
        "  - {" + keys + ", plan: " + yaml_quoted(plan_paths[plan_of[k]].filename().string()) +
        "}  # " + yaml_escaped(f.source.path) +
        (to_level ? "; " + exact_text(f.height_m) + " m high, up to the next level" : "") + "\n";
  }
  const std::string mark = plan_file_mark(out);
  for (std::size_t d = 0; d < distinct.size(); ++d)
    files.plans.push_back(
        mark + "\n" +
        plan_yaml(b.floors[distinct[d]].plan, model, "the IFC element (type, GlobalId, name)"));
  return files;
}

fs::path dxf_plan_path(const fs::path& building) {
  const fs::path folder = building.has_parent_path() ? building.parent_path() : fs::path(".");
  return folder / (building.stem().string() + ".plan.yaml");
}

BuildingFiles dxf_building_files(const DxfPlan& read, const std::string& drawing,
                                 const BuildingFileNames& names, int floors, double floor_height_m,
                                 double layer_height_m) {
  BuildingFiles files;
  const fs::path plan_path = dxf_plan_path(names.building);
  std::string& building = files.building;
  building = "# Imported by `ccbuild import` from " + yaml_escaped(drawing) +
             ": review it, then `ccbuild validate` it.\n";
  building += "name: " + yaml_quoted(names.building.stem().string()) +
              "\nunits: m\nlayer_height: " + exact_text(layer_height_m) +
              "\nmaterial: " + yaml_quoted(names.material) +
              "\nmachine: " + yaml_quoted(names.machine) + "\nfloors:\n";
  for (int k = 0; k < floors; ++k)
    building += printf_string("  - {name: %s, height: %s, plan: %s}\n",
                              yaml_quoted(k == 0 ? "ground" : "floor " + std::to_string(k)).c_str(),
                              exact_text(floor_height_m).c_str(),
                              yaml_quoted(plan_path.filename().string()).c_str());
  files.plan_paths.push_back(plan_path);
  files.plans.push_back(plan_file_mark(names.building) + "\n" + plan_yaml(read.plan, drawing));
  return files;
}

}  // namespace ccbuild::import
