#pragma once
// Planning one layer for one nozzle: the CC-TSP tool path (papers 000 §4, 003 §5), the
// baselines it is compared with, and an exact solver for small layers.

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "ccbuild/floors/slice.hpp"
#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/planner/cost_model.hpp"
#include "ccbuild/planner/lower_bound.hpp"
#include "ccbuild/planner/termination.hpp"
#include "ccbuild/planner/timeline.hpp"
#include "ccbuild/planner/tool_path.hpp"

namespace ccbuild::planner {

enum class Algorithm {
  kCcTsp,     ///< two nodes per wall, chained local search (2-opt, Or-opt, kicks)
  kNearest,   ///< greedy: always to the nearest end of a wall not yet built
  kOriginal,  ///< walls in file order, each in its drawn direction
  kExact,     ///< dynamic programming over subsets; small layers only
};
std::string to_string(Algorithm algorithm);
std::optional<Algorithm> parse_algorithm(const std::string& text);

/// The local search of cc-tsp.
enum class Neighbourhood {
  /// Lin–Kernighan chains of 3-opt moves (for the time objective after 2-opt and Or-opt)
  kLinKernighan,
  kTwoOptOrOpt,  ///< 2-opt and Or-opt alone (the search before issue 14; a baseline)
};
std::string to_string(Neighbourhood neighbourhood);
std::optional<Neighbourhood> parse_neighbourhood(const std::string& text);

/// Largest layer the exact solver accepts (walls, i.e. segments): its tables grow as
/// 2^walls (16 walls: 75 MB for the time objective).
inline constexpr int kExactMaxSegments = 16;

/// How far cc-tsp's search has come: reported each time its best tour improves.
struct SearchProgress {
  double elapsed_s = 0.0;  ///< since plan_layer was called (the bound included)
  long kicks = 0;          ///< kicks done so far (0: the first local search)
  /// The search's cost of its best tour: airtime distance, m (or the time objective's
  /// approximation, s), without a fixed first wall's approach.
  double cost = 0.0;
  /// True: reported by the exact-time polish that follows the search under the time
  /// objective; `cost` is then the tour's exact airtime, s, and `kicks` the polish's.
  bool polish = false;
};

struct PlanOptions {
  Algorithm algorithm = Algorithm::kCcTsp;
  Metric metric = Metric::kEuclidean;
  Objective objective = Objective::kDistance;
  PathSpec path;
  Neighbourhood neighbourhood = Neighbourhood::kLinKernighan;
  /// Bounds the whole run, set-up included, s. The search also ends on its own when it
  /// proves optimality or spends its kick budget; only then is the answer independent of
  /// machine speed.
  double time_limit_s = 30.0;
  std::uint64_t seed = 1;
  /// Kicks of the chained local search; unset: the default budget, chosen from the
  /// layer's size (see `anytime`). When set, the search also never stops for lack of
  /// progress: it makes exactly this many kicks unless the time limit or a proof of
  /// optimality comes first.
  std::optional<long> max_kicks;
  /// True: no default budget. The search keeps improving until the time limit, a proof
  /// of optimality, or `max_kicks` when set. Its answer then depends on the machine's
  /// speed; the plan's `kicks`, given back as `max_kicks`, reproduces it exactly (unless
  /// the limit came during the first descent, before any kick). Under the time
  /// objective the symmetric search keeps its default budget and the exact-time polish
  /// kicks until the limit instead, without its step budget; the plan's `kicks` and
  /// `polish_kicks`, given back as `max_kicks` and `polish_kicks` (with `anytime`),
  /// reproduce that too (unless the limit came during the polish's first descent). The
  /// exact algorithm's warm start and plan_layer_multi ignore it: there the limit is a
  /// cap.
  bool anytime = false;
  /// Kicks of the exact-time polish after its descent (time objective only); unset: 500
  /// on layers of up to 16 walls (enough to reach the optimum the exact solver finds),
  /// 20 up to 200 walls, and above that 0, the descent alone; with `anytime`, until the
  /// time limit.
  std::optional<long> polish_kicks;
  /// False: no exact-time polish at all; the symmetric search's tour as it is.
  bool exact_polish = true;
  /// Lower bound reported (and used to stop the search once met): the connected bound
  /// by default; the matching bound alone is faster on very large layers.
  BoundKind bound = BoundKind::kConnected;
  /// Work limits of the connected bound, and whether to keep its dual solution
  /// (LayerPlan::connected_bound).
  ConnectedBoundLimits connected_bound;
  const std::atomic<bool>* cancel = nullptr;
  /// Called on the planning thread each time cc-tsp's best tour improves, in its search
  /// and then in the exact-time polish (SearchProgress::polish) (unset: not
  /// called). For progress displays and benchmarks; it must not throw.
  std::function<void(const SearchProgress&)> on_progress;
  /// False: no waypoints in the plan (a caller that keeps only the sequence, e.g. a
  /// section's tour inside the multi-nozzle planner).
  bool waypoints = true;
};

struct LayerPlan {
  Algorithm algorithm = Algorithm::kCcTsp;
  Metric metric = Metric::kEuclidean;
  Objective objective = Objective::kDistance;
  PathSpec path;
  Sequence sequence;                ///< every segment of the layer exactly once
  Evaluation evaluation;            ///< exact (CostModel::evaluate)
  std::vector<Waypoint> waypoints;  ///< the timed path (timeline.hpp), at the layer's top;
                                    ///< empty when PlanOptions::waypoints is false
  double lower_bound_m = 0.0;       ///< valid bound on airtime distance (see lower_bound.hpp)
  BoundSource lower_bound_source = BoundSource::kMatching;  ///< which bound it is
  int odd_points = 0;
  /// The connected bound's run (rounds, why it stopped, the certificate when kept);
  /// unset when it was not computed (BoundKind::kMatching, or no time for it).
  std::optional<ConnectedBound> connected_bound;
  double solve_s = 0.0;  ///< wall-clock time of the whole run
  double bound_s = 0.0;  ///< of which the lower bound, s
  StopReason stop = StopReason::kFinished;
  long kicks = 0;  ///< kicks tried by cc-tsp
  /// Kicks of the exact-time polish after its descent (time objective); unset: none ran.
  std::optional<long> polish_kicks;

  /// (airtime distance - bound) / bound; 0 when both are 0.
  double gap() const;
};

/// A sequence planned on one layer, replayed on another layer of the same geometry:
/// `matches` from floors::match_segments(planned layer, other layer). Each step goes to
/// the matching segment, in the direction that visits the same points in the same order,
/// so the replay costs exactly what the plan did.
Sequence map_sequence(const Sequence& sequence, const std::vector<floors::SegmentMatch>& matches);

/// A sequence ordered by the caller (every segment of the layer exactly once), timed
/// exactly as plan_layer times its own: its evaluation and, unless options.waypoints is
/// false, its waypoints. The scheduler uses it to make a layer follow the order of the
/// layer below. Only metric, objective, path and waypoints of `options` are used; the
/// algorithm is reported as given. Throws InternalError when a segment is missing or
/// repeated.
LayerPlan time_sequence(const floors::Layer& layer, const machine::MachineModel& machine,
                        const Sequence& sequence, const PlanOptions& options);

/// Plans a layer, within `options.time_limit_s` for the whole call. Throws InputError,
/// naming the PlanOptions or PathSpec field, for options that do not fit the layer (exact
/// on a large layer, a first wall that is not in it, a non-positive time limit), and for
/// a layer without walls (field `layer`).
LayerPlan plan_layer(const floors::Layer& layer, const machine::MachineModel& machine,
                     const PlanOptions& options);

}  // namespace ccbuild::planner
