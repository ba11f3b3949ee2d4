#include "ccbuild/floors/building.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include "ccbuild/common/document.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/plane.hpp"
#include "ccbuild/floors/print_names.hpp"
#include "ccbuild/floors/units.hpp"
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

// A floor's level and where the floors under it end agree within a millimetre (models
// state levels to the millimetre).
constexpr double kLevelTolerance_m = 1e-3;

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
          "expected `centre` (the building centred on the machine's x and y travel), got '" +
          echoed(how) + "'");
    if (site.origin_m) place->fail("give either `origin` or `place: centre`, not both");
    site.centre = true;
  }
  return site;
}

int read_crew(const Field& field) {
  const double crew = field.as_number_in(limits::kCrew, "people");
  if (crew != std::floor(crew))
    field.fail("expected a whole number of people, got " + plain_number(crew));
  return static_cast<int>(crew);
}

// `lintels: {type, height, bearing, place_min, crew, by}`.
LintelSpec read_lintels(const Field& field, LengthUnit unit) {
  MapReader map(field, {"type", "height", "bearing", "place_min", "crew", "by"});
  map.reject_unknown();
  LintelSpec lintel;
  if (auto type = map.optional("type")) {
    const std::string t = type->as_string();
    if (t != "precast" && t != "formwork")
      type->fail(
          "expected precast (an element set on bearings) or formwork (a soffit form the layers "
          "are printed over), got '" +
          echoed(t) + "'");
    lintel.type = t == "precast" ? LintelSpec::Type::kPrecast : LintelSpec::Type::kFormwork;
  }
  if (auto height = map.optional("height")) {
    if (lintel.type != LintelSpec::Type::kPrecast)
      height->fail("only a precast lintel has a height (a formwork lintel is printed)");
    lintel.height_m = read_length(*height, limits::kLintelHeight_m, unit);
  } else if (lintel.type == LintelSpec::Type::kPrecast) {
    map.required("height");
  }
  if (auto bearing = map.optional("bearing"))
    lintel.bearing_m = read_length(*bearing, limits::kLintelBearing_m, unit);
  if (auto place = map.optional("place_min"))
    lintel.place_s = place->as_number_in(limits::kLintelPlace_s, "min", 60.0);
  if (auto by = map.optional("by")) {
    const std::string who = by->as_string();
    if (who != "crew" && who != "arm")
      by->fail("expected crew (people set it, in working hours) or arm (the machine's arm), got '" +
               echoed(who) + "'");
    lintel.by_arm = who == "arm";
    if (lintel.by_arm) lintel.crew = 0;
  }
  if (auto crew = map.optional("crew")) {
    lintel.crew = read_crew(*crew);
    if (lintel.by_arm && lintel.crew > 0) crew->fail("a lintel set by the arm has no crew");
  }
  return lintel;
}

// `slabs: {thickness, setup_h, pour_m3_h, ready_mpa, concrete, crew, roof}`.
SlabSpec read_slabs(const Field& field, LengthUnit unit) {
  MapReader map(field,
                {"thickness", "setup_h", "pour_m3_h", "ready_mpa", "concrete", "crew", "roof"});
  map.reject_unknown();
  SlabSpec slab;
  if (auto t = map.optional("thickness")) {
    slab.thickness_m = read_length(*t, limits::kSlabThickness_m, unit);
    if (slab.thickness_m <= 0.0) t->fail("a slab is thicker than 0");
  }
  if (auto setup = map.optional("setup_h"))
    slab.setup_s = setup->as_number_in(limits::kSlabSetup_s, "h", 3600.0);
  if (auto rate = map.optional("pour_m3_h"))
    slab.pour_rate_m3_s = rate->as_number_in(limits::kPourRate_m3_s, "m3/h", 1.0 / 3600.0);
  if (auto ready = map.optional("ready_mpa"))
    slab.ready_mpa = ready->as_number_in(limits::kSlabReady_mpa, "MPa");
  if (auto concrete = map.optional("concrete"))
    slab.concrete = read_en1992_strength(*concrete, {"fcm_mpa", "cement_class"});
  if (auto ready = map.optional("ready_mpa"))
    if (slab.ready_mpa >= slab.concrete.ultimate_mpa())
      ready->fail("the slab's concrete never reaches " + plain_number(slab.ready_mpa) +
                  " MPa (EN 1992-1-1: at most fcm e^s = " +
                  plain_number(slab.concrete.ultimate_mpa()) + " MPa)");
  if (auto crew = map.optional("crew")) slab.crew = read_crew(*crew);
  if (auto roof = map.optional("roof")) slab.roof = roof->as_bool();
  return slab;
}

