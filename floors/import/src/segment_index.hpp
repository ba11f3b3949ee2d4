#pragma once
// A static spatial index of 2-D segments (points are segments of length zero), so that the
// importers' searches for what lies near what cost about n log n in the lines of a drawing
// or the walls of a model, not n squared (issue 49: 20,000 dashes, 100,000 face pairs).
// Internal to ccbuild::import.
//
// Segments live in a hierarchy of square grids: a segment whose bounding box is at most
// `cell_m(level)` across lives at that level (cells base * 2^level), in the at most four
// cells its box touches. A query around a point looks at the few cells around it on each
// level in use; a search for pairs looks, from each segment, only at its own level and the
// coarser ones, so that no query walks along a long segment cell by cell.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

namespace ccbuild::import::detail {

class SegmentIndex {
 public:
  using Segment = std::pair<Eigen::Vector2d, Eigen::Vector2d>;

  /// Indexes `segments` (metres; their order gives their ids 0..n-1) for queries that reach
  /// at most `reach_m` beyond a point or a segment's box. Non-finite coordinates are indexed
  /// at the edge of the grid (found by every query there; callers test exactly).
  SegmentIndex(const std::vector<Segment>& segments, double reach_m);

  /// The ids, ascending, of the segments whose bounding boxes come within `r_m` (at most the
  /// reach) of `p`: every segment within `r_m` of `p`, and maybe a few more (callers test
  /// exactly). Not thread-safe (it reuses a scratch buffer).
  const std::vector<std::size_t>& near_point(const Eigen::Vector2d& p, double r_m) const;

  /// Every unordered pair (i < j) of segments whose bounding boxes come within `r_m` (at
  /// most the reach) of each other, sorted: every pair of segments within `r_m` of each
  /// other, and maybe a few more. Stops once more than `max_pairs` are found (a crowd no
  /// plan of walls has) and returns the segment whose neighbours passed the limit (for the
  /// caller to say where); nullopt when all pairs are found.
  std::optional<std::size_t> near_pairs(
      double r_m, std::size_t max_pairs,
      std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs) const;

  std::size_t size() const { return boxes_.size(); }

 private:
  struct Box {
    double x0, y0, x1, y1;
  };
  struct Level {
    double cell_m = 0.0;
    std::unordered_map<std::uint64_t, std::pair<std::uint32_t, std::uint32_t>> cells;
    std::vector<std::uint32_t> ids;  ///< ids of each cell, ascending, one run per cell
  };
  static bool within(const Box& a, const Box& b, double r_m) {
    return a.x0 - r_m <= b.x1 && b.x0 - r_m <= a.x1 && a.y0 - r_m <= b.y1 && b.y0 - r_m <= a.y1;
  }
  std::int64_t cell_of(double v, double cell_m) const;
  /// Calls visit(id) for each id registered in the cells of `level` that `box` touches
  /// (an id may come more than once).
  template <class Visit>
  void visit_cells(const Level& level, const Box& box, Visit visit) const;

  double base_m_ = 1.0;
  std::vector<Box> boxes_;
  std::vector<int> level_of_;
  std::vector<Level> levels_;  ///< by level number; empty ones have no cells
  mutable std::vector<std::uint32_t> stamp_;
  mutable std::uint32_t epoch_ = 0;
  mutable std::vector<std::size_t> found_;
};

}  // namespace ccbuild::import::detail
