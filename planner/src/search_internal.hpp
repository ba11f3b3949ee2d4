#pragma once
// Solvers behind plan_layer(), each over `segments` (layer segment indices) for a path
// that is closed, or open from `start` (a fixed first wall, when given, is already
// removed from `segments` by the caller and prepended to the answer).

#include <functional>
#include <optional>
#include <random>
#include <vector>

#include "ccbuild/planner/cost_model.hpp"
#include "ccbuild/planner/termination.hpp"
#include "ccbuild/planner/tool_path.hpp"

namespace ccbuild::planner::detail {

/// Largest layer whose time-objective tours get kicks in the exact-time polish (larger
/// ones get its descent alone) and the Lin–Kernighan search.
inline constexpr std::size_t kExactPolishKicksMaxSegments = 200;

/// Walls in the given order, each in its drawn direction.
Sequence original_sequence(const std::vector<int>& segments);

/// From the current point to the nearest end of any wall not yet built (ties: lowest
/// segment, its start before its end), then along it. A closed tour begins with the first
/// segment; an open path from `start`.
Sequence nearest_sequence(const CostModel& model, const std::vector<int>& segments,
                          const PathSpec& path);

/// The cheapest sequence of `objective` by dynamic programming over subsets, exact under
/// CostModel::evaluate (stopper state and lifts included). Here `segments` holds every
/// segment to deposit, a fixed first step (path.first) included. States at or above
/// `upper_bound` are pruned. Returns nullopt when stopped before finishing or when
/// nothing beats the bound.
std::optional<Sequence> exact_sequence(const CostModel& model, const std::vector<int>& segments,
                                       const PathSpec& path, Objective objective,
                                       double upper_bound, const StopCondition& stop);

struct ExactPolishSettings {
  std::size_t window = 8;  ///< how far (in positions) 2-opt and Or-opt reach
  long max_kicks = 20;
  /// Deterministic work bound: steps evaluated (one step = one move of one candidate).
  long max_step_evaluations = 4'000'000;
  /// Kicks followed by a descent around the kick only, not a whole pass (large layers,
  /// where a pass per kick leaves time for few kicks).
  bool local_kicks = false;
  /// Called after the first descent and each kick that finds a faster sequence, with
  /// the kicks done and its exact cost (unset: not called).
  std::function<void(long, double)> on_better;
};

struct ExactPolishOutcome {
  Sequence sequence;
  /// Kicks made after the first descent. A kick the clock (or a cancel) cuts off is
  /// dropped, not counted, so a polish stopped after K kicks returns what max_kicks = K
  /// does, with no time limit.
  long kicks = 0;
};

/// Improves a complete sequence under the exact time evaluation: rotations and reversal
/// of a closed tour, 2-opt (single flips included) and Or-opt within a window, then
/// kicks, until a budget is spent. `fixed_prefix` steps never move.
ExactPolishOutcome improve_exact_time(const CostModel& model, Sequence sequence,
                                      const PathSpec& path, std::size_t fixed_prefix,
                                      const ExactPolishSettings& settings, std::mt19937_64& rng,
                                      const StopCondition& stop);

/// The value the solvers minimise, exactly: airtime distance or airtime seconds.
double exact_objective(const CostModel& model, const Sequence& sequence, const PathSpec& path,
                       Objective objective);

}  // namespace ccbuild::planner::detail
