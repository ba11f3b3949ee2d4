// DXF drawings to floor plans (floors/import): walls from face pairs meeting at their L and T
// junctions, and from centrelines, in millimetres and metres; doors and windows from block
// inserts; what is left out said by handle; hostile drawings refused with file and line.
// The drawings are written by tests/tools/make_dxf.py, independently of dxflib.

#include "ccbuild/import/dxf.hpp"

#include <gtest/gtest.h>

#include <map>

#include "ccbuild/floors/plan.hpp"
#include "test_support.hpp"

namespace ccbuild::import {
namespace {
using Eigen::Vector2d;
using testing::contains;
using testing::expect_input_error;

std::filesystem::path drawing(const std::string& name) {
  return testing::source_path("tests/data/drawings/" + name);
}

DxfOptions faces_options() {
  DxfOptions o;
  o.wall_layers = {"a-wall"};  // layer names are matched whatever their case
  o.door_layers = {"A-DOOR"};
  o.window_layers = {"A-GLAZ"};
  return o;
}

/// How many walls end at each vertex, by position rounded to the millimetre.
std::map<std::pair<long, long>, int> degrees(const floors::FloorPlan& plan) {
  std::map<std::pair<long, long>, int> out;
  for (const auto& w : plan.walls)
    for (const Vector2d& p : {plan.wall_start_m(w), plan.wall_end_m(w)})
      ++out[{std::lround(p.x() * 1000), std::lround(p.y() * 1000)}];
  return out;
}

const floors::Opening* opening_of(const floors::FloorPlan& plan, char kind) {
  for (const auto& o : plan.openings)
    if (o.id[0] == kind) return &o;
  return nullptr;
}

TEST(DxfImport, FacePairsBecomeWallsThatMeetAtTheirJunctions) {
  const DxfPlan read = read_dxf_plan(drawing("faces_mm.dxf"), faces_options());
  EXPECT_DOUBLE_EQ(read.metres_per_unit, 0.001);  // $INSUNITS 4
  const floors::FloorPlan& plan = read.plan;
  // West, east, the wall between the rooms, and south and north cut in two by it.
  ASSERT_EQ(plan.walls.size(), 7u);
  for (const auto& w : plan.walls) {
    ASSERT_TRUE(w.thickness_m);
    EXPECT_NEAR(*w.thickness_m, 0.2, 1e-9);
    // Each middle line lies half a thickness inside the outline (0..6 x 0..4).
    for (const Vector2d& p : {plan.wall_start_m(w), plan.wall_end_m(w)}) {
      EXPECT_GE(p.x(), 0.1 - 1e-9);
      EXPECT_LE(p.x(), 5.9 + 1e-9);
      EXPECT_GE(p.y(), 0.1 - 1e-9);
      EXPECT_LE(p.y(), 3.9 + 1e-9);
    }
  }
  // Four L corners (two walls each) and two T junctions (three), nothing left dangling.
  const std::map<std::pair<long, long>, int> expected = {{{100, 100}, 2},   {{5900, 100}, 2},
                                                         {{5900, 3900}, 2}, {{100, 3900}, 2},
                                                         {{3000, 100}, 3},  {{3000, 3900}, 3}};
  EXPECT_EQ(degrees(plan), expected);
  EXPECT_NO_THROW(floors::validate_plan(plan, 3.0));
  // The door: 0.9 m along the wall between the rooms, 0.9 m from its south end.
  const floors::Opening* door = opening_of(plan, 'D');
  ASSERT_NE(door, nullptr);
  const floors::Wall& between = *plan.find_wall(door->wall_id);
  EXPECT_NEAR(plan.wall_start_m(between).x(), 3.0, 1e-9);
  EXPECT_NEAR(plan.wall_end_m(between).x(), 3.0, 1e-9);
  EXPECT_NEAR(door->width_m, 0.9, 1e-9);
  const double from_south = plan.wall_start_m(between).y() < plan.wall_end_m(between).y()
                                ? door->offset_m
                                : plan.wall_length_m(between) - door->offset_m - door->width_m;
  EXPECT_NEAR(from_south, 0.9, 1e-9);
  EXPECT_EQ(door->sill_m, 0.0);
  // The window: 1.2 m of the south wall from x = 3.8 m, at the default sill and head.
  const floors::Opening* window = opening_of(plan, 'W');
  ASSERT_NE(window, nullptr);
  EXPECT_NEAR(window->width_m, 1.2, 1e-9);
  EXPECT_DOUBLE_EQ(window->sill_m, 0.9);
  EXPECT_DOUBLE_EQ(window->head_m, 2.1);
  // The stray face line is said, by its handle, and left out.
  ASSERT_EQ(read.notes.size(), 1u);
  EXPECT_TRUE(contains(read.notes[0],
                       "on layer A-WALL: a face line from (0, -2000) to (1000, "
                       "-2000) with no parallel face"))
      << read.notes[0];
}

TEST(DxfImport, MillimetresAndMetresGiveTheSamePlan) {
  const DxfPlan mm = read_dxf_plan(drawing("faces_mm.dxf"), faces_options());
  const DxfPlan m = read_dxf_plan(drawing("faces_m.dxf"), faces_options());
  EXPECT_DOUBLE_EQ(m.metres_per_unit, 1.0);
  EXPECT_TRUE(floors::same_model(mm.plan, m.plan, 1e-9));
}

TEST(DxfImport, FacesPairUpToTheMaximumThicknessAndNoFurther) {
  DxfOptions o = faces_options();
  o.max_thickness_m = 0.2;  // exactly the walls' thickness: paired
  EXPECT_EQ(read_dxf_plan(drawing("faces_m.dxf"), o).plan.walls.size(), 7u);
  o.max_thickness_m = 0.199;
  const InputError none = expect_input_error([&] { read_dxf_plan(drawing("faces_m.dxf"), o); });
  EXPECT_EQ(none.first().field, "wall_layers");
  EXPECT_TRUE(contains(none.what(), "no wall found"));
}

TEST(DxfImport, CentrelinesAreWallsOfTheNozzlesWidth) {
  DxfOptions o;
  o.wall_layers = {"WALLS"};
  o.door_layers = {"DOORS"};
  o.wall_lines = DxfOptions::WallLines::kCentrelines;
  const DxfPlan read = read_dxf_plan(drawing("centrelines_m.dxf"), o);
  const floors::FloorPlan& plan = read.plan;
  ASSERT_EQ(plan.walls.size(), 5u);  // the closed polyline's four edges and the line
  for (const auto& w : plan.walls) EXPECT_FALSE(w.thickness_m);
  EXPECT_NO_THROW(floors::validate_plan(plan, 3.0));
  ASSERT_EQ(plan.openings.size(), 1u);
  EXPECT_NEAR(plan.openings[0].width_m, 0.9, 1e-9);
  EXPECT_TRUE(read.notes.empty());
  // A unit given overrides the drawing's: its metres read as centimetres.
  o.metres_per_unit = 0.01;
  const DxfPlan cm = read_dxf_plan(drawing("centrelines_m.dxf"), o);
  EXPECT_NEAR(cm.plan.wall_length_m(cm.plan.walls[0]), 0.058, 1e-12);
}

TEST(DxfImport, AttributedInsertsSetTheirOpeningsSillAndHead) {
  // ATTRIBs after an INSERT (66 = 1, up to its SEQEND) tagged SILL and HEAD, in any case:
  // a number in the drawing's unit, or with mm, cm or m. Without one, the floor's default
  // (a door's sill: 0).
  DxfOptions o;
  o.wall_layers = {"WALLS"};
  o.door_layers = {"DOORS"};
  o.window_layers = {"WINDOWS"};
  o.wall_lines = DxfOptions::WallLines::kCentrelines;
  o.door_head_m = 2.0;
  o.window_sill_m = 0.8;
  o.window_head_m = 1.9;
  const DxfPlan read = read_dxf_plan(drawing("attributes_m.dxf"), o);
  const auto& openings = read.plan.openings;
  ASSERT_EQ(openings.size(), 3u);
  const auto find = [&](const std::string& id) -> const floors::Opening& {
    for (const auto& op : openings)
      if (op.id == id) return op;
    ADD_FAILURE() << id;
    return openings.front();
  };
  const floors::Opening& door = find("D10F");  // head "2.3": metres, the drawing's unit
  EXPECT_NEAR(door.sill_m, 0.0, 1e-12);
  EXPECT_NEAR(door.head_m, 2.3, 1e-12);
  const floors::Opening& south = find("W112");  // SILL "1000mm", Head "2.2m"
  EXPECT_NEAR(south.sill_m, 1.0, 1e-12);
  EXPECT_NEAR(south.head_m, 2.2, 1e-12);
  EXPECT_NEAR(south.width_m, 1.2, 1e-9);
  const floors::Opening& north = find("W116");  // SILL 0.5; its head the floor's default
  EXPECT_NEAR(north.sill_m, 0.5, 1e-12);
  EXPECT_NEAR(north.head_m, 1.9, 1e-12);
  EXPECT_NO_THROW(floors::validate_plan(read.plan, 3.0));
  // A value that is not a number, or not a height above a floor (2100 in a drawing in
  // metres): refused, naming the insert's handle and the tag.
  const InputError text =
      expect_input_error([&] { read_dxf_plan(drawing("attribute_not_number.dxf"), o); });
  EXPECT_EQ(text.first().field, "entity 112");
  EXPECT_TRUE(contains(text.what(),
                       "its attribute SILL (ATTRIB 113) is 'about a metre', not a "
                       "number"))
      << text.what();
  const InputError range =
      expect_input_error([&] { read_dxf_plan(drawing("attribute_out_of_range.dxf"), o); });
  EXPECT_EQ(range.first().field, "entity 10F");
  EXPECT_TRUE(contains(range.what(),
                       "its attribute HEAD (ATTRIB 110) is '2100', 2100.000 m: "
                       "not a sill or head height"))
      << range.what();
  // A sill at or above the floor's default head: refused too.
  o.window_head_m = 0.5;
  const InputError order =
      expect_input_error([&] { read_dxf_plan(drawing("attributes_m.dxf"), o); });
  EXPECT_TRUE(contains(order.what(), "is not below its head")) << order.what();
}

TEST(DxfImport, HostileDrawingsAreRefusedWithTheirFileAndLine) {
  DxfOptions o;
  o.wall_layers = {"WALLS"};
  o.wall_lines = DxfOptions::WallLines::kCentrelines;
  const InputError nan = expect_input_error([&] { read_dxf_plan(drawing("nan.dxf"), o); });
  EXPECT_EQ(nan.first().field, "group 11");
  EXPECT_GT(nan.first().line, 0);
  EXPECT_TRUE(contains(nan.what(), "expected a finite number, got 'nan'"));
  const InputError cut = expect_input_error([&] { read_dxf_plan(drawing("truncated.dxf"), o); });
  EXPECT_TRUE(contains(cut.what(), "truncated?")) << cut.what();
  const InputError unitless =
      expect_input_error([&] { read_dxf_plan(drawing("unitless.dxf"), o); });
  EXPECT_EQ(unitless.first().field, "unit");
  o.metres_per_unit = 1.0;  // said by the user: read
  EXPECT_EQ(read_dxf_plan(drawing("unitless.dxf"), o).plan.walls.size(), 5u);
  o.wall_layers = {"A-WALLS"};
  const InputError layer =
      expect_input_error([&] { read_dxf_plan(drawing("centrelines_m.dxf"), o); });
  EXPECT_EQ(layer.first().field, "wall_layers");
  EXPECT_TRUE(contains(layer.what(), "its layers (entities): DOORS (1), WALLS (2)"))
      << layer.what();
  o.wall_layers = {};
  EXPECT_EQ(
      expect_input_error([&] { read_dxf_plan(drawing("centrelines_m.dxf"), o); }).first().field,
      "wall_layers");
  EXPECT_TRUE(contains(expect_input_error([&] { read_dxf_plan(drawing("binary.dxf"), o); }).what(),
                       "a binary DXF: save the drawing as an ASCII DXF"));
  // A text longer than dxflib's lines (it would loop forever) and trash after the EOF: read.
  o.wall_layers = {"WALLS"};
  EXPECT_EQ(read_dxf_plan(drawing("long_text.dxf"), o).plan.walls.size(), 5u);
  // Not a drawing at all.
  EXPECT_TRUE(contains(expect_input_error([&] {
                         read_dxf_plan(testing::source_path("config/buildings/house.yaml"), o);
                       }).what(),
                       "not a DXF drawing"));
}

TEST(DxfImport, PublicSampleDrawingsRead) {
  // tests/data/drawings/public/README.md says where they come from.
  DxfOptions o;
  o.wall_lines = DxfOptions::WallLines::kCentrelines;
  // CloudCompare's, through dxflib: an old-style POLYLINE (its VERTEX entities end at SEQEND).
  o.wall_layers = {"POLYLINE_001"};
  EXPECT_EQ(
      expect_input_error([&] { read_dxf_plan(drawing("public/cc_dxflib.dxf"), o); }).first().field,
      "unit");  // it says none
  o.metres_per_unit = 1.0;
  const DxfPlan quad = read_dxf_plan(drawing("public/cc_dxflib.dxf"), o);
  ASSERT_EQ(quad.plan.walls.size(), 4u);
  ASSERT_EQ(quad.plan.vertices.size(), 4u);  // its last vertex repeats its first
  for (const auto& [at, walls] : degrees(quad.plan)) EXPECT_EQ(walls, 2);
  EXPECT_NO_THROW(floors::validate_plan(quad.plan, 3.0));
  // Polylines with curved segments: the straight ones are walls, each curved one said.
  o.wall_layers = {"T-2DPLINE-ALL"};
  const DxfPlan curved = read_dxf_plan(drawing("public/POLI-ALL210_12.DXF"), o);
  EXPECT_EQ(curved.plan.walls.size(), 54u);
  ASSERT_EQ(curved.notes.size(), 31u);
  for (const auto& note : curved.notes) EXPECT_TRUE(contains(note, "a curved segment")) << note;
}

}  // namespace
}  // namespace ccbuild::import

