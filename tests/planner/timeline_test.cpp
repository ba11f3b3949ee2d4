// The exact x/t check against hand-computed conflicts, and timelines against the cost model.

#include "ccbuild/planner/timeline.hpp"

#include <gtest/gtest.h>

#include "layouts.hpp"

namespace ccbuild::planner {
namespace {

Timeline curve(std::initializer_list<std::pair<double, double>> points) {
  Timeline t;
  for (const auto& [time, x] : points) t.append(time, {x, 0.0});
  return t;
}

TEST(XtCheck, ApproachingGantriesConflictWhenTheGapReachesTheWidth) {
  // Left 0 -> 10 m over 10 s, right 12 -> 2 m: gap 12 - 2t reaches 1 m at t = 5.5 s.
  const auto c =
      first_conflict(curve({{0, 0}, {10, 10}}), curve({{0, 12}, {10, 2}}), RailAxis::kX, 1.0);
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->time_s, 5.5, 1e-12);
  EXPECT_NEAR(c->left_m, 5.5, 1e-12);
  EXPECT_NEAR(c->right_m, 6.5, 1e-12);
}

TEST(XtCheck, ConflictAtABreakpointOfOneCurveOnly) {
  // Left moves 0 -> 4 m over [0, 4] s; right holds at 6 m until 2 s, then 6 -> 3 m over
  // [2, 5] s. Gap for t in [2, 4]: (6 - (t - 2)) - t = 8 - 2t: 1 m at t = 3.5 s.
  const auto c =
      first_conflict(curve({{0, 0}, {4, 4}}), curve({{0, 6}, {2, 6}, {5, 3}}), RailAxis::kX, 1.0);
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->time_s, 3.5, 1e-12);
  EXPECT_NEAR(c->right_m - c->left_m, 1.0, 1e-12);
}

TEST(XtCheck, BreakpointCheckCatchesWhatSamplingMisses) {
  // The right gantry darts in and out between 5.3 s and 5.45 s, coming within 0.5 m of
  // the left one (parked at 0). Sampling every second (or every 0.25 s) never sees it:
  // at every sample the gap is 5 m. The gap is piecewise linear with breakpoints at 5.3,
  // 5.4 and 5.45 s, and checking there finds it: the gap is 5 m at 5.3 s and 0.5 m at
  // 5.4 s, so it reaches 1 m at 5.3 + (5 - 1) / (5 - 0.5) * 0.1 s.
  const Timeline left = curve({{0, 0}, {10, 0}});
  const Timeline right = curve({{0, 5}, {5.3, 5}, {5.4, 0.5}, {5.45, 5}, {10, 5}});
  for (double step : {1.0, 0.25}) {
    double sampled_min = 1e9;
    for (double t = 0; t <= 10.0 + 1e-9; t += step)
      sampled_min = std::min(sampled_min, right.at(t).x() - left.at(t).x());
    EXPECT_GE(sampled_min, 5.0 - 1e-12) << "sampling every " << step << " s";
  }
  const auto c = first_conflict(left, right, RailAxis::kX, 1.0);
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->time_s, 5.3 + 4.0 / 4.5 * 0.1, 1e-12);
  EXPECT_NEAR(min_gap_m(left, right, RailAxis::kX), 0.5, 1e-12);
}

TEST(XtCheck, AGapExactlyTheWidthIsAllowedAndNoLess) {
  // The right gantry comes to exactly a gantry width from the left one and goes back:
  // allowed. Half a millimetre closer is a conflict, found at the moment the gap reaches
  // the width.
  const Timeline left = curve({{0, 0}, {10, 0}});
  EXPECT_FALSE(first_conflict(left, curve({{0, 3}, {5, 1.0}, {10, 3}}), RailAxis::kX, 1.0));
  const auto c = first_conflict(left, curve({{0, 3}, {5, 0.9995}, {10, 3}}), RailAxis::kX, 1.0);
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->time_s, 5.0 * 2.0 / 2.0005, 1e-9);
  EXPECT_NEAR(min_gap_m(left, curve({{0, 3}, {5, 0.9995}, {10, 3}}), RailAxis::kX), 0.9995, 1e-12);
}

TEST(XtCheck, FinishedGantriesStayWhereTheyStopped) {
  // The left gantry stops at 8 m at t = 2 s; the right one arrives next to it much later.
  const auto c = first_conflict(curve({{0, 0}, {2, 8}}), curve({{0, 20}, {50, 20}, {60, 8.5}}),
                                RailAxis::kX, 1.0);
  ASSERT_TRUE(c);
  EXPECT_GT(c->time_s, 50.0);
}

TEST(XtCheck, FarApartNeverConflictAndTheYAxisWorksToo) {
  Timeline a, b;
  a.append(0, {0, 0});
  a.move_to({0, 3}, 3);
  b.append(0, {0, 10});
  b.move_to({0, 6}, 3);
  EXPECT_FALSE(first_conflict(a, b, RailAxis::kY, 2.0));
  EXPECT_NEAR(min_gap_m(a, b, RailAxis::kY), 3.0, 1e-12);
  EXPECT_TRUE(first_conflict(a, b, RailAxis::kY, 3.5));
}

TEST(Timeline, FollowsTheCostModel) {
  // Wall 0 (0,0)->(4,0), then a 3 m air move to wall 1 (4,3)->(4,6): with the simple
  // machine: deposition 8 s, move max(3 + 1, pi/2) = 4 s, deposition 6 s; closed tour
  // returns from (4,6) to (0,0): 7.21 m + 1 s, turning back (no lift: nothing crossed).
  const auto layer = testing::layer_from_walls({{0, 0, 4, 0}, {4, 3, 4, 6}});
  const CostModel model(layer, testing::simple_machine(), Metric::kEuclidean);
  const Sequence s{{0, false}, {1, false}};
  const Timeline t = timeline_of(model, s, PathSpec::closed_tour());
  EXPECT_NEAR(t.at(8.0).x(), 4.0, 1e-12);        // end of wall 0
  EXPECT_NEAR(t.at(8.0 + 4.0).y(), 3.0, 1e-12);  // at wall 1's start after the move
  EXPECT_NEAR(t.at(8.0 + 2.0).y(), 1.5, 1e-12);  // halfway through the move
  EXPECT_NEAR(t.at(18.0).y(), 6.0, 1e-12);       // end of wall 1
  const Evaluation e = model.evaluate(s, PathSpec::closed_tour());
  EXPECT_NEAR(t.end_s(), e.layer_time_s, 1e-9);
  EXPECT_TRUE(t.at(1e6).isApprox(Eigen::Vector2d(0, 0)));
  // A wait holds the nozzle at the end of the previous wall.
  const Timeline waited = timeline_of(model, s, PathSpec::closed_tour(), {0.0, 5.0});
  EXPECT_NEAR(waited.at(12.0).x(), 4.0, 1e-12);
  EXPECT_NEAR(waited.at(12.0).y(), 0.0, 1e-12);
  EXPECT_NEAR(waited.end_s(), e.layer_time_s + 5.0, 1e-9);
}

}  // namespace
}  // namespace ccbuild::planner
