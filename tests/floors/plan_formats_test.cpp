// The three plan encodings load into the same model, lengths convert to metres, and the
// bundled examples load.

#include <gtest/gtest.h>

#include <fstream>

#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/building.hpp"
#include "ccbuild/floors/plan.hpp"
#include "test_support.hpp"

namespace ccbuild::floors {
namespace {
using testing::data;

TEST(PlanFormats, ThreeEncodingsGiveTheSameModel) {
  const FloorPlan yaml = load_plan(data("plans/cottage.yaml"));
  const FloorPlan json = load_plan(data("plans/cottage.json"));
  const FloorPlan table = load_plan(data("plans/cottage.txt"));
  ASSERT_EQ(yaml.walls.size(), 7u);
  ASSERT_EQ(yaml.openings.size(), 2u);
  EXPECT_TRUE(same_model(yaml, json));
  EXPECT_TRUE(same_model(yaml, table));
  // And the comparison is not vacuous: change one coordinate and they differ.
  FloorPlan moved = table;
  moved.vertices[2].position_m.x() += 0.01;
  EXPECT_FALSE(same_model(yaml, moved));
}

TEST(PlanFormats, DetectsTheTableFormatWhateverTheExtension) {
  EXPECT_EQ(detect_plan_format("plan.txt", "# c\n\nvertices\n1 0 0\n"), PlanFormat::kTable);
  EXPECT_EQ(detect_plan_format("plan", "vertices:\n  - {id: 1, x: 0, y: 0}\n"), PlanFormat::kYaml);
  EXPECT_EQ(detect_plan_format("plan.json", "{}"), PlanFormat::kJson);
}

TEST(PlanFormats, FeetConvertToMetres) {
  const FloorPlan plan = load_plan(data("plans/cottage_ft.yaml"));
  EXPECT_NEAR(plan.wall_length_m(plan.walls[0]), 3.048, 1e-12);
  // A table file has no units key: its lengths are in the unit the caller says.
  const FloorPlan feet = load_plan(data("plans/paper_example1.txt"), LengthUnit::kFoot);
  EXPECT_NEAR(feet.wall_length_m(feet.walls[0]), 20 * 0.3048, 1e-12);
}

// A plan of one 6 m wall whose other keys are `keys` ("top: 0.7"), in `units`, validated.
FloorPlan plan_with_wall(const std::string& units, const std::string& keys) {
  const auto file = testing::scratch_dir("plan_formats", "wall") / "p.yaml";
  std::ofstream(file) << "units: " << units
                      << "\nvertices:\n  - {id: 1, x: 0, y: 0}\n  - {id: 2, x: 6, y: 0}\n"
                         "walls:\n  - {id: 1, start: 1, end: 2, "
                      << keys << "}\n";
  try {
    FloorPlan plan = load_plan(file);
    validate_plan(plan, 100.0);
    std::filesystem::remove_all(file.parent_path());
    return plan;
  } catch (...) {
    std::filesystem::remove_all(file.parent_path());
    throw;
  }
}

// A wall's `top:` is a height or [offset, height] points, in the plan's unit; offsets
// increase and stay on the wall; a height must be positive.
TEST(PlanFormats, AWallsTopIsAHeightOrPointsAlongIt) {
  using Top = std::vector<std::pair<double, double>>;
  EXPECT_EQ(plan_with_wall("m", "top: 0.7").walls[0].top_m, (Top{{0.0, 0.7}}));
  EXPECT_EQ(plan_with_wall("m", "top: [[0, 2.2], [3, 4.5], [6, 2.2]]").walls[0].top_m,
            (Top{{0.0, 2.2}, {3.0, 4.5}, {6.0, 2.2}}));
  const Top feet = plan_with_wall("ft", "top: 10").walls[0].top_m;
  ASSERT_EQ(feet.size(), 1u);
  EXPECT_NEAR(feet[0].second, 3.048, 1e-12);
  for (const char* bad : {"0", "-1", "[]", "[[0, 1], [0, 2]]", "[[3, 1], [1, 2]]", "[[0, 1, 2]]",
                          "[1, 2]", "[[0, 1], [7, 2]]", "x"}) {
    const InputError e =
        testing::expect_input_error([&] { plan_with_wall("m", std::string("top: ") + bad); });
    EXPECT_TRUE(testing::contains(e.what(), "top")) << bad << ": " << e.what();
  }
}

// `model_volume:` is in the plan's unit cubed, and a volume no wall has is refused, named.
TEST(PlanFormats, AModelVolumeIsInThePlansUnitCubedAndItsRangeIsChecked) {
  const FloorPlan feet = plan_with_wall("ft", "model_volume: 100");
  ASSERT_TRUE(feet.walls[0].model_volume_m3);
  EXPECT_NEAR(*feet.walls[0].model_volume_m3, 100 * 0.3048 * 0.3048 * 0.3048, 1e-12);
  EXPECT_NEAR(*plan_with_wall("m", "model_volume: 2.5").walls[0].model_volume_m3, 2.5, 1e-15);
  for (const char* bad : {"0", "-1", "2e6", "x"}) {
    const InputError e = testing::expect_input_error(
        [&] { plan_with_wall("m", std::string("model_volume: ") + bad); });
    EXPECT_TRUE(testing::contains(e.what(), "model_volume")) << bad << ": " << e.what();
  }
}

TEST(PlanFormats, PaperExampleLoadsAsWritten) {
  const FloorPlan plan = load_plan(data("plans/paper_example1.txt"));
  ASSERT_EQ(plan.vertices.size(), 8u);
  ASSERT_EQ(plan.walls.size(), 7u);
  EXPECT_EQ(plan.walls[4].start_vertex, 1);
  EXPECT_EQ(plan.walls[4].end_vertex, 7);
  EXPECT_DOUBLE_EQ(plan.wall_length_m(plan.walls[4]), 50.0);
}

TEST(PlanFormats, UnitsParseWithSuffixes) {
  EXPECT_NEAR(*parse_length_m("40ft", LengthUnit::kMeter), 12.192, 1e-12);
  EXPECT_NEAR(*parse_length_m("2.5 ft", LengthUnit::kMeter), 0.762, 1e-12);
  EXPECT_NEAR(*parse_length_m("3", LengthUnit::kFoot), 0.9144, 1e-12);
  EXPECT_NEAR(*parse_length_m("12m", LengthUnit::kFoot), 12.0, 1e-12);
  EXPECT_FALSE(parse_length_m("ten ft", LengthUnit::kMeter));
  EXPECT_FALSE(parse_length_m("nan", LengthUnit::kMeter));
}

// A feet building's small lengths in inches, its concrete in cubic yards; at the
// boundaries where the decimals change.
TEST(PlanFormats, FineLengthsAndVolumesSpeakTheBuildingsUnit) {
  EXPECT_EQ(fine_length_text(0.024, LengthUnit::kMeter), "24 mm");
  EXPECT_EQ(fine_length_text(0.01, LengthUnit::kMeter), "10 mm");     // whole from 10 mm
  EXPECT_EQ(fine_length_text(0.0099, LengthUnit::kMeter), "9.9 mm");  // a decimal under it
  EXPECT_EQ(fine_length_text(0.0003, LengthUnit::kMeter), "0.3 mm");
  EXPECT_EQ(fine_length_text(0.0254, LengthUnit::kFoot), "1.0 in");   // one decimal from 1 in
  EXPECT_EQ(fine_length_text(0.0253, LengthUnit::kFoot), "1.00 in");  // 0.996 in: two under it
  EXPECT_EQ(fine_length_text(0.024, LengthUnit::kFoot), "0.94 in");
  EXPECT_EQ(fine_length_text(0.05, LengthUnit::kFoot), "2.0 in");
  EXPECT_EQ(volume_text(8.0, LengthUnit::kMeter), "8.00 m³");
  EXPECT_EQ(volume_text(kCubicMetersPerCubicYard, LengthUnit::kFoot), "1.00 yd³");
  EXPECT_EQ(volume_text(8.0, LengthUnit::kFoot), "10.46 yd³");
  EXPECT_NEAR(volume_in(0.9144 * 0.9144 * 0.9144, LengthUnit::kFoot), 1.0, 1e-12);  // a yard cubed
  EXPECT_EQ(volume_unit(LengthUnit::kFoot), "yd³");
  EXPECT_EQ(speed_text(0.3048, LengthUnit::kFoot), "1.000 ft/s");
  EXPECT_EQ(speed_text(0.1, LengthUnit::kMeter), "0.100 m/s");
  EXPECT_DOUBLE_EQ(length_in(3.048, LengthUnit::kFoot), 10.0);
}

TEST(PlanFormats, BundledExampleBuildingsLoad) {
  const Building house = load_building(testing::source_path("config/buildings/house.yaml"));
  ASSERT_EQ(house.floors.size(), 2u);
  for (const auto& f : house.floors) {
    EXPECT_GE(f.plan.walls.size(), 35u);
    EXPECT_LE(f.plan.walls.size(), 50u);
    EXPECT_DOUBLE_EQ(f.height_m, 3.0);
  }
  const Building block = load_building(testing::source_path("config/buildings/apartment.yaml"));
  ASSERT_EQ(block.floors.size(), 5u);
  EXPECT_EQ(block.units, LengthUnit::kFoot);
  EXPECT_GE(block.floors[0].plan.walls.size(), 180u);
  // The top storeys have the smaller footprint.
  auto extent_x = [](const Floor& f) {
    double max_x = 0.0;
    for (const auto& v : f.plan.vertices) max_x = std::max(max_x, v.position_m.x());
    return max_x;
  };
  EXPECT_LT(extent_x(block.floors[4]), extent_x(block.floors[0]));
  EXPECT_NEAR(block.floors[1].base_elevation_m, 10 * 0.3048, 1e-9);
}

}  // namespace
}  // namespace ccbuild::floors
