#pragma once
// Several nozzles on one layer (papers 000 §5-6 and 002 Part II). N gantries ride on
// common rails along one axis, keep their order and never come closer than the gantry
// width. The layout is cut across the rail axis into one section per nozzle (iterative
// dividing: cuts move until the sections' CC-TSP times agree), and the sections' paths
// are made collision-free by one of:
//   path-cycling         each section's closed tour is started elsewhere (cycled), nozzle
//                        after nozzle, backtracking when one has no cycle left (individual)
//   global-path-cycling  one CC-TSP tour of the whole layer cut into N contiguous pieces:
//                        of the balanced cuts, those lying furthest apart along the
//                        rails; then cycled
//   bz-path-cycling      a buffer zone at each inner border, built first; the working zone
//                        behind it is cycled against the neighbour's buffer
//   aux-buffer-zone      buffer zones, plus an auxiliary zone where a nozzle's buffer work
//                        would end before its right neighbour's; no cycling
//   delay                ours: the fastest of three alternatives: waits inserted where a
//                        nozzle must hold until its neighbour has moved away; nozzles
//                        taking turns (even, then odd); one nozzle working alone on its
//                        single-nozzle tour while the others park
//   auto                 the papers' order (path cycling, buffer zone path cycling,
//                        auxiliary buffer zone), then delay; when a papers' method is
//                        used and delay would be faster, the stage says so
// Every plan returned has passed the exact x/t check of every adjacent pair.
//
// Overhead platform: with a platform width, the layout is split into platform-wide
// stages along the rails; each stage is planned as above and the platform travels
// between them.

#include <optional>
#include <string>
#include <vector>

#include "ccbuild/floors/slice.hpp"
#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/planner/plan_layer.hpp"
#include "ccbuild/planner/status.hpp"
#include "ccbuild/planner/timeline.hpp"

