#include "schedule_rules.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <tuple>

#include "anchor_strength.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/planner/timeline.hpp"
#include "ccbuild/rules/tolerances.hpp"
#include "ccbuild/rules/weather.hpp"
#include "ccbuild/schedule/quantities.hpp"
#include "schedule_deposits.hpp"

namespace ccbuild::schedule::detail {
namespace {

// The document rounds lengths to micrometres, times to microseconds and angles to
// microradians: two rounded values differ from the exact ones by up to these.
constexpr double kRoundLength_m = 2e-6, kRoundTime_s = 2e-6, kRoundAngle_rad = 2e-6;
/// A time the document states against the one recomputed from rounded paths.
constexpr double kStated_s = 1e-5;
constexpr double kStated_mpa = 1e-5;  // strengths are written to 1e-6 MPa
/// A deposited span against its piece's length.
constexpr double kCover_m = 1e-3;
constexpr std::size_t kMostReported = 20;

class Rules {
 public:
  Rules(const ScheduleDocument& doc, const JsonText& text) : doc_(doc), text_(text) {
    if (doc.inputs.conditions)
      maturity_.emplace(*doc.inputs.conditions, doc.inputs.material.maturity);
  }

  void check() {
    const auto& events = doc_.schedule.events;
    events_sorted_ =
        std::is_sorted(events.begin(), events.end(),
                       [](const Event& a, const Event& b) { return a.start_s < b.start_s; });
    for (const auto& [key, plan] : doc_.schedule.plans) check_plan(key, plan);
    check_layers();
    check_events();
    check_stages();
    check_totals();
    check_lintels_and_slabs();
    check_quantities();
    check_days();
    if (found_.empty()) return;
    if (count_ > found_.size())
      found_.push_back({text_.file(), 0, "", printf_string("... %zu broken rules in all", count_)});
    throw InputError(found_);
  }

 private:
  void broken(const std::string& pointer, const std::string& rule, const std::string& message) {
    if (++count_ <= kMostReported)
      found_.push_back({text_.file(), text_.line_of(pointer), pointer, rule + ": " + message});
  }
  static std::string plan_pointer(const std::string& key) { return pointer_to("/plans", key); }

  // ---------------------------------------------------------------- plans
  /// How many nozzle paths a plan holds, whole or as digests.
  static std::size_t paths_of(const SchedulePlan& plan) {
    return plan.digests.empty() ? plan.waypoints.size() : plan.digests.size();
  }

  void check_plan(const std::string& key, const SchedulePlan& plan) {
    const std::string at = plan_pointer(key);
    if (static_cast<int>(paths_of(plan)) != plan.nozzles) {
      broken(at + "/nozzles", "nozzles",
             printf_string("holds %zu nozzle paths; nozzles_used says %d", paths_of(plan),
                           plan.nozzles));
      return;
    }
    if (!plan.digests.empty()) return;  // only their digests: nothing to walk
    for (std::size_t n = 0; n < plan.waypoints.size(); ++n)
      if (plan.waypoints[n].size() < 2)
        return broken(pointer_to(at + "/nozzles", n) + "/waypoints", "paths",
                      "a nozzle's path needs at least two waypoints");
    check_coverage(at, plan);
    double end_s = 0.0;
    for (std::size_t n = 0; n < plan.waypoints.size(); ++n) {
      check_motion(pointer_to(at + "/nozzles", n) + "/waypoints", plan.waypoints[n]);
      end_s = std::max(end_s, plan.waypoints[n].back().t_s);
    }
    if (std::abs(end_s - plan.layer_time_s) > kStated_s)
      broken(at + "/layer_time_s", "layer time",
             printf_string("%.6f s, but its paths end at %.6f s", plan.layer_time_s, end_s));
    if (plan.nozzles > 1) check_gaps(at, plan);
    check_park_room(at, plan);
  }