/// The errors of one building file, gathered so that all are reported in one run. A
/// message about a floor's plan, repeated for every floor that shares the plan, is given
/// once with the floors listed.
class Findings {
 public:
  /// Runs `read`, keeping the errors it throws. `floor` names the floor it reads ("" for
  /// the building's own keys); `prefix` is what that floor's checks put before a message.
  template <class Read>
  void attempt(Read&& read, const std::string& floor = "", const std::string& prefix = "") {
    try {
      read();
    } catch (const InputError& error) {
      for (Diagnostic d : error.diagnostics()) {
        const bool prefixed = !prefix.empty() && d.message.rfind(prefix, 0) == 0;
        if (prefixed) d.message.erase(0, prefix.size());
        found_.push_back({std::move(d), floor, prefixed});
      }
    }
  }
  bool empty() const { return found_.empty(); }
  /// Throws InputError with every error, merged; does nothing when there is none.
  void throw_if_any() const {
    if (found_.empty()) return;
    std::vector<Diagnostic> out;
    std::vector<bool> used(found_.size(), false);
    for (std::size_t i = 0; i < found_.size(); ++i) {
      if (used[i]) continue;
      const Finding& f = found_[i];
      std::vector<std::string> floors;
      for (std::size_t k = i; k < found_.size(); ++k) {
        const Finding& g = found_[k];
        if (used[k] || g.prefixed != f.prefixed || g.d.file != f.d.file || g.d.line != f.d.line ||
            g.d.field != f.d.field || g.d.message != f.d.message)
          continue;
        used[k] = true;
        if (!g.floor.empty() && std::find(floors.begin(), floors.end(), g.floor) == floors.end())
          floors.push_back(g.floor);
      }
      Diagnostic d = f.d;
      std::string listed;
      for (std::size_t k = 0; k < floors.size(); ++k)
        listed += (k == 0 ? "" : k + 1 == floors.size() ? " and " : ", ") + ("'" + floors[k] + "'");
      if (f.prefixed)
        d.message = (floors.size() == 1 ? "floor " : "floors ") + listed + ": " + d.message;
      else if (floors.size() > 1)
        d.message += " (floors " + listed + ")";
      out.push_back(std::move(d));
    }
    throw InputError(std::move(out));
  }

 private:
  struct Finding {
    Diagnostic d;
    std::string floor;
    bool prefixed = false;
  };
  std::vector<Finding> found_;
};

