// The matching bound: optimal on small point sets (checked by brute force), a valid
// bound on tours, and certified on the complete graph even when the sparse candidate
// graph misses the pairs the optimum needs. The connected bound: exact on hand-computed
// layouts the matching cannot see, never above the exact optimum, certified beyond its
// candidate pairs, and valid when stopped early.

#include "ccbuild/planner/lower_bound.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <iterator>
#include <random>

#include "ccbuild/planner/plan_layer.hpp"
#include "layouts.hpp"

namespace ccbuild::planner {
namespace {

double brute_force_matching(const std::vector<Eigen::Vector2d>& p, bool wildcard) {
  std::vector<int> free;
  for (int i = 0; i < static_cast<int>(p.size()); ++i) free.push_back(i);
  if (wildcard) free.push_back(-1);
  std::function<double(std::vector<int>)> best = [&](std::vector<int> left) -> double {
    if (left.empty()) return 0.0;
    const int a = left.back();
    left.pop_back();
    double result = 1e300;
    for (std::size_t k = 0; k < left.size(); ++k) {
      const int b = left[k];
      std::vector<int> rest = left;
      rest.erase(rest.begin() + k);
      const double d = (a < 0 || b < 0) ? 0.0 : (p[a] - p[b]).norm();
      result = std::min(result, d + best(rest));
    }
    return result;
  };
  return best(free);
}

TEST(LowerBound, MatchingIsOptimalOnSmallSets) {
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 30; ++trial) {
    const bool wildcard = trial % 2 == 1;
    const int n = 2 + 2 * (trial % 4) + (wildcard ? 1 : 0);
    std::vector<Eigen::Vector2d> points;
    for (int i = 0; i < n; ++i)
      points.emplace_back(double(rng() % 1000) / 37.0, double(rng() % 1000) / 53.0);
    const MatchingBound m = min_weight_matching(points, Metric::kEuclidean, wildcard);
    const double brute = brute_force_matching(points, wildcard);
    EXPECT_TRUE(m.proven_optimal);
    EXPECT_NEAR(m.matching_cost_m, brute, 1e-9);
    EXPECT_LE(m.lower_bound_m, brute + 1e-12);
    EXPECT_NEAR(m.lower_bound_m, brute, 1e-4);  // costs are rounded down to 10 micrometres
  }
}

TEST(LowerBound, CertifiesBeyondTheNearestNeighbours) {
  // Two tight clusters of 13 points far apart: the optimum must pair one point of each
  // cluster across the gap, which no point has among its 10 nearest neighbours; the
  // duals must still hold on the complete graph.
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 13; ++i) points.emplace_back(0.01 * i, 0.0);
  for (int i = 0; i < 13; ++i) points.emplace_back(100.0 + 0.01 * i, 0.0);
  const MatchingBound m = min_weight_matching(points, Metric::kEuclidean, false);
  EXPECT_TRUE(m.proven_optimal);
  EXPECT_NEAR(m.matching_cost_m, 99.88 + 12 * 0.01, 1e-9);
  EXPECT_LE(m.lower_bound_m, m.matching_cost_m + 1e-12);
  EXPECT_NEAR(m.lower_bound_m, m.matching_cost_m, 1e-3);
}

TEST(LowerBound, OddPointsOfAFloorPlan) {
  // A square room with one wall sticking out of a corner: the free end and the corner
  // it leaves are the only odd points.
  const auto layer = testing::layer_from_walls(
      {{0, 0, 4, 0}, {4, 0, 4, 4}, {4, 4, 0, 4}, {0, 4, 0, 0}, {4, 4, 7, 8}});
  const LayerBound b = airtime_lower_bound(layer, Metric::kEuclidean, PathSpec::closed_tour());
  EXPECT_EQ(b.odd_points, 2);
  EXPECT_NEAR(b.distance_m, 5.0, 1e-4);
  // An open path starting at the free end needs no air move at all.
  const LayerBound open =
      airtime_lower_bound(layer, Metric::kEuclidean, PathSpec::open_from({7, 8}));
  EXPECT_NEAR(open.distance_m, 0.0, 1e-9);
}

