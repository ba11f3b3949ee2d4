#pragma once
// A WallTour as a few reversals would leave it, without changing the WallTour: its
// positions cut into runs, each walked forwards or backwards.
//
// A Lin–Kernighan chain makes its open steps before it knows whether they pay, and most
// chains end without a gain and are undone. Made on the array, each open step flips up to
// half the tour twice (do and undo): on 5,000-wall layers that was 80% of all the items
// flipped. Here an open step costs a split of the run list instead, and only a chain
// that closes with a gain is flipped on the WallTour.

#include <vector>

#include "cc_tsp.hpp"

namespace ccbuild::planner::detail {

class FlippedTour {
 public:
  /// A view of `base`, which must not change until reset().
  explicit FlippedTour(const WallTour& base);

  /// Back to the base tour as it is now (one forward run).
  void reset();
  int size() const { return base_.size(); }
  /// Number of runs: 1 after reset(), at most 2 more for each reverse().
  int runs() const { return static_cast<int>(runs_.size()); }

  /// Position of the item (0 .. size-1), and the node the view enters it by.
  struct Place {
    int position;
    int entry;
  };
  Place place(int item) const {
    if (runs_.size() == 1) {  // most calls
      const int p = base_.position_of(item);
      return {p, base_.entry(p)};
    }
    return place_in_runs(item);
  }
  /// The entry node at a position of the view.
  int entry(int position) const {
    if (runs_.size() == 1) return base_.entry(position);
    return entry_in_runs(position);
  }

  /// Reverses the cyclic range first..last (positions of the view) and turns its items
  /// round; a range that wraps past the end reverses its complement instead (the same
  /// cyclic tour, walked the other way).
  void reverse(int first, int last);

 private:
  struct Run {
    int first, last;  ///< base positions, first <= last
    bool backwards;   ///< walked last .. first
    int length() const { return last - first + 1; }
  };
  Place place_in_runs(int item) const;
  int entry_in_runs(int position) const;
  /// Recomputes offset_ and by_base_ after the runs changed.
  void index_runs();
  /// Cuts the run holding view position `position` so that a run starts there; returns
  /// its index (runs() when position == size()).
  int split_at(int position);

  const WallTour& base_;
  std::vector<Run> runs_;     ///< in the order the view walks them
  std::vector<int> offset_;   ///< view position where each run starts
  std::vector<int> by_base_;  ///< run indices by base position (binary search by item)
};

}  // namespace ccbuild::planner::detail
