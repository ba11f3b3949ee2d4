// What a floor's walls print against their model's volume (floors/quantities.hpp): the
// printed volume piece by piece, the 3% bound at its edges on both sides, and the widths
// used where the walls are sliced without beads.

#include "ccbuild/floors/quantities.hpp"

#include <gtest/gtest.h>

#include "ccbuild/floors/plan.hpp"
#include "test_support.hpp"

namespace ccbuild::floors {
namespace {

using testing::contains;

// Two walls of 10 m and 4 m, 0.2 m thick, 3 m high, a 1 m door through the first; the first
// states `model_m3`, the second states nothing.
Floor floor_stating(std::optional<double> model_m3) {
  Floor floor;
  floor.name = "ground";
  floor.height_m = 3.0;
  FloorPlan& plan = floor.plan;
  plan.vertices = {{1, {0, 0}, {}}, {2, {10, 0}, {}}, {3, {10, 4}, {}}};
  plan.walls = {{1, 1, 2, 0.2, {}, "G1", model_m3}, {2, 2, 3, 0.2, {}, "G2", std::nullopt}};
  plan.openings = {{"D1", 1, 2.0, 1.0, 0.0, 2.0, {}}};
  validate_plan(plan, 3.0);
  return floor;
}

// The first wall prints 10 x 0.2 x 3 less the door's 1 x 0.2 x 2.
constexpr double kFirst_m3 = 10 * 0.2 * 3 - 1 * 0.2 * 2;

TEST(Quantities, TheWallsAsDrawnPrintTheirThicknessPieceByPiece) {
  const FloorQuantities q = floor_quantities(floor_stating(kFirst_m3), 0.1, 0.0);
  EXPECT_NEAR(q.printed_m3, kFirst_m3 + 4 * 0.2 * 3, 1e-9);
  EXPECT_NEAR(q.printed_modelled_m3, kFirst_m3, 1e-9);
  ASSERT_TRUE(q.model_m3);
  EXPECT_NEAR(*q.model_m3, kFirst_m3, 1e-12);
  EXPECT_EQ(q.walls_modelled, 1);
  EXPECT_EQ(q.walls_unmodelled, 1);
  ASSERT_EQ(q.elements.size(), 2u);
  EXPECT_EQ(q.elements[0].global_id, "G1");
  EXPECT_FALSE(q.off());
  // On a machine: walls sliced without beads are the nozzle's width.
  const FloorQuantities nozzle = floor_quantities(floor_stating(kFirst_m3), 0.1, 0.15);
  EXPECT_NEAR(nozzle.printed_modelled_m3, kFirst_m3 * 0.15 / 0.2, 1e-9);
  EXPECT_TRUE(nozzle.off());  // -25%
}

TEST(Quantities, ThreePercentEitherWayIsWithinAndMoreIsOff) {
  // Printed 3% over the model (and a hair under that), then a tenth of a percent more.
  const auto off_with = [](double model_m3) {
    return floor_quantities(floor_stating(model_m3), 0.1, 0.0);
  };
  EXPECT_FALSE(off_with(kFirst_m3 / (1.03 - 1e-9)).off());
  EXPECT_TRUE(off_with(kFirst_m3 / 1.031).off());
  EXPECT_FALSE(off_with(kFirst_m3 / (0.97 + 1e-9)).off());
  EXPECT_TRUE(off_with(kFirst_m3 / 0.969).off());
  const FloorQuantities over = off_with(kFirst_m3 / 1.031);
  const std::string text = quantities_text("ground", over);
  EXPECT_TRUE(contains(text,
                       "(+3.1%); 1 wall states none — OFF by more than 3%: G1 (wall 1) "
                       "prints 5.60 m³, the model says 5.43 m³"))
      << text;
  // No wall stating a volume: nothing to compare, said so.
  const FloorQuantities none = floor_quantities(floor_stating(std::nullopt), 0.1, 0.0);
  EXPECT_FALSE(none.model_m3);
  EXPECT_FALSE(none.difference());
  EXPECT_FALSE(none.off());
  EXPECT_TRUE(contains(quantities_text("ground", none), "(the model states no volume"));
}

}  // namespace
}  // namespace ccbuild::floors