  void check_coverage(const std::string& at, const SchedulePlan& plan) {
    const floors::Layer& layer = plan.layer;
    std::map<std::pair<std::int64_t, int>, int> piece_of;  // (wall, piece 1-based) -> segment
    for (std::size_t s = 0; s < layer.segments.size(); ++s) {
      const auto& seg = layer.segments[s];
      const std::string where = pointer_to(at + "/pieces", s);
      if (!piece_of.emplace(std::make_pair(seg.wall_id, seg.piece + 1), static_cast<int>(s)).second)
        broken(where, "pieces",
               printf_string("wall %lld piece %d is listed twice",
                             static_cast<long long>(seg.wall_id), seg.piece + 1));
      const double length_m = (layer.end_m(seg) - layer.start_m(seg)).norm();
      if (std::abs(length_m - seg.length_m) > 2 * kRoundLength_m)
        broken(where + "/length_m", "pieces",
               printf_string("%.6f m, but its ends are %.6f m apart", seg.length_m, length_m));
    }
    // Each piece: the stretches along it that the nozzles deposit (from, to, length).
    std::vector<std::vector<std::array<double, 3>>> spans(layer.segments.size());
    for (std::size_t n = 0; n < plan.waypoints.size(); ++n) {
      const auto& path = plan.waypoints[n];
      for (std::size_t k = 0; k + 1 < path.size(); ++k) {
        if (!path[k].extruding) continue;
        const std::string where = pointer_to(pointer_to(at + "/nozzles", n) + "/waypoints", k);
        const auto it = piece_of.find({path[k].wall, path[k].piece});
        if (it == piece_of.end()) {
          broken(where, "coverage",
                 printf_string("deposits wall %lld piece %d, not a piece of this plan",
                               static_cast<long long>(path[k].wall), path[k].piece));
          continue;
        }
        const auto& seg = layer.segments[it->second];
        const Eigen::Vector2d a = layer.start_m(seg), d = layer.end_m(seg) - a;
        const double length_m = d.norm();
        const Eigen::Vector2d u =
            length_m > 0 ? Eigen::Vector2d(d / length_m) : Eigen::Vector2d(1, 0);
        double along[2];
        bool on = true;
        for (int e = 0; e < 2 && on; ++e) {
          const Eigen::Vector2d p = path[k + e].position_m - a;
          along[e] = p.dot(u);
          const double off = std::abs(p.x() * u.y() - p.y() * u.x());
          if (off > kOnSpan_m || along[e] < -kOnSpan_m || along[e] > length_m + kOnSpan_m) {
            broken(where, "coverage",
                   printf_string("the span on wall %lld piece %d leaves the piece: (%.4f, %.4f) "
                                 "m is %.4f m off it",
                                 static_cast<long long>(seg.wall_id), seg.piece + 1,
                                 path[k + e].position_m.x(), path[k + e].position_m.y(),
                                 std::max({off, -along[e], along[e] - length_m})));
            on = false;
          }
        }
        if (on)
          spans[it->second].push_back({std::min(along[0], along[1]), std::max(along[0], along[1]),
                                       (path[k + 1].position_m - path[k].position_m).norm()});
      }
    }
    for (std::size_t s = 0; s < layer.segments.size(); ++s) {
      const auto& seg = layer.segments[s];
      const std::string where = pointer_to(at + "/pieces", s);
      const std::string name =
          printf_string("wall %lld piece %d", static_cast<long long>(seg.wall_id), seg.piece + 1);
      auto& got = spans[s];
      if (got.empty()) {
        broken(where, "coverage", name + " is never deposited");
        continue;
      }
      std::sort(got.begin(), got.end());
      double total_m = 0.0, covered_m = 0.0;
      for (const auto& [from_m, to_m, length_m] : got) {
        total_m += length_m;
        if (from_m > covered_m + kOnSpan_m)
          broken(where, "coverage",
                 printf_string("%s: %.4f m to %.4f m along it are never deposited", name.c_str(),
                               covered_m, from_m));
        else if (from_m < covered_m - kOnSpan_m)
          broken(where, "coverage",
                 printf_string("%s: %.4f m to %.4f m along it are deposited twice", name.c_str(),
                               from_m, std::min(covered_m, to_m)));
        covered_m = std::max(covered_m, to_m);
      }
      if (covered_m < seg.length_m - kOnSpan_m)
        broken(where, "coverage",
               printf_string("%s: %.4f m to its end (%.4f m) are never deposited", name.c_str(),
                             covered_m, seg.length_m));
      if (std::abs(total_m - seg.length_m) > kCover_m + 1e-6 * seg.length_m)
        broken(where, "coverage",
               printf_string("%s: its spans add up to %.6f m, the piece is %.6f m", name.c_str(),
                             total_m, seg.length_m));
    }
  }

  void check_motion(const std::string& at, const std::vector<planner::Waypoint>& path) {
    const RecordedMachine& m = doc_.inputs.machine;
    if (path.front().t_s < -kRoundTime_s)
      broken(pointer_to(at, 0) + "/t_s", "timing", "the path starts before the layer does");
    if (path.back().extruding)
      broken(pointer_to(at, path.size() - 1) + "/extruding", "timing",
             "the last waypoint still extrudes");
    for (std::size_t k = 0; k < path.size(); ++k) {
      const double h = path[k].heading_rad;
      if (m.stopper_min_rad &&
          (h < *m.stopper_min_rad - kRoundAngle_rad || h > *m.stopper_max_rad + kRoundAngle_rad))
        broken(pointer_to(at, k) + "/heading_rad", "stopper",
               printf_string("heading %.6f rad, past the stopper [%g, %g] rad", h,
                             *m.stopper_min_rad, *m.stopper_max_rad));
    }
    for (std::size_t k = 0; k + 1 < path.size(); ++k) {
      const auto &a = path[k], &b = path[k + 1];
      const std::string where = pointer_to(at, k + 1);
      const double dt = b.t_s - a.t_s;
      if (dt < -1e-9) {
        broken(where + "/t_s", "timing",
               printf_string("time runs backwards (%.6f s -> %.6f s)", a.t_s, b.t_s));
        continue;
      }
      const double dx = std::abs(b.position_m.x() - a.position_m.x());
      const double dy = std::abs(b.position_m.y() - a.position_m.y());
      const double dz = std::abs(b.z_m - a.z_m), d = std::hypot(dx, dy);
      if (rules::faster_than(dz, dt, m.z_speed_m_s))
        broken(where, "speed",
               printf_string("z changes %.6f m in %.6f s, faster than the z speed %g m/s", dz, dt,
                             m.z_speed_m_s));
      const double turn = std::abs(b.heading_rad - a.heading_rad);
      if (rules::faster_than(turn, dt, m.rotation_speed_rad_s))
        broken(where, "speed",
               printf_string("turns %.6f rad in %.6f s, faster than the rotation speed %g rad/s",
                             turn, dt, m.rotation_speed_rad_s));
      if (a.extruding) {
        const double v = m.deposition_speed_m_s;
        if (std::abs(d - v * dt) > 1e-3 * v * dt + kRoundLength_m + v * kRoundTime_s)
          broken(where, "speed",
                 printf_string("wall %lld piece %d deposited at %.4f m/s, not the deposition "
                               "speed %g m/s",
                               static_cast<long long>(a.wall), a.piece, dt > 0 ? d / dt : INFINITY,
                               v));
      } else {
        const auto fast = [&](double dist_m, double v) {
          return rules::faster_than(dist_m, dt, v);
        };
        if (fast(dx, m.x_speed_m_s) || fast(dy, m.y_speed_m_s) || fast(d, m.travel_speed_m_s))
          broken(where, "speed",
                 printf_string("an air move of %.6f m (x %.6f, y %.6f) in %.6f s, faster than "
                               "the machine's axes or travel speed",
                               d, dx, dy, dt));
      }
    }
  }

  /// A rail coordinate at `t_s`, held before the path's first time and after its last.
  static double rail_at(const std::vector<planner::Waypoint>& path, machine::RailAxis axis,
                        double t_s) {
    const auto rail = [axis](const planner::Waypoint& w) {
      return planner::rail_coordinate(w.position_m, axis);
    };
    const auto it =
        std::upper_bound(path.begin(), path.end(), t_s,
                         [](double t, const planner::Waypoint& w) { return t < w.t_s; });
    if (it == path.begin()) return rail(path.front());
    if (it == path.end()) return rail(path.back());
    const auto& a = *(it - 1);
    const auto& b = *it;
    return b.t_s <= a.t_s ? rail(a)
                          : rail(a) + (t_s - a.t_s) / (b.t_s - a.t_s) * (rail(b) - rail(a));
  }

