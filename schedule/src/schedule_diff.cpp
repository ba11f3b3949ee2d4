#include "ccbuild/schedule/schedule_diff.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "ccbuild/common/format.hpp"
#include "ccbuild/schedule/json_blocks.hpp"

namespace ccbuild::schedule {
namespace {

/// A number as the schedule's JSON writes it ("null" when unset).
std::string text(std::optional<double> value) {
  return value ? nlohmann::json(*value).dump() : "null";
}
std::string text(int value) {
  return std::to_string(value);
}

std::string hours(double s) {
  return std::isfinite(s) ? printf_string("%.1f s (%.2f h)", s, s / 3600.0) : "null";
}

std::string layer_name(const ScheduledLayer& l) {
  return "floor " + std::to_string(l.floor) + " layer " + std::to_string(l.layer);
}

bool same_waypoints(const std::vector<planner::Waypoint>& a,
                    const std::vector<planner::Waypoint>& b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                    [](const planner::Waypoint& x, const planner::Waypoint& y) {
                      return x.t_s == y.t_s && x.position_m == y.position_m && x.z_m == y.z_m &&
                             x.heading_rad == y.heading_rad && x.extruding == y.extruding &&
                             x.wall == y.wall && x.piece == y.piece;
                    });
}

/// A plan's paths as digests (those it keeps, or those of its waypoints).
std::vector<PathDigest> digests_of(const SchedulePlan& plan) {
  if (!plan.digests.empty()) return plan.digests;
  std::vector<PathDigest> out;
  for (const auto& path : plan.waypoints) out.push_back(path_digest(path));
  return out;
}

bool same_plan(const SchedulePlan& a, const SchedulePlan& b) {
  if (a.geometry != b.geometry || a.nozzles != b.nozzles || a.method != b.method ||
      a.z_top_m != b.z_top_m || a.layer_time_s != b.layer_time_s || a.min_gap_m != b.min_gap_m ||
      a.layer.segments.size() != b.layer.segments.size())
    return false;
  for (std::size_t k = 0; k < a.layer.segments.size(); ++k) {
    const auto &s = a.layer.segments[k], &t = b.layer.segments[k];
    if (s.wall_id != t.wall_id || s.piece != t.piece || s.piece_count != t.piece_count ||
        s.length_m != t.length_m || s.role != t.role || s.width_m != t.width_m ||
        a.layer.start_m(s) != b.layer.start_m(t) || a.layer.end_m(s) != b.layer.end_m(t))
      return false;
  }
  // A golden may keep its paths' digests only: then the digests are compared.
  if (!a.digests.empty() || !b.digests.empty()) return digests_of(a) == digests_of(b);
  if (a.waypoints.size() != b.waypoints.size()) return false;
  for (std::size_t n = 0; n < a.waypoints.size(); ++n)
    if (!same_waypoints(a.waypoints[n], b.waypoints[n])) return false;
  return true;
}

}  // namespace

bool DiffTolerance::allows(std::optional<double> old_value, std::optional<double> new_value) const {
  if (!old_value || !new_value) return old_value.has_value() == new_value.has_value();
  return std::abs(*new_value - *old_value) <=
         std::max(absolute_s, relative * std::abs(*old_value)) + 1e-9;
}

