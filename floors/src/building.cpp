#include "ccbuild/floors/building.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
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
  // In the plan's unit, whatever it is.
  auto in_unit = [&](double value_m) { return length_text(value_m, floor.plan.units); };
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
                  context + "anchor '" + anchor.id + "': offset " + in_unit(anchor.offset_m) +
                      " is off wall " + std::to_string(wall->id) + " (length " + in_unit(length) +
                      ")"));
      continue;
    }
    // A pipe runs the whole floor height, so it needs solid wall at every layer.
    for (const auto& o : floor.plan.openings) {
      if (o.wall_id == anchor.wall_id && anchor.offset_m > o.offset_m &&
          anchor.offset_m < o.offset_m + o.width_m)
        sink.add(at(anchor.source, "offset",
                    context + "anchor '" + anchor.id + "' at " + in_unit(anchor.offset_m) +
                        " on wall " + std::to_string(anchor.wall_id) + " lies inside an opening (" +
                        in_unit(o.offset_m) + " to " + in_unit(o.offset_m + o.width_m) +
                        "); anchor pipes need solid wall"));
    }
  }
}

}  // namespace

namespace {

// The layers of a whole building, counted in floating point so that no height can
// overflow the count; over the limit is an input error at `field`.
void check_layer_budget(const Building& building, const std::string& file, int line,
                        const std::string& field) {
  double layers = 0.0;
  for (const auto& floor : building.floors)
    layers += std::ceil(floor.height_m / building.layer_height_m - 1e-9);
  if (layers > static_cast<double>(limits::kMaxLayers))
    throw InputError(
        file, line, field,
        printf_string("%.0f layers of %s make this building; ccbuild plans at most "
                      "%ld (a layer height in the wrong unit?)",
                      layers, length_text(building.layer_height_m, building.units).c_str(),
                      limits::kMaxLayers));
}

Site read_site(const Field& field, LengthUnit unit) {
  MapReader map(field, kSitePlacementKeys);
  Site site;
  site.source = source_of(field);
  if (!field.is_map()) field.fail("expected a map (origin, rotation_deg, place, start, ...)");
  // Every other key is the site's programme, which the schedule reads (and checks).
  DocNode programme;
  programme.kind = DocNode::Kind::kMap;
  programme.line = field.line();
  for (const auto& entry : field.node().entries)
    if (std::find(kSitePlacementKeys.begin(), kSitePlacementKeys.end(), entry.first) ==
        kSitePlacementKeys.end())
      programme.entries.push_back(entry);
  if (!programme.entries.empty()) site.programme = Document{field.file(), std::move(programme)};
  site.places = programme.entries.size() < field.node().entries.size();
  if (auto origin = map.optional("origin")) {
    const auto xy = origin->items();
    if (xy.size() != 2)
      origin->fail("expected [x, y], the plan origin's place in the machine's frame, got " +
                   std::to_string(xy.size()) + " numbers");
    site.origin_m = Eigen::Vector2d(read_length(xy[0], limits::kCoordinate_m, unit),
                                    read_length(xy[1], limits::kCoordinate_m, unit));
  }
  if (auto rotation = map.optional("rotation_deg"))
    site.rotation_rad = rotation->as_number_in(limits::kSiteRotation_rad, "deg", M_PI / 180.0);
  if (auto place = map.optional("place")) {
    const std::string how = place->as_string();
    if (how != "centre" && how != "center")
      place->fail(
          "expected `centre` (the building centred on the machine's x and y travel), got '" + how +
          "'");
    if (site.origin_m) place->fail("give either `origin` or `place: centre`, not both");
    site.centre = true;
  }
  return site;
}

Building building_from_document(const Document& doc, const fs::path& path,
                                const DrawingReader& drawings) {
  const Field root = Field::root(doc);
  MapReader map(root, {"name", "description", "units", "layer_height", "slab_stage_h", "material",
                       "machine", "site", "wall_pattern", "climbs", "floors"});
  map.reject_unknown();
  const fs::path base = path.has_parent_path() ? path.parent_path() : fs::path(".");

  Building building;
  building.source_file = path.string();
  building.files_read.push_back(path);
  if (auto name = map.optional("name")) building.name = name->as_string();
  building.units = read_units(map.required("units"));
  const LengthUnit unit = building.units;
  const Field layer_height = map.required("layer_height");
  building.layer_height_m = read_length(layer_height, limits::kLayerHeight_m, unit);
  if (auto slab = map.optional("slab_stage_h"))
    building.slab_stage_s = slab->as_number_in(limits::kSlabStage_s, "h", 3600.0);
  building.material_profile =
      resolve_reference(map.required("material"), base, building.material_source);
  building.machine_profile =
      resolve_reference(map.required("machine"), base, building.machine_source);

  if (auto site = map.optional("site")) building.site = read_site(*site, unit);
  if (auto pattern = map.optional("wall_pattern")) {
    const auto parsed = parse_wall_pattern(pattern->as_string());
    if (!parsed)
      pattern->fail(
          "expected skins, solid or skins-with-ties (what lies between a thick wall's "
          "two skins), got '" +
          pattern->as_string() + "'");
    building.wall_pattern = *parsed;
  }
  if (auto climbs = map.optional("climbs")) {
    const std::string where = climbs->as_string();
    if (where != "between-floors" && where != "within-storey")
      climbs->fail(
          "expected between-floors (a climbing machine climbs at floor tops, the default) or "
          "within-storey (wherever its legs allow), got '" +
          where + "'");
    building.climbs_within_storey = where == "within-storey";
  }

  const Field floors = map.required("floors");
  const auto floor_fields = floors.items();
  if (floor_fields.empty()) floors.fail("a building needs at least one floor");
  check_count(floors, floor_fields.size(), limits::kMaxFloors, "floors");

  std::map<fs::path, FloorPlan> plan_files;  // a plan shared by several floors is read once
  DiagnosticSink sink;
  double elevation_m = 0.0;
  for (std::size_t i = 0; i < floor_fields.size(); ++i) {
    const Field& f = floor_fields[i];
    MapReader fm(f, {"name", "height", "slab", "plan", "openings", "anchors"});
    fm.reject_unknown();
    Floor floor;
    floor.index = static_cast<int>(i);
    floor.source = source_of(f);
    floor.name = fm.has("name") ? fm.required("name").as_string() : "floor " + std::to_string(i);
    floor.height_m = read_length(fm.required("height"), limits::kFloorHeight_m, unit);
    if (auto slab = fm.optional("slab"))
      floor.slab_m = read_length(*slab, limits::kSlabThickness_m, unit);
    floor.base_elevation_m = elevation_m;
    elevation_m += floor.height_m + floor.slab_m;

    const Field plan = fm.required("plan");
    if (plan.is_map() && MapReader(plan, {}).has("dxf")) {
      if (!drawings) plan.fail("a drawn plan (dxf) needs ccbuild's importer; this tool has none");
      ImportedPlan imported = drawings(plan, base, unit);
      for (auto& note : imported.notes)
        building.import_notes.push_back("floor '" + floor.name + "': " + note);
      if (std::find(building.files_read.begin(), building.files_read.end(), imported.file) ==
          building.files_read.end())
        building.files_read.push_back(imported.file);
      floor.plan = std::move(imported.plan);
    } else if (plan.is_map()) {
      floor.plan = read_plan(plan, unit);
    } else {
      const std::string text = plan.as_string();
      const fs::path plan_path = (base / text).lexically_normal();
      std::error_code ec;
      if (!fs::is_regular_file(plan_path, ec))
        plan.fail("plan file '" + text + "' not found (looked for " + plan_path.string() + ")");
      auto cached = plan_files.find(plan_path);
      if (cached == plan_files.end()) {
        cached = plan_files.emplace(plan_path, load_plan(plan_path, unit)).first;
        building.files_read.push_back(plan_path);
      }
      floor.plan = cached->second;
    }
    if (auto openings = fm.optional("openings")) {
      const auto items = openings->items();
      check_count(*openings, items.size() + floor.plan.openings.size(), limits::kMaxOpenings,
                  "openings");
      for (const Field& item : items) floor.plan.openings.push_back(read_opening(item, unit));
    }
    if (auto anchors = fm.optional("anchors")) {
      const auto items = anchors->items();
      check_count(*anchors, items.size(), limits::kMaxAnchors, "anchors");
      for (const Field& item : items) {
        MapReader am(item, {"id", "wall", "offset"});
        am.reject_unknown();
        AnchorPoint anchor;
        anchor.source = source_of(item);
        anchor.id = am.required("id").as_string();
        anchor.wall_id = read_id(am.required("wall"));
        anchor.offset_m = read_length(am.required("offset"), limits::kAlongWall_m, unit);
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
  check_layer_budget(building, doc.file, layer_height.line(), layer_height.path());
  return building;
}

bool is_building_document(const Document& doc) {
  if (doc.root.kind != DocNode::Kind::kMap) return false;
  for (const auto& entry : doc.root.entries)
    if (entry.first == "floors") return true;
  return false;
}

}  // namespace

Envelope envelope(const Building& building) {
  Envelope out;
  out.min_m = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  out.max_m = -out.min_m;
  for (const auto& floor : building.floors) {
    for (const auto& v : floor.plan.vertices) {
      out.min_m = out.min_m.cwiseMin(v.position_m);
      out.max_m = out.max_m.cwiseMax(v.position_m);
    }
    out.top_m = std::max(out.top_m, floor.base_elevation_m + floor.height_m);
  }
  return out;
}

void place_building(Building& building, double rotation_rad, const Eigen::Vector2d& origin_m) {
  const double c = std::cos(rotation_rad), s = std::sin(rotation_rad);
  for (auto& floor : building.floors)
    for (auto& v : floor.plan.vertices) {
      const Eigen::Vector2d p = v.position_m;
      v.position_m = Eigen::Vector2d(c * p.x() - s * p.y(), s * p.x() + c * p.y()) + origin_m;
    }
}

Building load_building(const fs::path& path, const DrawingReader& drawings) {
  return building_from_document(load_document(path), path, drawings);
}

BuildingOrPlan load_building_or_plan(const fs::path& path, LengthUnit plan_unit,
                                     const DrawingReader& drawings) {
  const std::string text = read_text_file(path);
  BuildingOrPlan out;
  const PlanFormat format = detect_plan_format(path, text);
  if (format == PlanFormat::kTable) {
    out.plan = plan_from_text(text, path, plan_unit, format);
    return out;
  }
  const Document doc = format == PlanFormat::kJson ? parse_json(text, path.string())
                                                   : parse_yaml(text, path.string());
  if (is_building_document(doc)) {
    out.is_building = true;
    out.building = building_from_document(doc, path, drawings);
    return out;
  }
  out.plan = read_plan(Field::root(doc), plan_unit);
  out.plan.source_file = path.string();
  return out;
}

Building building_from_plan(FloorPlan plan, std::string name, double floor_height_m,
                            double layer_height_m) {
  const LengthUnit unit = plan.units;
  auto check = [&](double value_m, const Range& range, const char* field) {
    if (!range.contains(value_m))
      throw InputError("", 0, field,
                       "must be " + range.describe(to_string(unit), meters_per(unit)) + ", got " +
                           plain_number(value_m / meters_per(unit)) + " " + to_string(unit));
  };
  check(floor_height_m, limits::kFloorHeight_m, "floor_height");
  check(layer_height_m, limits::kLayerHeight_m, "layer_height");
  Building building;
  building.name = name;
  building.source_file = plan.source_file;
  building.files_read.push_back(plan.source_file);
  building.units = unit;
  building.layer_height_m = layer_height_m;
  Floor floor;
  floor.name = std::move(name);
  floor.height_m = floor_height_m;
  floor.plan = std::move(plan);
  // Openings must fit under the floor, also when its height is the default.
  validate_plan(floor.plan, floor.height_m);
  building.floors.push_back(std::move(floor));
  check_layer_budget(building, "", 0, "layer_height");
  return building;
}

}  // namespace ccbuild::floors