  void check_gaps(const std::string& at, const SchedulePlan& plan) {
    const RecordedMachine& m = doc_.inputs.machine;
    const machine::RailAxis axis = m.rail_axis;
    double smallest_m = INFINITY, worst_t_s = 0.0;
    std::size_t worst_pair = 0;
    for (std::size_t n = 0; n + 1 < plan.waypoints.size(); ++n) {
      const auto &left = plan.waypoints[n], &right = plan.waypoints[n + 1];
      // The gap is piecewise linear between the breakpoints of both paths: exact there.
      for (const auto& w : left) {
        const double gap =
            rail_at(right, axis, w.t_s) - planner::rail_coordinate(w.position_m, axis);
        if (gap < smallest_m) smallest_m = gap, worst_t_s = w.t_s, worst_pair = n;
      }
      for (const auto& w : right) {
        const double gap =
            planner::rail_coordinate(w.position_m, axis) - rail_at(left, axis, w.t_s);
        if (gap < smallest_m) smallest_m = gap, worst_t_s = w.t_s, worst_pair = n;
      }
    }
    if (smallest_m < m.gantry_width_m - 1e-6)
      broken(at + "/nozzles", "gantry gap",
             printf_string("nozzles %zu and %zu come %.6f m apart along %s at t = %.6f s, under "
                           "the gantry width %.6f m",
                           worst_pair, worst_pair + 1, smallest_m, machine::to_string(axis).c_str(),
                           worst_t_s, m.gantry_width_m));
    if (std::abs(plan.min_gap_m - smallest_m) > 1e-5)
      broken(
          at + "/min_gap_m", "gantry gap",
          printf_string("%.6f m, but the gantries come %.6f m apart", plan.min_gap_m, smallest_m));
  }

  /// A plan on fewer gantries than the machine has leaves the idle ones room to park at
  /// the far end of the rails, a gantry width apart.
  void check_park_room(const std::string& at, const SchedulePlan& plan) {
    const RecordedMachine& m = doc_.inputs.machine;
    const int idle = m.nozzles - static_cast<int>(plan.waypoints.size());
    if (idle <= 0) return;
    double reach_m = -INFINITY;
    for (const auto& path : plan.waypoints)
      for (const auto& w : path)
        reach_m = std::max(reach_m, planner::rail_coordinate(w.position_m, m.rail_axis));
    const double room_m =
        machine::rail_coordinate(m.x_max_m, m.y_max_m, m.rail_axis) - idle * m.gantry_width_m;
    if (reach_m > room_m + 1e-6)
      broken(at + "/nozzles", "gantry gap",
             printf_string("on %zu of the machine's %d gantries the path reaches %.6f m along "
                           "%s, where the idle ones leave room only up to %.6f m",
                           plan.waypoints.size(), m.nozzles, reach_m,
                           machine::to_string(m.rail_axis).c_str(), room_m));
  }

  /// A wait is as long as its longest reason (none: no wait), and each reason bound it
  /// as long as bind_wait_reasons says.
  void check_wait(const std::string& at, double wait_s, const std::vector<WaitReason>& reasons) {
    double longest_s = 0.0;
    for (const auto& r : reasons) longest_s = std::max(longest_s, r.required_s);
    if (std::abs(wait_s - longest_s) > kStated_s)
      broken(at + "/wait_before_s", "waits",
             printf_string("%.6f s, but its longest reason needs %.6f s", wait_s, longest_s));
    std::vector<WaitReason> bound = reasons;
    bind_wait_reasons(bound);
    for (std::size_t k = 0; k < reasons.size(); ++k)
      if (std::abs(reasons[k].binding_s - bound[k].binding_s) >
          kStated_s * static_cast<double>(reasons.size() + 1))
        broken(at + "/wait_reasons/" + std::to_string(k) + "/binding_s", "waits",
               printf_string("%.6f s; from its start and end among the wait's reasons it "
                             "binds %.6f s",
                             reasons[k].binding_s, bound[k].binding_s));
  }

  // ---------------------------------------------------------------- layers
  const DepositIndex& index(const std::string& key) {
    auto it = indexes_.find(key);
    if (it == indexes_.end())
      it = indexes_.emplace(key, index_of(doc_.schedule.plans.at(key).waypoints)).first;
    return it->second;
  }

  /// The layer's interval offsets at a point where they were taken (`offsets.each`, on
  /// either side of it): (smallest, largest); unset when none was taken there (within the
  /// rounding of a written position).
  static std::optional<std::pair<double, double>> offsets_at(const PieceEnd& end,
                                                             const IntervalOffsets& offsets) {
    constexpr double kWritten_m = 2e-6;
    std::optional<std::pair<double, double>> out;
    for (const auto& e : offsets.each) {
      if (e.at.wall != end.wall || e.at.piece != end.piece ||
          std::abs(e.at.x_m - end.x_m) > kWritten_m || std::abs(e.at.y_m - end.y_m) > kWritten_m)
        continue;
      const double lo = e.up_lo_s - e.low_hi_s, hi = e.up_hi_s - e.low_lo_s;
      out = out ? std::make_pair(std::min(out->first, lo), std::max(out->second, hi))
                : std::make_pair(lo, hi);
    }
    return out;
  }

