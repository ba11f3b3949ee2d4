#pragma once
// Internals of multi-nozzle planning, shared by its source files.

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ccbuild/common/input_error.hpp"
#include "ccbuild/planner/multi_nozzle.hpp"

namespace ccbuild::planner::detail {

/// A length for reasons and errors, in the user's unit: "2.80 m", "9.19 ft".
inline std::string length(const MultiNozzleOptions& options, double value_m) {
  return floors::length_text(value_m, options.message_unit, 2);
}

/// Everything a method needs about one stage.
struct StageContext {
  const machine::MachineModel& machine;
  const MultiNozzleOptions& options;
  const StopCondition& stop;
  floors::Layer layer;  ///< the stage's walls (uncut by sections)
  double from_m = 0.0;  ///< extent of the stage's walls along the rails
  double to_m = 0.0;
  double rail_min_m = 0.0;  ///< where gantry centres may go
  double rail_max_m = 0.0;
  /// Computed once per stage and shared by the methods auto tries in turn.
  mutable std::shared_ptr<const struct Division> division;
  mutable std::shared_ptr<const struct Sections> sections;
};

/// A layer cut across the rail axis at `cuts` (ascending): every wall crossing a cut is
/// split there. `band[s]` is the band (0 .. cuts.size()) segment s lies in; a wall on a
/// cut line belongs to the band below it.
struct CutLayer {
  floors::Layer layer;
  std::vector<int> band;
  std::vector<int> segments_in(int b) const;
  std::vector<int> segments_in(int first_band, int last_band) const;
};
CutLayer cut_layer(const floors::Layer& layer, RailAxis axis, const std::vector<double>& cuts);

/// A closed CC-TSP tour of some segments of `layer` (indices into `layer`), with the
/// stage's planning options, at most `max_kicks` kicks (unset: the default budget) and
/// a short exact-time polish (the options' kicks when set; `polish` false: none). Once the
/// stage's time is up, the segments in their given order (no search), so that what is
/// left of the call ends at once.
Sequence closed_tour(const floors::Layer& layer, const std::vector<int>& segments,
                     const StageContext& ctx, std::optional<long> max_kicks = std::nullopt,
                     bool polish = true);

/// Cuts chosen by iterative dividing (the section borders, nozzles - 1 of them).
struct Division {
  std::vector<double> cuts;
  std::vector<double> section_time_s;
  int iterations = 0;
};
/// The stage's division (computed on first use).
const Division& divide(const StageContext& ctx);

/// A candidate plan for the stage: per nozzle, its section and its order of work as
/// blocks (zones) of segments of `cut.layer`; the working block may be cycled.
struct NozzleWork {
  double from_m = 0.0, to_m = 0.0;
  std::vector<int> section_segments;   ///< indices into cut.layer
  std::vector<Sequence> fixed_blocks;  ///< built first, in order (buffer, auxiliary)
  std::vector<std::string> fixed_names;
  Sequence working;  ///< the cycled block (closed tour)
};

/// Sections from iterative dividing, each with its closed CC-TSP tour.
struct Sections {
  Division division;
  CutLayer cut;
  std::vector<NozzleWork> works;
};
/// The stage's sections (computed on first use).
const Sections& sections_of(const StageContext& ctx);

// A section's walls as their own layer, and the map from cut-layer index to local index.
struct SectionModel {
  floors::Layer layer;
  std::vector<int> local_of;  // by cut-layer segment; -1 when not in the section
  std::unique_ptr<CostModel> model;

  SectionModel(const StageContext& ctx, const CutLayer& cut, const std::vector<int>& segments)
      : layer(floors::sub_layer(cut.layer, segments)), local_of(cut.layer.segments.size(), -1) {
    for (std::size_t i = 0; i < segments.size(); ++i) local_of[segments[i]] = static_cast<int>(i);
    if (!segments.empty())
      model = std::make_unique<CostModel>(layer, ctx.machine, ctx.options.planning.metric);
  }
  Sequence local(const Sequence& s) const {
    Sequence out;
    out.reserve(s.size());
    for (const Step& step : s) {
      CCBUILD_CHECK(local_of[step.segment] >= 0, "a nozzle only builds walls of its section");
      out.push_back({local_of[step.segment], step.reversed});
    }
    return out;
  }
};

/// A nozzle's work in order: its fixed blocks, then its working tour started at step
/// `cycle`.
Sequence concatenated(const NozzleWork& work, int cycle);

/// When the last nozzle of a stage finishes, s.
double stage_time_s(const std::vector<NozzlePath>& paths);

/// Turns works into nozzle paths with given working-tour cycles and waits; computes
/// timelines. Empty sections park at their middle.
std::vector<NozzlePath> build_paths(const StageContext& ctx, const CutLayer& cut,
                                    const std::vector<NozzleWork>& works,
                                    const std::vector<int>& cycles,
                                    const std::vector<std::vector<double>>& waits = {});

/// Checks every adjacent pair exactly and each gantry's reach. Returns the first problem
/// (empty when none) and the smallest gap.
std::string verify(const StageContext& ctx, const std::vector<NozzlePath>& paths, double& min_gap);

/// What a method (or a step of one) came to: paths that passed verify() when solved.
struct MethodResult {
  PlanStatus status;
  std::vector<NozzlePath> paths;
  int vertices = 0;    ///< points of the stage's walls after the method's cuts
  std::string detail;  ///< how it succeeded, e.g. "delay (3 waits, 12.0 s in all)"
};

/// Solved with `paths` when they pass verify(); otherwise a collision with the problem.
MethodResult checked(const StageContext& ctx, std::vector<NozzlePath> paths);

/// kTimeLimit or kCancelled when the stage's stop condition says so, else solved.
PlanStatus stop_status(const StageContext& ctx, const std::string& during);

/// One cycle per nozzle so that all adjacent pairs are collision-free: nozzle after
/// nozzle, backtracking when one has no cycle left that fits its left neighbour.
struct CycleSearch {
  PlanStatus status;
  std::vector<int> cycles;
};
CycleSearch compatible_cycles(const StageContext& ctx, const CutLayer& cut,
                              const std::vector<NozzleWork>& works);

/// The methods: each returns paths that passed verify(), or a status that says why not.
MethodResult path_cycling(const StageContext& ctx);
MethodResult global_path_cycling(const StageContext& ctx);
MethodResult buffer_zone_path_cycling(const StageContext& ctx);
MethodResult aux_buffer_zone(const StageContext& ctx);
MethodResult delay_method(const StageContext& ctx);

}  // namespace ccbuild::planner::detail
