#include "ccbuild/floors/building.hpp"

#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>

#include <filesystem>
#include <fstream>

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
  ASSERT_TRUE(m.en1992.has_value());
  // The tests govern up to the last one (7 d, 20 MPa): 6.0 MPa at one day, where EN
  // 1992-1-1's estimate for fcm 43 MPa, class R, would say 18.2.
  const double day_s = 86400.0, week_s = 7 * day_s;
  EXPECT_NEAR(m.strength_at_mpa(day_s), 6.0, 1e-12);
  EXPECT_NEAR(m.en1992->strength_at_mpa(day_s), 18.2, 0.05);
  EXPECT_NEAR(m.strength_at_mpa(5.9 * 3600.0), 0.4 + (2.5 - 0.4) * (5.9 * 60 - 180) / 540, 1e-9);
  // 10 MPa, the anchors' strength: between the tests at 1 d (6) and 7 d (20), 65.1 h.
  const double ten_s = day_s + (10.0 - 6.0) / (20.0 - 6.0) * 6 * day_s;
  EXPECT_NEAR(m.age_for_strength_s(10.0), ten_s, 1e-6);
  EXPECT_NEAR(ten_s / 3600.0, 65.14, 0.01);
  EXPECT_NEAR(m.strength_at_mpa(ten_s), 10.0, 1e-9);
  // Both sides of the last test: continuous, 20 MPa.
  EXPECT_NEAR(m.strength_at_mpa(week_s - 1.0), 20.0 - 14.0 / (6 * day_s), 1e-9);
  EXPECT_NEAR(m.strength_at_mpa(week_s), 20.0, 1e-9);
  EXPECT_NEAR(m.age_for_strength_s(20.0), week_s, 1e-6);
  // Past it, the smaller estimate: the class's development through the last test,
  // 20 beta(t) / beta(7 d), under the stated fcm's 43 beta(t).
  const auto beta = [](double age_s) {
    return std::exp(0.2 * (1 - std::sqrt(28 * 86400.0 / age_s)));
  };
  EXPECT_NEAR(m.strength_at_mpa(28 * day_s), 20.0 / beta(week_s), 1e-9);  // 24.4 MPa
  EXPECT_LT(m.strength_at_mpa(28 * day_s), 43.0);
  EXPECT_NEAR(m.age_for_strength_s(20.0 / beta(week_s)), 28 * day_s, 1e-3);
  const double later_mpa = 22.0, later_s = m.age_for_strength_s(later_mpa);
  EXPECT_GT(later_s, week_s);
  EXPECT_NEAR(m.strength_at_mpa(later_s), later_mpa, 1e-9);
  EXPECT_NEAR(m.final_strength_mpa(), 20.0 * std::exp(0.2) / beta(week_s), 1e-9);
  EXPECT_TRUE(std::isinf(m.age_for_strength_s(m.final_strength_mpa() + 0.01)));
  // A stated curve under the last test never lowers it; where it is the smaller
  // estimate, it governs.
  MaterialProfile weak = m;
  weak.en1992->fcm_mpa = 22.0;  // 18.0 MPa at 7 d, 19.2 at 10 d, 22 at 28 d
  EXPECT_NEAR(weak.strength_at_mpa(week_s), 20.0, 1e-9);
  EXPECT_NEAR(weak.strength_at_mpa(10 * day_s), 20.0, 1e-9);
  EXPECT_NEAR(weak.strength_at_mpa(28 * day_s), 22.0, 1e-9);
  EXPECT_NEAR(weak.strength_at_mpa(90 * day_s), 22.0 * beta(90 * day_s), 1e-9);
  weak.en1992->fcm_mpa = 20.0;  // equal to the last test at 28 d
  EXPECT_NEAR(weak.strength_at_mpa(28 * day_s), 20.0, 1e-9);
  EXPECT_NEAR(weak.age_for_strength_s(20.0), week_s, 1e-6);  // the test reaches it first
}