Building building_from_document(const Document& doc, const fs::path& path,
                                const DrawingReader& drawings) {
  const Field root = Field::root(doc);
  MapReader map(root,
                {"name", "description", "units", "layer_height", "slab_stage_h", "slabs", "lintels",
                 "material", "machine", "site", "wall_pattern", "climbs", "floors", "print"});
  map.reject_unknown();
  const fs::path base = path.has_parent_path() ? path.parent_path() : fs::path(".");

  Building building;
  building.source_file = path.string();
  building.files_read.push_back(path);
  if (auto name = map.optional("name")) building.name = name->as_string();
  building.units = read_units(map.required("units"));  // every length depends on it
  const LengthUnit unit = building.units;
  // Every part is read on its own, and every error is reported at the end.
  Findings findings;
  std::optional<Field> layer_height;
  findings.attempt([&] {
    layer_height = map.required("layer_height");
    building.layer_height_m = read_length(*layer_height, limits::kLayerHeight_m, unit);
  });
  findings.attempt([&] {
    if (auto slab = map.optional("slab_stage_h"))
      building.slab_stage_s = slab->as_number_in(limits::kSlabStage_s, "h", 3600.0);
  });
  findings.attempt([&] {
    if (auto slabs = map.optional("slabs")) {
      if (map.has("slab_stage_h"))
        slabs->fail(
            "give either slab_stage_h (a fixed stage between floors) or slabs (poured and cured "
            "to a strength), not both");
      building.slabs = read_slabs(*slabs, unit);
    }
  });
  findings.attempt([&] {
    if (auto lintels = map.optional("lintels")) building.lintels = read_lintels(*lintels, unit);
  });
  // Optional: without them the flags' or the bundled profiles are used (the project).
  findings.attempt([&] {
    if (auto material = map.optional("material"))
      building.material_profile = resolve_reference(*material, base, building.material_source);
  });
  findings.attempt([&] {
    if (auto machine = map.optional("machine"))
      building.machine_profile = resolve_reference(*machine, base, building.machine_source);
  });
  findings.attempt([&] {
    if (auto site = map.optional("site")) building.site = read_site(*site, unit);
  });
  findings.attempt([&] {
    if (auto pattern = map.optional("wall_pattern")) {
      const auto parsed = parse_wall_pattern(pattern->as_string());
      if (!parsed)
        pattern->fail(
            "expected skins, solid or skins-with-ties (what lies between a thick wall's "
            "two skins), got '" +
            echoed(pattern->as_string()) + "'");
      building.wall_pattern = *parsed;
    }
  });
  findings.attempt([&] {
    if (auto print = map.optional("print")) {
      MapReader spec(*print, {"thin_walls", "wall_types", "exclude_materials"});
      spec.reject_unknown();
      building.print.stated = true;
      // Lists of names: IFC entity names for the types, any text for the materials.
      const auto names = [](const Field& list, bool entity) {
        if (!list.is_sequence()) list.fail("expected a list of names");
        const std::vector<Field> items = list.items();
        if (items.size() > limits::kMaxPrintNames)
          list.fail(printf_string("expected at most %zu names, got %zu", limits::kMaxPrintNames,
                                  items.size()));
        std::vector<std::string> out;
        for (const Field& item : items) {
          const std::string name = item.as_string();
          const std::string fault =
              entity ? wall_type_name_fault(name) : excluded_material_name_fault(name);
          if (!fault.empty()) item.fail(fault);
          out.push_back(name);
        }
        return out;
      };
      if (auto types = spec.optional("wall_types")) {
        building.print.wall_types = names(*types, true);
        if (building.print.wall_types.empty()) types->fail("name at least one wall type");
      }
      if (auto materials = spec.optional("exclude_materials"))
        building.print.excluded_materials = names(*materials, false);
      if (auto thin = spec.optional("thin_walls")) {
        const std::string how = thin->as_string();
        if (how != "leave-out" && how != "refuse")
          thin->fail(
              "expected leave-out (the crew builds a wall thinner than the narrowest "
              "bead) or refuse, got '" +
              echoed(how) + "'");
        building.print.refuse_thin_walls = how == "refuse";
      }
    }
  });
  findings.attempt([&] {
    if (auto climbs = map.optional("climbs")) {
      const std::string where = climbs->as_string();
      if (where != "between-floors" && where != "within-storey")
        climbs->fail(
            "expected between-floors (a climbing machine climbs at floor tops, the default) or "
            "within-storey (wherever its legs allow), got '" +
            echoed(where) + "'");
      building.climbs_within_storey = where == "within-storey";
    }
  });

  const Field floors = map.required("floors");
  const auto floor_fields = floors.items();
  if (floor_fields.empty()) floors.fail("a building needs at least one floor");
  check_count(floors, floor_fields.size(), limits::kMaxFloors, "floors");

  // The floors' levels first: a floor without a height runs up to the next floor's level,
  // under its own slab, so slabs fill the storeys rather than move them.
  std::vector<std::optional<double>> levels_m(floor_fields.size());
  for (std::size_t i = 0; i < floor_fields.size(); ++i)
    findings.attempt([&] {
      if (!floor_fields[i].is_map()) return;  // said when the floor is read
      if (auto level = MapReader(floor_fields[i], {}).optional("level"))
        levels_m[i] = read_length(*level, limits::kLevel_m, unit);
    });
  const double origin_m = levels_m.empty() || !levels_m[0] ? 0.0 : *levels_m[0];

  std::map<fs::path, FloorPlan> plan_files;  // a plan shared by several floors is read once
  double elevation_m = 0.0;
  for (std::size_t i = 0; i < floor_fields.size(); ++i) {
    const Field& f = floor_fields[i];
    Floor floor;
    floor.index = static_cast<int>(i);
    floor.source = source_of(f);
    floor.name = "floor " + std::to_string(i);
    bool read = false;
    findings.attempt(
        [&] {
          MapReader fm(f, {"name", "level", "height", "slab", "plan", "openings", "anchors"});
          if (fm.has("name")) floor.name = fm.required("name").as_string();
          fm.reject_unknown();
          if (auto slab = fm.optional("slab"))
            floor.slab_m = read_length(*slab, limits::kSlabThickness_m, unit);
          else if (building.slabs)
            floor.slab_m = building.slabs->thickness_m;  // the floor above stands on it
          if (auto level = fm.optional("level");
              level && levels_m[i] && !building.floors.empty() &&
              building.floors.back().index + 1 == floor.index &&
              std::abs(*levels_m[i] - origin_m - elevation_m) > kLevelTolerance_m + 1e-9) {
            const Floor& below = building.floors.back();
            level->fail(printf_string(
                "floor '%s' is at level %s, but the floor under it, '%s', ends at %s (%s high, "
                "%s of slab over it): the inputs would move this level; leave out '%s''s "
                "height to run it up to this level under its slab, or make the two agree",
                echoed(floor.name).c_str(), length_text(*levels_m[i], unit).c_str(),
                echoed(below.name).c_str(), length_text(origin_m + elevation_m, unit).c_str(),
                length_text(below.height_m, unit).c_str(), length_text(below.slab_m, unit).c_str(),
                echoed(below.name).c_str()));
          }
          const bool next_level = i + 1 < levels_m.size() && levels_m[i + 1];
          if (fm.has("height") || !next_level) {
            if (!fm.has("height"))
              f.fail(
                  "a floor needs a height (floor to floor, or up to its slab), or a level "
                  "on the floor above it to run up to");
            floor.height_m = read_length(fm.required("height"), limits::kFloorHeight_m, unit);
          } else {
            floor.height_m =
                round_to_nanometre(*levels_m[i + 1] - origin_m - elevation_m - floor.slab_m);
            if (!limits::kFloorHeight_m.contains(floor.height_m))
              f.fail(printf_string(
                  "without a height, the floor runs from %s up to the next floor's level, %s, "
                  "under its %s slab: %s high, outside %s",
                  length_text(origin_m + elevation_m, unit).c_str(),
                  length_text(*levels_m[i + 1], unit).c_str(),
                  length_text(floor.slab_m, unit).c_str(),
                  length_text(floor.height_m, unit).c_str(),
                  limits::kFloorHeight_m.describe(to_string(unit), meters_per(unit)).c_str()));
          }
          floor.base_elevation_m = elevation_m;
          floor.level_m = levels_m[i];
          elevation_m += floor.height_m + floor.slab_m;

          const Field plan = fm.required("plan");
          if (plan.is_map() && MapReader(plan, {}).has("dxf")) {
            if (!drawings)
              plan.fail("a drawn plan (dxf) needs ccbuild's importer; this tool has none");
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
              plan.fail("plan file '" + text + "' not found (looked for " + plan_path.string() +
                        ")");
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
          read = true;
        },
        floor.name);
    if (!read) continue;  // its errors are kept; the floors after it are still read
    floor.plan.lintel = building.lintels;
    const std::string context = "floor '" + floor.name + "'";
    findings.attempt(
        [&] {
          DiagnosticSink sink;
          try {
            validate_plan(floor.plan, floor.height_m, context);
          } catch (const InputError& error) {
            for (const auto& d : error.diagnostics()) sink.add(d);
          }
          check_anchors(floor, context + ": ", sink);
          sink.throw_if_any();
        },
        floor.name, context + ": ");
    building.floors.push_back(std::move(floor));
  }
  findings.throw_if_any();
  check_layer_budget(building, doc.file, layer_height->line(), layer_height->path());
  return building;
}

bool is_building_document(const Document& doc) {
  if (doc.root.kind != DocNode::Kind::kMap) return false;
  for (const auto& entry : doc.root.entries)
    if (entry.first == "floors") return true;
  return false;
}

}  // namespace

