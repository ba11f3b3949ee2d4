#pragma once
// Slicing walls into beads (not public; see beads.hpp).

#include <vector>

#include "ccbuild/floors/plan.hpp"
#include "ccbuild/floors/slice.hpp"

namespace ccbuild::floors {

/// The beads of one layer's pieces, for `plan.beads` (bead width above 0): walls one bead
/// thick stay one pass, thicker walls become skins and their pattern's core or ties.
/// Throws InputError, at the wall's source, for a wall thicker than one bead and thinner
/// than two.
std::vector<PieceSpec> bead_pieces(const FloorPlan& plan, const std::vector<PieceSpec>& pieces,
                                   const SliceOptions& options);

}  // namespace ccbuild::floors
