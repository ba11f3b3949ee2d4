// IFC models to buildings (floors/import): storeys, walls through the whole placement chain
// in millimetres, feet and metres, axes moved to the middle of their layer sets and joined,
// openings from their voids, what cannot be printed said by GlobalId, hostile models refused
// with the file named. The models are written by tests/tools/make_ifc.py, independently of
// IFC++; tests/data/ifc/public holds a real one (its README says where from).

#include "ccbuild/import/ifc.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <regex>

#include "ccbuild/common/limits.hpp"
#include "ccbuild/floors/plan.hpp"
#include "ccbuild/floors/quantities.hpp"
#include "test_support.hpp"

namespace ccbuild::import {
namespace {
namespace fs = std::filesystem;
using Eigen::Vector2d;
using testing::contains;
using testing::expect_input_error;

fs::path model(const std::string& name) {
  return testing::source_path("tests/data/ifc/" + name);
}

/// The GlobalId of the element named `name` in a model's text.
std::string guid_of(const fs::path& file, const std::string& name) {
  const std::string text = testing::slurp(file);
  const std::regex entity("\\('([0-9A-Za-z_$]{22})',[^,]*,'" + name + "'");
  std::smatch m;
  EXPECT_TRUE(std::regex_search(text, m, entity)) << name;
  return m.size() > 1 ? m[1].str() : std::string();
}

std::string all(const std::vector<std::string>& notes) {
  std::string out;
  for (const auto& n : notes) out += n + "\n";
  return out;
}

const floors::Wall* wall_named(const floors::FloorPlan& plan, const std::string& name) {
  for (const auto& w : plan.walls)
    if (contains(w.source.path, "'" + name + "'")) return &w;
  return nullptr;
}

const floors::Opening* opening_named(const floors::FloorPlan& plan, const std::string& name) {
  for (const auto& o : plan.openings)
    if (o.id == name) return &o;
  return nullptr;
}

void expect_near(const Vector2d& p, double x, double y) {
  EXPECT_NEAR(p.x(), x, 1e-6) << p.transpose();
  EXPECT_NEAR(p.y(), y, 1e-6) << p.transpose();
}

/// A point of make_ifc.py's building frame (x, y), where it lies in the model: the building
/// stands at (10 m, 5 m) on its site, turned by 90 degrees.
void expect_at(const Vector2d& p, double x, double y) {
  expect_near(p, 10.0 - y, 5.0 + x);
}

fs::path scratch(const std::string& name) {
  return testing::scratch_dir("ifc_test", name);
}

TEST(IfcImport, TheHouseInMillimetresBecomesTwoFloorsOfWallsAndOpenings) {
  const fs::path file = model("house_ifc4.ifc");
  const IfcImport read = read_ifc_building(file);
  EXPECT_EQ(read.schema, "IFC4");
  EXPECT_DOUBLE_EQ(read.metres_per_unit, 0.001);
  const floors::Building& b = read.building;
  EXPECT_EQ(b.name, "House");
  ASSERT_EQ(b.floors.size(), 2u);  // the roof storey has no walls
  EXPECT_EQ(b.floors[0].name, "Ground floor");
  EXPECT_EQ(b.floors[1].name, "First floor");
  // Walls up to the underside of the slab over them (TheWallsOfAFloorStopUnderTheSlabOverIt).
  EXPECT_DOUBLE_EQ(b.floors[0].height_m, 2.8);  // under the first floor's slab
  EXPECT_DOUBLE_EQ(b.floors[1].height_m, 2.8);  // under the roof slab
  EXPECT_DOUBLE_EQ(b.floors[1].base_elevation_m, 3.0);
  const floors::FloorPlan& ground = b.floors[0].plan;
  ASSERT_EQ(ground.walls.size(), 5u);
  ASSERT_EQ(b.floors[1].plan.walls.size(), 5u);
  for (const auto& f : b.floors)
    for (const auto& w : f.plan.walls) {
      ASSERT_TRUE(w.thickness_m);
      EXPECT_DOUBLE_EQ(*w.thickness_m, 0.15);  // 150 mm
      EXPECT_EQ(w.global_id.size(), 22u);
    }
  // The building stands at (10 m, 5 m) on its site, turned by 90 degrees: its own (x, y) is
  // (10 - y, 5 + x) in the model. The south wall runs along the building's x.
  const floors::Wall* south = wall_named(ground, "South wall");
  ASSERT_NE(south, nullptr);
  EXPECT_EQ(south->global_id, guid_of(file, "South wall"));
  expect_near(ground.wall_start_m(*south), 10.0, 5.0);
  expect_near(ground.wall_end_m(*south), 10.0, 13.0);
  // The west wall has no axis: its body's rectangle gives it.
  const floors::Wall* west = wall_named(ground, "West wall");
  ASSERT_NE(west, nullptr);
  expect_near(ground.wall_start_m(*west), 4.0, 5.0);
  expect_near(ground.wall_end_m(*west), 10.0, 5.0);
  // The inner wall's axis stops at the outer walls' faces; it is extended to their axes.
  const floors::Wall* inner = wall_named(ground, "Inner wall");
  ASSERT_NE(inner, nullptr);
  expect_near(ground.wall_start_m(*inner), 10.0, 9.0);
  expect_near(ground.wall_end_m(*inner), 4.0, 9.0);
  EXPECT_EQ(ground.vertices.size(), 6u);  // every junction one shared vertex
  // Openings: along the wall from its start, sill and head above the floor.
  const floors::Opening* door = opening_named(ground, "Front door");
  ASSERT_NE(door, nullptr);
  EXPECT_EQ(door->wall_id, south->id);
  EXPECT_NEAR(door->offset_m, 1.0, 1e-9);
  EXPECT_NEAR(door->width_m, 0.9, 1e-9);
  EXPECT_NEAR(door->sill_m, 0.0, 1e-9);
  EXPECT_NEAR(door->head_m, 2.1, 1e-9);
  EXPECT_EQ(door->global_id, guid_of(file, "Opening for Front door"));
  EXPECT_TRUE(contains(door->source.path, "filled by IfcDoor " + guid_of(file, "Front door")));
  // A window whose body is drawn in the wall's elevation and extruded through it.
  const floors::Opening* window = opening_named(ground, "Kitchen window");
  ASSERT_NE(window, nullptr);
  EXPECT_NEAR(window->offset_m, 4.8, 1e-9);
  EXPECT_NEAR(window->width_m, 1.2, 1e-9);
  EXPECT_NEAR(window->sill_m, 0.9, 1e-9);
  EXPECT_NEAR(window->head_m, 2.1, 1e-9);
  // The hall door lies 2 m along the inner wall's axis, which now starts 75 mm earlier.
  const floors::Opening* hall = opening_named(ground, "Hall door");
  ASSERT_NE(hall, nullptr);
  EXPECT_EQ(hall->wall_id, inner->id);
  EXPECT_NEAR(hall->offset_m, 2.075, 1e-9);
  // Upstairs: sill and head above the first floor.
  const floors::Opening* bedroom = opening_named(b.floors[1].plan, "Bedroom window");
  ASSERT_NE(bedroom, nullptr);
  EXPECT_NEAR(bedroom->sill_m, 1.0, 1e-9);
  EXPECT_NEAR(bedroom->head_m, 2.2, 1e-9);
  // What was left out or ignored, each by GlobalId.
  const std::string notes = all(read.notes);
  EXPECT_TRUE(contains(notes, "IfcCurtainWall " + guid_of(file, "Glass screen") +
                                  " 'Glass screen': a curtain wall, not printable; left out"));
  EXPECT_TRUE(contains(notes, "IfcWall " + guid_of(file, "Curved garden wall") +
                                  " 'Curved garden wall': its axis is curved"));
  EXPECT_TRUE(contains(notes, guid_of(file, "Bedroom partition") +
                                  " 'Bedroom partition': its material 'Gypsum board'"));
  EXPECT_TRUE(contains(notes, "storey 'Roof' at 6.000 m has no walls"));
  EXPECT_TRUE(contains(notes, "true north"));
  EXPECT_TRUE(contains(notes, "map conversion"));
  EXPECT_TRUE(contains(read.notes.back(), "imported 10 walls and 4 openings on 2 floors"));
  EXPECT_TRUE(contains(read.notes.back(), "left out: 3 elements"));
  EXPECT_EQ(b.import_notes, read.notes);
}

TEST(IfcImport, TheSameHouseInIfc2x3GivesTheSamePlansAndItsTopStoreyFromItsWalls) {
  const IfcImport four = read_ifc_building(model("house_ifc4.ifc"));
  const IfcImport two = read_ifc_building(model("house_ifc2x3.ifc"));
  EXPECT_EQ(two.schema, "IFC2X3");
  ASSERT_EQ(two.building.floors.size(), 2u);
  EXPECT_DOUBLE_EQ(two.building.floors[1].height_m, 2.8);  // no storey above: its walls
  EXPECT_TRUE(contains(all(two.notes), "the top one: 2.800 m high, as its tallest wall"));
  for (std::size_t k = 0; k < 2; ++k) {
    floors::FloorPlan a = four.building.floors[k].plan, b = two.building.floors[k].plan;
    // The same elements have other GlobalIds in the other file.
    for (auto* p : {&a, &b}) {
      for (auto& w : p->walls) w.global_id.clear();
      for (auto& o : p->openings) o.global_id.clear();
    }
    EXPECT_TRUE(floors::same_model(a, b, 1e-9)) << k;
  }
}

TEST(IfcImport, TheWallsOfAFloorStopUnderTheSlabOverIt) {
  // With slabs (house_ifc4.ifc): each floor's walls run from its storey's elevation to the
  // underside of the slab over them, the next storey's floor slab (ArchiCAD's way: placed at
  // its underside, extruded up) or the roof's slab (Revit's way: placed at its top,
  // extruded down; part of an IfcRoof). The slab lies between them and the next floor.
  const fs::path with_slabs = model("house_ifc4.ifc");
  const IfcImport four = read_ifc_building(with_slabs);
  const auto& f4 = four.building.floors;
  ASSERT_EQ(f4.size(), 2u);
  EXPECT_NEAR(f4[0].height_m, 2.8, 1e-9);
  EXPECT_NEAR(f4[0].slab_m, 0.2, 1e-9);
  EXPECT_NEAR(f4[1].base_elevation_m, 3.0, 1e-9);  // the storey's elevation still
  EXPECT_NEAR(f4[1].height_m, 2.8, 1e-9);
  EXPECT_NEAR(f4[1].slab_m, 0.2, 1e-9);
  const std::string notes = all(four.notes);
  EXPECT_TRUE(contains(notes,
                       "floor 'Ground floor': 2.800 m high, from its level (0.000 m) to "
                       "the underside of IfcSlab " +
                           guid_of(with_slabs, "First floor slab") +
                           " 'First floor slab' (FLOOR slab, 0.200 m thick, in storey "
                           "'First floor') at 2.800 m"))
      << notes;
  EXPECT_TRUE(contains(notes,
                       "floor 'First floor': 2.800 m high, from its level (3.000 m) to "
                       "the underside of IfcSlab " +
                           guid_of(with_slabs, "Roof slab") +
                           " 'Roof slab' (ROOF slab, 0.200 m thick, in storey 'Roof')"))
      << notes;
  // A stair landing is no slab the walls carry; the ground slab lies under the ground floor.
  EXPECT_TRUE(contains(notes, "'Stair landing': a slab neither FLOOR, BASESLAB nor ROOF"));
  EXPECT_FALSE(contains(notes, "the top one"));
  // The openings' heads stay under the slab.
  for (const auto& f : f4)
    for (const auto& o : f.plan.openings) EXPECT_LE(o.head_m, f.height_m + 1e-9) << o.id;
  // Without slabs (house_ifc2x3.ifc, the same storeys and walls): storey to storey, and the
  // top floor as its tallest wall, as before.
  const IfcImport two = read_ifc_building(model("house_ifc2x3.ifc"));
  const auto& f2 = two.building.floors;
  ASSERT_EQ(f2.size(), 2u);
  EXPECT_NEAR(f2[0].height_m, 3.0, 1e-9);
  EXPECT_NEAR(f2[0].slab_m, 0.0, 1e-12);
  EXPECT_NEAR(f2[1].height_m, 2.8, 1e-9);
  EXPECT_NEAR(f2[1].base_elevation_m, 3.0, 1e-9);
  EXPECT_TRUE(contains(all(two.notes), "the model has no slab"));
}

TEST(IfcImport, ThickWallsDrawnAlongTheirFaceAreCentredOnTheirLayerSetsAndMeet) {
  const IfcImport read = read_ifc_building(model("thick_ifc4.ifc"));
  EXPECT_DOUBLE_EQ(read.metres_per_unit, 1.0);
  const floors::FloorPlan& plan = read.building.floors.at(0).plan;
  ASSERT_EQ(plan.walls.size(), 5u);
  // The outer walls' middles are 0.15 m inside the 6 m x 5 m outline, meeting at corners.
  const floors::Wall* first = wall_named(plan, "Outer wall 1");
  ASSERT_NE(first, nullptr);
  EXPECT_DOUBLE_EQ(*first->thickness_m, 0.3);
  expect_at(plan.wall_start_m(*first), 0.15, 0.15);
  expect_at(plan.wall_end_m(*first), 5.85, 0.15);
  const floors::Wall* third = wall_named(plan, "Outer wall 3");
  ASSERT_NE(third, nullptr);
  expect_at(plan.wall_start_m(*third), 5.85, 4.85);
  expect_at(plan.wall_end_m(*third), 0.15, 4.85);
  // The inner wall, stopped at the outer walls' inner faces, reaches their middles.
  const floors::Wall* inner = wall_named(plan, "Inner wall");
  ASSERT_NE(inner, nullptr);
  EXPECT_DOUBLE_EQ(*inner->thickness_m, 0.15);
  expect_at(plan.wall_start_m(*inner), 3.0, 0.15);
  expect_at(plan.wall_end_m(*inner), 3.0, 4.85);
  EXPECT_EQ(plan.vertices.size(), 6u);
}

TEST(IfcImport, ALayeredBodyIsAllItsSolidsAndAnElevationExtrudedThroughAWallStandsUpright) {
  // Revit's IFC4 export (the public Gymzaal model): a cavity wall's body is one extrusion
  // per layer, side by side (the first alone is its 70 mm cavity: the wall was read as
  // 0.07 m thick); a wall with a gable or notch is its elevation extruded through it (it
  // was left out as sloped). No material layer set: the thickness is the bodies' width.
  const IfcImport read = read_ifc_building(model("layered_ifc4.ifc"));
  ASSERT_EQ(read.building.floors.size(), 1u);
  EXPECT_NEAR(read.building.floors[0].height_m, 3.5, 1e-9);  // the gable's top
  const floors::FloorPlan& plan = read.building.floors[0].plan;
  ASSERT_EQ(plan.walls.size(), 4u) << all(read.notes);
  for (const char* name : {"South wall", "East wall", "North wall", "West wall"}) {
    const floors::Wall* w = wall_named(plan, name);
    ASSERT_NE(w, nullptr) << name;
    EXPECT_NEAR(*w->thickness_m, 0.3, 1e-9) << name;
  }
  expect_at(plan.wall_start_m(*wall_named(plan, "South wall")), 0.0, 0.0);
  expect_at(plan.wall_end_m(*wall_named(plan, "South wall")), 6.0, 0.0);
  expect_at(plan.wall_start_m(*wall_named(plan, "East wall")), 6.0, 0.0);
  expect_at(plan.wall_end_m(*wall_named(plan, "East wall")), 6.0, 4.0);
  expect_at(plan.wall_end_m(*wall_named(plan, "West wall")), 0.0, 0.0);
  EXPECT_EQ(plan.vertices.size(), 4u);
  // Issue 50: each stops where its body does: the gable's outline steps up to its ridge, the
  // others stop at their 3 m under it.
  using Top = std::vector<std::pair<double, double>>;
  EXPECT_EQ(wall_named(plan, "West wall")->top_m, (Top{{0.0, 3.0}, {2.0, 3.5}, {4.0, 3.0}}));
  for (const char* name : {"South wall", "East wall", "North wall"})
    EXPECT_EQ(wall_named(plan, name)->top_m, (Top{{0.0, 3.0}})) << name;
  EXPECT_TRUE(contains(all(read.notes),
                       "'West wall' has a top from 3.000 to 3.500 m above the "
                       "floor's level"))
      << all(read.notes);
  EXPECT_TRUE(contains(read.notes.back(), "left out: 0 elements")) << all(read.notes);
  // The north wall's cornice, swept along it, is no part of its thickness; said.
  EXPECT_TRUE(contains(all(read.notes),
                       "'North wall': 1 of its body's 4 solids extruded "
                       "sideways along it (a sweep or a cornice?) are not "
                       "printed"))
      << all(read.notes);
}

TEST(IfcImport, AConversionBasedFootIsConvertedToMetres) {
  const IfcImport read = read_ifc_building(model("feet_ifc2x3.ifc"));
  EXPECT_NEAR(read.metres_per_unit, 0.3048, 1e-12);
  const floors::Building& b = read.building;
  ASSERT_EQ(b.floors.size(), 1u);
  EXPECT_NEAR(b.floors[0].height_m, 10 * 0.3048, 1e-9);  // its walls' height
  const floors::FloorPlan& plan = b.floors[0].plan;
  ASSERT_EQ(plan.walls.size(), 4u);
  EXPECT_NEAR(*plan.walls[0].thickness_m, 0.5 * 0.3048, 1e-9);
  EXPECT_NEAR(plan.wall_length_m(plan.walls[0]), 20 * 0.3048, 1e-9);
}

// Issue 50: the model's own quantities. The ground floor's walls state exactly what they
// print (a door taken out); the attic's knee walls state 0.7 m of the 2.8 m they are printed
// to, and one wall states none. IFC4 in cubic metres and IFC2X3 in cubic decimetres (the
// prefix applies to the metre: 1 dm3 = 1e-3 m3) give the same volumes.
TEST(IfcImport, TheModelsOwnWallVolumesAreKeptAndComparedFloorByFloor) {
  for (const char* name : {"quantities_ifc4.ifc", "quantities_ifc2x3.ifc"}) {
    SCOPED_TRACE(name);
    const IfcImport read = read_ifc_building(model(name));
    const floors::Building& b = read.building;
    ASSERT_EQ(b.floors.size(), 2u);
    const double t = 0.15;
    // The ground floor: four walls, 20 m of axis, 3 m high, less a 0.9 m x 2.1 m door.
    const floors::FloorQuantities ground = floors::floor_quantities(b.floors[0], 0.1, 0.0);
    ASSERT_TRUE(ground.model_m3);
    EXPECT_NEAR(*ground.model_m3, (20 * 3.0 - 0.9 * 2.1) * t, 1e-9);
    EXPECT_NEAR(ground.printed_m3, (20 * 3.0 - 0.9 * 2.1) * t, 1e-9);
    EXPECT_EQ(ground.walls_modelled, 4);
    EXPECT_EQ(ground.walls_unmodelled, 0);
    EXPECT_FALSE(ground.off());
    const std::string g = floors::quantities_text(b.floors[0].name, ground);
    EXPECT_TRUE(contains(g,
                         "prints 8.72 m³ of walls; the model's NetVolume of the 4 walls that "
                         "state one is 8.72 m³, printed 8.72 m³ (+0.0%)"))
        << g;
    EXPECT_FALSE(contains(g, "OFF")) << g;
    // The attic, 2.8 m high: its knee walls stop at their bodies' 0.7 m and its gables step
    // up from their eaves' 0.7 m to the 2.8 m ridge (walls at their real height), so what
    // it prints is what its model states; the west gable states none.
    const floors::FloorQuantities attic = floors::floor_quantities(b.floors[1], 0.1, 0.0);
    EXPECT_NEAR(b.floors[1].height_m, 2.8, 1e-9);
    const auto& walls = b.floors[1].plan.walls;
    ASSERT_EQ(walls.size(), 4u);
    EXPECT_EQ(walls[0].top_m, (std::vector<std::pair<double, double>>{{0.0, 0.7}}));
    // The east gable its elevation extruded through it, the west one a box cut by its roof's
    // two planes: the same outline.
    for (std::size_t k : {1u, 3u})
      EXPECT_EQ(walls[k].top_m,
                (std::vector<std::pair<double, double>>{{0.0, 0.7}, {2.0, 2.8}, {4.0, 0.7}}))
          << k;
    const double gable_m3 = 4 * (0.7 + 2.1 / 2) * t;
    ASSERT_TRUE(attic.model_m3);
    EXPECT_NEAR(*attic.model_m3, 2 * 6 * 0.7 * t + gable_m3, 1e-9);
    EXPECT_NEAR(attic.printed_modelled_m3, 2 * 6 * 0.7 * t + gable_m3, 1e-9);
    EXPECT_NEAR(attic.printed_m3, 2 * 6 * 0.7 * t + 2 * gable_m3, 1e-9);
    EXPECT_EQ(attic.walls_modelled, 3);
    EXPECT_EQ(attic.walls_unmodelled, 1);
    EXPECT_FALSE(attic.off());
    EXPECT_TRUE(contains(all(read.notes), guid_of(model(name), "South attic wall") +
                                              " 'South attic wall' stops 0.700 m above the "
                                              "floor's level"))
        << all(read.notes);
  }
}

// Revit's cavity walls (the public Gymzaal): a wall's NetVolume counts its leaves above the
// floor's top as well, and they do not stop at one height; the outer leaf runs up past the
// slab's edge, the inner stops under it. The floor's share of each wall is its body's volume
// up to the slab's underside (shared by height, the walls were +3.4%: 11.20 m³ printed
// against a 10.83 m³ share).
TEST(IfcImport, AWallsModelVolumeIsSharedByItsBodysVolumeWhereItsLeavesStopAtDifferentHeights) {
  const IfcImport read = read_ifc_building(model("ring_beam_ifc4.ifc"));
  ASSERT_EQ(read.building.floors.size(), 1u);
  const floors::Floor& ground = read.building.floors[0];
  EXPECT_NEAR(ground.height_m, 2.8, 1e-9);  // to the roof slab's underside
  ASSERT_EQ(ground.plan.walls.size(), 4u);
  for (const floors::Wall& w : ground.plan.walls) {
    ASSERT_TRUE(w.model_volume_m3) << w.id;
    // Both leaves up to 2.8 m of the NetVolume's 3.0 m + 2.8 m.
    const double axis_m = ground.plan.wall_length_m(w);
    EXPECT_NEAR(*w.model_volume_m3, axis_m * 0.1 * (2.8 + 2.8), 1e-9) << w.id;
  }
  const floors::FloorQuantities q = floors::floor_quantities(ground, 0.1, 0.0);
  ASSERT_TRUE(q.model_m3);
  EXPECT_NEAR(*q.model_m3, 20 * 0.2 * 2.8, 1e-9);
  EXPECT_NEAR(q.printed_m3, 20 * 0.2 * 2.8, 1e-9);
  EXPECT_FALSE(q.off());
}

// An axis that runs on past its body where nothing meets it (free_end_ifc4.ifc: a garden
// wall's axis 0.6 m past its 3 m body) is printed to the body, and said; the ends that meet
// other walls keep their axes. The floor then prints what its model states.
TEST(IfcImport, AnAxisRunningPastItsBodyAtAFreeEndIsPrintedToTheBody) {
  const IfcImport read = read_ifc_building(model("free_end_ifc4.ifc"));
  const floors::FloorPlan& plan = read.building.floors[0].plan;
  ASSERT_EQ(plan.walls.size(), 5u);
  const floors::Wall& garden = plan.walls[4];
  EXPECT_NEAR(plan.wall_length_m(garden), 3.0, 1e-9);
  // It still starts at the room's south-east corner, where it meets the south wall.
  EXPECT_NEAR((plan.wall_start_m(garden) - plan.wall_end_m(plan.walls[0])).norm(), 0.0, 1e-9);
  for (std::size_t k = 0; k < 4; ++k)
    EXPECT_NEAR(plan.wall_length_m(plan.walls[k]), k % 2 ? 4.0 : 6.0, 1e-9);
  EXPECT_TRUE(contains(all(read.notes),
                       "its axis runs 0.600 m past its body where no other "
                       "wall meets it; printed to its body"))
      << all(read.notes);
  const floors::FloorQuantities q = floors::floor_quantities(read.building.floors[0], 0.1, 0.0);
  ASSERT_TRUE(q.model_m3);
  EXPECT_NEAR(q.printed_modelled_m3, *q.model_m3, 1e-9);
}

// Polygonal bounded half-spaces (bounded_cuts_ifc4.ifc) take away only inside their prisms:
// a notch over 2-4 m of the south wall (a prism swept upwards), over 1-3 m of the west wall
// (swept across it, drawn in its elevation) and of the north wall (an L-shaped boundary, not
// convex). Each wall prints exactly its model's NetVolume, and nothing is read as the whole
// plane's half-space.
TEST(IfcImport, ABoundedHalfSpaceCutsOnlyInsideItsPrism) {
  const IfcImport read = read_ifc_building(model("bounded_cuts_ifc4.ifc"));
  const floors::FloorPlan& plan = read.building.floors[0].plan;
  ASSERT_EQ(plan.walls.size(), 4u);
  struct Expected {
    const char* name;
    double from_m, to_m, notch_m;
  };
  for (const Expected& e :
       {Expected{"South wall", 2.0, 4.0, 1.8}, Expected{"West wall", 1.0, 3.0, 2.4},
        Expected{"North wall", 1.0, 3.0, 2.0}}) {
    const floors::Wall* w = wall_named(plan, e.name);
    ASSERT_NE(w, nullptr) << e.name;
    ASSERT_FALSE(w->top_m.empty()) << e.name;
    const double length_m = plan.wall_length_m(*w);
    // Both ends of the notch, just inside and just outside it, and the wall's ends.
    for (const auto& [s_m, z_m] :
         std::vector<std::pair<double, double>>{{0.0, 3.0},
                                                {e.from_m - 1e-3, 3.0},
                                                {e.from_m + 1e-3, e.notch_m},
                                                {0.5 * (e.from_m + e.to_m), e.notch_m},
                                                {e.to_m - 1e-3, e.notch_m},
                                                {e.to_m + 1e-3, 3.0},
                                                {length_m, 3.0}})
      EXPECT_NEAR(floors::top_at(w->top_m, s_m), z_m, 1e-6) << e.name << " at " << s_m << " m";
  }
  EXPECT_TRUE(wall_named(plan, "East wall")->top_m.empty());
  EXPECT_FALSE(contains(all(read.notes), "half-space")) << all(read.notes);
  const floors::FloorQuantities q = floors::floor_quantities(read.building.floors[0], 0.1, 0.0);
  ASSERT_TRUE(q.model_m3);
  ASSERT_EQ(q.elements.size(), 4u);
  for (const auto& element : q.elements)
    EXPECT_NEAR(element.printed_m3, *element.model_m3, 1e-9) << element.global_id;
}

TEST(IfcImport, FiltersChooseWhichWallsArePrinted) {
  IfcOptions o;
  o.excluded_materials.clear();            // the gypsum partition too
  o.wall_types = {"ifcwallstandardcase"};  // any case; the west wall is an IfcWall
  const IfcImport read = read_ifc_building(model("house_ifc4.ifc"), o);
  EXPECT_EQ(read.building.floors[1].plan.walls.size(), 6u);  // the partition too
  EXPECT_EQ(read.building.floors[0].plan.walls.size(), 4u);  // the west wall (an IfcWall) out
  EXPECT_NE(wall_named(read.building.floors[1].plan, "Bedroom partition"), nullptr);
  EXPECT_EQ(wall_named(read.building.floors[0].plan, "West wall"), nullptr);
  EXPECT_TRUE(contains(all(read.notes), "an IfcWall is not among the wall types read"));
}

TEST(IfcImport, HostileModelsAreRefusedNamingTheFile) {
  const auto refused = [](const fs::path& file, const std::string& message,
                          const IfcOptions& o = {}) {
    const InputError e = expect_input_error([&] { read_ifc_building(file, o); });
    EXPECT_EQ(e.first().file, file.string());
    EXPECT_TRUE(contains(e.what(), message));
  };
  refused(model("truncated.ifc"), "truncated");
  refused(model("self_placement.ifc"), guid_of(model("self_placement.ifc"), "Only wall") +
                                           " 'Only wall': its placement "
                                           "chain loops");
  refused(model("nan.ifc"), "the number 1.0E999 is not a finite number");
  refused(model("no_walls.ifc"), "no wall ccbuild can print");
  IfcOptions few;
  few.max_entities = 100;
  refused(model("house_ifc4.ifc"), "more than 100 entities", few);
  const fs::path dir = scratch("hostile");
  // A 50 MB model (sparse: nothing is written) is over the limit, said before reading it.
  const fs::path big = dir / "big.ifc";
  std::ofstream(big) << "ISO-10303-21;\n";
  fs::resize_file(big, 50'000'000);
  refused(big, "is 47.7 MiB; ccbuild reads IFC models of at most 32 MiB");
  // Not a STEP file, another schema, an IFC-ZIP.
  std::ofstream(dir / "plan.ifc") << "vertices:\n  - {id: 1, x: 0, y: 0}\n";
  refused(dir / "plan.ifc", "not an IFC model");
  std::string text = testing::slurp(model("house_ifc4.ifc"));
  text.replace(text.find("FILE_SCHEMA(('IFC4'))"), 21, "FILE_SCHEMA(('IFC4X3'))");
  std::ofstream(dir / "ifc4x3.ifc") << text;
  refused(dir / "ifc4x3.ifc", "schema IFC4X3: ccbuild reads IFC4 and IFC2X3");
  std::ofstream(dir / "zipped.ifc") << "PK\x03\x04";
  refused(dir / "zipped.ifc", "IFC-ZIP");
  refused(dir / "missing.ifc", "cannot open file");
  fs::remove_all(dir);
}

TEST(IfcImport, ThePublicDuplexModelImportsItsConcreteWallsAndLeavesTheStudWallsOut) {
  // buildingSMART's Duplex Apartment (Revit 2011, IFC2X3; CC BY 4.0): four storeys from the
  // foundation at -1.25 m to the roof's parapets.
  const fs::path file = model("public/Duplex_A_20110907.ifc");
  const IfcImport read = read_ifc_building(file);
  EXPECT_EQ(read.schema, "IFC2X3");
  const floors::Building& b = read.building;
  ASSERT_EQ(b.floors.size(), 4u);
  EXPECT_EQ(b.floors[0].name, "T/FDN");
  EXPECT_EQ(b.floors[1].name, "Level 1");
  // Walls under the slabs over them: the foundation walls up to the underside of the
  // lowest slab on grade of Level 1 (-0.137 m; without slabs 1.25 m), Level 1 under Level
  // 2's wood joist floor (0.305 m; 3.1 m storey to storey), Level 2 under the roof's slab,
  // whose underside is the roof storey's elevation.
  EXPECT_NEAR(b.floors[0].height_m, 1.113, 1e-6);
  EXPECT_NEAR(b.floors[1].height_m, 2.795, 1e-6);
  EXPECT_NEAR(b.floors[2].height_m, 2.9, 1e-6);
  EXPECT_NEAR(b.floors[1].base_elevation_m, 1.25, 1e-6);
  EXPECT_NEAR(b.floors[2].base_elevation_m, 4.35, 1e-6);
  int walls = 0, openings = 0;
  for (const auto& f : b.floors) {
    walls += static_cast<int>(f.plan.walls.size());
    openings += static_cast<int>(f.plan.openings.size());
    for (const auto& w : f.plan.walls) {
      EXPECT_FALSE(w.global_id.empty());
      EXPECT_GT(*w.thickness_m, 0.1);
      EXPECT_LT(*w.thickness_m, 0.6);
    }
  }
  EXPECT_EQ(walls, 23);
  EXPECT_EQ(openings, 26);
  const std::string notes = all(read.notes);
  EXPECT_TRUE(contains(notes,
                       "'Basic Wall:Interior - Partition (92mm Stud):138584': its "
                       "material 'Plasterboard'"));
  EXPECT_TRUE(contains(notes, "the lowest floor, 'T/FDN', stands at -1.250 m"));
  EXPECT_TRUE(contains(read.notes.back(), "left out: 34 elements"));
}

}  // namespace
}  // namespace ccbuild::import