  void check_layers() {
    const Schedule& s = doc_.schedule;
    const floors::MaterialProfile& material = doc_.inputs.material;
    for (std::size_t i = 0; i < s.layers.size(); ++i) {
      const ScheduledLayer& l = s.layers[i];
      const std::string at = pointer_to("/layers", i);
      const ScheduledLayer* previous = i > 0 ? &s.layers[i - 1] : nullptr;
      const bool first_of_floor = !previous || previous->floor != l.floor;
      // Building order: floor by floor, layer by layer.
      const bool in_order = previous
                                ? (l.floor == previous->floor && l.layer == previous->layer + 1) ||
                                      (l.floor == previous->floor + 1 && l.layer == 0)
                                : l.layer == 0;
      if (!in_order)
        broken(
            at + "/layer", "building order",
            printf_string(
                "floor %d layer %d follows %s; layers go floor by floor, bottom to "
                "top",
                l.floor, l.layer,
                previous
                    ? printf_string("floor %d layer %d", previous->floor, previous->layer).c_str()
                    : "nothing"));
      const auto plan_it = s.plans.find(l.plan);
      if (plan_it == s.plans.end()) {
        broken(at + "/plan", "plans", "\"" + l.plan + "\" is not among the plans");
        continue;
      }
      const SchedulePlan& plan = plan_it->second;
      if (l.nozzles != plan.nozzles || static_cast<int>(paths_of(plan)) != l.nozzles)
        broken(at + "/nozzles", "nozzles",
               printf_string("%d, but its plan %s deposits with %d (%zu paths)", l.nozzles,
                             l.plan.c_str(), plan.nozzles, paths_of(plan)));
      if (l.geometry != plan.geometry)
        broken(at + "/geometry", "plans",
               printf_string("%d, but its plan %s is of geometry %d", l.geometry, l.plan.c_str(),
                             plan.geometry));
      if (l.method != plan.method)
        broken(at + "/method", "plans",
               "\"" + l.method + "\", but its plan was made by \"" + plan.method + "\"");
      if (std::abs(l.end_s - l.start_s - plan.layer_time_s) > kStated_s)
        broken(at + "/end_s", "layer time",
               printf_string("the layer lasts %.6f s, its plan %s %.6f s", l.end_s - l.start_s,
                             l.plan.c_str(), plan.layer_time_s));
      check_wait(at, l.wait_before_s, l.wait_reasons);
      if (previous) {
        // One layer at a time: after the one before, the events between, the move, the
        // wait and the purge.
        if (l.start_s < previous->end_s - kRoundTime_s)
          broken(at + "/start_s", "one layer at a time",
                 printf_string("floor %d layer %d starts at %.6f s, before floor %d layer %d "
                               "ends at %.6f s",
                               l.floor, l.layer, l.start_s, previous->floor, previous->layer,
                               previous->end_s));
        double ready_s = previous->end_s;
        if (events_sorted_)
          for (auto e =
                   std::lower_bound(s.events.begin(), s.events.end(), previous->end_s - kStated_s,
                                    [](const Event&x, double t) { return x.start_s < t; });
               e != s.events.end() && e->start_s <= l.start_s + kStated_s; ++e)
            if (e->kind != Event::Kind::kPurge && e->kind != Event::Kind::kJoint &&
                e->end_s <= l.start_s + kStated_s)
              ready_s = std::max(ready_s, e->end_s);
        const double expected_s = ready_s + l.move_before_s + l.wait_before_s +
                                  (l.planned_joint ? material.planned_joint.treatment_s : 0.0) +
                                  (l.purge_before ? doc_.inputs.machine.purge_s : 0.0);
        if (std::abs(l.start_s - expected_s) > kStated_s)
          broken(at + "/start_s", "one layer at a time",
                 printf_string("%.6f s; after the layer below (and the events between) at "
                               "%.6f s, the move %.6f s, the wait %.6f s%s%s it starts at %.6f s",
                               l.start_s, ready_s, l.move_before_s, l.wait_before_s,
                               l.planned_joint ? ", the joint's treatment" : "",
                               l.purge_before ? " and the purge" : "", expected_s));
      }
      check_calendar(at, l, first_of_floor ? nullptr : previous);
      // The interval and the local intervals, recomputed from the paths.
      if (first_of_floor) {
        if (l.interval_s || l.local_interval_min_s || l.piece_ends_checked != 0)
          broken(at + "/interval_s", "intervals",
                 "the first layer of a floor stands on the slab: no interval (null) and no piece "
                 "ends checked");
        continue;
      }
      if (!l.interval_s || std::abs(*l.interval_s - (l.start_s - previous->start_s)) > kStated_s)
        broken(at + "/interval_s", "intervals",
               printf_string("expected %.6f s, start to start from the layer below",
                             l.start_s - previous->start_s));
      // Recomputed from the paths when both are known whole.
      if (!s.plans.count(previous->plan) || !plan.digests.empty() ||
          !s.plans.at(previous->plan).digests.empty())
        continue;
      const DepositIndex& up = index(l.plan);
      const DepositIndex& low = index(previous->plan);
      const IntervalOffsets offsets = interval_offsets(plan.layer, up, low);
      if (offsets.ends != l.piece_ends_checked)
        broken(at + "/piece_ends_checked", "local intervals",
               printf_string("%d, but the intervals are taken at %d points over walls of the "
                             "layer below",
                             l.piece_ends_checked, offsets.ends));
      if (offsets.ends == 0) {
        if (l.local_interval_min_s)
          broken(at + "/local_interval_min_s", "local intervals",
                 "no piece end lies on a wall of the layer below: expected null");
        continue;
      }
      const double shift_s = l.start_s - previous->start_s;
      const double min_s = shift_s + offsets.min_offset_s, max_s = shift_s + offsets.max_offset_s;
      if (!l.local_interval_min_s || std::abs(*l.local_interval_min_s - min_s) > kStated_s)
        broken(at + "/local_interval_min_s", "local intervals",
               printf_string("expected %.6f s, recomputed from the two layers' paths", min_s));
      if (!l.local_interval_max_s || std::abs(*l.local_interval_max_s - max_s) > kStated_s)
        broken(at + "/local_interval_max_s", "local intervals",
               printf_string("expected %.6f s, recomputed from the two layers' paths", max_s));
      // Where the extremes are: the piece end named must have the extreme interval (ties
      // are equal within the rounding).
      for (const bool is_min : {true, false}) {
        const PieceEnd& named = is_min ? l.local_min_at : l.local_max_at;
        const auto there = offsets_at(named, offsets);
        const double extreme_s = is_min ? min_s : max_s;
        const double there_s = there ? shift_s + (is_min ? there->first : there->second) : NAN;
        if (!there || std::abs(there_s - extreme_s) > kStated_s)
          broken(at + (is_min ? "/local_interval_min_at" : "/local_interval_max_at"),
                 "local intervals",
                 there
                     ? printf_string("wall %lld piece %d at (%.6f, %.6f) m has %.6f s, not the "
                                     "%s %.6f s",
                                     static_cast<long long>(named.wall), named.piece, named.x_m,
                                     named.y_m, there_s, is_min ? "smallest" : "largest", extreme_s)
                     : printf_string("wall %lld piece %d at (%.6f, %.6f) m is not a point where "
                                     "the intervals are taken (a piece's end or a bead's end "
                                     "along it, deposited in both layers)",
                                     static_cast<long long>(named.wall), named.piece, named.x_m,
                                     named.y_m));
      }
      // With site weather the window bounds equivalent age, piece end by piece end.
      double window_min_s = min_s, window_max_s = max_s;
      if (maturity_) {
        window_min_s = INFINITY, window_max_s = -INFINITY;
        for (const auto& e : offsets.each) {
          window_min_s = std::min(
              window_min_s, maturity_->age(previous->start_s + e.low_hi_s, l.start_s + e.up_lo_s));
          window_max_s = std::max(
              window_max_s, maturity_->age(previous->start_s + e.low_lo_s, l.start_s + e.up_hi_s));
        }
        for (const auto& [key, stated, want] :
             {std::tuple<const char*, std::optional<double>, double>{
                  "/equivalent_interval_min_s", l.equivalent_interval_min_s, window_min_s},
              {"/equivalent_interval_max_s", l.equivalent_interval_max_s, window_max_s}})
          if (!stated || std::abs(*stated - want) > kStated_s)
            broken(at + key, "local intervals",
                   printf_string("expected %.6f s of equivalent age, recomputed from the paths and "
                                 "the site's temperatures",
                                 want));
      }
      check_buildability(at, l, *previous, window_min_s);
      if (s.feasible && window_min_s < material.min_layer_interval_s - kStated_s)
        broken(at + "/local_interval_min_s", "interval window",
               printf_string("a piece is covered %.6f s after it was deposited, under the "
                             "material's minimum %.6f s",
                             window_min_s, material.min_layer_interval_s));
      if (s.feasible && !l.planned_joint &&
          window_max_s > material.max_layer_interval_s + kStated_s)
        broken(at + "/local_interval_max_s", "interval window",
               printf_string("a piece is covered %.6f s after it was deposited, over the "
                             "material's maximum %.6f s, in a schedule marked feasible",
                             window_max_s, material.max_layer_interval_s));
    }
  }

