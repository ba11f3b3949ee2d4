#pragma once
// The IFC importer's rule for walls on one line: two pieces sharing a stretch would be
// printed twice, so the later keeps only what the earlier does not cover (or, when the
// earlier lies inside it, the earlier goes); found near-linearly. Internal to
// ccbuild::import.

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace ccbuild::import::detail {

struct LinePiece {
  Eigen::Vector2d a, b;  ///< m
  bool alive = true;
};

enum class Overlap {
  kEarlierInsideLater,  ///< the earlier piece goes (printed as part of the later)
  kLaterInsideEarlier,  ///< the later piece goes
  kLaterCutBack,        ///< the later piece keeps what lies beyond the earlier
};

/// Applies the rule to every pair (earlier i, later j) of live pieces, i then j ascending,
/// where both ends of j lie within `tolerance_m` of i's line and they share more than
/// `tolerance_m`; calls said(i, j, overlap_m, what) for each. A piece cut back to 1 mm or less
/// (floors::limits::kMinWallLength_m) goes too. Pieces are compared only with those near
/// them (a SegmentIndex), about n log n for a plan. Returns the piece around which more than
/// `max_near_pairs` pairs lie near one another (a crowd: the caller refuses it), else nullopt.
std::optional<std::size_t> remove_overlaps(
    std::vector<LinePiece>& pieces, double tolerance_m, std::size_t max_near_pairs,
    const std::function<void(std::size_t, std::size_t, double, Overlap)>& said);

/// The note for one overlap: "LATER and EARLIER overlap along 0.250 m on one line; the first
/// is cut back to where the second ends" (and the two other outcomes).
std::string overlap_note(const std::string& later, const std::string& earlier, double overlap_m,
                         Overlap what);

}  // namespace ccbuild::import::detail