std::string left_out_text(const std::string& floor_name, const LeftOutWall& wall, LengthUnit unit) {
  std::string where = wall.source.file.empty() ? std::string() : wall.source.file;
  if (!where.empty() && wall.source.line > 0) where += ":" + std::to_string(wall.source.line);
  return "floor '" + floor_name + "': wall " + std::to_string(wall.wall_id) +
         (wall.global_id.empty() ? "" : " (" + wall.global_id + ")") + " is " +
         length_text(wall.thickness_m, unit, 3) +
         " thick, thinner than the machine's narrowest bead (" +
         length_text(wall.narrowest_m, unit, 3) + "): left out, for the crew to build" +
         (where.empty() ? "" : " [" + where + "]") + " (print: {thin_walls: refuse} stops instead)";
}

void leave_out_thin_walls(Building& building, const BeadSpec& beads) {
  if (building.print.refuse_thin_walls || !(beads.bead_width_m > 0.0)) return;
  const double narrowest_m = beads.narrowest_m > 0.0 ? beads.narrowest_m : beads.bead_width_m;
  for (Floor& floor : building.floors) {
    FloorPlan& plan = floor.plan;
    std::set<std::int64_t> out;
    for (const Wall& w : plan.walls)
      if (w.thickness_m && wall_beads(*w.thickness_m, beads).how == WallPrint::kTooThin) {
        out.insert(w.id);
        building.left_out.push_back(
            {floor.index, w.id, *w.thickness_m, narrowest_m, w.global_id, w.source});
      }
    if (out.empty()) continue;
    for (const AnchorPoint& a : floor.anchors)
      if (out.count(a.wall_id))
        throw InputError(at(a.source, "wall",
                            "anchor '" + a.id + "' stands on wall " + std::to_string(a.wall_id) +
                                ", which is thinner than the machine's narrowest bead (" +
                                length_text(narrowest_m, building.units, 3) +
                                ") and left out of the print: put the anchor on a printed wall, "
                                "or say print: {thin_walls: refuse}"));
    if (out.size() == plan.walls.size())
      throw InputError(at(plan.walls.front().source, "thickness",
                          "every wall of floor '" + floor.name +
                              "' is thinner than the machine's narrowest bead (" +
                              length_text(narrowest_m, building.units, 3) +
                              "): nothing of it would be printed"));
    std::set<std::int64_t> ends;  // of the walls left out
    for (const Wall& w : plan.walls)
      if (out.count(w.id)) ends.insert({w.start_vertex, w.end_vertex});
    std::erase_if(plan.walls, [&](const Wall& w) { return out.count(w.id) > 0; });
    std::erase_if(plan.openings, [&](const Opening& o) { return out.count(o.wall_id) > 0; });
    // Their ends no printed wall uses go too: the building's extent on the machine, its
    // placement and its slab are the printed walls'.
    for (const Wall& w : plan.walls) {
      ends.erase(w.start_vertex);
      ends.erase(w.end_vertex);
    }
    std::erase_if(plan.vertices, [&](const Vertex& v) { return ends.count(v.id) > 0; });
  }
}

double slab_area_m2(const Floor& floor) {
  std::vector<Eigen::Vector2d> points;
  for (const auto& v : floor.plan.vertices) points.push_back(v.position_m);
  if (points.size() < 3) return 0.0;
  return polygon_area(convex_hull(std::move(points)));
}

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
