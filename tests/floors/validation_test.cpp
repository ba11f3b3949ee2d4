// Each broken fixture holds one mistake; the error must name the file, the line (or
// field) and say what was expected.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "ccbuild/floors/building.hpp"
#include "ccbuild/floors/plan.hpp"
#include "ccbuild/floors/slice.hpp"
#include "test_support.hpp"

namespace ccbuild::floors {
namespace {
using testing::contains;
using testing::data;
using testing::expect_input_error;

struct BrokenCase {
  const char* file;
  int line;             // expected line of the first diagnostic (0: not checked)
  const char* field;    // expected field path, "" when not checked
  const char* message;  // expected part of the message
};

class BrokenPlan : public ::testing::TestWithParam<BrokenCase> {};

TEST_P(BrokenPlan, IsRejectedWithLocatedMessage) {
  const BrokenCase c = GetParam();
  const std::string path = data(std::string("broken/") + c.file);
  const InputError e = expect_input_error([&] { load_plan(path); });
  const Diagnostic& d = e.first();
  EXPECT_EQ(d.file, path);
  if (c.line > 0) {
    EXPECT_EQ(d.line, c.line) << e.what();
  }
  if (*c.field) {
    EXPECT_EQ(d.field, c.field) << e.what();
  }
  EXPECT_TRUE(contains(e.what(), c.message));
}

INSTANTIATE_TEST_SUITE_P(
    Fixtures, BrokenPlan,
    ::testing::Values(
        BrokenCase{"unknown_vertex.yaml", 7, "walls[1].end", "end vertex 9 is not defined"},
        BrokenCase{"duplicate_vertex.txt", 4, "vertices.id",
                   "vertex id 2 is defined twice (first at line 3)"},
        BrokenCase{"duplicate_wall.json", 5, "walls[1].id",
                   "wall id 1 is defined twice (first at line 4)"},
        BrokenCase{"zero_length.yaml", 8, "walls[1]", "wall 2 has zero length"},
        BrokenCase{"nan_coordinate.txt", 3, "vertices: x", "expected a finite number, got 'nan'"},
        BrokenCase{"inf_coordinate.yaml", 3, "vertices[1].x",
                   "expected a finite number, got '.inf'"},
        BrokenCase{"non_numeric.json", 4, "vertices[1].x",
                   "expected a number, got the string \"four\""},
        BrokenCase{"non_numeric.txt", 3, "vertices: y", "expected a number, got 'zero'"},
        BrokenCase{"collinear_overlap.txt", 9, "walls",
                   "wall 2 overlaps wall 1 (line 8) along 5.000 m"},
        BrokenCase{
            "opening_off_wall.yaml", 7, "openings[0]",
            "opening 'W1' on wall 1 does not fit on its wall: offset 3.500 m + width 1.200 m"},
        BrokenCase{"opening_overlap.yaml", 8, "openings[1]",
                   "opening 'W2' on wall 1 overlaps opening 'W1' on wall 1 (line 7) by 0.200 m"},
        BrokenCase{"sill_above_head.yaml", 7, "openings[0].sill",
                   "sill (2.100 m) must be below head (0.900 m)"},
        BrokenCase{"no_walls.yaml", 0, "walls", "the plan has no walls"},
        BrokenCase{"unknown_key.yaml", 5, "walls[0].thicknes",
                   "unknown key 'thicknes'; did you mean 'thickness'?"},
        BrokenCase{"wrong_units.yaml", 1, "units", "expected 'm' or 'ft', got 'meters'"},
        BrokenCase{"bad_syntax.json", 4, "", "invalid JSON"},
        BrokenCase{"walls_before_vertices.txt", 1, "walls",
                   "must come after the 'vertices' section"}),
    [](const auto& info) {
      std::string name = info.param.file;
      for (char& ch : name)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return name;
    });

TEST(Validation, ReportsEveryProblemNotJustTheFirst) {
  FloorPlan plan = load_plan(data("plans/cottage.yaml"));
  plan.walls.push_back(plan.walls.front());        // duplicate id 1
  plan.openings.push_back(plan.openings.front());  // overlaps itself
  plan.openings.back().sill_m = 3.0;               // and sill above head
  const InputError e = expect_input_error([&] { validate_plan(plan); });
  EXPECT_GE(e.diagnostics().size(), 2u) << e.what();
  EXPECT_TRUE(contains(e.what(), "wall id 1 is defined twice"));
  EXPECT_TRUE(contains(e.what(), "must be below head"));
}

TEST(Validation, OpeningsStackedVerticallyOnOneStretchAreFine) {
  FloorPlan plan = load_plan(data("plans/cottage.yaml"));
  Opening transom = plan.openings[0];  // above the door on wall 7
  transom.sill_m = 2.3;
  transom.head_m = 2.6;
  plan.openings.push_back(transom);
  EXPECT_NO_THROW(validate_plan(plan));
}

TEST(Validation, NegativeSillAndZeroWidthAreRejected) {
  FloorPlan plan = load_plan(data("plans/cottage.yaml"));
  plan.openings[0].sill_m = -0.1;
  plan.openings[1].width_m = 0.0;
  const InputError e = expect_input_error([&] { validate_plan(plan); });
  EXPECT_TRUE(contains(e.what(), "sill height must be zero or more"));
  EXPECT_TRUE(contains(e.what(), "width must be positive"));
}

struct BrokenBuilding {
  const char* file;
  int line;
  const char* field;
  const char* message;
};

class BrokenBuildingFile : public ::testing::TestWithParam<BrokenBuilding> {};

TEST_P(BrokenBuildingFile, IsRejectedWithLocatedMessage) {
  const BrokenBuilding c = GetParam();
  const std::string path = data(std::string("buildings/") + c.file);
  const InputError e = expect_input_error([&] { load_building(path); });
  EXPECT_EQ(e.first().file, path) << e.what();
  EXPECT_EQ(e.first().line, c.line) << e.what();
  EXPECT_EQ(e.first().field, c.field) << e.what();
  EXPECT_TRUE(contains(e.what(), c.message));
}

INSTANTIATE_TEST_SUITE_P(
    Fixtures, BrokenBuildingFile,
    ::testing::Values(
        BrokenBuilding{"negative_height.yaml", 7, "floors[0].height",
                       "must be more than 0 and at most 100 m, got -3 m"},
        BrokenBuilding{"zero_layer_height.yaml", 2, "layer_height",
                       "must be from 0.001 to 1 m, got 0 m"},
        BrokenBuilding{"wrong_units.yaml", 1, "units", "expected 'm' or 'ft', got 'feet'"},
        BrokenBuilding{"missing_plan.yaml", 6, "floors[0].plan",
                       "plan file 'plans/nowhere.yaml' not found"},
        BrokenBuilding{"typo_floor_key.yaml", 6, "floors[0].hieght", "did you mean 'height'?"},
        BrokenBuilding{"anchor_in_opening.yaml", 10, "floors[0].anchors[0].offset",
                       "anchor 'A1' at 2.000 m on wall 3 lies inside an opening"}),
    [](const auto& info) {
      std::string name = info.param.file;
      for (char& ch : name)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return name;
    });

TEST(Validation, OpeningAboveTheFloorIsNamedInThePlanFile) {
  const InputError e =
      expect_input_error([] { load_building(data("buildings/head_above_floor.yaml")); });
  // The opening is written in the plan file; the floor that is too low is named too.
  EXPECT_TRUE(contains(e.first().file, "plans/cottage.yaml"));
  EXPECT_EQ(e.first().line, 20);
  EXPECT_TRUE(contains(e.what(), "floor 'low'"));
  EXPECT_TRUE(contains(e.what(), "is above the floor height (2.000 m)"));
}

}  // namespace
}  // namespace ccbuild::floors

