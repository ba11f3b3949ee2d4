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

double rail_coordinate(const Eigen::Vector2d& p, RailAxis axis);

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
/// `polish_kicks` of exact-time polish (unset: the options', else a short one).
Sequence closed_tour(const floors::Layer& layer, const std::vector<int>& segments,
                     const StageContext& ctx, std::optional<long> max_kicks = std::nullopt,
                     std::optional<long> polish_kicks = std::nullopt);

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

/// `paths` when they pass verify(); otherwise nullopt, with the problem in `why`.
std::optional<std::vector<NozzlePath>> checked(const StageContext& ctx,
                                               std::vector<NozzlePath> paths, std::string& why);

/// Finds one cycle per nozzle so that all adjacent pairs are collision-free: nozzle after
/// nozzle, backtracking when one has no cycle left that fits its left neighbour.
std::optional<std::vector<int>> compatible_cycles(const StageContext& ctx, const CutLayer& cut,
                                                  const std::vector<NozzleWork>& works,
                                                  std::string& why);

/// The methods: each returns paths that passed verify(), or nullopt with `why`.
std::optional<std::vector<NozzlePath>> path_cycling(const StageContext& ctx, std::string& why,
                                                    int& vertices);
std::optional<std::vector<NozzlePath>> global_path_cycling(const StageContext& ctx,
                                                           std::string& why, int& vertices);
std::optional<std::vector<NozzlePath>> buffer_zone_path_cycling(const StageContext& ctx,
                                                                std::string& why, int& vertices);
std::optional<std::vector<NozzlePath>> aux_buffer_zone(const StageContext& ctx, std::string& why,
                                                       int& vertices);
std::optional<std::vector<NozzlePath>> delay_method(const StageContext& ctx, std::string& why,
                                                    int& vertices, std::string& detail);

}  // namespace ccbuild::planner::detail
