#include "ccbuild/schedule/quantities.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace ccbuild::schedule {

namespace {
double width_of(double bead_width_m, double nozzle_width_m) {
  return bead_width_m > 0.0 ? bead_width_m : nozzle_width_m;
}
}  // namespace

double layer_volume_m3(const floors::Layer& layer, double nozzle_width_m, double height_m) {
  double volume_m3 = 0.0;
  for (const auto& s : layer.segments)
    volume_m3 += s.length_m * width_of(s.width_m, nozzle_width_m) * height_m;
  return volume_m3;
}

double peak_flow_m3_s(const std::vector<std::vector<planner::Waypoint>>& nozzles,
                      const floors::Layer& layer, double nozzle_width_m, double height_m) {
  std::map<std::pair<std::int64_t, int>, double> width_m;  // (wall, 1-based piece)
  for (const auto& s : layer.segments)
    width_m[{s.wall_id, s.piece + 1}] = width_of(s.width_m, nozzle_width_m);
  // Each extruding span adds its flow from its start to its end: sweep the changes.
  std::vector<std::pair<double, double>> changes;  // (time, +/- flow)
  for (const auto& path : nozzles)
    for (std::size_t k = 0; k + 1 < path.size(); ++k) {
      const auto &a = path[k], &b = path[k + 1];
      const double dt = b.t_s - a.t_s;
      if (!a.extruding || dt <= 0.0) continue;
      const auto it = width_m.find({a.wall, a.piece});
      const double w = it == width_m.end() ? nozzle_width_m : it->second;
      const double flow = (b.position_m - a.position_m).norm() / dt * w * height_m;
      changes.push_back({a.t_s, flow});
      changes.push_back({b.t_s, -flow});
    }
  // Ends before starts at the same time: a nozzle handing over is not counted twice.
  std::sort(changes.begin(), changes.end());
  double flow = 0.0, peak = 0.0;
  for (const auto& [t, d] : changes) {
    flow += d;
    peak = std::max(peak, flow);
  }
  return peak;
}

std::vector<Delivery> deliveries_of(const std::vector<ScheduledLayer>& layers, double batch_m3) {
  std::vector<Delivery> out;
  double used_m3 = 0.0, total_m3 = 0.0;
  for (const auto& l : layers) total_m3 += l.concrete_m3;
  if (total_m3 <= 0.0 || batch_m3 <= 0.0) return out;
  const auto count = static_cast<std::size_t>(std::ceil(total_m3 / batch_m3 - 1e-9));
  std::size_t k = 0;
  for (const auto& l : layers) {
    const double next_m3 = used_m3 + l.concrete_m3;
    // Every batch boundary this layer reaches (k batches used at the delivery's due time).
    while (k < count && k * batch_m3 <= next_m3 + 1e-12) {
      const double share = l.concrete_m3 > 0.0
                               ? std::clamp((k * batch_m3 - used_m3) / l.concrete_m3, 0.0, 1.0)
                               : 0.0;
      Delivery d;
      d.due_s = l.start_s + share * (l.end_s - l.start_s);
      d.m3 = std::min(batch_m3, total_m3 - k * batch_m3);
      d.floor = l.floor;
      d.layer = l.layer;
      out.push_back(d);
      ++k;
    }
    used_m3 = next_m3;
  }
  return out;
}

}  // namespace ccbuild::schedule