  /// The buildability the report draws: the layer below's strength at the age its soonest
  /// covered end has (`soonest_s`, recomputed), against what the walls on it need.
  void check_buildability(const std::string& at, const ScheduledLayer& l,
                          const ScheduledLayer& below, double soonest_s) {
    if (!l.below_strength_mpa) return;  // written before it
    const floors::MaterialProfile& material = doc_.inputs.material;
    const double strength_mpa = material.strength_at_mpa(soonest_s);
    const double need_mpa = material.strength_to_carry_mpa(l.z_top_m - below.z_bottom_m);
    for (const auto& [key, stated, want] :
         {std::tuple<const char*, double, double>{"/below_strength_mpa", *l.below_strength_mpa,
                                                  strength_mpa},
          {"/below_required_mpa", *l.below_required_mpa, need_mpa}})
      if (std::abs(stated - want) > kStated_mpa)
        broken(at + key, "strength",
               printf_string("%.6f MPa; the material and the layer's intervals give %.6f MPa",
                             stated, want));
    if (doc_.schedule.feasible && strength_mpa < need_mpa - kStated_mpa)
      broken(at + "/below_strength_mpa", "strength",
             printf_string("floor %d layer %d is %.6f MPa strong when this layer covers it, "
                           "under the %.6f MPa the walls on it need, in a schedule marked "
                           "feasible",
                           below.floor, below.layer, strength_mpa, need_mpa));
  }

  /// The youngest anchor's strength the report draws, recomputed.
  void check_anchor_strength(const std::string& at, const ClimbEvent& c, double start_s) {
    if (c.youngest_anchor_strength.empty() && !c.anchors.empty()) return;  // written before it
    ClimbEvent timed = c;  // as read, its start is the event's
    timed.start_s = start_s;
    const auto want = detail::youngest_anchor_strength(timed, doc_.inputs.material,
                                                       maturity_ ? &*maturity_ : nullptr);
    if (want.size() != c.youngest_anchor_strength.size()) {
      broken(at + "/youngest_anchor_strength", "climbs",
             printf_string("%zu points; expected %zu", c.youngest_anchor_strength.size(),
                           want.size()));
      return;
    }
    for (std::size_t k = 0; k < want.size(); ++k) {
      const auto& got = c.youngest_anchor_strength[k];
      if (std::abs(got.t_s - want[k].t_s) > kStated_s ||
          std::abs(got.strength_mpa - want[k].strength_mpa) > kStated_mpa)
        broken(at + "/youngest_anchor_strength/" + std::to_string(k), "climbs",
               printf_string("[%.6f, %.6f]; the youngest anchor's age and the material give "
                             "[%.6f, %.6f]",
                             got.t_s, got.strength_mpa, want[k].t_s, want[k].strength_mpa));
    }
  }

  // ---------------------------------------------------------------- the site's calendar
  /// When the layer's block (the joint's treatment, the purge, the layer) starts.
  double block_start_s(const ScheduledLayer& l) const {
    return l.start_s - (l.purge_before ? doc_.inputs.machine.purge_s : 0.0) -
           (l.planned_joint ? doc_.inputs.material.planned_joint.treatment_s : 0.0);
  }