namespace ccbuild::planner {

enum class MultiMethod {
  kAuto,
  kPathCycling,
  kGlobalPathCycling,
  kBufferZonePathCycling,
  kAuxBufferZone,
  kDelay
};
std::string to_string(MultiMethod method);
std::optional<MultiMethod> parse_multi_method(const std::string& text);

/// Most nozzles on one set of rails.
inline constexpr int kMaxNozzles = 16;

struct MultiNozzleOptions {
  int nozzles = 2;
  double gantry_width_m = 1.5;
  RailAxis rail_axis = RailAxis::kX;
  MultiMethod method = MultiMethod::kAuto;
  /// Overhead platform: the length along the rails the nozzles can reach at once.
  std::optional<double> platform_width_m;
  /// Metric, objective, seed, time limit (for the whole run) and kick budget of the
  /// single-nozzle planning of each section. Paths are closed tours; `bound` is ignored
  /// (the matching bound is used, as no single-nozzle bound is reported), and so is
  /// `neighbourhood` (2-opt/Or-opt is used).
  PlanOptions planning;
  /// Iterative dividing stops when (slowest - fastest) / mean section time is below this.
  double balance_tolerance = 0.05;
  int max_dividing_iterations = 12;
  /// Buffer zone width = this times the gantry width (must exceed the gantry width).
  double buffer_width_factor = 1.25;
  /// Cycle pairs checked by the cycling methods before they give up.
  long max_cycle_checks = 200000;
  /// The same layer's single-nozzle layer time when the caller already has it (several
  /// configurations of one layer); unset: planned here, for the comparison, unless
  /// `plan_single_nozzle_reference` is false.
  std::optional<double> single_nozzle_time_s;
  /// False: no one-nozzle reference is planned (MultiNozzlePlan::single_nozzle_time_s
  /// stays 0). It never changes the plan; a caller that does not show it saves a whole
  /// one-nozzle plan of the layer.
  bool plan_single_nozzle_reference = true;
  /// With `MultiMethod::kAuto`: also run the delay method after the papers' method that
  /// succeeded, to report when it would have been faster (`Stage::faster_delay_s`). It
  /// never changes the plan; a caller that does not show it saves that run.
  bool compare_with_delay = true;
  /// The unit lengths are given in in reasons and errors (planning itself is in metres):
  /// the user's own.
  floors::LengthUnit message_unit = floors::LengthUnit::kMeter;
};

/// One nozzle's share of one stage.
struct NozzlePath {
  int nozzle = 0;               ///< 0 = smallest rail coordinate
  double section_from_m = 0.0;  ///< its section along the rail axis
  double section_to_m = 0.0;
  floors::Layer layer;             ///< its walls (cut at the section borders)
  Sequence sequence;               ///< build order, indices into `layer`
  std::vector<std::string> zones;  ///< per step: "buffer", "auxiliary" or "working"
  int start_offset = 0;            ///< how far the working tour was cycled
  std::vector<double> wait_before_step_s;
  std::vector<double> step_start_s;  ///< when each step's wait (then air move) begins
  Evaluation evaluation;             ///< exact, without waits
  Timeline timeline;                 ///< with waits, from the stage's start (t = 0)
  /// Every breakpoint of its motion with waits, in layer time (the stage's start_s on).
  std::vector<Waypoint> waypoints;
  double finish_s = 0.0;  ///< when it is done (waits included), from the stage's start
  double wait_s = 0.0;
  double busy_s = 0.0;  ///< finish - waits
};

/// One method tried on a stage, and what came of it.
struct MethodAttempt {
  MultiMethod method = MultiMethod::kAuto;
  PlanStatus status;
  /// "path-cycling: solved", "bz-path-cycling: not-applicable: section 2 (...) is ...".
  std::string to_string() const;
};

/// One platform position (the whole layer when there is no platform).
struct Stage {
  double from_m = 0.0;  ///< extent along the rails
  double to_m = 0.0;
  double start_s = 0.0;  ///< when it begins in layer time (earlier stages and platform moves)
  PlanStatus status;     ///< solved when a method found a checked plan; else the last failure
  MultiMethod method = MultiMethod::kAuto;  ///< the method that produced this stage's plan
  std::string method_detail;                ///< e.g. "delay (odd/even turns)"
  std::vector<MethodAttempt> attempts;      ///< each method tried, in order
  /// auto only: when it used one of the papers' methods and delay would have finished the
  /// stage sooner, delay's time and how; auto still keeps the papers' plan.
  std::optional<double> faster_delay_s;
  std::string faster_delay_detail;
  std::vector<NozzlePath> nozzles;
  double time_s = 0.0;     ///< until the last nozzle finishes
  double min_gap_m = 0.0;  ///< smallest gap between adjacent gantries
  int vertex_count = 0;    ///< points of the stage's walls after cutting at sections
};

struct MultiNozzlePlan {
  /// Solved when every stage has a checked, collision-free plan; otherwise the first
  /// stage without one says why (kTimeLimit when the time limit came first).
  PlanStatus status;
  std::vector<Stage> stages;
  double platform_travel_s = 0.0;
  double layer_time_s = 0.0;    ///< stages + platform travel
  double machine_time_s = 0.0;  ///< sum of busy time over nozzles and stages
  int vertex_count = 0;
  double min_gap_m = 0.0;
  double single_nozzle_time_s = 0.0;  ///< the same layer planned for one nozzle (0: not planned)
};

/// Plans a layer for several nozzles, within `options.planning.time_limit_s` for the
/// whole call (once it has passed, the remaining work is cut short and the answer says
/// so). Throws InputError, naming the MultiNozzleOptions field, for parameters that
/// cannot work: fewer than 2 nozzles, non-positive widths, more nozzles than fit on the
/// machine's rails, a layout longer than the rails, a platform narrower than the nozzles
/// need. An answer without a collision-free plan is a value: a PlanStatus that says why.
MultiNozzlePlan plan_layer_multi(const floors::Layer& layer, const machine::MachineModel& machine,
                                 const MultiNozzleOptions& options);

}  // namespace ccbuild::planner
