#include "ccbuild/planner/plan_nozzles.hpp"

#include <algorithm>

#include "ccbuild/common/input_error.hpp"

namespace ccbuild::planner {

double LayerPlanResult::layer_time_s() const {
  if (single) return single->evaluation.layer_time_s;
  if (multi) return multi->layer_time_s;
  return 0.0;
}

double LayerPlanResult::max_idle_s() const {
  double idle = 0.0;
  if (single) idle = single->evaluation.max_idle_s;
  if (multi)
    for (const auto& stage : multi->stages)
      for (const auto& n : stage.nozzles) idle = std::max(idle, n.evaluation.max_idle_s);
  return idle;
}

int LayerPlanResult::idle_limit_violations() const {
  int count = 0;
  if (single) count = single->evaluation.idle_limit_violations;
  if (multi)
    for (const auto& stage : multi->stages)
      for (const auto& n : stage.nozzles) count += n.evaluation.idle_limit_violations;
  return count;
}

LayerPlanResult plan_layer_nozzles(const floors::Layer& layer, const machine::MachineModel& machine,
                                   const LayerPlanRequest& request) {
  LayerPlanResult out;
  out.nozzles = request.nozzles;
  if (request.nozzles < 1)
    throw InputError("", 0, "MultiNozzleOptions::nozzles", "must be at least 1");
  if (request.nozzles == 1) {
    out.single = plan_layer(layer, machine, request.planning);
    out.status = PlanStatus();
    return out;
  }
  MultiNozzleOptions multi = request.multi;
  multi.nozzles = request.nozzles;
  out.multi = plan_layer_multi(layer, machine, multi);
  out.status = out.multi->status;
  return out;
}

}  // namespace ccbuild::planner
