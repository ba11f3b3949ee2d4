#include <limits>

#include "search_internal.hpp"

namespace ccbuild::planner::detail {

Sequence original_sequence(const std::vector<int>& segments) {
  Sequence out;
  out.reserve(segments.size());
  for (int s : segments) out.push_back({s, false});
  return out;
}

Sequence nearest_sequence(const CostModel& model, const std::vector<int>& segments,
                          const PathSpec& path) {
  Sequence out;
  if (segments.empty()) return out;
  const auto& layer = model.layer();
  std::vector<char> built(segments.size(), 0);
  Eigen::Vector2d here = path.start_m;
  std::size_t remaining = segments.size();
  if (path.closed) {
    out.push_back({segments[0], false});
    built[0] = 1;
    here = layer.end_m(layer.segments[segments[0]]);
    --remaining;
  }
  // Plain scan: exact for both metrics, and cheap next to planning (n^2 / 2 distances).
  while (remaining > 0) {
    double best = std::numeric_limits<double>::infinity();
    std::size_t best_k = 0;
    bool best_reversed = false;
    for (std::size_t k = 0; k < segments.size(); ++k) {
      if (built[k]) continue;
      const auto& s = layer.segments[segments[k]];
      const double to_start = model.distance_m(here, layer.start_m(s));
      const double to_end = model.distance_m(here, layer.end_m(s));
      if (to_start < best) {
        best = to_start;
        best_k = k;
        best_reversed = false;
      }
      if (to_end < best) {
        best = to_end;
        best_k = k;
        best_reversed = true;
      }
    }
    built[best_k] = 1;
    --remaining;
    const Step step{segments[best_k], best_reversed};
    out.push_back(step);
    here = model.step_end_m(step);
  }
  return out;
}

double exact_objective(const CostModel& model, const Sequence& sequence, const PathSpec& path,
                       Objective objective) {
  const Evaluation e = model.evaluate(sequence, path);
  return objective == Objective::kDistance ? e.airtime_distance_m : e.airtime_s;
}

}  // namespace ccbuild::planner::detail
