#pragma once
// Reports of a planned layer: signed wall sequences, JSON, SVG drawings.

#include <nlohmann/json.hpp>
#include <string>

#include "ccbuild/floors/slice.hpp"
#include "ccbuild/planner/plan_layer.hpp"

namespace ccbuild::orchestrator {

/// "12" for a whole wall traversed in its own direction, "-12" reversed; a wall cut into
/// pieces by openings shows the piece, 1-based: "12:2", "-12:1".
std::string signed_step(const floors::Layer& layer, const planner::Step& step);
/// The whole sequence, space-separated.
std::string signed_sequence(const floors::Layer& layer, const planner::Sequence& sequence);

/// The plan as one JSON object (lengths in m, times in s, angles in rad).
nlohmann::ordered_json layer_plan_json(const floors::Layer& layer, const planner::LayerPlan& plan);

/// An SVG drawing: walls with arrows in the deposition direction, air moves dashed and
/// numbered (lifted ones in red), the start marked.
std::string layer_plan_svg(const floors::Layer& layer, const planner::LayerPlan& plan,
                           const std::string& title);

}  // namespace ccbuild::orchestrator
