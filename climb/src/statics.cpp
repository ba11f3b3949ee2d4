#include "statics.hpp"

#include <algorithm>
#include <cmath>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "scene.hpp"

namespace ccbuild::climb::detail {

PinTarget target(const machine::ClimbingMachine& m, const Anchor& a) {
  PinTarget t;
  t.direction = -a.outward;
  t.foot = a.centre_m;
  t.foot.head<2>() += a.outward * (0.5 * a.wall_thickness_m + m.pin_gap_m + m.foot_to_pin_m());
  t.engaged_m = 0.5 * a.wall_thickness_m + m.pin_gap_m + m.pin_past_centre_m;
  return t;
}

std::vector<double> parked_on(const machine::ClimbingMachine& m, const ClimbStage& from) {
  const machine::Kinematics& robot = *m.robot;
  const Eigen::Isometry3d platform(Eigen::Translation3d(0, 0, from.platform_z_m));
  std::vector<double> q = robot.zero();
  const auto& gx = robot.joint_info(m.gantry_joints[0]);
  const auto& gy = robot.joint_info(m.gantry_joints[1]);
  q[m.gantry_joints[0]] = 0.5 * (gx.lower + gx.upper);
  q[m.gantry_joints[1]] = 0.5 * (gy.lower + gy.upper);
  q[m.gantry_joints[2]] = robot.joint_info(m.gantry_joints[2]).upper;
  for (int u = 0; u < static_cast<int>(m.units.size()); ++u) {
    const PinTarget t = target(m, from.anchors[u]);
    const auto pose = m.unit_ik(u, platform, q, t.foot, t.direction, t.engaged_m);
    if (!pose) return {};
    m.set_unit(u, *pose, q);
  }
  return q;
}

Transfers::Transfers(const machine::ClimbingMachine& m, const ClimbStage& from,
                     const ClimbStage& to, const Eigen::Isometry3d& platform,
                     const std::vector<double>& q)
    : m_(m), from_(from), to_(to), platform_(platform) {
  const machine::Kinematics& robot = *m.robot;
  const int units = static_cast<int>(m.units.size());
  // Where each unit goes.
  out_old.resize(units);
  out_new.resize(units);
  in_new.resize(units);
  in_old.resize(units);
  for (int u = 0; u < units; ++u) {
    const PinTarget old_t = target(m, from.anchors[u]), new_t = target(m, to.anchors[u]);
    const auto a = m.unit_ik(u, platform, q, old_t.foot, old_t.direction, 0.0);
    const auto b = m.unit_ik(u, platform, q, new_t.foot, new_t.direction, 0.0);
    const auto c = m.unit_ik(u, platform, q, new_t.foot, new_t.direction, new_t.engaged_m);
    if (!a || !b || !c || !m.unit_within_limits(u, *b) || !m.unit_within_limits(u, *c)) {
      unreachable = "unit " + m.units[u].name + " cannot reach anchor " + to.anchors[u].id +
                    " from the platform at " + metres(from.platform_z_m, 2);
      return;
    }
    out_old[u] = *a;
    out_new[u] = *b;
    in_new[u] = *c;
    in_old[u] = m.get_unit(u, q);
  }
  // The gantry is the counterweight: the centre of mass moves linearly with it, by its
  // mass (x) and its carriage's (y) over the machine's.
  const int carriage = robot.link(robot.joint_info(m.gantry_joints[1]).child_link);
  for (int l : m.gantry_links) {
    mass_x_ += robot.link_info(l).mass_kg;
    if (robot.is_ancestor(carriage, l)) mass_y_ += robot.link_info(l).mass_kg;
  }
  mass_x_ /= robot.total_mass_kg();
  mass_y_ /= robot.total_mass_kg();

  // The order of the units: of all orders, the one whose least stable transfer is the
  // most stable (ties: the first in the units' own order). Beyond kExhaustiveUnits units
  // (720 orders) the orders are too many: then each next unit is the one whose transfer is
  // the most stable, given those before it.
  constexpr int kExhaustiveUnits = 6;
  every_order = units <= kExhaustiveUnits;
  order.resize(units);
  for (int u = 0; u < units; ++u) order[u] = u;
  const double gx0 = q[m.gantry_joints[0]], gy0 = q[m.gantry_joints[1]];
  if (every_order) {
    std::vector<int> trial = order, best_order = order;
    double best_margin = -std::numeric_limits<double>::infinity();
    do {
      std::vector<char> moved(units, 0);
      double worst = std::numeric_limits<double>::infinity();
      for (int first = 0; first < units && worst > best_margin; first += m.units_per_transfer) {
        const std::vector<int> group(trial.begin() + first,
                                     trial.begin() + std::min(units, first + m.units_per_transfer));
        worst = std::min(worst, counterweight(group, moved, q, gx0, gy0).margin);
        for (int u : group) moved[u] = 1;
      }
      if (worst > best_margin + 1e-9) {
        best_margin = worst;
        best_order = trial;
      }
    } while (std::next_permutation(trial.begin(), trial.end()));
    order = best_order;
  } else {
    order.clear();
    std::vector<char> moved(units, 0), placed(units, 0);
    std::vector<int> group;
    while (static_cast<int>(order.size()) < units) {
      int best = -1;
      double best_margin = -std::numeric_limits<double>::infinity();
      for (int u = 0; u < units; ++u) {
        if (placed[u]) continue;
        std::vector<int> trial = group;
        trial.push_back(u);
        const double margin = counterweight(trial, moved, q, gx0, gy0).margin;
        if (best < 0 || margin > best_margin + 1e-9) {
          best = u;
          best_margin = margin;
        }
      }
      placed[best] = 1;
      order.push_back(best);
      group.push_back(best);
      if (static_cast<int>(group.size()) == m.units_per_transfer) {
        for (int u : group) moved[u] = 1;
        group.clear();
      }
    }
  }
  std::vector<char> moved(units, 0);
  least_margin_m = std::numeric_limits<double>::infinity();
  for (int first = 0; first < units; first += m.units_per_transfer) {
    const std::vector<int> group(order.begin() + first,
                                 order.begin() + std::min(units, first + m.units_per_transfer));
    least_margin_m = std::min(least_margin_m, counterweight(group, moved, q, gx0, gy0).margin);
    for (int u : group) moved[u] = 1;
  }
}

Transfers::Counterweight Transfers::counterweight(const std::vector<int>& group,
                                                  const std::vector<char>& moved,
                                                  const std::vector<double>& q, double x0,
                                                  double y0) const {
  const machine::ClimbingMachine& m = m_;
  const machine::Kinematics& robot = *m.robot;
  const int units = static_cast<int>(m.units.size());
  const auto& gx = robot.joint_info(m.gantry_joints[0]);
  const auto& gy = robot.joint_info(m.gantry_joints[1]);
  const ClimbStage& from = from_;
  const ClimbStage& to = to_;
  const Eigen::Isometry3d& platform = platform_;
  const double mass_x = mass_x_, mass_y = mass_y_;
  std::vector<double> base = q;
  std::vector<Eigen::Vector2d> support;
  for (int u = 0; u < units; ++u) {
    m.set_unit(u, moved[u] ? in_new[u] : in_old[u], base);
    if (std::find(group.begin(), group.end(), u) == group.end())
      support.push_back((moved[u] ? to.anchors[u] : from.anchors[u]).centre_m.head<2>());
  }
  base[m.gantry_joints[0]] = x0;
  base[m.gantry_joints[1]] = y0;
  std::vector<Eigen::Vector2d> coms;
  for (const auto* poses : {&out_old, &out_new}) {
    std::vector<double> at = base;
    for (int u : group) m.set_unit(u, (*poses)[u], at);
    coms.push_back(robot.centre_of_mass(robot.link_poses(platform, at)).head<2>());
  }
  Counterweight best;
  double best_score = -std::numeric_limits<double>::infinity();
  for (int ix = 0; ix <= 48; ++ix)
    for (int iy = 0; iy <= 16; ++iy) {
      const double x = gx.lower + (gx.upper - gx.lower) * ix / 48.0;
      const double y = gy.lower + (gy.upper - gy.lower) * iy / 16.0;
      double worst = std::numeric_limits<double>::infinity();
      for (const auto& c : coms)
        worst = std::min(
            worst, detail::inside_hull_m(c + Eigen::Vector2d(mass_x * (x - x0), mass_y * (y - y0)),
                                         support));
      // The stablest; among near-equals, the nearest.
      const double score = worst - 1e-3 * std::hypot(x - x0, y - y0);
      if (score > best_score) {
        best_score = score;
        best = {x, y, worst};
      }
    }
  return best;
}

}  // namespace ccbuild::climb::detail
