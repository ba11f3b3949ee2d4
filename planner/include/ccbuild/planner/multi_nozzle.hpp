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

struct MultiNozzleOptions {
  int nozzles = 2;
  double gantry_width_m = 1.5;
  RailAxis rail_axis = RailAxis::kX;
  MultiMethod method = MultiMethod::kAuto;
  /// Overhead platform: the length along the rails the nozzles can reach at once.
  std::optional<double> platform_width_m;
  /// Metric, objective, seed, time limit (for the whole run) and kick budget of the
  /// single-nozzle planning of each section. Paths are closed tours; `bound` is ignored
  /// (the matching bound is used, as no single-nozzle bound is reported).
  PlanOptions planning;
  /// Iterative dividing stops when (slowest - fastest) / mean section time is below this.
  double balance_tolerance = 0.05;
  int max_dividing_iterations = 12;
  /// Buffer zone width = this times the gantry width (must exceed the gantry width).
  double buffer_width_factor = 1.25;
  /// Cycle pairs checked by the cycling methods before they give up.
  long max_cycle_checks = 200000;
  /// The same layer's single-nozzle layer time when the caller already has it (several
  /// configurations of one layer); unset: planned here, for the comparison.
  std::optional<double> single_nozzle_time_s;
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
  Timeline timeline;                 ///< with waits
  double finish_s = 0.0;             ///< when it is done (waits included)
  double wait_s = 0.0;
  double busy_s = 0.0;  ///< finish - waits
};

/// One platform position (the whole layer when there is no platform).
struct Stage {
  double from_m = 0.0;  ///< extent along the rails
  double to_m = 0.0;
  MultiMethod method = MultiMethod::kAuto;  ///< the method that produced this stage's plan
  std::string method_detail;                ///< e.g. "delay (odd/even turns)"
  std::vector<std::string> attempts;        ///< each method tried, and why it failed
  /// auto only: when it used one of the papers' methods and delay would have finished the
  /// stage sooner, delay's time (also said in `attempts`); auto still keeps the papers' plan.
  std::optional<double> faster_delay_s;
  std::vector<NozzlePath> nozzles;
  double time_s = 0.0;     ///< until the last nozzle finishes
  double min_gap_m = 0.0;  ///< smallest gap between adjacent gantries
  int vertex_count = 0;    ///< points of the stage's walls after cutting at sections
};

struct MultiNozzlePlan {
  bool collision_free = false;  ///< a plan was found (and checked) for every stage
  std::string failure;          ///< why not, when not
  std::vector<Stage> stages;
  double platform_travel_s = 0.0;
  double layer_time_s = 0.0;    ///< stages + platform travel
  double machine_time_s = 0.0;  ///< sum of busy time over nozzles and stages
  int vertex_count = 0;
  double min_gap_m = 0.0;
  double single_nozzle_time_s = 0.0;  ///< the same layer planned for one nozzle
};

/// Plans a layer for several nozzles. Throws InputError for parameters that cannot work:
/// fewer than 2 nozzles, non-positive widths, more nozzles than fit on the machine's rails,
/// a platform narrower than the nozzles need. An answer without a collision-free plan
/// (the method failed) is a value: collision_free = false with the reason.
MultiNozzlePlan plan_layer_multi(const floors::Layer& layer, const machine::MachineModel& machine,
                                 const MultiNozzleOptions& options);

}  // namespace ccbuild::planner