namespace ccbuild::floors {
namespace {
using testing::contains;
using testing::expect_input_error;

// A plan of one 6 m wall along x, with one opening, in metres.
FloorPlan one_wall(double offset, double width, double sill, double head) {
  FloorPlan plan;
  plan.vertices = {{1, {0.0, 0.0}, {}}, {2, {6.0, 0.0}, {}}};
  plan.walls = {{1, 1, 2, std::nullopt, {}}};
  plan.openings = {{"W", 1, offset, width, sill, head, {}}};
  return plan;
}

TEST(Boundaries, OpeningsAtTheirLimits) {
  // Exactly as long as the wall from its offset: fits.
  EXPECT_NO_THROW(validate_plan(one_wall(5.0, 1.0, 0.9, 2.1), 3.0));
  // A millimetre more does not.
  EXPECT_TRUE(
      contains(expect_input_error([] { validate_plan(one_wall(5.001, 1.0, 0.9, 2.1)); }).what(),
               "does not fit on its wall"));
  // Sill equal to head is an opening of no height: refused, as is sill above head.
  EXPECT_TRUE(
      contains(expect_input_error([] { validate_plan(one_wall(1.0, 1.0, 1.2, 1.2)); }).what(),
               "sill (1.200 m) must be below head (1.200 m)"));
  EXPECT_NO_THROW(validate_plan(one_wall(1.0, 1.0, 1.2, 1.2 + 1e-3)));
  // Head exactly at the floor height fits under it; above does not.
  EXPECT_NO_THROW(validate_plan(one_wall(1.0, 1.0, 0.0, 3.0), 3.0));
  EXPECT_TRUE(contains(
      expect_input_error([] { validate_plan(one_wall(1.0, 1.0, 0.0, 3.001), 3.0); }).what(),
      "is above the floor height"));
}

TEST(Boundaries, RangesIncludeTheirEndsAndNoMore) {
  const FloorPlan plan = one_wall(1.0, 1.0, 0.9, 2.1);
  // Layer heights from 1 mm to 1 m, floors above 0 up to 100 m.
  EXPECT_NO_THROW(building_from_plan(plan, "p", 3.0, 0.001));
  EXPECT_NO_THROW(building_from_plan(plan, "p", 3.0, 1.0));
  const InputError thin = expect_input_error([&] { building_from_plan(plan, "p", 3.0, 0.000999); });
  EXPECT_EQ(thin.first().field, "layer_height");
  EXPECT_TRUE(contains(thin.what(), "must be from 0.001 to 1 m, got 0.000999 m"));
  EXPECT_EQ(expect_input_error([&] { building_from_plan(plan, "p", 3.0, 1.0001); }).first().field,
            "layer_height");
  EXPECT_NO_THROW(building_from_plan(plan, "p", 100.0, 1.0));
  EXPECT_EQ(expect_input_error([&] { building_from_plan(plan, "p", 100.001, 1.0); }).first().field,
            "floor_height");
  // A feet plan hears its ranges in feet.
  FloorPlan feet = plan;
  feet.units = LengthUnit::kFoot;
  EXPECT_TRUE(contains(expect_input_error([&] { building_from_plan(feet, "p", 3.0, 1e-4); }).what(),
                       "must be from 0.003281 to 3.28084 ft, got 0.000328 ft"));
  // The layer budget: 100,000 layers are planned, one more is refused.
  EXPECT_NO_THROW(building_from_plan(plan, "p", 100.0, 0.001));  // exactly 100,000 layers
  const auto dir =
      std::filesystem::temp_directory_path() / ("ccbuild_budget_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  auto building = [&](double second_floor_m) {
    const std::string config = testing::source_path("config").string();
    std::ofstream(dir / "b.yaml") << "units: m\nlayer_height: 0.001\nmaterial: " << config
                                  << "/materials/standard-mix.yaml\nmachine: " << config
                                  << "/machines/cc-gantry.yaml\nfloors:\n  - {height: 50, plan: "
                                  << testing::data("plans/cottage.yaml")
                                  << "}\n  - {height: " << second_floor_m
                                  << ", plan: " << testing::data("plans/cottage.yaml") << "}\n";
    return (dir / "b.yaml").string();
  };
  EXPECT_NO_THROW(load_building(building(50.0)));
  const InputError over = expect_input_error([&] { load_building(building(50.001)); });
  EXPECT_TRUE(contains(over.what(), "100001 layers of 0.001 m make this building")) << over.what();
  EXPECT_EQ(over.first().field, "layer_height");
  EXPECT_EQ(over.first().line, 2);
  std::filesystem::remove_all(dir);
}

TEST(Boundaries, CoordinatesAndIdsAtTheirLimits) {
  auto table = [](const std::string& x, const std::string& id) {
    return "vertices\n" + id + " 0 0\n2 " + x + " 0\nwalls\n1 " + id + " 2\n";
  };
  EXPECT_NO_THROW(validate_plan(parse_plan_table(table("100000", "1"), "t", LengthUnit::kMeter)));
  EXPECT_TRUE(contains(expect_input_error([&] {
                         parse_plan_table(table("100000.001", "1"), "t", LengthUnit::kMeter);
                       }).what(),
                       "must be from -100000 to 100000 m, got 100000.001 m"));
  EXPECT_NO_THROW(parse_plan_table(table("5", "999999999"), "t", LengthUnit::kMeter));
  EXPECT_TRUE(contains(expect_input_error([&] {
                         parse_plan_table(table("5", "1000000000"), "t", LengthUnit::kMeter);
                       }).what(),
                       "ids are 1 to 999999999"));
  EXPECT_TRUE(contains(expect_input_error([&] {
                         parse_plan_table(table("5", "0"), "t", LengthUnit::kMeter);
                       }).what(),
                       "expected a positive integer id, got '0'"));
}

TEST(Boundaries, AWallMustBeLongerThanALayerResolves) {
  // Exactly 1 mm would vanish from every layer (points that close are one); a hair more
  // is a wall of its layer.
  auto one_wall = [](const std::string& x) {
    return parse_plan_table("vertices\n1 0 0\n2 " + x + " 0\nwalls\n1 1 2\n", "t",
                            LengthUnit::kMeter);
  };
  EXPECT_TRUE(contains(expect_input_error([&] { validate_plan(one_wall("0.001")); }).what(),
                       "wall 1 is 0.001 m long; walls must be longer than 0.001 m"));
  const FloorPlan kept = one_wall("0.0011");
  EXPECT_NO_THROW(validate_plan(kept));
  EXPECT_EQ(plan_as_layer(kept).segments.size(), 1u);
}

}  // namespace
}  // namespace ccbuild::floors

