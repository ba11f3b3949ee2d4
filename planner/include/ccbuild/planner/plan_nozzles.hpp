#pragma once
// One layer planned with one nozzle or several: the single-nozzle CC-TSP (plan_layer.hpp)
// or the multi-nozzle planner (multi_nozzle.hpp), chosen by the nozzle count, with the
// figures both answer alike.

#include <optional>

#include "ccbuild/floors/slice.hpp"
#include "ccbuild/machine/machine_model.hpp"
#include "ccbuild/planner/multi_nozzle.hpp"
#include "ccbuild/planner/plan_layer.hpp"

namespace ccbuild::planner {

/// What to plan a layer with: one nozzle (planning), or several (multi, whose own
/// `nozzles` field is ignored in favour of `nozzles`).
struct LayerPlanRequest {
  int nozzles = 1;
  PlanOptions planning;
  MultiNozzleOptions multi;
};

struct LayerPlanResult {
  int nozzles = 1;
  std::optional<LayerPlan> single;       ///< nozzles == 1
  std::optional<MultiNozzlePlan> multi;  ///< nozzles >= 2
  PlanStatus status;                     ///< solved, or why no plan
  double layer_time_s() const;
  /// The longest air move of any nozzle, s, and how many exceed the idle limit.
  double max_idle_s() const;
  int idle_limit_violations() const;
};

/// Plans `layer` on `machine` with `request.nozzles` nozzles. Throws InputError (fields of
/// PlanOptions, PathSpec or MultiNozzleOptions) for options that cannot work.
LayerPlanResult plan_layer_nozzles(const floors::Layer& layer, const machine::MachineModel& machine,
                                   const LayerPlanRequest& request);

}  // namespace ccbuild::planner
