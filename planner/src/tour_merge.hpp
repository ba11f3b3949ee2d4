#pragma once
// Merging a second tour's better parts into the best one (a partition crossover).
//
// Each wall end has one air move in either tour. Where the two differ, their air moves
// form alternating cycles: from an end, the best tour's air move, then the other tour's
// from the end reached, and so on back to the start. Swapping one cycle's air moves for
// the other tour's changes the cost by exactly that cycle's difference, but usually
// splits the tour into pieces. The pieces are joined again by the cheapest 2-exchanges
// between them: remove an air move of each of two pieces and reconnect their four ends
// crosswise. On floor plans that is often free: where three or more wall ends meet at one
// point, which of them join which costs nothing, and a tour whose better parts lie in
// another local optimum differs from it mostly by such choices (bench/README.md, plan 2).
// A cycle is kept when its gain exceeds what joining costs.

#include <vector>

#include "cc_tsp.hpp"

namespace ccbuild::planner::detail {

/// The end across each end's air move in `tour` (node ids as in TourCosts).
std::vector<int> air_mates(const WallTour& tour);

/// The tour the walls and `mates` make (every end's air move), which must be one cycle
/// through every item; it starts at item 0 entered at node 0.
WallTour tour_of_mates(const std::vector<int>& mates);

/// What a merge did.
struct MergeCounts {
  int cycles = 0;  ///< alternating cycles cheaper in the other tour
  int kept = 0;    ///< of those, swapped in
  int joins = 0;   ///< 2-exchanges that joined the pieces of the cycles kept
};

/// Swaps into `best` every alternating cycle with `other` whose gain exceeds the cost of
/// joining the pieces it leaves, best gain first. Returns the total gain (>= 0, exact
/// under `costs` up to rounding); appends to `touched` the items whose air moves changed.
double merge_tours(const TourCosts& costs, WallTour& best, const WallTour& other,
                   std::vector<int>& touched, MergeCounts* counts = nullptr);

}  // namespace ccbuild::planner::detail