  /// Attended printing within working hours; a planned joint only after off-shift hours,
  /// on a floor's layer above another, treated within its ages.
  void check_calendar(const std::string& at, const ScheduledLayer& l, const ScheduledLayer* below) {
    const site::SiteCalendar* calendar = doc_.inputs.calendar.get();
    const double block_s = block_start_s(l);
    if (calendar && calendar->programme().printing_attended &&
        !calendar->within_one_window(block_s, l.end_s - kStated_s))
      broken(at + "/start_time", "working hours",
             printf_string("printing is attended, but floor %d layer %d (with its purge and "
                           "joint) runs from %s to %s, outside one working window",
                           l.floor, l.layer, calendar->local_text(block_s).c_str(),
                           calendar->local_text(l.end_s).c_str()));
    if (!l.planned_joint) return;
    if (!below) {
      broken(at + "/planned_joint", "planned joints",
             "the first layer of a floor stands on its slab, not on a joint");
      return;
    }
    const floors::MaterialProfile& mix = doc_.inputs.material;
    const bool cold_between =
        maturity_ &&
        maturity_->fit_s(
            below->end_s, block_s - below->end_s, [&mix](const site::WeatherReading& r) {
              return rules::placeable_at(r.temperature_c, mix.placing_min_c, mix.placing_max_c);
            }) > below->end_s + kStated_s;
    const bool lintels_between =
        std::any_of(doc_.schedule.events.begin(), doc_.schedule.events.end(), [&](const Event& e) {
          return e.kind == Event::Kind::kLintel && e.start_s >= below->end_s - kStated_s &&
                 e.end_s <= block_s + kStated_s;
        });
    const bool off_shift_between = calendar && !calendar->within_one_window(below->end_s, block_s);
    if (!off_shift_between && !cold_between && !lintels_between)
      broken(
          at + "/planned_joint", "planned joints",
          printf_string("no off-shift hours, cold or lintels lie between floor %d layer %d's end "
                        "(%.6f s) and this joint (%.6f s): a joint is planned only where work "
                        "stops for them",
                        below->floor, below->layer, below->end_s, block_s));
    const floors::PlannedJoint& pj = doc_.inputs.material.planned_joint;
    const double age_s = block_s - below->end_s;
    if (age_s < pj.min_age_s - kStated_s)
      broken(at + "/planned_joint", "planned joints",
             printf_string("treated when the layer below is %.6f s old, under the material's "
                           "%.6f s",
                           age_s, pj.min_age_s));
    if (doc_.schedule.feasible && age_s > pj.max_age_s + kStated_s)
      broken(at + "/planned_joint", "planned joints",
             printf_string("treated when the layer below is %.6f s old, over the material's "
                           "%.6f s, in a schedule marked feasible",
                           age_s, pj.max_age_s));
    const bool treated =
        std::any_of(doc_.schedule.events.begin(), doc_.schedule.events.end(), [&](const Event& e) {
          return e.kind == Event::Kind::kJoint && e.floor == below->floor &&
                 e.layer == below->layer && std::abs(e.start_s - block_s) <= kStated_s &&
                 std::abs(e.end_s - e.start_s - pj.treatment_s) <= kStated_s;
        });
    if (!treated)
      broken(at + "/planned_joint", "planned joints",
             printf_string("no joint event of %.6f s after floor %d layer %d starts at %.6f s",
                           pj.treatment_s, below->floor, below->layer, block_s));
  }

  /// Each layer's concrete is its plan's pieces' volume; the deliveries are the
  /// material's batches of it (schedules written before quantities have neither).
  void check_quantities() {
    const Schedule& s = doc_.schedule;
    if (s.deliveries.empty()) return;
    const double nozzle_m = doc_.inputs.machine.nozzle_width_m;
    for (std::size_t i = 0; i < s.layers.size(); ++i) {
      const ScheduledLayer& l = s.layers[i];
      const auto plan = s.plans.find(l.plan);
      if (plan == s.plans.end()) continue;
      const double want_m3 =
          layer_volume_m3(plan->second.layer, nozzle_m, l.z_top_m - l.z_bottom_m);
      if (std::abs(l.concrete_m3 - want_m3) > 1e-6 + 1e-9 * want_m3)
        broken(pointer_to("/layers", i) + "/concrete_m3", "quantities",
               printf_string("%.6f m3, but its pieces hold %.6f m3", l.concrete_m3, want_m3));
    }
    const auto want = deliveries_of(s.layers, doc_.inputs.material.delivery_batch_m3);
    if (want.size() != s.deliveries.size()) {
      broken("/deliveries", "quantities",
             printf_string("%zu deliveries, but %.6f m3 in batches of %.6f m3 make %zu",
                           s.deliveries.size(), s.totals.concrete_m3,
                           doc_.inputs.material.delivery_batch_m3, want.size()));
      return;
    }
    for (std::size_t k = 0; k < want.size(); ++k) {
      const Delivery &a = s.deliveries[k], &b = want[k];
      if (std::abs(a.due_s - b.due_s) > kStated_s || std::abs(a.m3 - b.m3) > 1e-6 ||
          a.floor != b.floor || a.layer != b.layer)
        broken(pointer_to("/deliveries", k), "quantities",
               printf_string("expected %.6f m3 due at %.6f s (floor %d layer %d)", b.m3, b.due_s,
                             b.floor, b.layer));
    }
  }

  void check_days() {
    const site::SiteCalendar* calendar = doc_.inputs.calendar.get();
    if (!calendar) return;
    const auto want =
        work_days(doc_.schedule.layers, doc_.schedule.events, doc_.schedule.deliveries, *calendar);
    const auto& got = doc_.schedule.days;
    if (want.size() != got.size()) {
      broken("/days", "days",
             printf_string("%zu days, but the layers start on %zu local days", got.size(),
                           want.size()));
      return;
    }
    for (std::size_t k = 0; k < got.size(); ++k) {
      const WorkDay &a = got[k], &b = want[k];
      if (a.date != b.date || a.layers != b.layers || a.first_floor != b.first_floor ||
          a.first_layer != b.first_layer || a.last_floor != b.last_floor ||
          a.last_layer != b.last_layer || a.stop != b.stop || a.detail != b.detail ||
          a.deliveries != b.deliveries || std::abs(a.concrete_m3 - b.concrete_m3) > 1e-6 ||
          std::abs(a.crew_h - b.crew_h) > 1e-6 * (1 + b.crew_h) ||
          std::abs(a.printing_s - b.printing_s) > kStated_s * (b.layers + 1))
        broken(pointer_to("/days", k), "days",
               printf_string("%s: expected %d layers, floor %d layer %d to floor %d layer %d, "
                             "%.6f s printing, stop \"%s\"",
                             b.date.c_str(), b.layers, b.first_floor, b.first_layer, b.last_floor,
                             b.last_layer, b.printing_s, to_string(b.stop).c_str()));
    }
  }

