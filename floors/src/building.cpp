#include "ccbuild/floors/building.hpp"

#include <cstdio>
#include <map>
#include <set>

#include "ccbuild/common/document.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "plan_internal.hpp"

namespace ccbuild::floors {
namespace fs = std::filesystem;

namespace {

// Profiles are opened by their owners; here we only resolve and check they exist.
fs::path resolve_reference(const Field& field, const fs::path& base, SourceRef& source) {
  const std::string text = field.as_string();
  if (text.empty()) field.fail("expected a file path");
  const fs::path resolved = (base / text).lexically_normal();
  std::error_code ec;
  if (!fs::is_regular_file(resolved, ec))
    field.fail("file '" + text + "' not found (looked for " + resolved.string() + ")");
  source = SourceRef{field.file(), field.line(), field.path()};
  return resolved;
}

void check_anchors(const Floor& floor, const std::string& context, DiagnosticSink& sink) {
  std::map<std::string, const AnchorPoint*> seen;
  for (const auto& anchor : floor.anchors) {
    if (auto [it, fresh] = seen.emplace(anchor.id, &anchor); !fresh)
      sink.add(at(anchor.source, "id", context + "anchor id '" + anchor.id + "' is used twice"));
    const Wall* wall = floor.plan.find_wall(anchor.wall_id);
    if (wall == nullptr) {
      sink.add(at(anchor.source, "wall",
                  context + "anchor '" + anchor.id + "': wall " + std::to_string(anchor.wall_id) +
                      " is not defined"));
      continue;
    }
    const double length = floor.plan.wall_length_m(*wall);
    if (anchor.offset_m < 0.0 || anchor.offset_m > length) {
      sink.add(at(anchor.source, "offset",
                  context + "anchor '" + anchor.id + "': offset " + metres(anchor.offset_m) +
                      " is off wall " + std::to_string(wall->id) + " (length " + metres(length) +
                      ")"));
      continue;
    }
    // A pipe runs the whole floor height, so it needs solid wall at every layer.
    for (const auto& o : floor.plan.openings) {
      if (o.wall_id == anchor.wall_id && anchor.offset_m > o.offset_m &&
          anchor.offset_m < o.offset_m + o.width_m)
        sink.add(at(anchor.source, "offset",
                    context + "anchor '" + anchor.id + "' at " + metres(anchor.offset_m) +
                        " on wall " + std::to_string(anchor.wall_id) + " lies inside an opening (" +
                        metres(o.offset_m) + " to " + metres(o.offset_m + o.width_m) +
                        "); anchor pipes need solid wall"));
    }
  }
}

}  // namespace

bool looks_like_building(const fs::path& path) {
  const std::string text = read_text_file(path);
  if (detect_plan_format(path, text) == PlanFormat::kTable) return false;
  const Document doc = path.extension() == ".json" ? parse_json(text, path.string())
                                                   : parse_yaml(text, path.string());
  if (doc.root.kind != DocNode::Kind::kMap) return false;
  for (const auto& entry : doc.root.entries)
    if (entry.first == "floors") return true;
  return false;
}

Building load_building(const fs::path& path) {
  const Document doc = load_document(path);
  const Field root = Field::root(doc);
  MapReader map(root,
                {"name", "description", "units", "layer_height", "material", "machine", "floors"});
  map.reject_unknown();
  const fs::path base = path.has_parent_path() ? path.parent_path() : fs::path(".");

  Building building;
  building.source_file = path.string();
  if (auto name = map.optional("name")) building.name = name->as_string();
  building.units = read_units(map.required("units"));
  const double scale = meters_per(building.units);
  const Field layer_height = map.required("layer_height");
  building.layer_height_m = layer_height.as_number() * scale;
  if (building.layer_height_m <= 0.0) layer_height.fail("layer height must be positive");
  building.material_profile =
      resolve_reference(map.required("material"), base, building.material_source);
  building.machine_profile =
      resolve_reference(map.required("machine"), base, building.machine_source);

  const Field floors = map.required("floors");
  const auto floor_fields = floors.items();
  if (floor_fields.empty()) floors.fail("a building needs at least one floor");

  std::map<fs::path, FloorPlan> plan_files;  // a plan shared by several floors is read once
  DiagnosticSink sink;
  double elevation_m = 0.0;
  for (std::size_t i = 0; i < floor_fields.size(); ++i) {
    const Field& f = floor_fields[i];
    MapReader fm(f, {"name", "height", "plan", "openings", "anchors"});
    fm.reject_unknown();
    Floor floor;
    floor.index = static_cast<int>(i);
    floor.source = source_of(f);
    floor.name = fm.has("name") ? fm.required("name").as_string() : "floor " + std::to_string(i);
    const Field height = fm.required("height");
    floor.height_m = height.as_number() * scale;
    if (floor.height_m <= 0.0) height.fail("floor height must be positive");
    floor.base_elevation_m = elevation_m;
    elevation_m += floor.height_m;

    const Field plan = fm.required("plan");
    if (plan.is_map()) {
      floor.plan = read_plan(plan, building.units);
    } else {
      const std::string text = plan.as_string();
      const fs::path plan_path = (base / text).lexically_normal();
      std::error_code ec;
      if (!fs::is_regular_file(plan_path, ec))
        plan.fail("plan file '" + text + "' not found (looked for " + plan_path.string() + ")");
      auto cached = plan_files.find(plan_path);
      if (cached == plan_files.end())
        cached = plan_files.emplace(plan_path, load_plan(plan_path, building.units)).first;
      floor.plan = cached->second;
    }
    if (auto openings = fm.optional("openings")) {
      for (const Field& item : openings->items())
        floor.plan.openings.push_back(read_opening(item, building.units));
    }
    if (auto anchors = fm.optional("anchors")) {
      for (const Field& item : anchors->items()) {
        MapReader am(item, {"id", "wall", "offset"});
        am.reject_unknown();
        AnchorPoint anchor;
        anchor.source = source_of(item);
        anchor.id = am.required("id").as_string();
        anchor.wall_id = am.required("wall").as_positive_id();
        anchor.offset_m = am.required("offset").as_number() * scale;
        floor.anchors.push_back(anchor);
      }
    }
    const std::string context = "floor '" + floor.name + "'";
    try {
      validate_plan(floor.plan, floor.height_m, context);
      check_anchors(floor, context + ": ", sink);
    } catch (const InputError& error) {
      for (const auto& d : error.diagnostics()) sink.add(d);
    }
    building.floors.push_back(std::move(floor));
  }
  sink.throw_if_any();
  return building;
}

}  // namespace ccbuild::floors
