#pragma once
// Internals of the CC-TSP solver. Each wall piece ("item") becomes two nodes, its two
// ends; the edge between them is fixed (the papers' -M edge), every other pair costs the
// air move between them. A tour is an array of items, each traversed forwards or
// backwards, so the fixed edges can never be broken: 2-opt reverses whole items and
// Or-opt moves whole items.
//
// Open paths add a depot item whose one node sits at the start point and whose other
// node (the free end) costs nothing to reach from anywhere, so the tour read from the
// depot is the path, and its return is free.

#include <cstdint>
#include <functional>
#include <optional>
#include <random>
#include <utility>
#include <vector>

#include "ccbuild/planner/cost_model.hpp"
#include "ccbuild/planner/plan_layer.hpp"
#include "ccbuild/planner/termination.hpp"
#include "ccbuild/planner/tool_path.hpp"
#include "geometry.hpp"

namespace ccbuild::planner::detail {

/// Symmetric air-move costs between item ends, approximating the time model where it is
/// sequence-dependent: rotation ignores the stopper's state, and no move is priced as
/// lifted (the exact-time polish deals with lifts).
class TourCosts {
 public:
  /// `segments` are the layer segments to order. For open paths, the depot sits at
  /// `start`, facing `start_heading` when given (a fixed first wall) or free to turn.
  TourCosts(const CostModel& model, std::vector<int> segments, Objective objective, bool open,
            const Vec2& start, std::optional<Vec2> start_heading);

  int item_count() const { return item_count_; }  ///< segments, plus the depot if open
  bool has_depot() const { return has_depot_; }
  int depot() const { return static_cast<int>(segments_.size()); }
  int segment_of(int item) const { return segments_[item]; }
  /// The item of a layer segment, -1 when the segment is not part of this tour.
  int item_of_segment(int segment) const { return item_of_segment_[segment]; }
  const Vec2& position(int node) const { return position_[node]; }
  bool is_free(int node) const { return has_depot_ && node == 2 * depot(); }

  /// Inline: the searches ask for millions of costs, most of them distances.
  double cost(int u, int v) const {
    if (is_free(u) || is_free(v)) return 0.0;
    if (objective_ == Objective::kDistance)
      return metric_distance_m(metric_, position_[u], position_[v]);
    // Time costs are remembered: the searches ask for the same pairs again and again
    // (tour edges, candidates), and a time cost has a root and an arc cosine.
    const std::uint64_t key = (static_cast<std::uint64_t>(u) << 32) | static_cast<std::uint32_t>(v);
    CachedCost& slot = cache_[(key * 0x9E3779B97F4A7C15ull) >> cache_shift_];
    if (slot.key != key) slot = {key, time_cost(u, v)};
    return slot.value;
  }
  /// Neighbour candidates of a node, cheapest first (the free end, if any, first of all).
  const std::vector<int>& neighbours(int node) const { return neighbours_[node]; }
  void build_neighbours(int k);

 private:
  const CostModel& model_;
  std::vector<int> segments_;
  std::vector<int> item_of_segment_;
  Objective objective_;
  Metric metric_;
  bool has_depot_;
  int item_count_;
  std::vector<Vec2> position_;
  std::vector<Vec2> arrive_;  ///< unit heading arriving at a node along its wall (0: free to turn)
  std::vector<std::vector<int>> neighbours_;
  struct CachedCost {
    std::uint64_t key = ~std::uint64_t{0};
    double value = 0.0;
  };
  mutable std::vector<CachedCost> cache_;  ///< direct-mapped; not thread-safe
  int cache_shift_ = 64;
  double time_cost(int u, int v) const;
};

/// A cyclic order of items, each with a direction.
class WallTour {
 public:
  WallTour() = default;
  /// Items in `order`, `reversed[item]` for each item.
  WallTour(std::vector<int> order, std::vector<char> reversed);

  int size() const { return static_cast<int>(node_at_.size()); }
  int item_at(int position) const { return node_at_[position] >> 1; }
  int position_of(int item) const { return where_[item]; }
  bool reversed(int item) const { return (node_at_[where_[item]] & 1) != 0; }
  int entry(int position) const { return node_at_[position]; }
  int exit(int position) const { return node_at_[position] ^ 1; }
  int next(int position) const { return position + 1 == size() ? 0 : position + 1; }
  int prev(int position) const { return position == 0 ? size() - 1 : position - 1; }