  // ---------------------------------------------------------------- events, stages, totals
  void check_events() {
    const Schedule& s = doc_.schedule;
    std::map<std::pair<int, int>, const ScheduledLayer*> layer_of;
    for (const auto& l : s.layers) layer_of[{l.floor, l.layer}] = &l;
    for (std::size_t k = 0; k < s.events.size(); ++k) {
      const Event& e = s.events[k];
      const std::string at = pointer_to("/events", k);
      if (k > 0 && e.start_s < s.events[k - 1].start_s)
        broken(at + "/start_s", "events", "events are listed by start time");
      const auto it = layer_of.find({e.floor, e.layer});
      if (it == layer_of.end()) {
        broken(at + "/after_layer", "events",
               printf_string("names floor %d layer %d, which the schedule does not have", e.floor,
                             e.layer));
      } else if (e.start_s < it->second->end_s - kStated_s) {
        broken(at + "/start_s", "events",
               printf_string("%.6f s, before floor %d layer %d, which it follows, ends (%.6f s)",
                             e.start_s, e.floor, e.layer, it->second->end_s));
      }
      // The first layer ending after the event starts must start after it ends (layers in
      // order: checked above).
      const auto later =
          std::upper_bound(s.layers.begin(), s.layers.end(), e.start_s + kStated_s,
                           [](double t, const ScheduledLayer& l) { return t < l.end_s; });
      if (later != s.layers.end()) {
        const ScheduledLayer& l = *later;
        if (e.end_s > l.start_s + kStated_s) {
          broken(at + "/start_s", "one layer at a time",
                 printf_string("the %s from %.6f s to %.6f s overlaps floor %d layer %d (%.6f s "
                               "to %.6f s)",
                               to_string(e.kind).c_str(), e.start_s, e.end_s, l.floor, l.layer,
                               l.start_s, l.end_s));
        }
      }
      if (e.kind == Event::Kind::kPipe && !e.anchor)
        broken(at, "events", "a pipe names its anchor");
      if (const site::SiteCalendar* calendar = doc_.inputs.calendar.get()) {
        const bool crew =
            e.kind == Event::Kind::kClimb || e.kind == Event::Kind::kJoint ||
            (e.kind == Event::Kind::kPipe && calendar->programme().pipes_need_crew) ||
            (e.kind == Event::Kind::kLintel &&
             (!doc_.inputs.lintels.by_arm || calendar->programme().printing_attended)) ||
            ((e.kind == Event::Kind::kSlab && doc_.inputs.slabs) || e.kind == Event::Kind::kPour);
        if (crew && !calendar->within_one_window(e.start_s, e.end_s - kStated_s))
          broken(at + "/start_time", "working hours",
                 printf_string("the %s needs a crew, but runs from %s to %s, outside one working "
                               "window",
                               to_string(e.kind).c_str(), calendar->local_text(e.start_s).c_str(),
                               calendar->local_text(e.end_s).c_str()));
      }
      if (e.kind == Event::Kind::kClimb && e.climb) {
        const ClimbEvent& c = *e.climb;
        double phases_s = 0.0;
        for (const auto& p : c.plan.phases) phases_s += p.duration_s;
        const double slack_s = kStated_s * static_cast<double>(c.plan.phases.size() + 1);
        if (std::abs(phases_s - c.plan.duration_s) > slack_s)
          broken(at + "/climb/duration_s", "climbs",
                 printf_string("%.6f s, but its phases add up to %.6f s", c.plan.duration_s,
                               phases_s));
        if (std::abs(e.end_s - e.start_s - c.plan.duration_s) > kStated_s)
          broken(at + "/end_s", "climbs",
                 printf_string("the climb lasts %.6f s here, its phases %.6f s",
                               e.end_s - e.start_s, c.plan.duration_s));
        const int stages = static_cast<int>(s.stages.size());
        if (c.from_stage >= stages || c.to_stage >= stages || c.to_stage != c.from_stage + 1 ||
            c.plan.from_stage != c.from_stage || c.plan.to_stage != c.to_stage)
          broken(at + "/to_stage", "climbs",
                 printf_string("climbs from stage %d to %d; expected consecutive stages among "
                               "the %d",
                               c.from_stage, c.to_stage, stages));
        check_wait(at, c.wait_before_s, c.wait_reasons);
        check_anchor_strength(at, c, e.start_s);
      }
    }
    // A purge before every layer that says so, ending where it starts.
    std::vector<double> purge_ends_s;
    for (const auto& e : s.events)
      if (e.kind == Event::Kind::kPurge) purge_ends_s.push_back(e.end_s);
    std::sort(purge_ends_s.begin(), purge_ends_s.end());
    for (std::size_t i = 0; i < s.layers.size(); ++i) {
      const ScheduledLayer& l = s.layers[i];
      const auto near =
          std::lower_bound(purge_ends_s.begin(), purge_ends_s.end(), l.start_s - kStated_s);
      const bool purged = near != purge_ends_s.end() && *near <= l.start_s + kStated_s;
      if (l.purge_before != purged)
        broken(pointer_to("/layers", i) + "/purge_before", "purges",
               l.purge_before ? "true, but no purge event ends where the layer starts"
                              : "false, but a purge event ends where the layer starts");
    }
  }

