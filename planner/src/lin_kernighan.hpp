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
// one never added back.

#include <utility>
#include <vector>

#include "cc_tsp.hpp"
#include "item_queue.hpp"

namespace ccbuild::planner::detail {

class LinKernighan {
 public:
  LinKernighan(const TourCosts& costs, WallTour& tour, int max_depth);

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
  bool is_entry(int node) const;
  int suc(int node) const;
  int pred(int node) const;
  /// The node across this node's free edge.
  int free_neighbour(int node) const;
  /// Position of `node` in the node-level walk (0 .. 2n-1).
  int index(int node) const;
  /// Whether b lies on the walk from a to c (inclusive), walking forwards or backwards.
  bool between(bool forwards, int a, int b, int c) const;

  /// Removes (a, b) and (c, d), adds (b, c) and (d, a). Needs the walk a, b, ..., d, c
  /// in one of the two directions; reverses b .. d.
  void make_2opt(int a, int b, int c, int d);
  void undo_chain();

  bool improve_from(int t1, double& gain);
  /// The chain's next step from (t1, t2): a closing move with a gain is made at once;
  /// otherwise, unless `last`, the best open step is made.
  Step best_step(int t1, int t2, double open_gain, bool last);

  bool was_added(int u, int v) const;
  bool was_removed(int u, int v) const;

  const TourCosts& costs_;
  WallTour& tour_;
  int max_depth_;
  ItemQueue queue_;  ///< items whose ends are still to be tried
  // The chain being built from one t1.
  struct Flip {
    int a, b, c, d;
  };
  std::vector<Flip> flips_;
  std::vector<std::pair<int, int>> added_, removed_;
  std::vector<int> touched_;
};

}  // namespace ccbuild::planner::detail