namespace ccbuild::floors {
namespace {

TEST(Boundaries, AnchorsFromOneEndOfTheirWallToTheOther) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("ccbuild_anchor_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  auto building = [&](const std::string& offset) {
    const std::string config = testing::source_path("config").string();
    std::ofstream(dir / "b.yaml")
        << "units: m\nlayer_height: 0.5\nmaterial: " << config
        << "/materials/standard-mix.yaml\nmachine: " << config
        << "/machines/cc-gantry.yaml\nfloors:\n  - height: 3\n    plan:\n      vertices: [{id: 1, "
           "x: 0, y: 0}, {id: 2, x: 6, y: 0}]\n      walls: [{id: 1, start: 1, end: 2}]\n    "
           "anchors: [{id: A1, wall: 1, offset: "
        << offset << "}]\n";
    return (dir / "b.yaml").string();
  };
  EXPECT_NO_THROW(load_building(building("0")));
  EXPECT_NO_THROW(load_building(building("6")));  // at the wall's end vertex
  const InputError past = testing::expect_input_error([&] { load_building(building("6.001")); });
  EXPECT_TRUE(testing::contains(past.what(), "offset 6.001 m is off wall 1 (length 6.000 m)"));
  EXPECT_EQ(past.first().field, "floors[0].anchors[0].offset");
  EXPECT_TRUE(testing::contains(
      testing::expect_input_error([&] { load_building(building("-0.001")); }).what(),
      "must be from 0 to 200000 m"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace ccbuild::floors