// Two 4 m square rooms 6 m apart along x: every point has even degree, so the matching
// bound is 0, but any closed tour must cross the 6 m gap and come back (12 m). An open
// path from the first room's far corner (0, 0) crosses once, but a room is a closed
// loop, so it leaves the first room where it started it (or comes back): 10 m.
floors::Layer two_rooms(double gap_m) {
  const double x = 4.0 + gap_m;
  return testing::layer_from_walls({{0, 0, 4, 0},
                                    {4, 0, 4, 4},
                                    {4, 4, 0, 4},
                                    {0, 4, 0, 0},
                                    {x, 0, x + 4, 0},
                                    {x + 4, 0, x + 4, 4},
                                    {x + 4, 4, x, 4},
                                    {x, 4, x, 0}});
}

TEST(ConnectedBound, SeesTheGapBetweenSeparateRooms) {
  const auto layer = two_rooms(6.0);
  for (Metric metric : {Metric::kEuclidean, Metric::kRectilinear}) {
    const LayerBound closed = airtime_lower_bound(layer, metric, PathSpec::closed_tour());
    EXPECT_NEAR(closed.matching_m, 0.0, 1e-9);
    ASSERT_TRUE(closed.connected && closed.connected->certified);
    EXPECT_NEAR(closed.distance_m, 12.0, 1e-6);
    EXPECT_EQ(closed.source(), BoundSource::kConnected);
    EXPECT_EQ(to_string(closed.source()), "connected");
    const LayerBound open = airtime_lower_bound(layer, metric, PathSpec::open_from({0, 0}));
    EXPECT_NEAR(open.distance_m, 10.0, 1e-6);
    // The matching-only bound is what it was.
    const LayerBound matching =
        airtime_lower_bound(layer, metric, PathSpec::closed_tour(), BoundKind::kMatching);
    EXPECT_FALSE(matching.connected);
    EXPECT_NEAR(matching.distance_m, 0.0, 1e-9);
  }
}

TEST(ConnectedBound, CertifiesPairsFarBeyondTheCandidates) {
  // Twelve small rooms in a tight row and one room 100 m away: no point of the row has
  // the far room among its nearest neighbours, yet every tour travels there and back.
  std::vector<std::array<double, 4>> walls;
  auto room = [&](double x) {
    walls.push_back({x, 0, x + 1, 0});
    walls.push_back({x + 1, 0, x + 1, 1});
    walls.push_back({x + 1, 1, x, 1});
    walls.push_back({x, 1, x, 0});
  };
  for (int k = 0; k < 12; ++k) room(1.5 * k);  // gaps of 0.5 m
  room(17.5 + 100.0);
  const auto layer = testing::layer_from_walls(walls);
  const LayerBound b = airtime_lower_bound(layer, Metric::kEuclidean, PathSpec::closed_tour());
  // 11 gaps of 0.5 m, each crossed twice, and 100 m there and back.
  EXPECT_NEAR(b.distance_m, 2 * 11 * 0.5 + 200.0, 1e-6);
}

TEST(ConnectedBound, NeverAboveTheExactOptimum) {
  int stronger = 0, cases = 0;
  for (std::uint64_t seed = 1; seed <= 24; ++seed) {
    const floors::Layer layer =
        seed % 2 ? testing::random_layer(5 + static_cast<int>(seed % 6), seed)
                 : testing::floor_plan_layer(2 + static_cast<int>(seed % 3), seed);
    if (layer.segments.size() > 12) continue;
    for (Metric metric : {Metric::kEuclidean, Metric::kRectilinear}) {
      for (bool closed : {true, false}) {
        PlanOptions o;
        o.algorithm = Algorithm::kExact;
        o.metric = metric;
        o.path = closed ? PathSpec::closed_tour() : PathSpec::open_from(layer.points[0]);
        const LayerPlan exact = plan_layer(layer, testing::simple_machine(), o);
        const LayerBound b = airtime_lower_bound(layer, metric, o.path);
        SCOPED_TRACE("seed " + std::to_string(seed) + (closed ? " closed" : " open"));
        ASSERT_TRUE(b.connected && b.connected->certified);
        EXPECT_LE(b.connected->lower_bound_m, exact.evaluation.airtime_distance_m + 1e-6);
        EXPECT_GE(b.distance_m, b.matching_m);
        ++cases;
        if (b.connected->lower_bound_m > b.matching_m + 1e-6) ++stronger;
      }
    }
  }
  EXPECT_GE(cases, 40);
  EXPECT_GE(stronger, cases / 4);  // it does more than repeat the matching
}

