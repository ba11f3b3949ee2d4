// Where the platform stands, stage after stage, and which pipes hold it there.

#include <algorithm>
#include <cmath>
#include <limits>

#include "ccbuild/climb/climb.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/floors/slice.hpp"
#include "stage_frames.hpp"

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
    case ClimbStatus::Code::kTooLarge:
      return "too-large";
  }
  return "?";
}

namespace {

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

}  // namespace

namespace detail {

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

bool pin_reaches(const machine::ClimbingMachine& m, int u, const Eigen::Isometry3d& platform,
                 const Eigen::Vector2d& mount, const Candidate& c, double anchor_z,
                 Eigen::Vector2d& outward) {
  const std::vector<double> q0 = m.robot->zero();
  Eigen::Vector2d n(-c.along.y(), c.along.x());
  if (n.dot(mount - c.point) < 0) n = -n;  // the unit is on this side of the wall
  outward = n;
  const double depth = 0.5 * c.thickness_m + m.pin_gap_m + m.pin_past_centre_m;
  Eigen::Vector3d foot(c.point.x(), c.point.y(), anchor_z);
  foot.head<2>() += n * (0.5 * c.thickness_m + m.pin_gap_m + m.foot_to_pin_m());
  const auto pose = m.unit_ik(u, platform, q0, foot, -n, depth);
  return pose && m.unit_within_limits(u, *pose);
}

StageFrames stage_frames(const floors::Building& building, const machine::ClimbingMachine& m) {
  StageFrames out;
  for (const auto& floor : building.floors) {
    out.sliced.push_back(floors::slice_floor(floor, building.layer_height_m));
    for (const auto& l : out.sliced.back())
      out.layers.push_back({floor.index, l.index, l.z_bottom_m, l.z_top_m});
  }
  const auto& layers = out.layers;
  if (layers.empty()) return out;
  std::vector<Leg> legs;
  double climb_max_m = std::numeric_limits<double>::infinity();
  for (int u = 0; u < static_cast<int>(m.units.size()); ++u) {
    legs.push_back(leg_of(m, u));
    climb_max_m = std::min(climb_max_m, legs.back().stroke_max_m - legs.back().stroke_min_m);
  }
  const double below = m.nozzle_reach_below_m, above = m.nozzle_reach_above_m;

  // Stage 0 stands on the foundation, as high as lets it print the first layer.
  StageFrame frame;
  frame.stage.platform_z_m = layers.front().z_top_m + below;
  frame.platform_zs = {frame.stage.platform_z_m};
  frame.levels = {{-1, 0, -m.foundation_anchor_depth_m, 0}};
  std::size_t next = 0;
  for (int s = 0;; ++s) {
    ClimbStage& stage = frame.stage;
    stage.index = s;
    const std::size_t first = next;
    while (next < layers.size() && layers[next].z_top_m <= stage.platform_z_m + above + 1e-9)
      ++next;
    if (!building.climbs_within_storey && next < layers.size() && next > first &&
        layers[next].floor == layers[next - 1].floor) {
      std::size_t floor_start = next - 1;
      while (floor_start > first && layers[floor_start - 1].floor == layers[next - 1].floor)
        --floor_start;
      if (floor_start > first && layers[floor_start - 1].floor != layers[next - 1].floor)
        next = floor_start;
    }
    if (next == first) {
      out.status = {ClimbStatus::Code::kNoAnchor,
                    printf_string("stage %d at %.2f m reaches no layer: the next one's top is at "
                                  "%.2f m, the nozzle prints from %.2f to %.2f m",
                                  s, stage.platform_z_m, layers[next].z_top_m,
                                  stage.platform_z_m - below, stage.platform_z_m + above)};
      return out;
    }
    stage.first = {layers[first].floor, layers[first].layer};
    stage.last = {layers[next - 1].floor, layers[next - 1].layer};
    stage.top_m = layers[next - 1].z_top_m;
    out.frames.push_back(frame);
    if (next == layers.size()) break;
    // The next stage: as high as the legs allow, the next layer still printable. Its
    // pipes: as low as the legs allow (so they cure while printing goes on), in a layer
    // printed by now.
    StageFrame up;
    up.stage.platform_z_m =
        std::min(stage.platform_z_m + climb_max_m, layers[next].z_top_m + below);
    up.platform_zs = {stage.platform_z_m, up.stage.platform_z_m};
    double low = -std::numeric_limits<double>::infinity(),
           high = std::numeric_limits<double>::infinity();
    for (const auto& leg : legs) {
      low = std::max(low, up.stage.platform_z_m + leg.foot_at_zero_m - leg.stroke_max_m);
      high = std::min(high, stage.platform_z_m + leg.foot_at_zero_m - leg.stroke_min_m);
    }
    for (std::size_t k = 0; k < next; ++k) {
      const double mid = 0.5 * (layers[k].z_bottom_m + layers[k].z_top_m);
      if (mid < low - 1e-9 || mid > high + 1e-9) continue;
      up.levels.push_back({layers[k].floor, layers[k].layer, mid, k});
    }
    if (up.levels.empty())
      up.no_level = "the legs leave no level between " + metres(low, 2) + " and " +
                    metres(high, 2) + " in a printed layer";
    frame = std::move(up);
  }
  return out;
}

StagePlan place_anchors(const floors::Building& building, const machine::ClimbingMachine& m,
                        const StageFrames& frames) {
  StagePlan plan;
  const int units = static_cast<int>(m.units.size());
  const double thickness = m.gantry.nozzle_width_m;
  const std::vector<double> q0 = m.robot->zero();
  // Each unit's foot at zero, in plan: the platform only rises, so it stays there.
  std::vector<Eigen::Vector2d> mounts;
  {
    const auto poses = m.robot->link_poses(Eigen::Isometry3d::Identity(), q0);
    for (const auto& unit : m.units)
      mounts.push_back(poses[unit.foot_link].translation().head<2>());
  }

  // Picks one pipe per unit at `level`, reachable with the platform at each of
  // `platform_zs`, nearest each unit's previous pin; empty with `why` when some unit has
  // none: then `why` names the unit, the nearest solid wall and what would reach it.
  auto choose = [&](const detail::AnchorLevel& level, const std::vector<double>& platform_zs,
                    const std::vector<Anchor>& previous, std::string& why) {
    const int floor = level.floor;
    const floors::Floor& f = building.floors[std::max(0, floor)];
    const auto cands =
        detail::candidates(f, frames.sliced[std::max(0, floor)][std::max(0, level.layer)],
                           thickness, m.anchor_clearance_m);
    std::vector<Anchor> chosen;
    std::vector<char> taken(cands.size(), 0);
    for (int u = 0; u < units; ++u) {
      int best = -1;
      Eigen::Vector2d best_n = Eigen::Vector2d::Zero();
      const Eigen::Vector2d home =
          previous.empty() ? mounts[u] : Eigen::Vector2d(previous[u].centre_m.head<2>());
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
        for (double z : platform_zs)
          ok = ok && detail::pin_reaches(m, u, Eigen::Isometry3d(Eigen::Translation3d(0, 0, z)),
                                         mounts[u], cands[k], level.z_m, n);
        if (!ok) continue;
        best = static_cast<int>(k);
        best_n = n;
        break;
      }
      if (best < 0) {
        why = "no " +
              std::string(f.anchors.empty() ? "solid wall"
                                            : "anchor point of floor '" + f.name + "'") +
              " within reach of unit " + m.units[u].name + " at " + metres(level.z_m, 2) +
              (floor < 0 ? " (in the foundation)"
                         : " (floor " + std::to_string(floor) + " layer " +
                               std::to_string(level.layer) + ")");
        // The nearest solid wall to the unit's mount, and how far the unit reaches.
        const Eigen::Vector2d mount = mounts[u];
        const detail::Candidate* nearest = nullptr;
        for (const auto& c : cands)
          if (!nearest || (c.point - mount).norm() < (nearest->point - mount).norm()) nearest = &c;
        if (nearest) {
          const auto [reach_min_m, reach_max_m] = m.usable_range(m.units[u].joints[1]);
          why += printf_string(
              ": the nearest is wall %lld at (%.2f, %.2f), %.2f m from %s's mount at (%.2f, "
              "%.2f), and its boom reaches %.2f to %.2f m; mount %s within reach of it, or fit "
              "the machine to the building (`ccbuild fit BUILDING --machine FAMILY.yaml`)",
              static_cast<long long>(nearest->wall_id), nearest->point.x(), nearest->point.y(),
              (nearest->point - mount).norm(), m.units[u].name.c_str(), mount.x(), mount.y(),
              reach_min_m, reach_max_m, m.units[u].name.c_str());
        } else {
          why += ": the layer has no solid wall at least " + metres(m.anchor_clearance_m, 2) +
                 " from wall ends and openings";
        }
        return std::vector<Anchor>{};
      }
      taken[best] = 1;
      const detail::Candidate& c = cands[best];
      Anchor a;
      a.unit = u;
      a.floor = floor;
      a.wall_id = floor < 0 ? 0 : c.wall_id;
      a.layer = floor < 0 ? -1 : level.layer;
      a.centre_m = Eigen::Vector3d(c.point.x(), c.point.y(), level.z_m);
      a.outward = best_n;
      a.wall_thickness_m = c.thickness_m;
      a.by_default_rule = c.by_default_rule;
      a.id = c.by_default_rule || floor < 0
                 ? m.units[u].name + (floor < 0 ? "-foundation"
                                                : "-f" + std::to_string(floor) + "l" +
                                                      std::to_string(level.layer))
                 : c.id;
      chosen.push_back(a);
    }
    return chosen;
  };

  std::vector<Anchor> previous;
  for (const detail::StageFrame& frame : frames.frames) {
    ClimbStage stage = frame.stage;
    std::string why = frame.no_level;
    // The lowest level first; when none has pipes for every unit, the lowest one's reason.
    for (const auto& level : frame.levels) {
      std::string level_why;
      stage.anchors = choose(level, frame.platform_zs, previous, level_why);
      if (!stage.anchors.empty()) break;
      if (&level == &frame.levels.front()) why = level_why;
    }
    if (stage.anchors.empty()) {
      plan.status = {ClimbStatus::Code::kNoAnchor,
                     stage.index == 0
                         ? "stage 0: " + why
                         : printf_string("climb %d -> %d: ", stage.index - 1, stage.index) + why};
      return plan;
    }
    previous = stage.anchors;
    plan.stages.push_back(std::move(stage));
  }
  if (!frames.status) plan.status = frames.status;
  return plan;
}

}  // namespace detail

StagePlan climb_stages(const floors::Building& building, const machine::ClimbingMachine& m) {
  return detail::place_anchors(building, m, detail::stage_frames(building, m));
}

}  // namespace ccbuild::climb
