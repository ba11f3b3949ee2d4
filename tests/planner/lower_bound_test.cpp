// The matching bound: optimal on small point sets (checked by brute force), a valid
// bound on tours, and certified on the complete graph even when the sparse candidate
// graph misses the pairs the optimum needs.

#include "ccbuild/planner/lower_bound.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <random>

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

}  // namespace
}  // namespace ccbuild::planner
