// Fitting the climbing machine family to a building: the platform as small as the
// building allows (its length limit met exactly, and missed by a centimetre), the fewest
// units with every stage reached and every transfer stable, a family too small to hold
// the platform, the fitted profile loading from its files as the same machine, and a
// family's bad keys reported where they were written.

#include "ccbuild/climb/fit.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "ccbuild/common/input_error.hpp"
#include "test_support.hpp"

namespace ccbuild::climb {
namespace {
namespace fs = std::filesystem;
using testing::contains;

std::string family_text() {
  return testing::slurp(testing::source_path("config/machines/cc-climber-family.yaml"));
}

machine::ClimbingFamily family_from(const std::string& text) {
  auto doc = std::make_shared<Document>(
      parse_yaml(text, testing::source_path("config/machines/cc-climber-family.yaml").string()));
  return machine::read_climbing_family(doc);
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

const floors::Building& house() {
  static const floors::Building b =
      floors::load_building(testing::source_path("config/buildings/house.yaml"));
  return b;
}

TEST(Fit, TheHouseGetsTheSmallestPlatformAndTheFewestStableUnits) {
  const auto family = family_from(family_text());
  const FitResult r = fit_climbing_machine(house(), family);
  ASSERT_TRUE(r.status) << r.status.to_string();
  // The house is 12 m x 9 m at the origin: the beams 1.2 m outside its walls.
  EXPECT_NEAR(r.platform.x_min_m, -1.2, 1e-9);
  EXPECT_NEAR(r.platform.x_max_m, 13.2, 1e-9);
  EXPECT_NEAR(r.platform.y_min_m, -1.2, 1e-9);
  EXPECT_NEAR(r.platform.y_max_m, 10.2, 1e-9);
  // Three hold while one moves: four units, the fewest.
  ASSERT_EQ(r.platform.units.size(), 4u);
  EXPECT_GE(r.least_margin_m, r.profile.climbing->stability_margin_m);
  EXPECT_NEAR(r.mass_kg, r.platform.mass_kg(family), 1e-6);
  // The fitted machine climbs the building: every stage has a pipe for every unit.
  const StagePlan stages = climb_stages(house(), *r.profile.climbing);
  ASSERT_TRUE(stages.status) << stages.status.to_string();
  EXPECT_EQ(stages.stages.size(), 2u);
  for (const auto& s : stages.stages) EXPECT_EQ(s.anchors.size(), 4u);
  // The gantry reaches half a metre past every wall.
  EXPECT_NEAR(r.profile.gantry.x.min_m, -0.5, 1e-9);
  EXPECT_NEAR(r.profile.gantry.x.max_m, 12.5, 1e-9);
  EXPECT_NEAR(r.profile.gantry.y.max_m, 9.5, 1e-9);
  EXPECT_TRUE(contains(r.optimised, "the fewest units (4")) << r.optimised;
}

TEST(Fit, ThePlatformLimitHoldsAtItsValue) {
  // The house needs 12 + 2 x 1.2 + 0.6 = 15 m of platform along x.
  const std::string text = family_text();
  const auto exact = family_from(replaced(text, "length_m: [6, 48]", "length_m: [6, 15]"));
  EXPECT_TRUE(fit_climbing_machine(house(), exact).status);
  const auto short_by_a_centimetre =
      family_from(replaced(text, "length_m: [6, 48]", "length_m: [6, 14.99]"));
  const FitResult r = fit_climbing_machine(house(), short_by_a_centimetre);
  ASSERT_FALSE(r.status);
  EXPECT_EQ(r.status.code(), ClimbCode::kTooLarge);
  EXPECT_TRUE(contains(r.status.reason(), "would be 15.00 m, and the family's largest is 14.99 m"))
      << r.status.reason();
  EXPECT_TRUE(contains(r.nearest_change, "reaches 15.00 m")) << r.nearest_change;
  // A smallest platform larger than the house: the beams move out, evenly.
  const auto big = family_from(replaced(text, "length_m: [6, 48]", "length_m: [20, 48]"));
  const FitResult grown = fit_climbing_machine(house(), big);
  ASSERT_TRUE(grown.status) << grown.status.to_string();
  EXPECT_NEAR(grown.platform.length_m() + 0.6, 20.0, 1e-9);
  EXPECT_NEAR(grown.platform.x_min_m, -3.7, 1e-9);
}

// The platform the message proposes, applied as written, is large enough: rounded up to the
// centimetre (15.0037 m needed: 15.01, where the nearest, 15.00, would be refused again),
// and the building it proposes instead, rounded down, fits the family as it is.
TEST(Fit, TheProposedPlatformAppliedAsWrittenFits) {
  const std::string text =
      replaced(family_text(), "beam_clearance_m: 1.2 ", "beam_clearance_m: 1.20185 ");
  const FitResult r = fit_climbing_machine(
      house(), family_from(replaced(text, "length_m: [6, 48]", "length_m: [6, 14.99]")));
  ASSERT_EQ(r.status.code(), ClimbCode::kTooLarge) << r.status.to_string();
  const std::string key = "`family.platform.length_m`: ";
  const auto at = r.nearest_change.find(key);
  ASSERT_NE(at, std::string::npos) << r.nearest_change;
  const std::string proposed = r.nearest_change.substr(at + key.size(), 5);
  EXPECT_EQ(proposed, "15.01") << r.nearest_change;
  const FitResult applied = fit_climbing_machine(
      house(), family_from(replaced(text, "length_m: [6, 48]", "length_m: [6, " + proposed + "]")));
  EXPECT_NE(applied.status.code(), ClimbCode::kTooLarge) << applied.status.to_string();
  // 14.99 - 0.6 - 2 x 1.20185 = 11.9863 m of building at most: 11.98, not 11.99.
  EXPECT_TRUE(contains(r.nearest_change, "a building at most 11.98 m along x")) << r.nearest_change;
}

TEST(Fit, AStabilityMarginEqualToTheBestSetsLeastMarginKeepsThatSet) {
  // The house's most stable set of four, on statics alone (its climbs not planned, which
  // the margin would also bound), then the same family asking exactly that set's least
  // margin: it is stable by it (a margin equal to the one asked is enough). A micrometre
  // more and no set of four is.
  const std::string text = family_text();
  FitOptions statics;
  statics.plan_climbs = false;
  const FitResult r = fit_climbing_machine(house(), family_from(text), statics);
  ASSERT_TRUE(r.status) << r.status.to_string();
  ASSERT_EQ(r.platform.units.size(), 4u);
  const auto asking = [&](double margin_m) {
    char line[64];
    std::snprintf(line, sizeof line, "stability_margin_m: %.17g", margin_m);
    return fit_climbing_machine(
        house(), family_from(replaced(text, "stability_margin_m: 0.3", line)), statics);
  };
  const FitResult again = asking(r.least_margin_m);
  ASSERT_TRUE(again.status) << again.status.to_string();
  ASSERT_EQ(again.platform.units.size(), 4u);
  EXPECT_DOUBLE_EQ(again.least_margin_m, r.least_margin_m);
  for (std::size_t u = 0; u < 4; ++u)
    EXPECT_TRUE(again.platform.units[u].position_m.isApprox(r.platform.units[u].position_m)) << u;
  const FitResult over = asking(r.least_margin_m + 1e-6);
  EXPECT_TRUE(!over.status || over.platform.units.size() > 4u);
}

TEST(Fit, AFamilyOfThreeUnitsCannotHoldWhileOneMoves) {
  const auto three = family_from(replaced(family_text(), "count: [3, 16]", "count: [3, 3]"));
  const FitResult r = fit_climbing_machine(house(), three);
  ASSERT_FALSE(r.status);
  EXPECT_EQ(r.status.code(), ClimbCode::kUnstable);
  EXPECT_TRUE(contains(r.status.reason(), "at most 3 units, and 3 must hold")) << r.status.reason();
  EXPECT_TRUE(contains(r.nearest_change, "4 units or more")) << r.nearest_change;
  const auto four = family_from(replaced(family_text(), "count: [3, 16]", "count: [3, 4]"));
  EXPECT_TRUE(fit_climbing_machine(house(), four).status);
}

TEST(Fit, TheFittedFilesLoadAsTheSameMachine) {
  const auto family = family_from(family_text());
  const fs::path dir = fs::temp_directory_path() / ("ccbuild_fit_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  FitOptions options;
  options.profile_path = (dir / "house-climber.yaml").string();
  options.urdf_file = "house-climber.urdf";
  const FitResult r = fit_climbing_machine(house(), family, options);
  ASSERT_TRUE(r.status);
  std::ofstream(dir / "house-climber.yaml") << r.profile_yaml;
  std::ofstream(dir / "house-climber.urdf") << r.urdf_xml;
  const machine::MachineProfile loaded = machine::load_machine_profile(dir / "house-climber.yaml");
  ASSERT_TRUE(loaded.climbing);
  EXPECT_EQ(loaded.climbing->units.size(), r.platform.units.size());
  EXPECT_DOUBLE_EQ(loaded.climbing->robot->total_mass_kg(),
                   r.profile.climbing->robot->total_mass_kg());
  const StagePlan a = climb_stages(house(), *loaded.climbing);
  const StagePlan b = climb_stages(house(), *r.profile.climbing);
  ASSERT_EQ(a.stages.size(), b.stages.size());
  for (std::size_t s = 0; s < a.stages.size(); ++s)
    for (std::size_t u = 0; u < a.stages[s].anchors.size(); ++u)
      EXPECT_TRUE(a.stages[s].anchors[u].centre_m.isApprox(b.stages[s].anchors[u].centre_m));
  // The same inputs fit the same machine, byte for byte.
  const FitResult again = fit_climbing_machine(house(), family, options);
  EXPECT_EQ(again.profile_yaml, r.profile_yaml);
  EXPECT_EQ(again.urdf_xml, r.urdf_xml);
  fs::remove_all(dir);
}

TEST(Family, BadKeysAreReportedWhereTheyWereWritten) {
  const std::string text = family_text();
  auto expect_refused = [](const std::string& bad, const std::string& message) {
    try {
      family_from(bad);
      ADD_FAILURE() << "accepted: " << message;
    } catch (const InputError& e) {
      EXPECT_TRUE(contains(e.what(), message)) << e.what();
      EXPECT_TRUE(contains(e.what(), "cc-climber-family.yaml:")) << e.what();
    }
  };
  expect_refused(replaced(text, "width_m: [5, 24]", "width_m: [24, 5]"),
                 "family.platform.width_m: the range is the wrong way round");
  expect_refused(replaced(text, "count: [3, 16]", "count: [2, 16]"),
                 "a climbing machine has 3 to 16 units");
  expect_refused(replaced(text, "name: CC climber\n", "name: CC climber\nurdf: x.urdf\n"),
                 "a family has no urdf");
  expect_refused(replaced(text, "stroke_m: [1.2, 5.6]", "stroke_m: [1.2, 1.4]"),
                 "at least 0.5 m of stroke");
  expect_refused(replaced(text, "climbing:\n", "climbing:\n  units: []\n"),
                 "chosen by `ccbuild fit`");
}

}  // namespace
}  // namespace ccbuild::climb
