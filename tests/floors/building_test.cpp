#include "ccbuild/floors/building.hpp"

#include <gtest/gtest.h>

#include "ccbuild/floors/material.hpp"
#include "ccbuild/floors/slice.hpp"
#include "test_support.hpp"

namespace ccbuild::floors {
namespace {
using testing::data;

TEST(Building, FloorsStackAndKeepTheirOwnOpenings) {
  const Building b = load_building(data("buildings/cottage.yaml"));
  ASSERT_EQ(b.floors.size(), 2u);
  EXPECT_DOUBLE_EQ(b.floors[1].base_elevation_m, 3.0);
  EXPECT_EQ(b.floors[0].plan.openings.size(), 2u);
  EXPECT_EQ(b.floors[1].plan.openings.size(), 3u);  // the plan's two plus W9
  EXPECT_EQ(b.floors[1].plan.openings.back().id, "W9");
  ASSERT_EQ(b.floors[0].anchors.size(), 1u);
  EXPECT_EQ(b.floors[0].anchors[0].id, "A1");
  EXPECT_TRUE(b.material_profile.filename() == "standard-mix.yaml");
  const auto upper = slice_floor(b.floors[1], b.layer_height_m);
  ASSERT_EQ(upper.size(), 5u);
  EXPECT_DOUBLE_EQ(upper[0].z_bottom_m, 3.0);
}

TEST(Building, OneReadTellsBuildingsFromPlans) {
  const BuildingOrPlan building =
      load_building_or_plan(data("buildings/cottage.yaml"), LengthUnit::kMeter);
  EXPECT_TRUE(building.is_building);
  ASSERT_EQ(building.building.floors.size(), 2u);
  // The building file and the plan it names (read once, though two floors use it).
  ASSERT_EQ(building.building.files_read.size(), 2u);
  EXPECT_EQ(building.building.files_read[1].filename(), "cottage.yaml");
  for (const char* file : {"plans/cottage.yaml", "plans/cottage.json", "plans/cottage.txt"}) {
    const BuildingOrPlan plan = load_building_or_plan(data(file), LengthUnit::kFoot);
    EXPECT_FALSE(plan.is_building) << file;
    EXPECT_EQ(plan.plan.walls.size(), 7u) << file;
  }
  // The table text has no units key: the caller's unit holds.
  EXPECT_EQ(load_building_or_plan(data("plans/cottage.txt"), LengthUnit::kFoot).plan.units,
            LengthUnit::kFoot);
}

TEST(Material, StandardMixLoadsAndInterpolates) {
  const MaterialProfile m =
      load_material_profile(testing::source_path("config/materials/standard-mix.yaml"));
  EXPECT_LT(m.min_layer_interval_s, m.max_layer_interval_s);
  EXPECT_DOUBLE_EQ(m.strength_at_mpa(0.0), 0.005);
  EXPECT_NEAR(m.strength_at_mpa(7.5 * 60), 0.0125, 1e-12);  // half way to 15 min
  EXPECT_DOUBLE_EQ(m.strength_at_mpa(1e9), 20.0);
}

}  // namespace
}  // namespace ccbuild::floors