namespace ccbuild::import {
namespace {

// Doors and windows left as gaps in the wall lines (with gap_openings): the walls on
// either side become one wall with an opening exactly in the gap, a window where a line
// on a window layer (glazing) lies in it, else a door; without gap_openings, walls.
TEST(DxfImport, GapsInWallLinesAreOpeningsWhenAsked) {
  for (const char* file : {"gaps_faces_mm.dxf", "gaps_m.dxf"}) {
    SCOPED_TRACE(file);
    DxfOptions o;
    if (std::string(file) == "gaps_m.dxf") o.wall_lines = DxfOptions::WallLines::kCentrelines;
    o.wall_layers = {std::string(file) == "gaps_m.dxf" ? "WALLS" : "A-WALL"};
    o.window_layers = {std::string(file) == "gaps_m.dxf" ? "GLAZING" : "A-GLAZ"};
    const std::size_t walls_without = read_dxf_plan(drawing(file), o).plan.walls.size();
    o.gap_openings = true;
    const DxfPlan read = read_dxf_plan(drawing(file), o);
    floors::validate_plan(read.plan, 3.0);
    EXPECT_EQ(read.plan.walls.size() + 2, walls_without);  // two gaps: two walls fewer
    ASSERT_EQ(read.plan.openings.size(), 2u);
    for (const auto& op : read.plan.openings) {
      const floors::Wall& w = *read.plan.find_wall(op.wall_id);
      const Vector2d a = read.plan.wall_start_m(w), b = read.plan.wall_end_m(w);
      const Vector2d d = (b - a).normalized();
      const Vector2d from = a + op.offset_m * d, to = a + (op.offset_m + op.width_m) * d;
      if (op.id[1] == 'W') {  // the south wall's window, x 3.8 to 5.0 at y 0.15
        EXPECT_NEAR(std::min(from.x(), to.x()), 3.8, 1e-9);
        EXPECT_NEAR(std::max(from.x(), to.x()), 5.0, 1e-9);
        EXPECT_NEAR(from.y(), 0.15, 1e-9);
        EXPECT_NEAR(op.sill_m, o.window_sill_m, 1e-12);
        EXPECT_TRUE(contains(op.source.path, "glazing")) << op.source.path;
      } else {  // the partition's door, y 1.0 to 1.9 at x 3
        EXPECT_EQ(op.id[1], 'D');
        EXPECT_NEAR(std::min(from.y(), to.y()), 1.0, 1e-9);
        EXPECT_NEAR(std::max(from.y(), to.y()), 1.9, 1e-9);
        EXPECT_NEAR(from.x(), 3.0, 1e-9);
        EXPECT_EQ(op.sill_m, 0.0);
        EXPECT_NEAR(op.head_m, o.door_head_m, 1e-12);
      }
    }
    // A gap wider than the largest asked for stays a gap.
    o.max_gap_m = 1.0;
    EXPECT_EQ(read_dxf_plan(drawing(file), o).plan.openings.size(), 1u);
  }
}

// Drawn as drafters draw it: the wall lines broken at the door and the window, jambs, and a
// door or window block inserted in each gap (AIA layers, millimetres). Each gap is its
// block's opening, of the block's kind and the gap's size, the walls either side joined
// into one; the window's heights from its SILL and HEAD attributes. With gap_openings too,
// a block and its gap are still one opening; a block on a wall drawn through is an opening
// of the block's width.
TEST(DxfImport, ABlockInAGapIsThatGapsOpening) {
  const auto all = [](const std::vector<std::string>& notes) {
    std::string text;
    for (const auto& note : notes) text += note + "\n";
    return text;
  };
  DxfOptions o;
  o.wall_layers = {"A-WALL"};
  o.door_layers = {"A-DOOR"};
  o.window_layers = {"A-GLAZ"};
  DxfOptions walls_only;
  walls_only.wall_layers = {"A-WALL"};
  const std::size_t broken = read_dxf_plan(drawing("drafted_mm.dxf"), walls_only).plan.walls.size();
  for (const bool every_gap : {false, true}) {
    SCOPED_TRACE(every_gap ? "gap_openings" : "blocks only");
    o.gap_openings = every_gap;
    const DxfPlan read = read_dxf_plan(drawing("drafted_mm.dxf"), o);
    floors::validate_plan(read.plan, 3.0);
    EXPECT_EQ(read.plan.walls.size() + 2, broken);  // two gaps joined: two walls fewer
    ASSERT_EQ(read.plan.openings.size(), 3u) << all(read.notes);
    int doors = 0, windows = 0;
    for (const auto& op : read.plan.openings) {
      const floors::Wall& w = *read.plan.find_wall(op.wall_id);
      const Vector2d a = read.plan.wall_start_m(w), b = read.plan.wall_end_m(w);
      const Vector2d d = (b - a).normalized();
      const Vector2d from = a + op.offset_m * d, to = a + (op.offset_m + op.width_m) * d;
      if (op.id[0] == 'D') {  // the partition's door, y 1.0 to 1.9 at x 3, in its gap
        ++doors;
        EXPECT_NEAR(std::min(from.y(), to.y()), 1.0, 1e-9);
        EXPECT_NEAR(std::max(from.y(), to.y()), 1.9, 1e-9);
        EXPECT_NEAR(from.x(), 3.0, 1e-9);
        EXPECT_EQ(op.sill_m, 0.0);
        EXPECT_NEAR(op.head_m, o.door_head_m, 1e-12);
        EXPECT_TRUE(contains(op.source.path, "of block DOOR900")) << op.source.path;
        EXPECT_TRUE(contains(op.source.path, "in the gap between")) << op.source.path;
      } else if (std::abs(from.y() - 0.15) < 1e-6) {  // the south window, x 3.8 to 5.0
        ++windows;
        EXPECT_EQ(op.id[0], 'W');
        EXPECT_NEAR(std::min(from.x(), to.x()), 3.8, 1e-9);
        EXPECT_NEAR(std::max(from.x(), to.x()), 5.0, 1e-9);
        EXPECT_NEAR(op.sill_m, 1.0, 1e-9);  // SILL 1000 in the drawing's millimetres
        EXPECT_NEAR(op.head_m, 2.2, 1e-9);
      } else {  // the north window on a wall drawn through: the block's width
        ++windows;
        EXPECT_EQ(op.id[0], 'W');
        EXPECT_NEAR(std::min(from.x(), to.x()), 1.0, 1e-9);
        EXPECT_NEAR(std::max(from.x(), to.x()), 2.2, 1e-9);
        EXPECT_NEAR(op.sill_m, o.window_sill_m, 1e-12);
      }
    }
    EXPECT_EQ(doors, 1);
    EXPECT_EQ(windows, 2);
  }
  // A gap wider than the largest asked for is not joined: its block lies on no wall.
  o.gap_openings = false;
  o.max_gap_m = 1.0;
  const DxfPlan narrow = read_dxf_plan(drawing("drafted_mm.dxf"), o);
  EXPECT_EQ(narrow.plan.walls.size() + 1, broken);
  EXPECT_EQ(narrow.plan.openings.size(), 2u);
  EXPECT_TRUE(contains(all(narrow.notes),
                       "of block WIN1200 on layer A-GLAZ: at (4.400, 0.150) m, on no wall"))
      << all(narrow.notes);
}

// A door or window layer's own sill and head (layer_heights, any case) stand in for the
// kind's defaults where a block has no SILL or HEAD attribute; its attributes still win. A
// layer that holds no doors or windows, or a sill that ends up at or over its head, is
// refused naming where each height came from.
TEST(DxfImport, ALayersOwnSillAndHeadStandInForTheDefaults) {
  DxfOptions o;
  o.wall_layers = {"A-WALL"};
  o.door_layers = {"A-DOOR"};
  o.window_layers = {"A-GLAZ"};
  o.layer_heights = {{"a-door", {std::nullopt, 2.4}}, {"A-Glaz", {1.2, std::nullopt}}};
  const DxfPlan read = read_dxf_plan(drawing("drafted_mm.dxf"), o);
  ASSERT_EQ(read.plan.openings.size(), 3u);
  int checked = 0;
  for (const auto& op : read.plan.openings) {
    SCOPED_TRACE(op.id + " " + op.source.path);
    if (op.id[0] == 'D') {  // the door block: the layer's head, a door's sill
      EXPECT_EQ(op.sill_m, 0.0);
      EXPECT_NEAR(op.head_m, 2.4, 1e-12);
      ++checked;
    } else if (contains(op.source.path, "in the gap")) {  // SILL 1000, HEAD 2200: they win
      EXPECT_NEAR(op.sill_m, 1.0, 1e-9);
      EXPECT_NEAR(op.head_m, 2.2, 1e-9);
      ++checked;
    } else {  // no attributes: the layer's sill, the windows' default head
      EXPECT_NEAR(op.sill_m, 1.2, 1e-12);
      EXPECT_NEAR(op.head_m, o.window_head_m, 1e-12);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 3);
  EXPECT_NO_THROW(floors::validate_plan(read.plan, 3.0));
  // A sill exactly at its head: refused, both sources named.
  o.layer_heights = {{"A-GLAZ", {o.window_head_m, std::nullopt}}};
  const InputError at_head =
      expect_input_error([&] { read_dxf_plan(drawing("drafted_mm.dxf"), o); });
  EXPECT_TRUE(contains(at_head.what(),
                       "its sill (2.100 m, layer A-GLAZ's) is not below its head (2.100 m, the "
                       "windows' default)"))
      << at_head.what();
  // Just below it: read.
  o.layer_heights = {{"A-GLAZ", {o.window_head_m - 1e-3, std::nullopt}}};
  EXPECT_NO_THROW(read_dxf_plan(drawing("drafted_mm.dxf"), o));
  o.layer_heights = {{"A-WALL", {0.5, std::nullopt}}};
  const InputError walls = expect_input_error([&] { read_dxf_plan(drawing("drafted_mm.dxf"), o); });
  EXPECT_EQ(walls.first().field, "layer_heights");
  EXPECT_TRUE(contains(walls.what(), "layer 'A-WALL' is not among the door or window layers"))
      << walls.what();
}

}  // namespace
}  // namespace ccbuild::import
