// The exact evaluation against hand-computed cases: concurrent rotation, the stopper,
// lifts, corners, the closing move, rectilinear travel.

#include "ccbuild/planner/cost_model.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "layouts.hpp"

namespace ccbuild::planner {
namespace {
using testing::layer_from_walls;
using testing::simple_machine;

constexpr double kPi = M_PI;

// Wall 0 along +x from (0,0) to (4,0); wall 1 along +y from (4,3) to (4,6).
floors::Layer two_walls() {
  return layer_from_walls({{0, 0, 4, 0}, {4, 3, 4, 6}});
}

TEST(CostModel, RotationOverlapsTravelOrAddsToIt) {
  const auto layer = two_walls();
  auto machine = simple_machine();
  const PathSpec open = PathSpec::open_from({0, 0});
  {
    const CostModel model(layer, machine, Metric::kEuclidean);
    const Evaluation e = model.evaluate({{0, false}, {1, false}}, open);
    ASSERT_EQ(e.moves.size(), 2u);
    // 3 m at 1 m/s + 1 s accel = 4 s; a quarter turn at 1 rad/s = 1.571 s: max = 4 s.
    EXPECT_NEAR(e.moves[1].rotation_rad, kPi / 2, 1e-12);
    EXPECT_NEAR(e.moves[1].time_s, 4.0, 1e-12);
    EXPECT_NEAR(e.airtime_s, 4.0, 1e-12);  // the first move is 0 long: free
    EXPECT_NEAR(e.deposition_s, (4.0 + 3.0) / 0.5, 1e-12);
    EXPECT_NEAR(e.layer_time_s, 14.0 + 4.0, 1e-12);
  }
  machine.rotate_while_moving = false;
  {
    const CostModel model(layer, machine, Metric::kEuclidean);
    const Evaluation e = model.evaluate({{0, false}, {1, false}}, open);
    EXPECT_NEAR(e.moves[1].time_s, 4.0 + kPi / 2, 1e-12);
  }
  machine.rotate_while_moving = true;
  machine.rotation_speed_rad_s = 0.25;  // now rotation (6.28 s) outlasts the move
  {
    const CostModel model(layer, machine, Metric::kEuclidean);
    const Evaluation e = model.evaluate({{0, false}, {1, false}}, open);
    EXPECT_NEAR(e.moves[1].time_s, (kPi / 2) / 0.25, 1e-12);
  }
}

TEST(CostModel, StopperForcesTheLongWayRound) {
  // A square spiral walked anticlockwise: every corner turns +90 degrees. After four
  // corners the nozzle has wound +360 degrees; the fifth +90 would pass the stopper, so
  // it turns -270 degrees instead.
  const auto layer = layer_from_walls(
      {{0, 0, 4, 0}, {4, 0, 4, 4}, {4, 4, 0, 4}, {0, 4, 0, 1}, {0, 1, 3, 1}, {3, 1, 3, 3}});
  const CostModel model(layer, simple_machine(), Metric::kEuclidean);
  const Sequence spiral{{0, false}, {1, false}, {2, false}, {3, false}, {4, false}, {5, false}};
  const Evaluation e = model.evaluate(spiral, PathSpec::open_from({0, 0}));
  ASSERT_EQ(e.moves.size(), 6u);
  EXPECT_NEAR(e.moves[1].rotation_rad, kPi / 2, 1e-12);
  EXPECT_NEAR(e.moves[2].rotation_rad, kPi / 2, 1e-12);
  EXPECT_NEAR(e.moves[3].rotation_rad, kPi / 2, 1e-12);
  EXPECT_NEAR(e.moves[4].rotation_rad, kPi / 2, 1e-12);  // cumulative now +360
  EXPECT_NEAR(e.moves[5].rotation_rad, -3 * kPi / 2, 1e-12);
  // Corners are coincident moves: they cost only their rotation.
  EXPECT_NEAR(e.moves[1].time_s, kPi / 2, 1e-12);
  EXPECT_NEAR(e.moves[5].time_s, 3 * kPi / 2, 1e-12);
  EXPECT_NEAR(e.final_heading_rad, kPi / 2, 1e-12);
  // Without a stopper (a continuous joint) the short way is always taken.
  auto free_machine = simple_machine();
  free_machine.stopper_min_rad = -INFINITY;
  free_machine.stopper_max_rad = INFINITY;
  const CostModel free_model(layer, free_machine, Metric::kEuclidean);
  EXPECT_NEAR(free_model.evaluate(spiral, PathSpec::open_from({0, 0})).moves[5].rotation_rad,
              kPi / 2, 1e-12);
}

TEST(CostModel, HalfTurnUnwindsTowardsZero) {
  const auto layer = two_walls();
  const CostModel model(layer, simple_machine(), Metric::kEuclidean);
  EXPECT_NEAR(model.stopper_turn_rad(1.0, 1.0 + kPi), -kPi, 1e-12);
  EXPECT_NEAR(model.stopper_turn_rad(-1.0, -1.0 + kPi), kPi, 1e-12);
  EXPECT_NEAR(model.stopper_turn_rad(2 * kPi - 0.1, 0.3), 0.4 - 2 * kPi, 1e-12);
}

TEST(CostModel, LiftOnlyOverWallsAlreadyBuilt) {
  // Wall 0 runs across the middle; walls 1 and 2 lie on either side of it.
  const auto layer = layer_from_walls({{0, 5, 10, 5}, {2, 2, 4, 2}, {6, 8, 8, 8}});
  const CostModel model(layer, simple_machine(), Metric::kEuclidean);
  const PathSpec open = PathSpec::open_from({0, 5});
  // Build wall 0 first: the move from wall 1 to wall 2 crosses it: lifted.
  const Evaluation after = model.evaluate({{0, false}, {1, false}, {2, false}}, open);
  ASSERT_EQ(after.moves.size(), 3u);
  EXPECT_TRUE(after.moves[2].lifted);
  const double d = std::hypot(6 - 4, 8 - 2);
  EXPECT_NEAR(after.moves[2].time_s, d / 1.0 + 1.0 + 2.0 + 3.0, 1e-12);
  EXPECT_FALSE(after.moves[1].lifted);  // leaving wall 0 from its own end is not crossing it
  EXPECT_EQ(after.lift_count, 1);
  // Build it last: nothing built is in the way of the moves between walls 1 and 2.
  const Evaluation before =
      model.evaluate({{1, false}, {2, false}, {0, false}}, PathSpec::open_from({2, 2}));
  EXPECT_FALSE(before.moves[1].lifted);
}

TEST(CostModel, TouchingAtTheMovesOwnEndsIsNotCrossing) {
  // Walls 0 and 1 meet at (4, 0). The moves (4,0)->(4,3) and (4,0)->(0,3) leave from
  // that corner: they touch the built walls only at their own start.
  const auto layer = layer_from_walls({{0, 0, 4, 0}, {4, 0, 4, 3}, {0, 0, 0, 3}});
  const CostModel model(layer, simple_machine(), Metric::kEuclidean);
  const Evaluation e =
      model.evaluate({{0, false}, {1, true}, {2, true}}, PathSpec::open_from({0, 0}));
  // Moves: (0,0)->(0,0), (4,0)->(4,3), (4,0)->(0,3).
  EXPECT_FALSE(e.moves[1].lifted);
  EXPECT_FALSE(e.moves[2].lifted);
  // A move that runs along a built wall is lifted.
  const auto line = layer_from_walls({{0, 0, 4, 0}, {6, 0, 8, 0}});
  const CostModel line_model(line, simple_machine(), Metric::kEuclidean);
  EXPECT_TRUE(
      line_model.evaluate({{0, true}, {1, false}}, PathSpec::open_from({4, 0})).moves[1].lifted);
}

TEST(CostModel, ArrivingAtABuiltWallsEndIsNotCrossing) {
  // A: (0,0) -> (4,0), built first. B: (8,3) -> (8,6). C starts where A ends, at (4,0).
  // The move from B's end (8,6) to C's start (4,0) touches the built wall A only at its
  // own arrival point: not lifted, in either metric (rectilinear: (8,6) -> (4,6) ->
  // (4,0), its second leg arriving at A's end).
  const auto layer = layer_from_walls({{0, 0, 4, 0}, {8, 3, 8, 6}, {4, 0, 4, -3}});
  for (Metric metric : {Metric::kEuclidean, Metric::kRectilinear}) {
    const CostModel model(layer, simple_machine(), metric);
    const Evaluation e =
        model.evaluate({{0, false}, {1, false}, {2, false}}, PathSpec::open_from({0, 0}));
    ASSERT_EQ(e.moves.size(), 3u);
    EXPECT_FALSE(e.moves[1].lifted) << to_string(metric);  // departs from A's end
    EXPECT_FALSE(e.moves[2].lifted) << to_string(metric);  // arrives at A's end
    EXPECT_EQ(e.lift_count, 0);
  }
  // Passing through a built wall's end on the way is touching it: lifted.
  const auto through = layer_from_walls({{0, 0, 4, 0}, {4, 2, 6, 2}, {4, -2, 6, -2}});
  const CostModel model(through, simple_machine(), Metric::kEuclidean);
  const Evaluation e =
      model.evaluate({{0, false}, {1, false}, {2, true}}, PathSpec::open_from({0, 0}));
  // (6,2) -> (6,-2) does not touch A; build C reversed so the move is (6,2) -> (6,-2).
  EXPECT_FALSE(e.moves[2].lifted);
  const Evaluation via =
      model.evaluate({{0, false}, {1, true}, {2, false}}, PathSpec::open_from({0, 0}));
  // (4,2) -> (4,-2) runs through (4,0), where A ends.
  EXPECT_TRUE(via.moves[2].lifted);
}

// The crossings between two layer points are cached by the pair: in a table for layers of
// up to 1,500 points, in a hash table above. Either way every pair, asked in any order and
// again, gives exactly the walls its straight move crosses (the grid's own answer), and the
// pair (a, b) is never mistaken for (b, a) or another pair.
TEST(CostModel, CrossingsByPointPairAreThoseOfTheMoveInSmallAndLargeLayers) {
  for (const int columns : {10, 400}) {  // 40 and 1,600 points
    std::vector<std::array<double, 4>> walls;
    for (int c = 0; c < columns; ++c) {
      walls.push_back({c * 1.0, 0.0, c * 1.0 + 0.5, 0.0});          // short walls along y = 0
      walls.push_back({c * 1.0 + 0.25, 1.0, c * 1.0 + 0.25, 3.0});  // posts across y = 2
    }
    const auto layer = layer_from_walls(walls);
    ASSERT_EQ(static_cast<int>(layer.points.size()), 4 * columns);
    const CostModel model(layer, simple_machine(), Metric::kEuclidean);
    const int points = static_cast<int>(layer.points.size());
    std::mt19937 rng(7);
    std::vector<std::pair<int, int>> pairs;
    for (int k = 0; k < 3000; ++k)
      pairs.emplace_back(static_cast<int>(rng() % points), static_cast<int>(rng() % points));
    int crossing = 0;
    for (int round = 0; round < 2; ++round)
      for (const auto& [a, b] : pairs) {
        const auto& cached = model.crossed_between_points(a, b);
        EXPECT_EQ(cached, model.crossed_segments(layer.points[a], layer.points[b]))
            << columns << " columns, points " << a << " and " << b;
        crossing += cached.empty() ? 0 : 1;
      }
    EXPECT_GT(crossing, 0) << "some moves cross a post";
  }
}

TEST(CostModel, ClosingMoveReturnsAndUnwinds) {
  // Square walked anticlockwise and closed: the nozzle has turned +270 degrees over the
  // three corners, then must come back to its first heading: -270 degrees at the close.
  const auto layer = layer_from_walls({{0, 0, 4, 0}, {4, 0, 4, 4}, {4, 4, 0, 4}, {0, 4, 0, 0}});
  const CostModel model(layer, simple_machine(), Metric::kEuclidean);
  const Evaluation e =
      model.evaluate({{0, false}, {1, false}, {2, false}, {3, false}}, PathSpec::closed_tour());
  ASSERT_EQ(e.moves.size(), 4u);  // three corners and the closing move
  EXPECT_EQ(e.moves.back().next_step, -1);
  EXPECT_NEAR(e.moves.back().rotation_rad, -3 * kPi / 2, 1e-12);
  EXPECT_NEAR(e.airtime_distance_m, 0.0, 1e-12);
  EXPECT_NEAR(e.airtime_s, 3 * (kPi / 2) + 3 * kPi / 2, 1e-12);
}

TEST(CostModel, RectilinearTravelsEachAxisAtItsSpeed) {
  const auto layer = two_walls();
  const CostModel model(layer, simple_machine(), Metric::kRectilinear);
  EXPECT_NEAR(model.distance_m({0, 0}, {3, 4}), 7.0, 1e-12);
  EXPECT_NEAR(model.travel_s({0, 0}, {3, 4}), 3.0 / 1.0 + 4.0 / 0.5, 1e-12);
  // The x-then-y path goes round a wall that blocks the straight line.
  const auto blocked = layer_from_walls({{1, -1, 1, 1}, {0, 0, 0, -2}, {2, 2, 2, 4}});
  const CostModel euclid(blocked, simple_machine(), Metric::kEuclidean);
  const CostModel rect(blocked, simple_machine(), Metric::kRectilinear);
  EXPECT_TRUE(euclid.path_crosses({0, 0}, {2, 2}, 0));  // straight: through the wall at x = 1
  EXPECT_TRUE(rect.path_crosses({0, 0}, {2, 2}, 0));    // x first along y = 0: through it too
  EXPECT_FALSE(rect.path_crosses({0, 0}, {-2, 2}, 0));
}

TEST(CostModel, CoverageCheck) {
  EXPECT_TRUE(covers_every_segment_once({{1, false}, {0, true}}, 2));
  EXPECT_FALSE(covers_every_segment_once({{1, false}, {1, true}}, 2));
  EXPECT_FALSE(covers_every_segment_once({{0, false}}, 2));
}

}  // namespace
}  // namespace ccbuild::planner