std::filesystem::path scratch() {
  const auto dir =
      std::filesystem::temp_directory_path() / ("ccbuild_floors_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(Material, SafetyFactorDefaultsAndKeepsItsRange) {
  const auto dir = scratch();
  auto with = [&](const std::string& extra) {
    std::ofstream(dir / "m.yaml") << "name: m\ndensity_kg_m3: 2200\nmin_layer_interval_s: 1\n"
                                     "max_layer_interval_s: 2\nstrength_curve:\n"
                                     "  - {age_min: 0, strength_mpa: 1}\n"
                                     "  - {age_min: 1, strength_mpa: 2}\n"
                                  << extra;
    return load_material_profile(dir / "m.yaml");
  };
  EXPECT_DOUBLE_EQ(with("").safety_factor, 1.5);
  EXPECT_DOUBLE_EQ(with("safety_factor: 1\n").safety_factor, 1.0);
  EXPECT_DOUBLE_EQ(with("safety_factor: 10\n").safety_factor, 10.0);
  const InputError low = testing::expect_input_error([&] { with("safety_factor: 0.99\n"); });
  EXPECT_EQ(low.first().field, "safety_factor");
  EXPECT_EQ(low.first().line, 8);
  EXPECT_EQ(testing::expect_input_error([&] { with("safety_factor: 10.01\n"); }).first().field,
            "safety_factor");
  std::filesystem::remove_all(dir);
}

TEST(Material, APlacingRangeMustSpanMoreThanOneTemperature) {
  const auto dir = scratch();
  auto with = [&](const std::string& range) {
    std::ofstream(dir / "m.yaml") << "name: m\ndensity_kg_m3: 2200\nmin_layer_interval_s: 1\n"
                                     "max_layer_interval_s: 2\nstrength_curve:\n"
                                     "  - {age_min: 0, strength_mpa: 1}\n"
                                     "  - {age_min: 1, strength_mpa: 2}\n"
                                  << "placing_temperature_c: " << range << "\n";
    return load_material_profile(dir / "m.yaml");
  };
  const MaterialProfile tenth = with("[5, 5.1]");  // a tenth of a degree wide: a range
  EXPECT_DOUBLE_EQ(tenth.placing_min_c, 5.0);
  EXPECT_DOUBLE_EQ(tenth.placing_max_c, 5.1);
  for (const std::string range : {"[5, 5]", "[5, 4.9]"}) {
    const InputError e = testing::expect_input_error([&] { with(range); });
    EXPECT_EQ(e.first().field, "placing_temperature_c[1]") << range << ": " << e.what();
    EXPECT_TRUE(testing::contains(e.what(), "must be above the minimum")) << e.what();
  }
  std::filesystem::remove_all(dir);
}

TEST(Building, SlabStageInHoursWithItsDefault) {
  const Building house = load_building(testing::source_path("config/buildings/house.yaml"));
  EXPECT_DOUBLE_EQ(house.slab_stage_s, 8 * 3600.0);
  EXPECT_FALSE(house.slabs);
  // The tower's slabs are formed, poured and cured (`slabs:`); each floor stands on one.
  const Building tower = load_building(testing::source_path("config/buildings/tower.yaml"));
  ASSERT_TRUE(tower.slabs);
  EXPECT_DOUBLE_EQ(tower.slabs->setup_s, 8 * 3600.0);
  EXPECT_DOUBLE_EQ(tower.slabs->pour_rate_m3_s, 30.0 / 3600.0);
  EXPECT_DOUBLE_EQ(tower.slabs->concrete.s, 0.25);
  EXPECT_NEAR(tower.floors[0].slab_m, 0.66 * 0.3048, 1e-12);
  EXPECT_NEAR(tower.floors[1].base_elevation_m, (10 + 0.66) * 0.3048, 1e-9);
  const auto dir = scratch();
  std::filesystem::copy_file(data("plans/cottage.yaml"), dir / "plan.yaml",
                             std::filesystem::copy_options::overwrite_existing);
  auto with =
      [&](const std::string& hours) {
        std::ofstream(dir / "b.yaml")
            << "units: m\nlayer_height: 0.5\nslab_stage_h: " << hours
            << "\nmaterial: " << testing::source_path("config/materials/standard-mix.yaml").string()
            << "\nmachine: " << testing::source_path("config/machines/cc-gantry.yaml").string()
            << "\n"
               "floors:\n  - {height: 3, plan: plan.yaml}\n";
        return load_building(dir / "b.yaml");
      };
  EXPECT_DOUBLE_EQ(with("0").slab_stage_s, 0.0);
  EXPECT_DOUBLE_EQ(with("720").slab_stage_s, 720 * 3600.0);
  const InputError e = testing::expect_input_error([&] { with("720.5"); });
  EXPECT_EQ(e.first().field, "slab_stage_h");
  EXPECT_EQ(e.first().line, 3);
  EXPECT_EQ(testing::expect_input_error([&] { with("-1"); }).first().field, "slab_stage_h");
  std::filesystem::remove_all(dir);
}

TEST(Building, EveryErrorOfTheFileInOneRunEachOnceWithItsFloors) {
  // A plan with an opening past its wall's end, on two floors; a negative height; a
  // missing plan; a bad wall pattern: all reported together, the plan's error once.
  const auto dir = scratch();
  std::filesystem::copy_file(data("broken/opening_off_wall.yaml"), dir / "off.yaml",
                             std::filesystem::copy_options::overwrite_existing);
  std::ofstream(dir / "b.yaml") << "units: m\nlayer_height: 0.5\nwall_pattern: hollow\nfloors:\n"
                                   "  - {name: ground, height: 3, plan: off.yaml}\n"
                                   "  - {name: first, height: -3, plan: off.yaml}\n"
                                   "  - {name: second, height: 3, plan: nothere.yaml}\n"
                                   "  - {name: third, height: 3, plan: off.yaml}\n";
  const InputError e = testing::expect_input_error([&] { load_building(dir / "b.yaml"); });
  ASSERT_EQ(e.diagnostics().size(), 4u) << e.what();
  EXPECT_EQ(e.diagnostics()[0].field, "wall_pattern");
  const auto& plan = e.diagnostics()[1];
  EXPECT_EQ(plan.file, (dir / "off.yaml").string());
  EXPECT_TRUE(testing::contains(plan.message, "does not fit on its wall")) << plan.message;
  EXPECT_TRUE(testing::contains(plan.message, "(floors 'ground' and 'third')")) << plan.message;
  EXPECT_EQ(e.diagnostics()[2].field, "floors[1].height");
  EXPECT_EQ(e.diagnostics()[3].field, "floors[2].plan");
  // One floor alone: no list.
  std::ofstream(dir / "b.yaml") << "units: m\nlayer_height: 0.5\nfloors:\n"
                                   "  - {name: ground, height: 3, plan: off.yaml}\n";
  const InputError one = testing::expect_input_error([&] { load_building(dir / "b.yaml"); });
  ASSERT_EQ(one.diagnostics().size(), 1u);
  EXPECT_FALSE(testing::contains(one.first().message, "floors")) << one.first().message;
  std::filesystem::remove_all(dir);
}

// A floor's `slab:` (from its walls' top to the next floor's base) lifts every floor above
// it, in the file's unit; out of its range it is refused at its line.
TEST(Building, AFloorsSlabLiftsTheFloorsAboveIt) {
  const auto dir = scratch();
  std::filesystem::copy_file(data("plans/cottage.yaml"), dir / "plan.yaml",
                             std::filesystem::copy_options::overwrite_existing);
  auto with =
      [&](const std::string& units, const std::string& slab) {
        std::ofstream(dir / "b.yaml")
            << "units: " << units << "\nlayer_height: 0.5\nmaterial: "
            << testing::source_path("config/materials/standard-mix.yaml").string()
            << "\nmachine: " << testing::source_path("config/machines/cc-gantry.yaml").string()
            << "\nfloors:\n  - {height: 3, slab: " << slab << ", plan: plan.yaml}\n"
            << "  - {height: 3, plan: plan.yaml}\n  - {height: 3, plan: plan.yaml}\n";
        return load_building(dir / "b.yaml");
      };
  const Building b = with("m", "0.25");
  EXPECT_DOUBLE_EQ(b.floors[0].slab_m, 0.25);
  EXPECT_DOUBLE_EQ(b.floors[1].base_elevation_m, 3.25);
  EXPECT_DOUBLE_EQ(b.floors[2].base_elevation_m, 6.25);
  EXPECT_DOUBLE_EQ(with("m", "0").floors[1].base_elevation_m, 3.0);
  const InputError e = testing::expect_input_error([&] { with("m", "-0.1"); });
  EXPECT_EQ(e.first().field, "floors[0].slab");
  EXPECT_EQ(e.first().line, 6);
  EXPECT_EQ(testing::expect_input_error([&] { with("m", "10.5"); }).first().field,
            "floors[0].slab");
  std::filesystem::remove_all(dir);
}

// Levels from the model: a floor without a height runs up to the next floor's level under
// its slab, so `slabs:` fills the storeys and moves no level; a height and slab that would
// move a level are refused at that level, naming both values; the boundary is 1 mm.
TEST(Building, SlabsFillTheStoreysBetweenLevelsAndNeverMoveThem) {
  const auto dir = scratch();
  std::filesystem::copy_file(data("plans/cottage.yaml"), dir / "plan.yaml",
                             std::filesystem::copy_options::overwrite_existing);
  auto with =
      [&](const std::string& units, const std::string& head, const std::string& floors) {
        std::ofstream(dir / "b.yaml")
            << "units: " << units << "\nlayer_height: 0.1\nmaterial: "
            << testing::source_path("config/materials/standard-mix.yaml").string()
            << "\nmachine: " << testing::source_path("config/machines/cc-gantry.yaml").string()
            << "\n"
            << head << "floors:\n"
            << floors;
        return load_building(dir / "b.yaml");
      };
  // An imported office: levels 1.5 (the datum of its ground), 5.767 and 9.425, no slabs.
  const std::string office =
      "  - {name: L1, level: 1.5, plan: plan.yaml}\n"
      "  - {name: L2, level: 5.767, plan: plan.yaml}\n"
      "  - {name: roof, level: 9.425, height: 3.0, plan: plan.yaml}\n";
  const Building bare = with("m", "", office);
  EXPECT_NEAR(bare.floors[0].height_m, 4.267, 1e-9);
  EXPECT_NEAR(bare.floors[1].base_elevation_m, 4.267, 1e-9);
  EXPECT_NEAR(bare.floors[2].base_elevation_m, 7.925, 1e-9);
  ASSERT_TRUE(bare.floors[1].level_m.has_value());
  EXPECT_DOUBLE_EQ(*bare.floors[1].level_m, 5.767);
  // Slabs added for all: the levels stay, the walls under them are a slab shorter.
  const Building slabbed = with("m", "slabs: {thickness: 0.2}\n", office);
  EXPECT_NEAR(slabbed.floors[0].height_m, 4.067, 1e-9);
  EXPECT_NEAR(slabbed.floors[1].base_elevation_m, 4.267, 1e-9);
  EXPECT_NEAR(slabbed.floors[1].height_m, 3.458, 1e-9);
  EXPECT_NEAR(slabbed.floors[2].base_elevation_m, 7.925, 1e-9);
  EXPECT_NEAR(slabbed.floors[2].height_m, 3.0, 1e-9);  // the top floor's own height
  // In feet, the same rule in the file's unit.
  const Building feet = with("ft", "",
                             "  - {level: 0, plan: plan.yaml}\n"
                             "  - {level: 10, height: 9, plan: plan.yaml}\n");
  EXPECT_NEAR(feet.floors[0].height_m, 10 * 0.3048, 1e-9);
  // A height and a slab that end 0.2 m above the next level: refused at that level, with
  // both values and the floor under it.
  const std::string moved =
      "  - {name: L1, level: 0, height: 4.267, slab: 0.2, plan: plan.yaml}\n"
      "  - {name: L2, level: 4.267, height: 3, plan: plan.yaml}\n";
  const InputError e = testing::expect_input_error([&] { with("m", "", moved); });
  EXPECT_EQ(e.first().field, "floors[1].level");
  for (const char* part : {"4.267 m", "4.467 m", "'L1'", "0.200 m"})
    EXPECT_TRUE(testing::contains(e.first().message, part)) << part << ": " << e.first().message;
  // The boundary: 1 mm apart is where they agree, a little more is not.
  auto apart = [&](const std::string& level) {
    return with("m", "",
                "  - {level: 0, height: 3, plan: plan.yaml}\n  - {level: " + level +
                    ", height: 3, plan: plan.yaml}\n");
  };
  EXPECT_NEAR(apart("3.001").floors[1].base_elevation_m, 3.0, 1e-12);
  EXPECT_NEAR(apart("2.999").floors[1].base_elevation_m, 3.0, 1e-12);
  EXPECT_EQ(testing::expect_input_error([&] { apart("3.0012"); }).first().field, "floors[1].level");
  EXPECT_EQ(testing::expect_input_error([&] { apart("2.9988"); }).first().field, "floors[1].level");
  // No height and no level above: the floor needs one; a level under the floor's own base
  // leaves it no height: both said at the floor.
  EXPECT_TRUE(testing::contains(
      testing::expect_input_error([&] { with("m", "", "  - {level: 0, plan: plan.yaml}\n"); })
          .first()
          .message,
      "needs a height"));
  const InputError low = testing::expect_input_error([&] {
    with("m", "",
         "  - {level: 0, slab: 0.3, plan: plan.yaml}\n  - {level: 0.2, height: 3, plan: "
         "plan.yaml}\n");
  });
  EXPECT_EQ(low.first().field, "floors[0]");
  EXPECT_TRUE(testing::contains(low.first().message, "-0.100 m high")) << low.first().message;
  EXPECT_EQ(testing::expect_input_error(
                [&] { with("m", "", "  - {level: 10001, height: 3, plan: plan.yaml}\n"); })
                .first()
                .field,
            "floors[0].level");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace ccbuild::floors
