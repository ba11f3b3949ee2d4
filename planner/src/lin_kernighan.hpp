#pragma once
// A Lin–Kernighan-style variable-depth search over a WallTour (see cc_tsp.hpp), which
// never breaks a wall's fixed edge.
//
// Nodes are item ends. Walking the tour, a node's two neighbours are its wall partner
// (the fixed edge) and the node across a free edge (an air move). Every removed edge is
// a free edge, every added edge joins two different items.
//
// One step is the best sequential 3-opt move from t1 (LKH's "basic move"): remove the
// free edge (t1, t2), add (t2, t3) for t3 among t2's candidates, remove the free edge at
// t3, and either close with (t4, t1) (a 2-opt move), or, when that would split the
// tour, add (t4, t5) with t5 inside the split-off loop, remove the free edge at t5 and
// close with (t6, t1): a segment insertion with or without reversal ("Or-3opt"). When
// no step closes with a gain, the step that leaves the largest open gain is made and
// the search goes on from the new edge at t1, up to `max_depth` steps (so sequential
// moves of up to 2 * max_depth + 1 edges), then undoes them all. Positive gain
// criterion throughout; an edge added in a chain is never removed in it, and a removed
// one never added back. Most chains are undone: their long flips are made in a
// FlippedTour, not on the tour's arrays.

#include <utility>
#include <vector>

#include "cc_tsp.hpp"
#include "flipped_tour.hpp"
#include "item_queue.hpp"

namespace ccbuild::planner::detail {

class LinKernighan {
 public:
  /// A chain's flips of up to `short_flip_items` items are made on the tour at once;
  /// from its first longer flip on, in a FlippedTour until the chain closes with a gain.
  /// Both give the same moves and the same tour; the split is only speed (400: the
  /// fastest of 100, 400, 1,000 and 2,000 on 1,000- to 5,000-wall plans).
  LinKernighan(const TourCosts& costs, WallTour& tour, int max_depth, int short_flip_items = 400);

  /// Queues an item whose ends are tried as t1 (a don't-look bit cleared).
  void push(int item) { queue_.push(item); }
  /// Forgets what a run cut short left queued.
  void drop_queue() { queue_.clear(); }
  /// Improves from queued items until none improves; returns the total gain.
  double run(const StopCondition& stop);

 private:
  struct Step {
    bool improved = false;  ///< a closing gain was found and the move made
    bool found = false;     ///< a non-improving step was made; go on from (t1, next_t2)
    int next_t2 = -1;
    double gain = 0.0;  ///< improved: the tour got this much cheaper; found: the open gain
  };

  double c(int u, int v) const { return costs_.cost(u, v); }
  // The walk as the chain so far leaves it (view_), not yet the WallTour.
  /// A node with its item's position in the view and whether it enters the item there.
  struct Spot {
    int node, position;
    bool entry;
  };
  Spot spot(int node) const {
    const FlippedTour::Place at = view_.place(node / 2);
    return {node, at.position, node == at.entry};
  }
  int suc(const Spot& x) const {
    if (x.entry) return x.node ^ 1;  // the item's other end
    return view_.entry(x.position + 1 == view_.size() ? 0 : x.position + 1);
  }
  int pred(const Spot& x) const {
    if (!x.entry) return x.node ^ 1;
    return view_.entry(x.position == 0 ? view_.size() - 1 : x.position - 1) ^ 1;
  }
  /// The node across this node's free edge.
  int free_neighbour(const Spot& x) const { return x.entry ? pred(x) : suc(x); }
  /// Position in the node-level walk (0 .. 2n-1).
  static int index(const Spot& x) { return 2 * x.position + (x.entry ? 0 : 1); }
  /// Whether the node at walk index ib lies on the walk from ia to ic (inclusive),
  /// walking forwards or backwards.
  bool between(bool forwards, int ia, int ib, int ic) const;

  /// The view positions first .. last that the flip for (a, b, ., d) reverses.
  std::pair<int, int> flip_range(int a, int b, int d) const;
  /// Removes (a, b) and (c, d), adds (b, c) and (d, a): on the WallTour while the chain's
  /// flips are short, else in the view. Needs the walk a, b, ..., d, c in one of the two
  /// directions; reverses b .. d.
  void make_2opt(int a, int b, int c, int d);
  /// Undoes the chain: the view is reset, the flips made on the WallTour undone.
  void undo_chain();
  /// Makes the chain's flips still in the view on the WallTour.
  void commit_chain();
  /// Makes the flip for (a, b, ., d) on the WallTour; the view must be reset (it then
  /// reads the WallTour).
  void flip_on_tour(int a, int b, int d);

  bool improve_from(int t1, double& gain);
  /// The chain's next step from (t1, t2): a closing move with a gain is made at once;
  /// otherwise, unless `last`, the best open step is made.
  Step best_step(int t1, int t2, double open_gain, bool last);

  bool was_added(int u, int v) const;
  bool was_removed(int u, int v) const;

  const TourCosts& costs_;
  WallTour& tour_;
  FlippedTour view_;
  int max_depth_;
  int short_flip_items_;
  ItemQueue queue_;  ///< items whose ends are still to be tried
  // The chain being built from one t1.
  struct Flip {
    int a, b, c, d;
  };
  std::vector<Flip> tour_flips_;  ///< made on the WallTour, oldest first
  std::vector<Flip> view_flips_;  ///< made in the view only, after those
  std::vector<std::pair<int, int>> added_, removed_;
  std::vector<int> touched_;
};

}  // namespace ccbuild::planner::detail
