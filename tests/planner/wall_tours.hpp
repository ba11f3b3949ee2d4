#pragma once
// Tours for the search's own tests (lin_kernighan_test.cpp, tour_merge_test.cpp).

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "cc_tsp.hpp"

namespace ccbuild::planner::detail {

/// Items in random order, each forwards or backwards at random.
inline WallTour random_tour(int items, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<int> order(items);
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<char> reversed(items);
  for (char& r : reversed) r = static_cast<char>(rng() % 2);
  return WallTour(order, reversed);
}

/// Every item at exactly one position, and found there by position_of.
inline bool visits_every_item_once(const WallTour& tour) {
  std::vector<int> seen(tour.size(), 0);
  for (int p = 0; p < tour.size(); ++p) ++seen[tour.item_at(p)];
  for (int p = 0; p < tour.size(); ++p)
    if (tour.position_of(tour.item_at(p)) != p) return false;
  return std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; });
}

}  // namespace ccbuild::planner::detail
