// The building-level API: every file read once, the machine and material resolved the
// same way for every command, the fit checks at their boundaries, distinct layers.

#include "ccbuild/schedule/project.hpp"

#include <gtest/gtest.h>

#include <unistd.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "ccbuild/common/document.hpp"
#include "ccbuild/schedule/layer_summary.hpp"
#include "test_support.hpp"

namespace ccbuild::schedule {
namespace {
namespace fs = std::filesystem;
using testing::contains;
using testing::expect_input_error;

TEST(Project, EveryFileIsReadOnce) {
  const std::size_t before = text_files_read();
  const Project house = open_project(testing::source_path("config/buildings/house.yaml"));
  // house.yaml, its two plans, the material, the machine profile and its URDF.
  EXPECT_EQ(text_files_read() - before, 6u);
  const auto files = house.files_read();
  std::set<std::string> names;
  for (const auto& f : files) names.insert(f.filename().string());
  EXPECT_EQ(names,
            (std::set<std::string>{"house.yaml", "ground.yaml", "upper.json", "standard-mix.yaml",
                                   "cc-gantry.yaml", "cc_gantry.urdf"}));
  // A plan shared by two floors is read once too.
  const std::size_t again = text_files_read();
  open_project(testing::data("buildings/cottage.yaml"));
  EXPECT_EQ(text_files_read() - again, 5u);
}

TEST(Project, ALonePlanGetsTheBundledMachineAndMaterial) {
  const Project plan = open_project(testing::data("plans/cottage.yaml"));
  EXPECT_FALSE(plan.is_building);
  EXPECT_EQ(plan.machine_model().name, "CC gantry, up to three nozzles");
  EXPECT_TRUE(contains(plan.machine_origin, "(bundled default)"));
  EXPECT_EQ(plan.material.name, "Standard CC mix");
  // The same machine a building names: the same numbers in every command.
  const Project house = open_project(testing::source_path("config/buildings/house.yaml"));
  EXPECT_EQ(plan.machine_model().travel_speed_m_s, house.machine_model().travel_speed_m_s);
  EXPECT_EQ(plan.machine_model().x.max_m, house.machine_model().x.max_m);
  // Overrides win, and a broken material fails every command that opens the file.
  ProjectOptions o;
  o.material_profile = testing::data("hostile/absurd_material.yaml");
  EXPECT_TRUE(contains(
      expect_input_error([&] { open_project(testing::data("plans/cottage.yaml"), o); }).what(),
      "strength_mpa"));
}

TEST(Project, ABuildingWithoutProfilesGetsTheFlagsOrTheBundledOnes) {
  const fs::path dir =
      fs::temp_directory_path() / ("ccbuild_noprofiles_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "b.yaml") << "units: m\nlayer_height: 0.5\nfloors:\n  - {height: 3, plan: "
                                << testing::data("plans/cottage.yaml") << "}\n";
  const Project bundled = open_project(dir / "b.yaml");
  EXPECT_TRUE(bundled.is_building);
  EXPECT_EQ(bundled.machine_model().name, "CC gantry, up to three nozzles");
  EXPECT_TRUE(contains(bundled.machine_origin, "(bundled default)")) << bundled.machine_origin;
  EXPECT_TRUE(contains(bundled.material_origin, "(bundled default)")) << bundled.material_origin;
  ProjectOptions o;
  o.machine_profile = testing::data("machines/two-gantries.yaml");
  o.material_profile = testing::data("materials/quick-bond-mix.yaml");
  const Project flagged = open_project(dir / "b.yaml", o);
  EXPECT_TRUE(contains(flagged.machine_origin, "(--machine)")) << flagged.machine_origin;
  EXPECT_TRUE(contains(flagged.material_origin, "(--material)")) << flagged.material_origin;
  // One that names a profile that is not there is refused, naming the key's line.
  std::ofstream(dir / "b.yaml", std::ios::app) << "material: missing.yaml\n";
  EXPECT_TRUE(
      contains(expect_input_error([&] { open_project(dir / "b.yaml"); }).what(), "missing.yaml"));
  fs::remove_all(dir);
}

// A one-wall plan `length` long along x, `height` m tall, on a tiny machine.
std::string fit_case(const fs::path& dir, double length_m, double floor_m, double thickness_m) {
  std::ofstream(dir / "plan.yaml")
      << "units: m\nvertices:\n  - {id: 1, x: 0, y: 0}\n  - {id: 2, x: " << length_m
      << ", y: 0}\nwalls:\n  - {id: 1, start: 1, end: 2, "
      << "thickness: " << thickness_m << "}\n";
  std::ofstream(dir / "b.yaml")
      << "units: m\nlayer_height: 0.5\nmaterial: "
      << testing::source_path("config/materials/standard-mix.yaml").string()
      << "\nmachine: " << testing::data("machines/tiny_gantry.yaml")
      << "\nfloors:\n  - {height: " << floor_m << ", plan: plan.yaml}\n";
  return (dir / "b.yaml").string();
}

// A building too large for the travel as it stands is told a turn under which it fits: an
// edge of its outline along x or y, within (-90, 90], rounded to 0.01 degree and checked at
// that value, with 1 µm to spare; said from its own axes whatever turn it stands at now.
std::optional<double> turn_deg(const floors::Building& b, double now_deg, double x_m, double y_m) {
  const auto turn = turn_that_fits(b, now_deg, x_m, y_m);
  return turn ? std::optional<double>(turn->deg) : std::nullopt;
}

TEST(Project, TheTurnThatFitsLaysAnEdgeOfTheOutlineAlongTheTravel) {
  const fs::path dir = fs::temp_directory_path() / ("ccbuild_turn_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  // One wall 5 m long from (0, 0) to (3, 4): 53.13 degrees off x.
  std::ofstream(dir / "plan.yaml") << "units: m\nvertices:\n  - {id: 1, x: 0, y: 0}\n"
                                   << "  - {id: 2, x: 3, y: 4}\nwalls:\n"
                                   << "  - {id: 1, start: 1, end: 2, thickness: 0.15}\n";
  floors::Building b =
      floors::building_from_plan(floors::load_plan(dir / "plan.yaml"), "b", 3.0, 0.1);
  EXPECT_EQ(turn_deg(b, 0.0, 5.0 + 2e-6, 1.0), -53.13);  // along x
  const auto along_x = turn_that_fits(b, 0.0, 5.0 + 2e-6, 1.0);
  ASSERT_TRUE(along_x);
  EXPECT_NEAR(along_x->size_m.x(), 5.0, 1e-6);  // the size as turned, said in the message
  EXPECT_NEAR(along_x->size_m.y(), 0.0, 1e-4);
  EXPECT_EQ(turn_deg(b, 0.0, 1.0, 5.0 + 2e-6), 36.87);  // along y
  EXPECT_EQ(turn_deg(b, 0.0, 5.0 - 1e-6, 1.0), std::nullopt);
  EXPECT_EQ(turn_deg(b, 0.0, 5.0 + 0.5e-6, 1.0), std::nullopt);  // under 1 µm to spare
  // Already turned by 10 degrees: the turn is still said from its own axes.
  floors::place_building(b, 10.0 * M_PI / 180.0, Eigen::Vector2d::Zero());
  EXPECT_EQ(turn_deg(b, 10.0, 5.0 + 2e-6, 1.0), -53.13);
  // No edge along either axis fits 4 m x 4 m (the diagonal, 3.54 m each way, is not looked
  // for): none.
  EXPECT_EQ(turn_deg(b, 10.0, 4.0, 4.0), std::nullopt);
  fs::remove_all(dir);
}

TEST(Project, TheMachineMustReachEveryWallAndTheTop) {
  // tiny_gantry: 5 m of x travel, z 0..18 m, lifts 0.15 m, nozzle 0.15 m.
  const fs::path dir = fs::temp_directory_path() / ("ccbuild_fit_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  EXPECT_NO_THROW(open_project(fit_case(dir, 5.0, 3.0, 0.15)));  // equal to the reach: fits
  EXPECT_TRUE(
      contains(expect_input_error([&] { open_project(fit_case(dir, 5.001, 3.0, 0.15)); }).what(),
               "the building is 5.00 m x 0.00 m but the machine reaches 5.00 m"));
  EXPECT_NO_THROW(open_project(fit_case(dir, 5.0, 17.85, 0.15)));  // 17.85 + 0.15 lift = 18
  EXPECT_TRUE(
      contains(expect_input_error([&] { open_project(fit_case(dir, 5.0, 17.86, 0.15)); }).what(),
               "machine's z joint reaches 18.00 m"));
  const InputError thick =
      expect_input_error([&] { open_project(fit_case(dir, 5.0, 3.0, 0.151)); });
  EXPECT_TRUE(contains(thick.what(), "wall 1 is 0.151 m thick"));
  EXPECT_EQ(thick.first().field, "walls[0].thickness");
  EXPECT_EQ(thick.first().line, 6);
  // Beads of 0.15 m: one bead, or two skins from 0.30 m on; thinner than one is refused.
  EXPECT_NO_THROW(open_project(fit_case(dir, 5.0, 3.0, 0.30)));
  EXPECT_NO_THROW(open_project(fit_case(dir, 5.0, 3.0, 0.60)));
  EXPECT_TRUE(
      contains(expect_input_error([&] { open_project(fit_case(dir, 5.0, 3.0, 0.299)); }).what(),
               "0.299 m thick"));
  // Thinner than one bead: left out for the crew, and the floor has no other wall.
  EXPECT_TRUE(
      contains(expect_input_error([&] { open_project(fit_case(dir, 5.0, 3.0, 0.149)); }).what(),
               "every wall of floor"));
  fs::remove_all(dir);
}

// A one-wall building (4 m, `thickness_m`) on the tiny gantry whose profile gains `extra`.
std::string bead_case(const fs::path& dir, double thickness_m, const std::string& extra,
                      const std::string& building_extra = "") {
  std::ifstream in(testing::data("machines/tiny_gantry.yaml"));
  std::stringstream profile;
  profile << in.rdbuf();
  fs::copy_file(testing::data("machines/tiny_gantry.urdf"), dir / "tiny_gantry.urdf",
                fs::copy_options::overwrite_existing);
  std::ofstream(dir / "m.yaml") << profile.str() << "\n" << extra << "\n";
  fit_case(dir, 4.0, 3.0, thickness_m);
  std::ofstream(dir / "b.yaml")
      << "units: m\nlayer_height: 0.5\nmaterial: "
      << testing::source_path("config/materials/standard-mix.yaml").string()
      << "\nmachine: m.yaml\n"
      << building_extra << "floors:\n  - {height: 3, plan: plan.yaml}\n";
  return (dir / "b.yaml").string();
}

// A wall no bead widths make up is refused with the thicknesses and the widths that would
// print, and each of them, applied as written, prints.
TEST(Project, TheBeadWidthsARefusalProposesPrint) {
  const fs::path dir = fs::temp_directory_path() / ("ccbuild_beads_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const auto refusal = [&](double t, const std::string& extra) {
    return std::string(expect_input_error([&] {
                         open_project(bead_case(dir, t, extra, "print: {thin_walls: refuse}\n"));
                       }).what());
  };
  // The nozzle's 0.15 m only: a 0.27 m cavity wall.
  const std::string cavity = refusal(0.27, "");
  EXPECT_TRUE(contains(cavity, "make it 0.150 m or less (one bead) or 0.300 m or more (two skins)"))
      << cavity;
  EXPECT_TRUE(contains(cavity,
                       "beads reach 0.270 m (the widest of bead_width_m) or down to "
                       "0.135 m (the narrowest)"))
      << cavity;
  EXPECT_NO_THROW(open_project(bead_case(dir, 0.15, "")));
  EXPECT_NO_THROW(open_project(bead_case(dir, 0.30, "")));
  EXPECT_NO_THROW(open_project(bead_case(dir, 0.27, "bead_width_m: [0.15, 0.27]")));
  EXPECT_NO_THROW(open_project(bead_case(dir, 0.27, "bead_width_m: [0.135, 0.15]")));
  // 0.12 to 0.16 m: a 0.2 m wall is over one bead and under two skins.
  const std::string between = refusal(0.2, "bead_width_m: [0.12, 0.16]");
  EXPECT_TRUE(contains(between, "make it 0.160 m or less (one bead) or 0.240 m or more"))
      << between;
  EXPECT_NO_THROW(open_project(bead_case(dir, 0.16, "bead_width_m: [0.12, 0.16]")));
  EXPECT_NO_THROW(open_project(bead_case(dir, 0.24, "bead_width_m: [0.12, 0.16]")));
  EXPECT_NO_THROW(open_project(bead_case(dir, 0.2, "bead_width_m: [0.12, 0.2]")));
  EXPECT_NO_THROW(open_project(bead_case(dir, 0.2, "bead_width_m: [0.1, 0.16]")));
  // 0.10 to 0.25 m: a 0.05 m wall is thinner than the narrowest bead.
  const std::string thin = refusal(0.05, "bead_width_m: [0.10, 0.25]");
  EXPECT_TRUE(contains(thin, "at least one bead wide: make it 0.100 m or more")) << thin;
  EXPECT_NO_THROW(open_project(bead_case(dir, 0.10, "bead_width_m: [0.10, 0.25]")));
  EXPECT_NO_THROW(open_project(bead_case(dir, 0.05, "bead_width_m: [0.05, 0.25]")));
  // Left to the crew (the default), it is the floor's only wall: nothing would be printed.
  EXPECT_TRUE(contains(expect_input_error([&] {
                         open_project(bead_case(dir, 0.05, "bead_width_m: [0.10, 0.25]"));
                       }).what(),
                       "every wall of floor"));
  // The pump bounds the widest bead: 80 m³/h feeds 0.222 m at 0.5 m layers and 0.2 m/s, so
  // a 0.24 m wall is two skins of 0.12 m; 90 m³/h feeds the whole 0.25 m: one pass.
  const auto how = [&](const std::string& extra) {
    const Project p = open_project(bead_case(dir, 0.24, extra));
    const floors::BeadSpec& spec = p.building.floors[0].plan.beads;
    return floors::wall_beads(0.24, spec);
  };
  EXPECT_EQ(how("bead_width_m: [0.10, 0.25]\npump_capacity_m3_h: 80").how,
            floors::WallPrint::kTwoSkins);
  EXPECT_NEAR(how("bead_width_m: [0.10, 0.25]\npump_capacity_m3_h: 80").bead_width_m, 0.12, 1e-12);
  EXPECT_EQ(how("bead_width_m: [0.10, 0.25]\npump_capacity_m3_h: 90").how,
            floors::WallPrint::kOnePass);
  // Never under the nozzle's own width: a pump too small for that refuses the plans instead.
  const Project small =
      open_project(bead_case(dir, 0.15, "bead_width_m: [0.10, 0.25]\npump_capacity_m3_h: 5"));
  EXPECT_NEAR(small.building.floors[0].plan.beads.widest_m, 0.15, 1e-12);
  const std::string pumped = refusal(0.25, "bead_width_m: [0.14, 0.25]\npump_capacity_m3_h: 80");
  EXPECT_TRUE(contains(pumped, "the widest its pump feeds")) << pumped;
  fs::remove_all(dir);
}

// A 4 m wall along x from the plan's origin, on the tiny gantry (x 0..5 m, y -2..27 m),
// the building standing where `site` (YAML, empty for none) says.
std::string placed_case(const fs::path& dir, const std::string& site) {
  std::ofstream(dir / "plan.yaml") << "units: m\nvertices:\n  - {id: 1, x: 0, y: 0}\n  - {id: 2, "
                                      "x: 4, y: 0}\nwalls:\n  - {id: 1, start: 1, end: 2}\n";
  std::ofstream(dir / "b.yaml")
      << "units: m\nlayer_height: 0.5\nmaterial: "
      << testing::source_path("config/materials/standard-mix.yaml").string()
      << "\nmachine: " << testing::data("machines/tiny_gantry.yaml") << "\n"
      << site << "\nfloors:\n  - {height: 3, plan: plan.yaml}\n";
  return (dir / "b.yaml").string();
}

// A 50 mm garden wall running 3 m on from the cottage is thinner than any bead: left for the
// crew, with its far end, before the building is placed and before a climbing family is
// fitted to it. The family's member is the plain cottage's (its platform 9 m x 7 m where
// the garden wall would make it 12 m), and the slab covers the cottage only.
TEST(Project, WallsLeftToTheCrewAreNotTheMachinesToReach) {
  const fs::path dir = fs::temp_directory_path() / ("ccbuild_crew_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const auto fitted = [&](const std::string& building) {
    ProjectOptions o;
    o.machine_profile = testing::source_path("config/machines/cc-climber-family.yaml");
    o.fitted_profile = dir / "fitted.yaml";
    const Project p = open_project(testing::data("buildings/" + building), o);
    EXPECT_TRUE(p.fit) << building;
    return p;
  };
  const Project plain = fitted("cottage-on-site.yaml");  // the cottage with no anchor listed
  const Project garden = fitted("cottage-garden-wall.yaml");
  ASSERT_TRUE(plain.fit && garden.fit);
  EXPECT_NEAR(garden.fit->platform.length_m(), plain.fit->platform.length_m(), 1e-9);
  EXPECT_NEAR(garden.fit->platform.width_m(), plain.fit->platform.width_m(), 1e-9);
  EXPECT_NEAR(garden.fit->platform.x_max_m, plain.fit->platform.x_max_m, 1e-9);
  ASSERT_EQ(garden.building.left_out.size(), 2u);  // on both floors
  for (const auto& floor : garden.building.floors) {
    EXPECT_EQ(floor.plan.find_vertex(7), nullptr) << "the garden wall's far end";
    EXPECT_NE(floor.plan.find_vertex(2), nullptr) << "the corner it starts from";
  }
  const floors::Envelope printed = floors::envelope(garden.building);
  EXPECT_NEAR(printed.size_m().x(), 6.0, 1e-9);
  EXPECT_NEAR(floors::slab_area_m2(garden.building.floors[0]),
              floors::slab_area_m2(plain.building.floors[0]), 1e-9);
  // On a gantry: placed and centred as the printed cottage.
  ProjectOptions centred;
  centred.place_centre = true;
  const Project a = open_project(testing::data("buildings/cottage.yaml"), centred);
  const Project b = open_project(testing::data("buildings/cottage-garden-wall.yaml"), centred);
  EXPECT_NEAR(floors::envelope(b.building).min_m.x(), floors::envelope(a.building).min_m.x(), 1e-9);
  fs::remove_all(dir);
}

TEST(Project, EveryVertexMustStandWithinTheMachinesTravel) {
  const fs::path dir = fs::temp_directory_path() / ("ccbuild_site_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const auto refused = [&](const std::string& site) {
    return expect_input_error([&] { open_project(placed_case(dir, site)); });
  };
  // Both ends of the x travel, exactly and a millimetre beyond.
  EXPECT_NO_THROW(open_project(placed_case(dir, "site: {origin: [1, 0]}")));  // x 1..5
  const InputError past = refused("site: {origin: [1.001, 0]}");
  EXPECT_TRUE(contains(past.what(),
                       "vertex 2 stands at x = 5.00 m on the machine, 0.001 m past "
                       "the end of its x travel (5.00 m)"))
      << past.what();
  EXPECT_TRUE(contains(past.what(), "move the building by -0.001 m or more along x"));
  EXPECT_EQ(past.first().field, "vertices[1]");
  EXPECT_EQ(past.first().line, 4);
  EXPECT_EQ(fs::path(past.first().file).filename(), "plan.yaml");
  EXPECT_EQ(past.diagnostics().size(), 1u);
  EXPECT_NO_THROW(open_project(placed_case(dir, "")));  // as drawn: x 0..4
  const InputError before = refused("site: {origin: [-0.001, 0]}");
  EXPECT_TRUE(contains(before.what(), "0.001 m before the start of its x travel (0.00 m)"))
      << before.what();
  EXPECT_EQ(before.first().field, "vertices[0]");
  // y: the travel starts at -2 m.
  EXPECT_NO_THROW(open_project(placed_case(dir, "site: {origin: [0, -2]}")));
  EXPECT_TRUE(contains(refused("site: {origin: [0, -2.5]}").what(), "+0.500 m or more along y"));
  // The case: a plan far along the rails fits their length but not their place.
  EXPECT_TRUE(contains(refused("site: {origin: [55, 0]}").what(),
                       "the building spans x 55.00 m to 59.00 m, the machine's x travel 0.00 m "
                       "to 5.00 m"));
  fs::remove_all(dir);
}

TEST(Project, ASiteTurnsThenMovesThePlanOrCentresIt) {
  const fs::path dir = fs::temp_directory_path() / ("ccbuild_turn_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  // Turned a quarter anticlockwise about the plan's origin, then moved: (4, 0) -> (2, 4).
  const Project turned = open_project(placed_case(dir, "site: {origin: [2, 0], rotation_deg: 90}"));
  const auto& v = turned.building.floors[0].plan.vertices;
  EXPECT_NEAR(v[0].position_m.x(), 2.0, 1e-12);
  EXPECT_NEAR(v[0].position_m.y(), 0.0, 1e-12);
  EXPECT_NEAR(v[1].position_m.x(), 2.0, 1e-12);
  EXPECT_NEAR(v[1].position_m.y(), 4.0, 1e-12);
  EXPECT_EQ(turned.placement.how, PlacedBy::kSite);
  // Centred: the footprint's middle on the travel's middle (2.5, 12.5), whatever the origin.
  for (const std::string site : {"site: {place: centre}", "site: {origin: [50, 50]}"}) {
    ProjectOptions o;
    o.place_centre = site.find("origin") != std::string::npos;  // --place centre overrides
    const Project centred = open_project(placed_case(dir, site), o);
    const auto& c = centred.building.floors[0].plan.vertices;
    EXPECT_NEAR(c[0].position_m.x(), 0.5, 1e-12) << site;
    EXPECT_NEAR(c[1].position_m.x(), 4.5, 1e-12) << site;
    EXPECT_NEAR(c[1].position_m.y(), 12.5, 1e-12) << site;
    EXPECT_EQ(centred.placement.how, PlacedBy::kCentred) << site;
    EXPECT_NEAR(centred.placement.origin_m.x(), 0.5, 1e-12) << site;
  }
  // What a site cannot say.
  const struct {
    const char* site;
    const char* field;
    const char* says;
  } bad[] = {{"site: {origin: [1]}", "site.origin", "expected [x, y]"},
             {"site: {place: middle}", "site.place", "expected `centre`"},
             {"site: {origin: [1, 0], place: centre}", "site.place", "not both"},
             {"site: {rotation_deg: 400}", "site.rotation_deg", "400"},
             {"site: {origin: [1, 0], turn: 5}", "site.turn", ""}};
  for (const auto& b : bad) {
    const InputError e = expect_input_error([&] { open_project(placed_case(dir, b.site)); });
    EXPECT_EQ(e.first().field, b.field) << b.site << ": " << e.what();
    EXPECT_TRUE(contains(e.what(), b.says)) << b.site << ": " << e.what();
  }
  fs::remove_all(dir);
}

TEST(Project, ADrawnPlanIsReadOnceAndCountsAsAnInput) {
  // Two floors of one DXF drawing (tests/data/drawings/centrelines_m.dxf).
  const Project p = open_project(testing::data("buildings/drawn-centrelines.yaml"));
  ASSERT_EQ(p.building.floors.size(), 2u);
  EXPECT_EQ(p.building.floors[0].plan.walls.size(), 5u);
  EXPECT_TRUE(floors::same_model(p.building.floors[0].plan, p.building.floors[1].plan));
  int drawings = 0;
  for (const auto& f : p.files_read()) drawings += f.filename() == "centrelines_m.dxf";
  EXPECT_EQ(drawings, 1) << "the drawing is an input (never overwritten, its checksum recorded)";
  // Face lines 0.2 m apart: on the bundled gantry (beads 0.10 to 0.25 m) each wall one
  // pass of its 0.2 m; on a machine of 0.15 m beads only, thicker than one bead and thinner
  // than two, refused, naming the drawing's entities.
  const Project faces = open_project(testing::data("buildings/drawn-faces.yaml"));
  ASSERT_FALSE(faces.building.floors[0].plan.walls.empty());
  for (const auto& w : faces.building.floors[0].plan.walls) {
    const floors::WallBeads beads =
        floors::wall_beads(*w.thickness_m, faces.building.floors[0].plan.beads);
    EXPECT_EQ(beads.how, floors::WallPrint::kOnePass);
    EXPECT_NEAR(beads.bead_width_m, 0.2, 1e-9);
  }
  ProjectOptions narrow;
  narrow.machine_profile = testing::data("machines/two-gantries.yaml");
  const InputError thick = expect_input_error(
      [&] { open_project(testing::data("buildings/drawn-faces.yaml"), narrow); });
  EXPECT_TRUE(contains(thick.what(), "faces_mm.dxf: entities")) << thick.what();
  EXPECT_TRUE(contains(thick.what(), "is 0.200 m thick"));
}

TEST(Project, DistinctLayersAreProvenEqualAndCoverTheBuilding) {
  const Project house = open_project(testing::source_path("config/buildings/house.yaml"));
  const auto distinct = distinct_layers(house);
  EXPECT_EQ(distinct.size(), 6u);
  int layers = 0;
  for (const auto& d : distinct) {
    layers += static_cast<int>(d.where.size());
    for (const auto& ref : d.where) {
      const auto layer = layer_of(house, ref.floor, ref.layer);
      EXPECT_EQ(floors::GeometryKey(layer), d.key);
      EXPECT_TRUE(floors::match_segments(d.layer, layer));
    }
  }
  EXPECT_EQ(layers, 60);
  EXPECT_EQ(expect_input_error([&] { layer_of(house, 2, 0); }).first().field, "floor");
  EXPECT_EQ(expect_input_error([&] { layer_of(house, 1, 30); }).first().field, "layer");
  EXPECT_NO_THROW(layer_of(house, 1, 29));
}

// One numbering of the distinct layers (floors::GeometryNumbering): `ccbuild layers`'
// geometries, distinct_layers' labels and the schedule's plan keys g<number>n<nozzles>
// name the same geometry by the same number, layer by layer, on the tower (the apartment's
// floors repeated under a set-back top); every layer numbered is one the schedule prints.
TEST(Project, LayersDistinctLayersAndTheScheduleNumberGeometriesAlike) {
  const auto golden = nlohmann::json::parse(
      testing::slurp(testing::source_path("tests/regression/tower.schedule.json")));
  const Project tower = open_project(testing::source_path("config/buildings/tower.yaml"));
  const BuildingSummary summary = summarize_building(tower.building);
  std::map<std::pair<int, int>, int> label_of;
  for (const auto& f : summary.floors)
    for (const auto& run : f.runs)
      for (int l = run.first_layer; l <= run.last_layer; ++l)
        label_of[{f.floor_index, l}] = run.geometry_label;
  std::map<std::pair<int, int>, int> distinct_label;
  for (const auto& d : distinct_layers(tower))
    for (const auto& ref : d.where) distinct_label[{ref.floor, ref.layer}] = d.label;
  int checked = 0;
  for (const auto& l : golden["layers"]) {
    const std::string key = l["plan"];  // g<number>n<nozzles>
    const int number = std::stoi(key.substr(1, key.find('n') - 1));
    const std::pair<int, int> at{l["floor"].get<int>(), l["layer"].get<int>()};
    ASSERT_TRUE(label_of.count(at)) << key;
    EXPECT_EQ(label_of.at(at), number) << "floor " << at.first << " layer " << at.second;
    EXPECT_EQ(distinct_label.at(at), number) << "floor " << at.first << " layer " << at.second;
    ++checked;
  }
  EXPECT_EQ(checked, static_cast<int>(label_of.size())) << "a layer numbered but not scheduled";
  EXPECT_EQ(summary.distinct_geometries, static_cast<int>(distinct_layers(tower).size()));
}

TEST(Project, PlansALayerWithOneNozzleOrSeveral) {
  const Project house = open_project(testing::source_path("config/buildings/house.yaml"));
  const floors::Layer layer = layer_of(house, 0, 12);
  LayerPlanRequest one;
  one.planning.max_kicks = 100;
  const LayerPlanResult single = plan_layer(house, layer, one);
  ASSERT_TRUE(single.single);
  EXPECT_TRUE(single.status);
  LayerPlanRequest two = one;
  two.nozzles = 2;
  two.multi.gantry_width_m = 1.5;
  two.multi.planning = one.planning;
  const LayerPlanResult multi = plan_layer(house, layer, two);
  ASSERT_TRUE(multi.multi);
  EXPECT_EQ(static_cast<bool>(multi.status), static_cast<bool>(multi.multi->status));
  if (multi.status) {
    EXPECT_LT(multi.layer_time_s(), single.layer_time_s());
  }
}

}  // namespace
}  // namespace ccbuild::schedule