TEST(ConnectedBound, StoppedAtOnceIsStillValid) {
  const floors::Layer layer = testing::floor_plan_layer(12, 7);
  PlanOptions o;
  const LayerPlan plan = plan_layer(layer, testing::simple_machine(), o);
  const ConnectedBound stopped = connected_airtime_bound(
      layer, Metric::kEuclidean, PathSpec::closed_tour(), {}, StopCondition(0.0));
  EXPECT_TRUE(stopped.certified);
  EXPECT_EQ(stopped.stopped_by, BoundStop::kTimeLimit);
  EXPECT_EQ(to_string(stopped.stopped_by), "time-limit");
  EXPECT_LE(stopped.lower_bound_m, plan.evaluation.airtime_distance_m + 1e-6);
  const ConnectedBound full =
      connected_airtime_bound(layer, Metric::kEuclidean, PathSpec::closed_tour());
  EXPECT_GE(full.lower_bound_m, stopped.lower_bound_m - 1e-9);
  EXPECT_LE(full.lower_bound_m, plan.evaluation.airtime_distance_m + 1e-6);
}

TEST(ConnectedBound, SkippedWhenTheTimeLeftCannotHoldItsFirstSolve) {
  const floors::Layer layer = testing::floor_plan_layer(12, 7);
  const LayerBound in_time = airtime_lower_bound(layer, Metric::kEuclidean, PathSpec::closed_tour(),
                                                 BoundKind::kConnected);
  ASSERT_TRUE(in_time.connected.has_value());
  const LayerBound late = airtime_lower_bound(layer, Metric::kEuclidean, PathSpec::closed_tour(),
                                              BoundKind::kConnected, StopCondition(0.0));
  EXPECT_FALSE(late.connected.has_value());
  EXPECT_EQ(late.source(), BoundSource::kMatching);
  EXPECT_DOUBLE_EQ(late.distance_m, in_time.matching_m);
}

