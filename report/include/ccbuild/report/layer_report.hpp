#pragma once
// Reports of a planned layer: signed wall sequences, JSON (docs/json.md), SVG drawings.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "ccbuild/floors/slice.hpp"
#include "ccbuild/floors/units.hpp"
#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/planner/plan_layer.hpp"

namespace ccbuild::report {

/// Where a report's plan came from, and the unit its drawings speak.
struct ReportContext {
  std::string file;          ///< the user's FILE
  int floor = 0;             ///< 0 = ground
  std::optional<int> layer;  ///< unset: a lone plan with every wall whole
  std::uint64_t seed = 1;
  floors::LengthUnit unit = floors::LengthUnit::kMeter;  ///< of ticks, scale bar, titles
  /// "floor 0 layer 12", or "all walls whole".
  std::string where() const;
};

/// "12" for a whole wall traversed in its own direction, "-12" reversed; a wall cut into
/// pieces shows the piece, 1-based, as the JSON does: "12:2", "-12:1".
std::string signed_step(const floors::Layer& layer, const planner::Step& step);
/// The whole sequence, space-separated.
std::string signed_sequence(const floors::Layer& layer, const planner::Sequence& sequence);

/// The plan as one JSON object (docs/json.md): where it came from, the machine's limits,
/// the layer's pieces, the results, the sequence, the air moves and the waypoints.
nlohmann::ordered_json layer_plan_json(const ReportContext& context, const floors::Layer& layer,
                                       const machine::MachineModel& machine,
                                       const planner::LayerPlan& plan);

/// The connected bound's certificate as one JSON object (docs/json.md,
/// "plan-layer --bound-certificate"): the layer's points and walls and the bound's dual
/// moats, unrounded, so that tests/tools/check_bound.py (or anyone) can re-check the bound
/// without ccbuild. Throws std::logic_error when the plan kept no certificate
/// (PlanOptions::connected_bound.keep_certificate).
nlohmann::ordered_json bound_certificate_json(const ReportContext& context,
                                              const floors::Layer& layer,
                                              const planner::LayerPlan& plan);

/// An SVG drawing: axes and a scale bar in the user's unit, walls labelled with their
/// ids and arrowed in the deposition direction, air moves dashed on top (lifted ones
/// red), the start marked, a legend.
std::string layer_plan_svg(const ReportContext& context, const floors::Layer& layer,
                           const planner::LayerPlan& plan);

}  // namespace ccbuild::report
