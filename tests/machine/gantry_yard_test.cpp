// Where gantries stand between layers and the moves before a layer (machine::GantryYard):
// the one rule the scheduler times a layer's move by and the dispatcher sends its moves by.

#include "ccbuild/machine/gantry_yard.hpp"

#include <gtest/gtest.h>

namespace ccbuild::machine {
namespace {

const AxisSpeeds kSpeeds{0.5, 0.25, 0.05, 1.0};  // x, y, z (m/s), heading (rad/s)

TEST(GantryYard, AStraightMoveTakesAsLongAsItsSlowestAxis) {
  // 2 m along x at 0.5 m/s (4 s) against 1 m along y at 0.25 m/s (4 s): equal, 4 s.
  EXPECT_DOUBLE_EQ(straight_move_s(kSpeeds, {0, 0, 0, 0}, {2, 1, 0, 0}), 4.0);
  // The other way round, and the heading the slowest (5 rad at 1 rad/s).
  EXPECT_DOUBLE_EQ(straight_move_s(kSpeeds, {2, 1, 0, 5}, {0, 0, 0, 0}), 5.0);
  // One layer up: 0.1 m at 0.05 m/s.
  EXPECT_DOUBLE_EQ(straight_move_s(kSpeeds, {0, 0, 1.0, 0}, {0, 0, 1.1, 0}), 2.0);
  EXPECT_DOUBLE_EQ(straight_move_s(kSpeeds, {3, 4, 1, 2}, {3, 4, 1, 2}), 0.0);
  // An axis without a limit is not counted.
  EXPECT_DOUBLE_EQ(straight_move_s({0.5, 0.25, 0.0, 1.0}, {0, 0, 0, 0}, {0, 0, 9, 0}), 0.0);
}

TEST(GantryYard, AnIdleGantryParksOnceAtTheFarEndAndComesBackFromThere) {
  // Three gantries 1.5 m wide on rails along x up to 20 m: parks at 17, 18.5 and 20 m.
  GantryYard yard(kSpeeds, RailAxis::kX, 20.0, 3, 1.5);
  EXPECT_DOUBLE_EQ(yard.park_of(0, {5, 3, 1, 0})[0], 17.0);
  EXPECT_DOUBLE_EQ(yard.park_of(2, {5, 3, 1, 0})[0], 20.0);
  EXPECT_DOUBLE_EQ(yard.park_of(1, {5, 3, 1, 0})[1], 3.0);  // only the rail coordinate
  using Starts = std::vector<std::optional<GantryPose>>;
  // Before anything has moved, no gantry stands anywhere: no move.
  EXPECT_DOUBLE_EQ(
      yard.longest_move_before_s(Starts{GantryPose{1, 1, 0.1, 0}, GantryPose{8, 1, 0.1, 0}}), 0.0);
  yard.finish_layer({GantryPose{2, 1, 0.1, 0}, GantryPose{9, 1, 0.1, 0}});
  // Next layer on gantry 1 alone: gantry 2 parks (9 -> 18.5 m along x: 19 s), gantry 1
  // moves to its start (0.1 m up: 2 s).
  const Starts one{GantryPose{2, 1, 0.2, 0}};
  std::vector<GantryMove> parks, to_starts;
  yard.moves_before(one, parks, to_starts);
  ASSERT_EQ(parks.size(), 1u);
  EXPECT_EQ(parks[0].nozzle, 1);
  EXPECT_DOUBLE_EQ(parks[0].to[0], 18.5);
  EXPECT_DOUBLE_EQ(parks[0].duration_s, 19.0);
  ASSERT_EQ(to_starts.size(), 1u);
  EXPECT_DOUBLE_EQ(to_starts[0].duration_s, 2.0);
  EXPECT_DOUBLE_EQ(yard.longest_move_before_s(one), 19.0);
  yard.finish_layer({GantryPose{2, 1, 0.2, 0}});
  // Parked already: the next one-gantry layer has no park move.
  yard.moves_before(Starts{GantryPose{2, 1, 0.3, 0}}, parks, to_starts);
  EXPECT_TRUE(parks.empty());
  EXPECT_DOUBLE_EQ(yard.longest_move_before_s(Starts{GantryPose{2, 1, 0.3, 0}}), 2.0);
  yard.finish_layer({GantryPose{2, 1, 0.3, 0}});
  // Both again: gantry 2 comes back from its park (18.5 -> 10 m: 17 s; 0.3 m up, from
  // the layer it parked at: 6 s).
  const Starts two{GantryPose{2, 1, 0.4, 0}, GantryPose{10, 1, 0.4, 0}};
  yard.moves_before(two, parks, to_starts);
  EXPECT_TRUE(parks.empty());
  ASSERT_EQ(to_starts.size(), 2u);
  EXPECT_EQ(to_starts[1].nozzle, 1);
  EXPECT_DOUBLE_EQ(to_starts[1].from[0], 18.5);
  EXPECT_DOUBLE_EQ(to_starts[1].duration_s, 17.0);
  EXPECT_DOUBLE_EQ(yard.longest_move_before_s(two), 17.0);
}

TEST(GantryYard, RailsAlongYParkAlongY) {
  const GantryYard yard(kSpeeds, RailAxis::kY, 12.0, 2, 2.0);
  const GantryPose park = yard.park_of(0, {5, 3, 1, 0.5});
  EXPECT_DOUBLE_EQ(park[0], 5.0);
  EXPECT_DOUBLE_EQ(park[1], 10.0);
  EXPECT_DOUBLE_EQ(park[3], 0.5);
}

}  // namespace
}  // namespace ccbuild::machine