  void check_stages() {
    const auto& stages = doc_.schedule.stages;
    for (std::size_t k = 0; k < stages.size(); ++k)
      if (stages[k].index != static_cast<int>(k))
        broken(pointer_to("/stages", k) + "/stage", "stages",
               printf_string("%d; stages are numbered in order from 0", stages[k].index));
    if (!stages.empty() && !doc_.inputs.machine.climbing)
      broken("/stages", "stages", "a fixed gantry has no stages");
  }

  /// Each lintel set while its floor's layers below its head are done and before the first
  /// one at or over it, for as long as the building says; each slab's formwork and pour as
  /// long as the building says, and the next floor's first layer after the slab carries it.
  void check_lintels_and_slabs() {
    const Schedule& s = doc_.schedule;
    for (std::size_t k = 0; k < s.events.size(); ++k) {
      const Event& e = s.events[k];
      const std::string at = pointer_to("/events", k);
      if (e.kind == Event::Kind::kLintel) {
        if (!e.lintel) continue;
        if (std::abs(e.end_s - e.start_s - doc_.inputs.lintels.place_s) > kStated_s)
          broken(at + "/end_s", "lintels",
                 printf_string("the lintel takes %.6f s, the building's place time %.6f s",
                               e.end_s - e.start_s, doc_.inputs.lintels.place_s));
        for (const auto& l : s.layers) {
          if (l.floor != e.floor) continue;
          // A mid-height within rounding of the head may fall either side of it.
          const double mid_m = 0.5 * (l.z_bottom_m + l.z_top_m);
          const bool over = mid_m >= e.lintel->head_z_m + kRoundLength_m;
          const bool under = mid_m < e.lintel->head_z_m - kRoundLength_m;
          if (over && l.start_s < e.end_s - kStated_s)
            broken(at + "/end_s", "lintels",
                   printf_string("the lintel over opening %s is set until %.6f s, but floor %d "
                                 "layer %d, over its head, starts at %.6f s",
                                 e.lintel->opening.c_str(), e.end_s, l.floor, l.layer, l.start_s));
          if (under && l.end_s > e.start_s + kStated_s)
            broken(at + "/start_s", "lintels",
                   printf_string("the lintel over opening %s is set from %.6f s, before floor %d "
                                 "layer %d, under its head, ends at %.6f s",
                                 e.lintel->opening.c_str(), e.start_s, l.floor, l.layer, l.end_s));
        }
      }
      if (!doc_.inputs.slabs) continue;
      const floors::SlabSpec& spec = *doc_.inputs.slabs;
      if (e.kind == Event::Kind::kSlab && std::abs(e.end_s - e.start_s - spec.setup_s) > kStated_s)
        broken(at + "/end_s", "slabs",
               printf_string("the slab's formwork takes %.6f s, the building's %.6f s",
                             e.end_s - e.start_s, spec.setup_s));
      if (e.kind != Event::Kind::kPour) continue;
      const double pour_s = e.concrete_m3 / spec.pour_rate_m3_s;
      if (std::abs(e.end_s - e.start_s - pour_s) > kStated_s + 1e-9 * pour_s)
        broken(at + "/end_s", "slabs",
               printf_string("the pour of %.6f m3 takes %.6f s, at the building's rate %.6f s",
                             e.concrete_m3, e.end_s - e.start_s, pour_s));
      if (e.roof) continue;
      const double age_s = spec.concrete.age_for_strength_s(spec.ready_mpa);
      const double ready_s = site::age_reached_s(maturity_ ? &*maturity_ : nullptr, e.end_s, age_s);
      for (const auto& l : s.layers)
        if (l.floor > e.floor) {
          if (l.start_s < ready_s - kStated_s)
            broken(at, "slabs",
                   printf_string("floor %d layer %d starts at %.6f s, before the slab over floor "
                                 "%d reaches %.6f MPa at %.6f s",
                                 l.floor, l.layer, l.start_s, e.floor, spec.ready_mpa, ready_s));
          break;
        }
    }
  }

  void check_totals() {
    const Schedule& s = doc_.schedule;
    if (s.feasible == s.infeasibility.has_value())
      broken("/feasible", "feasibility",
             s.feasible ? "true, but the schedule states an infeasibility"
                        : "false, but the schedule states no infeasibility (null)");
    const ScheduleTotals want = totals_of(s.layers, s.events);
    const double slack_s = 1e-6 * static_cast<double>(s.layers.size() + s.events.size() + 2);
    const ScheduleTotals& got = s.totals;
    const std::pair<const char*, std::pair<double, double>> totals[] = {
        {"makespan_s", {got.makespan_s, want.makespan_s}},
        {"deposition_s", {got.deposition_s, want.deposition_s}},
        {"airtime_s", {got.airtime_s, want.airtime_s}},
        {"moves_s", {got.moves_s, want.moves_s}},
        {"waits_s", {got.waits_s, want.waits_s}},
        {"pipes_s", {got.pipes_s, want.pipes_s}},
        {"purges_s", {got.purges_s, want.purges_s}},
        {"climbs_s", {got.climbs_s, want.climbs_s}},
        {"slabs_s", {got.slabs_s, want.slabs_s}},
        {"joints_s", {got.joints_s, want.joints_s}},
        {"lintels_s", {got.lintels_s, want.lintels_s}},
        {"crew_h", {got.crew_h, want.crew_h}},
        {"concrete_m3", {got.concrete_m3, want.concrete_m3}},
        {"machine_s", {got.machine_s, want.machine_s}}};
    for (const auto& [key, values] : totals)
      if (std::abs(values.first - values.second) > slack_s + 1e-9 * std::abs(values.second))
        broken(pointer_to("/totals", key), "totals",
               printf_string("%.6f s, but the layers and events add up to %.6f s", values.first,
                             values.second));
  }

  const ScheduleDocument& doc_;
  const JsonText& text_;
  std::vector<Diagnostic> found_;
  std::size_t count_ = 0;
  bool events_sorted_ = true;
  std::map<std::string, DepositIndex> indexes_;
  std::optional<site::EquivalentAge> maturity_;  ///< with site weather
};

}  // namespace

void check_schedule_rules(const ScheduleDocument& document, const JsonText& text) {
  Rules(document, text).check();
}

}  // namespace ccbuild::schedule::detail
