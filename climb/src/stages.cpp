// Where the platform stands, stage after stage, and which pipes hold it there.

#include <algorithm>
#include <cmath>
#include <limits>

#include "ccbuild/climb/climb.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/floors/slice.hpp"

namespace ccbuild::climb {

std::string to_string(ClimbCode code) {
  switch (code) {
    case ClimbStatus::Code::kFeasible:
      return "feasible";
    case ClimbStatus::Code::kNoAnchor:
      return "no-anchor";
    case ClimbStatus::Code::kBlocked:
      return "blocked";
    case ClimbStatus::Code::kUnstable:
      return "unstable";
    case ClimbStatus::Code::kTimeLimit:
      return "time-limit";
  }
  return "?";
}

namespace {

struct GlobalLayer {
  int floor = 0;
  int layer = 0;
  double z_bottom_m = 0.0, z_top_m = 0.0;
};

// What a unit's leg allows: the foot's height below the platform's frame at stroke 0,
// and the stroke's usable range.
struct Leg {
  double foot_at_zero_m = 0.0;
  double stroke_min_m = 0.0, stroke_max_m = 0.0;
};

Leg leg_of(const machine::ClimbingMachine& m, int u) {
  const machine::Kinematics& robot = *m.robot;
  const auto poses = robot.link_poses(Eigen::Isometry3d::Identity(), robot.zero());
  const auto [stroke_min_m, stroke_max_m] = m.usable_range(m.units[u].joints[3]);
  return {poses[m.units[u].foot_link].translation().z(), stroke_min_m, stroke_max_m};
}

// A place a unit's pin could go: a point on a wall's centre line, and the wall.
struct Candidate {
  std::string id;
  std::int64_t wall_id = 0;
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
  Eigen::Vector2d along = Eigen::Vector2d::UnitX();  ///< the wall's direction
  double thickness_m = 0.0;
  bool by_default_rule = false;
};

// The wall pieces of `layer` (one floor's) that cover `point` on wall `wall_id`.
bool solid_at(const floors::Layer& layer, std::int64_t wall_id, const Eigen::Vector2d& point,
              double clearance_m) {
  for (const auto& s : layer.segments) {
    if (s.wall_id != wall_id) continue;
    const Eigen::Vector2d a = layer.start_m(s), b = layer.end_m(s);
    const double t = (point - a).dot((b - a).normalized());
    if (t >= clearance_m - 1e-9 && t <= s.length_m - clearance_m + 1e-9 &&
        std::abs((point - a).x() * (b - a).normalized().y() -
                 (point - a).y() * (b - a).normalized().x()) < 1e-6)
      return true;
  }
  return false;
}

std::vector<Candidate> candidates(const floors::Floor& floor, const floors::Layer& layer,
                                  double default_thickness_m, double clearance_m) {
  std::vector<Candidate> out;
  auto thickness = [&](std::int64_t id) {
    const floors::Wall* w = floor.plan.find_wall(id);
    return w && w->thickness_m ? *w->thickness_m : default_thickness_m;
  };
  if (!floor.anchors.empty()) {
    // The building's anchor points, where this layer has solid wall.
    for (const auto& a : floor.anchors) {
      const floors::Wall* wall = floor.plan.find_wall(a.wall_id);
      if (!wall) continue;
      const Eigen::Vector2d s = floor.plan.wall_start_m(*wall), e = floor.plan.wall_end_m(*wall);
      const Eigen::Vector2d dir = (e - s).normalized();
      const Eigen::Vector2d point = s + dir * a.offset_m;
      if (!solid_at(layer, a.wall_id, point, 0.0)) continue;
      out.push_back({a.id, a.wall_id, point, dir, thickness(a.wall_id), false});
    }
    return out;
  }
  // The default rule: points every 5 cm along every piece of solid wall in this layer, at
  // least the clearance from the piece's ends (wall ends, corners, openings' edges), and
  // from every opening's width on that wall at any height (not under a window either: the
  // wall below a sill is a slender piece, no place for a climbing load).
  auto under_an_opening = [&](std::int64_t wall_id, const Eigen::Vector2d& point) {
    const floors::Wall* wall = floor.plan.find_wall(wall_id);
    if (!wall) return false;
    const Eigen::Vector2d start = floor.plan.wall_start_m(*wall);
    const double along = (point - start).norm();
    for (const auto& o : floor.plan.openings)
      if (o.wall_id == wall_id && along > o.offset_m - clearance_m + 1e-9 &&
          along < o.offset_m + o.width_m + clearance_m - 1e-9)
        return true;
    return false;
  };
  for (const auto& s : layer.segments) {
    const Eigen::Vector2d a = layer.start_m(s), b = layer.end_m(s);
    const Eigen::Vector2d dir = (b - a).normalized();
    for (double t = clearance_m; t <= s.length_m - clearance_m + 1e-9; t += 0.05)
      if (!under_an_opening(s.wall_id, a + dir * t))
        out.push_back({"", s.wall_id, a + dir * t, dir, thickness(s.wall_id), true});
  }
  return out;
}

}  // namespace

StagePlan climb_stages(const floors::Building& building, const machine::ClimbingMachine& m,
                       const StageOptions& options) {
  StagePlan plan;
  const int units = static_cast<int>(m.units.size());
  std::vector<GlobalLayer> layers;
  std::vector<std::vector<floors::Layer>> sliced;
  for (const auto& floor : building.floors) {
    sliced.push_back(floors::slice_floor(floor, building.layer_height_m));
    for (const auto& l : sliced.back())
      layers.push_back({floor.index, l.index, l.z_bottom_m, l.z_top_m});
  }
  if (layers.empty()) return plan;
  std::vector<Leg> legs;
  double climb_max_m = std::numeric_limits<double>::infinity();
  for (int u = 0; u < units; ++u) {
    legs.push_back(leg_of(m, u));
    climb_max_m = std::min(climb_max_m, legs.back().stroke_max_m - legs.back().stroke_min_m);
  }
  const double below = m.nozzle_reach_below_m, above = m.nozzle_reach_above_m;
  const double thickness = m.gantry.nozzle_width_m;
  const std::vector<double> q0 = m.robot->zero();

  // Unit u's pin in `c`, the platform at `z`: the joint values, when within the limits.
  auto reach = [&](int u, const Candidate& c, double anchor_z, double platform_z,
                   Eigen::Vector2d& outward) -> bool {
    const Eigen::Isometry3d platform(Eigen::Translation3d(0, 0, platform_z));
    const auto poses = m.robot->link_poses(platform, q0);
    const Eigen::Vector2d mount = poses[m.units[u].foot_link].translation().head<2>();
    Eigen::Vector2d n(-c.along.y(), c.along.x());
    if (n.dot(mount - c.point) < 0) n = -n;  // the unit is on this side of the wall
    outward = n;
    const double depth = 0.5 * c.thickness_m + m.pin_gap_m + m.pin_past_centre_m;
    Eigen::Vector3d foot(c.point.x(), c.point.y(), anchor_z);
    foot.head<2>() += n * (0.5 * c.thickness_m + m.pin_gap_m + m.foot_to_pin_m());
    const auto pose = m.unit_ik(u, platform, q0, foot, -n, depth);
    return pose && m.unit_within_limits(u, *pose);
  };

  // Picks one pipe per unit at `anchor_z` in `floor`'s layer `layer` (or the foundation),
  // reachable with the platform at each of `platform_zs`, nearest each unit's previous
  // pin; empty with `why` when some unit has none.
  auto choose = [&](int floor, int layer, double anchor_z, const std::vector<double>& platform_zs,
                    const std::vector<Anchor>& previous, std::string& why) {
    const floors::Floor& f = building.floors[std::max(0, floor)];
    const auto cands = candidates(f, sliced[std::max(0, floor)][std::max(0, layer)], thickness,
                                  m.anchor_clearance_m);
    std::vector<Anchor> chosen;
    std::vector<char> taken(cands.size(), 0);
    for (int u = 0; u < units; ++u) {
      int best = -1;
      Eigen::Vector2d best_n = Eigen::Vector2d::Zero();
      const Eigen::Vector2d home =
          previous.empty()
              ? Eigen::Vector2d(
                    m.robot->link_poses(Eigen::Isometry3d::Identity(), q0)[m.units[u].foot_link]
                        .translation()
                        .head<2>())
              : Eigen::Vector2d(previous[u].centre_m.head<2>());
      // Nearest first: the first one the unit reaches is the one.
      std::vector<std::size_t> order(cands.size());
      for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
      std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return (cands[a].point - home).norm() < (cands[b].point - home).norm();
      });
      for (std::size_t k : order) {
        if (taken[k]) continue;
        Eigen::Vector2d n = Eigen::Vector2d::Zero();
        bool ok = true;
        for (double z : platform_zs) ok = ok && reach(u, cands[k], anchor_z, z, n);
        if (!ok) continue;
        best = static_cast<int>(k);
        best_n = n;
        break;
      }
      if (best < 0) {
        why = "no " +
              std::string(f.anchors.empty() ? "solid wall"
                                            : "anchor point of floor '" + f.name + "'") +
              " within reach of unit " + m.units[u].name + " at " + metres(anchor_z, 2) +
              (floor < 0
                   ? " (in the foundation)"
                   : " (floor " + std::to_string(floor) + " layer " + std::to_string(layer) + ")");
        return std::vector<Anchor>{};
      }
      taken[best] = 1;
      const Candidate& c = cands[best];
      Anchor a;
      a.unit = u;
      a.floor = floor;
      a.wall_id = floor < 0 ? 0 : c.wall_id;
      a.layer = floor < 0 ? -1 : layer;
      a.centre_m = Eigen::Vector3d(c.point.x(), c.point.y(), anchor_z);
      a.outward = best_n;
      a.wall_thickness_m = c.thickness_m;
      a.by_default_rule = c.by_default_rule;
      a.id = c.by_default_rule || floor < 0
                 ? m.units[u].name +
                       (floor < 0 ? "-foundation"
                                  : "-f" + std::to_string(floor) + "l" + std::to_string(layer))
                 : c.id;
      chosen.push_back(a);
    }
    return chosen;
  };

  // Stage 0 stands on the foundation, as high as lets it print the first layer.
  ClimbStage stage;
  stage.platform_z_m = layers.front().z_top_m + below;
  {
    std::string why;
    stage.anchors = choose(-1, 0, -m.foundation_anchor_depth_m, {stage.platform_z_m}, {}, why);
    if (stage.anchors.empty()) {
      plan.status = {ClimbStatus::Code::kNoAnchor, "stage 0: " + why};
      return plan;
    }
  }
  std::size_t next = 0;
  for (int s = 0;; ++s) {
    stage.index = s;
    const std::size_t first = next;
    while (next < layers.size() && layers[next].z_top_m <= stage.platform_z_m + above + 1e-9)
      ++next;
    if (options.at_floor_tops && next < layers.size() && next > first &&
        layers[next].floor == layers[next - 1].floor) {
      std::size_t floor_start = next - 1;
      while (floor_start > first && layers[floor_start - 1].floor == layers[next - 1].floor)
        --floor_start;
      if (floor_start > first && layers[floor_start - 1].floor != layers[next - 1].floor)
        next = floor_start;
    }
    if (next == first) {
      plan.status = {ClimbStatus::Code::kNoAnchor,
                     printf_string("stage %d at %.2f m reaches no layer: the next one's top is at "
                                   "%.2f m, the nozzle prints from %.2f to %.2f m",
                                   s, stage.platform_z_m, layers[next].z_top_m,
                                   stage.platform_z_m - below, stage.platform_z_m + above)};
      return plan;
    }
    stage.first = {layers[first].floor, layers[first].layer};
    stage.last = {layers[next - 1].floor, layers[next - 1].layer};
    stage.top_m = layers[next - 1].z_top_m;
    plan.stages.push_back(stage);
    if (next == layers.size()) break;
    // The next stage: as high as the legs allow, the next layer still printable.
    ClimbStage up;
    up.platform_z_m = std::min(stage.platform_z_m + climb_max_m, layers[next].z_top_m + below);
    // Its pipes: as low as the legs allow (so they cure while printing goes on), in a
    // layer printed by now.
    double low = -std::numeric_limits<double>::infinity(),
           high = std::numeric_limits<double>::infinity();
    for (const auto& leg : legs) {
      low = std::max(low, up.platform_z_m + leg.foot_at_zero_m - leg.stroke_max_m);
      high = std::min(high, stage.platform_z_m + leg.foot_at_zero_m - leg.stroke_min_m);
    }
    std::string why = "the legs leave no level between " + metres(low, 2) + " and " +
                      metres(high, 2) + " in a printed layer";
    for (std::size_t k = 0; k < next && up.anchors.empty(); ++k) {
      const double mid = 0.5 * (layers[k].z_bottom_m + layers[k].z_top_m);
      if (mid < low - 1e-9 || mid > high + 1e-9) continue;
      up.anchors = choose(layers[k].floor, layers[k].layer, mid,
                          {stage.platform_z_m, up.platform_z_m}, stage.anchors, why);
    }
    if (up.anchors.empty()) {
      plan.status = {ClimbStatus::Code::kNoAnchor,
                     printf_string("climb %d -> %d: ", s, s + 1) + why};
      return plan;
    }
    stage = up;
  }
  return plan;
}

}  // namespace ccbuild::climb