// Re-proves a connected bound from its certificate alone: each moat's rhs from the
// walls, every pair of points within its distance, and the moats' sum against the bound.
void expect_certificate_proves(const floors::Layer& layer, Metric metric, const PathSpec& path,
                               const ConnectedBound& bound) {
  ASSERT_TRUE(bound.certificate);
  const ConnectedBoundCertificate& c = *bound.certificate;
  const int real = static_cast<int>(c.points_m.size());
  const bool open = c.start >= 0;
  ASSERT_EQ(open, !path.closed);
  const int nodes = real + (open ? 1 : 0);
  std::vector<std::pair<int, int>> walls;
  for (const auto& s : layer.segments) walls.emplace_back(s.start_point, s.end_point);
  if (open) walls.emplace_back(real, c.start);
  std::vector<std::vector<int>> moats_of(nodes);  // moat ids holding each node, ascending
  std::vector<double> around(nodes, 0.0);         // the widths of those moats, summed
  double sum = 0.0;
  for (std::size_t k = 0; k < c.moats.size(); ++k) {
    const BoundMoat& m = c.moats[k];
    std::vector<char> in(nodes, 0);
    for (int p : m.points) in[p] = 1;
    int leaving = 0;
    for (const auto& [a, b] : walls) leaving += in[a] != in[b];
    if (m.rhs == 1.0) {
      EXPECT_EQ(leaving % 2, 1) << "a moat of rhs 1 that an even number of walls leave";
    } else {
      EXPECT_EQ(m.rhs, 2.0);
      EXPECT_EQ(leaving, 0) << "a moat of rhs 2 that walls leave";
    }
    if (m.exact) {
      EXPECT_TRUE(open && m.points == std::vector<int>{real});
    } else {
      EXPECT_GE(m.width_m, 0.0);
    }
    sum += m.rhs * m.width_m;
    for (int p : m.points) {
      moats_of[p].push_back(static_cast<int>(k));
      around[p] += m.width_m;
    }
  }
  int violations = 0;
  for (int u = 0; u < nodes; ++u)
    for (int v = u + 1; v < nodes; ++v) {
      double shared = 0.0;
      std::vector<int> both;
      std::set_intersection(moats_of[u].begin(), moats_of[u].end(), moats_of[v].begin(),
                            moats_of[v].end(), std::back_inserter(both));
      for (int k : both) shared += c.moats[k].width_m;
      const double separating = around[u] + around[v] - 2.0 * shared;
      const double d = v >= real ? 0.0 : metric_distance_m(metric, c.points_m[u], c.points_m[v]);
      if (separating > d + 1e-9) ++violations;
    }
  EXPECT_EQ(violations, 0) << "pairs of points with moats wider than their distance between them";
  // The bound is the sum less its margin for floating-point sums, no more.
  EXPECT_LE(bound.lower_bound_m, sum);
  EXPECT_NEAR(bound.lower_bound_m, sum, 1e-8 * (1.0 + sum));
}

TEST(ConnectedBound, ItsCertificateProvesIt) {
  ConnectedBoundLimits keep;
  keep.keep_certificate = true;
  // A generated floor plan (odd points, doors and windows), closed and open, both
  // metrics; and the two rooms, where only moats of rhs 2 see the gap.
  const auto plan = testing::floor_plan_layer(12, 3);
  // Open paths from one of its points, and from a point off the plan (an extra node).
  const PathSpec from_a_point = PathSpec::open_from(plan.points[5]);
  const PathSpec from_outside = PathSpec::open_from({-1.0, -1.0});
  for (Metric metric : {Metric::kEuclidean, Metric::kRectilinear})
    for (const PathSpec& path : {PathSpec::closed_tour(), from_a_point, from_outside}) {
      const ConnectedBound b = connected_airtime_bound(plan, metric, path, keep);
      ASSERT_TRUE(b.certified);
      EXPECT_GT(b.lower_bound_m, 1.0);
      expect_certificate_proves(plan, metric, path, b);
    }
  // The first LP's duals alone, scaled down to hold beyond its candidate pairs (on a
  // larger plan its nearest-neighbour pairs miss some the duals load beyond their cost).
  const auto larger = floors::slice_plan_at(floors::generate_plan_with_segments(1000, 1), 1.0, 2.0);
  ConnectedBoundLimits first = keep;
  first.max_pricing_rounds = 1;
  first.max_rounds = 0;
  const ConnectedBound scaled =
      connected_airtime_bound(larger, Metric::kEuclidean, PathSpec::closed_tour(), first);
  EXPECT_LT(scaled.lower_bound_m, scaled.lp_value_m - 1.0);  // scaled indeed
  expect_certificate_proves(larger, Metric::kEuclidean, PathSpec::closed_tour(), scaled);
  const auto rooms = two_rooms(6.0);
  const ConnectedBound b =
      connected_airtime_bound(rooms, Metric::kEuclidean, PathSpec::closed_tour(), keep);
  EXPECT_NEAR(b.lower_bound_m, 12.0, 1e-6);
  expect_certificate_proves(rooms, Metric::kEuclidean, PathSpec::closed_tour(), b);
  // Kept only when asked for.
  EXPECT_FALSE(
      connected_airtime_bound(rooms, Metric::kEuclidean, PathSpec::closed_tour()).certificate);
}

}  // namespace
}  // namespace ccbuild::planner