ScheduleDiff diff_schedules(const ScheduleDocument& old_doc, const ScheduleDocument& new_doc,
                            const DiffTolerance& tol, int shown) {
  const Schedule& a = old_doc.schedule;
  const Schedule& b = new_doc.schedule;
  ScheduleDiff out;
  if (a.feasible != b.feasible)
    out.changes.push_back(std::string("feasible: ") + (a.feasible ? "yes" : "no") + " -> " +
                          (b.feasible ? "yes" : "no") +
                          (b.infeasibility ? " (" + b.infeasibility->message + ")" : ""));
  // Inputs: checksums tell whether the same files went in.
  std::map<std::string, std::string> old_files, new_files;
  for (const auto& f : old_doc.inputs.files) old_files[f.path] = f.sha256;
  for (const auto& f : new_doc.inputs.files) new_files[f.path] = f.sha256;
  for (const auto& [path, sum] : new_files) {
    const auto it = old_files.find(path);
    if (it == old_files.end())
      out.notes.push_back("input " + path + " is new");
    else if (it->second != sum)
      out.notes.push_back("input " + path + " changed (SHA-256 " + it->second.substr(0, 12) +
                          " -> " + sum.substr(0, 12) + ")");
  }
  for (const auto& [path, sum] : old_files)
    if (!new_files.count(path)) out.notes.push_back("input " + path + " is no longer read");
  // Placement: every coordinate moves with it, so a change is a change of the paths.
  const Placement &pa = old_doc.inputs.placement, &pb = new_doc.inputs.placement;
  if (pa.how != pb.how || pa.origin_m != pb.origin_m || pa.rotation_rad != pb.rotation_rad)
    out.changes.push_back(printf_string(
        "placement: %s, origin (%.3f, %.3f) m, %.2f deg -> %s, origin (%.3f, %.3f) m, %.2f deg",
        to_string(pa.how).c_str(), pa.origin_m.x(), pa.origin_m.y(), pa.rotation_rad * 180.0 / M_PI,
        to_string(pb.how).c_str(), pb.origin_m.x(), pb.origin_m.y(),
        pb.rotation_rad * 180.0 / M_PI));

  // Totals.
  const auto total = [&](const char* key, double x, double y) {
    if (x == y) return;
    const std::string line = std::string("totals.") + key + ": " + hours(x) + " -> " + hours(y) +
                             (std::isfinite(x) && std::isfinite(y) && x != 0
                                  ? printf_string(" (%+.2f%%)", 100.0 * (y - x) / x)
                                  : "");
    (tol.allows(x, y) ? out.notes : out.changes).push_back(line);
  };
  const ScheduleTotals &ta = a.totals, &tb = b.totals;
  total("makespan_s", ta.makespan_s, tb.makespan_s);
  if (a.layers.size() != b.layers.size())
    out.changes.push_back(
        printf_string("totals.layers: %zu -> %zu", a.layers.size(), b.layers.size()));
  total("deposition_s", ta.deposition_s, tb.deposition_s);
  total("airtime_s", ta.airtime_s, tb.airtime_s);
  total("moves_s", ta.moves_s, tb.moves_s);
  total("waits_s", ta.waits_s, tb.waits_s);
  total("pipes_s", ta.pipes_s, tb.pipes_s);
  total("purges_s", ta.purges_s, tb.purges_s);
  total("climbs_s", ta.climbs_s, tb.climbs_s);
  total("slabs_s", ta.slabs_s, tb.slabs_s);
  total("machine_s", ta.machine_s, tb.machine_s);
  total("joints_s", ta.joints_s, tb.joints_s);
  // Concrete is no time: any change is one.
  if (std::abs(ta.concrete_m3 - tb.concrete_m3) > 1e-6)
    out.changes.push_back(
        printf_string("totals.concrete_m3: %.3f -> %.3f", ta.concrete_m3, tb.concrete_m3));
  if (a.deliveries.size() != b.deliveries.size())
    out.changes.push_back(
        printf_string("deliveries: %zu -> %zu", a.deliveries.size(), b.deliveries.size()));

  // Per floor: its span, nozzles and waits.
  struct FloorSummary {
    double start_s = INFINITY, end_s = -INFINITY, waits_s = 0;
    int layers = 0, max_nozzles = 0;
  };
  auto floors_of = [](const Schedule& s) {
    std::map<int, FloorSummary> f;
    for (const auto& l : s.layers) {
      FloorSummary& x = f[l.floor];
      x.start_s = std::min(x.start_s, l.start_s);
      x.end_s = std::max(x.end_s, l.end_s);
      x.waits_s += l.wait_before_s;
      x.layers += 1;
      x.max_nozzles = std::max(x.max_nozzles, l.nozzles);
    }
    return f;
  };
  const auto fa = floors_of(a), fb = floors_of(b);
  for (const auto& [floor, x] : fa) {
    const auto it = fb.find(floor);
    if (it == fb.end()) {
      out.changes.push_back("floor " + std::to_string(floor) + ": no longer scheduled");
      continue;
    }
    const FloorSummary& y = it->second;
    const double dx = x.end_s - x.start_s, dy = y.end_s - y.start_s;
    if (x.layers != y.layers || x.max_nozzles != y.max_nozzles || !tol.allows(dx, dy) ||
        !tol.allows(x.waits_s, y.waits_s))
      out.changes.push_back(printf_string(
          "floor %d: %d -> %d layers, up to %d -> %d nozzles, %s -> %s from first start to last "
          "end, waits %s -> %s",
          floor, x.layers, y.layers, x.max_nozzles, y.max_nozzles, hours(dx).c_str(),
          hours(dy).c_str(), hours(x.waits_s).c_str(), hours(y.waits_s).c_str()));
  }
  for (const auto& [floor, y] : fb)
    if (!fa.count(floor)) out.changes.push_back("floor " + std::to_string(floor) + ": new");

  // Layers, matched by floor and layer.
  std::map<std::pair<int, int>, const ScheduledLayer*> new_layers;
  for (const auto& l : b.layers) new_layers[{l.floor, l.layer}] = &l;
  for (const auto& l : a.layers) {
    const auto it = new_layers.find({l.floor, l.layer});
    std::string what;
    const auto add = [&what](const std::string& key, const std::string& from,
                             const std::string& to) {
      what += (what.empty() ? "" : ", ") + key + " " + from + " -> " + to;
    };
    if (it == new_layers.end()) {
      what = "only in the old schedule";
    } else {
      const ScheduledLayer& m = *it->second;
      new_layers.erase(it);
      if (l.nozzles != m.nozzles) add("nozzles", text(l.nozzles), text(m.nozzles));
      if (l.plan != m.plan) add("plan", l.plan, m.plan);
      if (l.method != m.method) add("method", l.method, m.method);
      if (l.geometry != m.geometry) add("geometry", text(l.geometry), text(m.geometry));
      const std::pair<const char*, std::pair<std::optional<double>, std::optional<double>>>
          times[] = {{"start_s", {l.start_s, m.start_s}},
                     {"end_s", {l.end_s, m.end_s}},
                     {"wait_before_s", {l.wait_before_s, m.wait_before_s}},
                     {"local_interval_min_s", {l.local_interval_min_s, m.local_interval_min_s}},
                     {"local_interval_max_s", {l.local_interval_max_s, m.local_interval_max_s}}};
      for (const auto& [key, values] : times)
        if (!tol.allows(values.first, values.second))
          add(key, text(values.first), text(values.second));
    }
    if (what.empty()) continue;
    if (++out.differing_layers <= shown) out.changes.push_back(layer_name(l) + ": " + what);
  }
  for (const auto& [key, l] : new_layers)
    if (++out.differing_layers <= shown)
      out.changes.push_back(layer_name(*l) + ": only in the new schedule");
  if (out.differing_layers > shown)
    out.changes.push_back(printf_string("... %d differing layers in all", out.differing_layers));

  // Plans, by key: those in one schedule only, and those whose timed paths differ.
  const auto plan_change = [&](const std::string& line) {
    if (++out.differing_plans <= shown) out.changes.push_back(line);
  };
  for (const auto& [key, p] : a.plans) {
    const auto it = b.plans.find(key);
    if (it == b.plans.end())
      plan_change("plan " + key + ": only in the old schedule");
    else if (!same_plan(p, it->second))
      plan_change("plan " + key + ": its timed paths differ");
  }
  for (const auto& [key, p] : b.plans)
    if (!a.plans.count(key)) plan_change("plan " + key + ": only in the new schedule");
  if (out.differing_plans > shown)
    out.changes.push_back(printf_string("... %d differing plans in all", out.differing_plans));

  // Events, in order.
  const auto& ea = a.events;
  const auto& eb = b.events;
  const std::size_t n = std::max(ea.size(), eb.size());
  const auto name = [](const Event& e) { return to_string(e.kind) + " " + e.detail; };
  for (std::size_t k = 0; k < n; ++k) {
    std::string what;
    if (k >= ea.size()) {
      what = "new: " + name(eb[k]);
    } else if (k >= eb.size()) {
      what = "gone: " + name(ea[k]);
    } else {
      if (name(ea[k]) != name(eb[k])) what = name(ea[k]) + " -> " + name(eb[k]);
      const std::pair<const char*, std::pair<double, double>> times[] = {
          {"start_s", {ea[k].start_s, eb[k].start_s}}, {"end_s", {ea[k].end_s, eb[k].end_s}}};
      for (const auto& [key, values] : times)
        if (!tol.allows(values.first, values.second))
          what += std::string(what.empty() ? name(ea[k]) + ": " : ", ") + key + " " +
                  text(values.first) + " -> " + text(values.second);
    }
    if (what.empty()) continue;
    if (++out.differing_events <= shown)
      out.changes.push_back("event " + std::to_string(k) + ": " + what);
  }
  if (out.differing_events > shown)
    out.changes.push_back(printf_string("... %d differing events in all", out.differing_events));
  return out;
}

}  // namespace ccbuild::schedule