  /// Reverses the cyclic range first..last (positions) and the direction of its items;
  /// reverses the complement instead when that is shorter (same tour, other way round).
  void reverse(int first, int last);
  /// Moves the `length` items from position `first` to just after position `after`
  /// (outside them), reversed or not.
  void move_block(int first, int length, int after, bool reversed);

  double cost(const TourCosts& costs) const;

  /// From now on, remembers what changes, so that undo_journal() can return to now.
  void begin_journal();
  /// Keeps the changes and stops remembering.
  void commit_journal();
  /// Returns to the tour at begin_journal() and stops remembering.
  void undo_journal();

 private:
  /// Puts `node` (an item's entry node) at `position`.
  void write(int position, int node);
  /// Reverses `length` positions from `first` (cyclic) and turns each item round; not
  /// journaled (reverse() is).
  void flip(int first, int length);

  /// The entry node at each position: 2 * item, +1 when the item runs reversed. One
  /// array for order and direction keeps a flip to one pass of swaps (flips are most of
  /// the search's time on large layers).
  std::vector<int> node_at_;
  std::vector<int> where_;  ///< position of each item
  std::vector<int> scratch_;
  bool journaling_ = false;
  /// Oldest first: (position, node it held) for a write, (-1 - first, length) for a
  /// flip, which undoes itself.
  std::vector<std::pair<int, int>> log_;
};

struct SearchSettings {
  Neighbourhood neighbourhood = Neighbourhood::kLinKernighan;
  int lk_depth = 10;  ///< steps of one Lin–Kernighan chain (3-opt moves each)
  /// With Lin–Kernighan: run 2-opt and Or-opt before each LK pass. LK's own first steps
  /// are those moves, and on distance the extra pass only cost time (and 0.2% of
  /// length on scattered segments); the time objective still gains from it (without it
  /// 0.45% more airtime on 98-wall plans, from 6.3% less to 12.6% more per plan;
  /// bench/README.md).
  bool two_opt_before_lk = false;
  long max_kicks = 0;
  long stall_kicks = 0;  ///< stop after this many kicks without improvement
  /// After this many kicks in a row without a better tour, a restart: a search of its
  /// own from `restart_tour` (at most `restart_kicks` kicks, ending after
  /// `restart_own_stall_kicks` without a better tour), whose better parts are then
  /// merged into the best tour (tour_merge.hpp). A restart counts as one kick plus its
  /// own. 0: never.
  long restart_stall_kicks = 0;
  long restart_kicks = 0;
  long restart_own_stall_kicks = 0;
  std::function<WallTour(std::mt19937_64&)> restart_tour;
  std::uint64_t seed = 1;
  /// Stop as soon as the cost reaches this (a lower bound), when set.
  std::optional<double> target_cost;
  /// Called with (kicks, cost) when the best tour improves.
  std::function<void(long, double)> on_better;
};

struct SearchOutcome {
  WallTour tour;
  double cost = 0.0;
  long kicks = 0;
  StopReason reason = StopReason::kConverged;
  long restarts = 0;           ///< restarts finished
  long kicks_in_restarts = 0;  ///< of `kicks`, those the restarts' own searches made
  double restart_gain = 0.0;   ///< what merging them (and the descents after) gained
};

/// Chained local search: 2-opt and Or-opt (blocks of 1-3 items) driven by neighbour
/// lists and don't-look bits, or, with Neighbourhood::kLinKernighan, Lin–Kernighan
/// chains (lin_kernighan.hpp; after 2-opt and Or-opt with `two_opt_before_lk`); then
/// kicks (double bridges, local or between places close in the plan) each followed by
/// the same local search, keeping the best tour.
SearchOutcome chained_local_search(const TourCosts& costs, WallTour tour,
                                   const SearchSettings& settings, const StopCondition& stop);

/// An initial tour: the T-join of odd points (minimum matching), components joined by
/// doubled shortest links, then an Euler walk whose choices follow the current heading.
/// `segments` and the path are as in TourCosts.
/// With `variation`, another start for a restart: the odd points are matched as if each
/// lay up to 10 cm off (so matchings of nearly equal cost come out otherwise) and each
/// point's next wall is drawn at random (so the walls meeting at a point join otherwise).
Sequence euler_construction(const CostModel& model, const std::vector<int>& segments, bool open,
                            const Vec2& start, std::optional<Vec2> start_heading,
                            std::mt19937_64* variation = nullptr);

/// Tour <-> sequence, for the items of `costs`.
WallTour tour_from_sequence(const TourCosts& costs, const Sequence& sequence);
Sequence sequence_from_tour(const TourCosts& costs, const WallTour& tour);

}  // namespace ccbuild::planner::detail
