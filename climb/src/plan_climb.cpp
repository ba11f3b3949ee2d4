// One climb: park, then unit after unit balance, release, transit, insert; then lift.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "ccbuild/climb/climb.hpp"
#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "motion.hpp"
#include "scene.hpp"
#include "statics.hpp"

namespace ccbuild::climb {

std::string to_string(ClimbPhase::Kind kind) {
  switch (kind) {
    case ClimbPhase::Kind::kPark:
      return "park";
    case ClimbPhase::Kind::kBalance:
      return "balance";
    case ClimbPhase::Kind::kRelease:
      return "release";
    case ClimbPhase::Kind::kTransit:
      return "transit";
    case ClimbPhase::Kind::kInsert:
      return "insert";
    case ClimbPhase::Kind::kLift:
      return "lift";
  }
  return "?";
}

namespace {

using detail::MotionProblem;
using detail::MotionResult;
using detail::Scene;
using detail::Verdict;

std::uint64_t mix(std::uint64_t a, std::uint64_t b) {
  std::uint64_t h = a * 0x9E3779B97F4A7C15ULL ^ (b + 0x632BE59BD9B4E019ULL + (a << 6) + (a >> 2));
  h ^= h >> 31;
  return h * 0xBF58476D1CE4E5B9ULL;
}

using detail::PinTarget;
using detail::target;

// Every unit's leg following its pin in `pins` (in that order), the platform at
// `platform`: the units' joints written into `q`. Refused when a leg would leave its
// usable range (or cannot reach its pin at all).
Verdict legs_follow(const machine::ClimbingMachine& m, const std::vector<PinTarget>& pins,
                    const Eigen::Isometry3d& platform, std::vector<double>& q) {
  for (std::size_t u = 0; u < pins.size(); ++u) {
    const int unit = static_cast<int>(u);
    const auto pose =
        m.unit_ik(unit, platform, q, pins[u].foot, pins[u].direction, pins[u].engaged_m);
    if (!pose || !m.unit_within_limits(unit, *pose)) {
      const std::string leg = "unit " + m.units[u].name + "'s leg would leave its stroke";
      return Verdict::refused(leg + " at platform " + metres(platform.translation().z(), 2), leg);
    }
    m.set_unit(unit, *pose, q);
  }
  return {};
}

class Climber {
 public:
  Climber(const machine::ClimbingMachine& m, const Scene& scene, const ClimbOptions& options,
          double deadline_s, int stage)
      : m_(m),
        scene_(scene),
        options_(options),
        stage_(stage),
        began_(std::chrono::steady_clock::now()),
        deadline_s_(deadline_s) {}

  double elapsed_s() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - began_).count();
  }

  // The answer for a motion not started: the climb's planning time is spent.
  MotionResult out_of_time() const {
    MotionResult r;
    r.timed_out = true;
    r.verdict = Verdict::refused("the climb's planning time (" + printf_string("%g", deadline_s_) +
                                 " s) ran out before this motion");
    return r;
  }

  // Plans a motion of `joints` (robot joint indices) from q's values to `goal`, the
  // platform at `platform`, checking `moving` links and statics over `support`.
  MotionResult move_joints(const std::vector<int>& joints, const std::vector<double>& goal,
                           std::vector<double>& q, const Eigen::Isometry3d& platform,
                           const std::vector<int>& moving,
                           const std::vector<Eigen::Vector2d>& support) {
    if (elapsed_s() >= deadline_s_) return out_of_time();
    MotionProblem p;
    for (int j : joints) {
      const auto [lower, upper] = m_.usable_range(j);
      p.lower.push_back(lower);
      p.upper.push_back(upper);
      p.start.push_back(q[j]);
    }
    p.goal = goal;
    p.seed = mix(options_.seed, mix(static_cast<std::uint64_t>(stage_), ++motions_));
    p.time_s = deadline_s_ - elapsed_s();
    std::vector<double> work = q;
    p.valid = [&, joints](const std::vector<double>& s) {
      for (std::size_t k = 0; k < joints.size(); ++k) work[joints[k]] = s[k];
      return scene_.check(work, platform, moving, moving, support);
    };
    MotionResult r = detail::plan_motion(p);
    if (r.verdict.ok)
      for (std::size_t k = 0; k < joints.size(); ++k) q[joints[k]] = goal[k];
    return r;
  }

  // Seconds along a path of `joints` at their velocity limits.
  double path_time_s(const std::vector<int>& joints, const std::vector<std::vector<double>>& path,
                     std::vector<double>& t_s) const {
    t_s.assign(1, 0.0);
    for (std::size_t k = 1; k < path.size(); ++k) {
      double dt = 0.0;
      for (std::size_t j = 0; j < joints.size(); ++j)
        dt = std::max(
            dt, std::abs(path[k][j] - path[k - 1][j]) / m_.robot->joint_info(joints[j]).velocity);
      t_s.push_back(t_s.back() + dt);
    }
    return t_s.back();
  }

  double clearance(const std::vector<int>& joints, const std::vector<std::vector<double>>& path,
                   std::vector<double> q, const Eigen::Isometry3d& platform,
                   const std::vector<int>& moving) const {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& state : path) {
      for (std::size_t k = 0; k < joints.size(); ++k) q[joints[k]] = state[k];
      best = std::min(best, scene_.clearance(q, platform, moving));
    }
    return best;
  }

 private:
  const machine::ClimbingMachine& m_;
  const Scene& scene_;
  const ClimbOptions& options_;
  int stage_;
  std::chrono::steady_clock::time_point began_;
  double deadline_s_;
  std::uint64_t motions_ = 0;
};

}  // namespace

ClimbPlan plan_climb(const machine::ClimbingMachine& m, const floors::Building& building,
                     const ClimbStage& from, const ClimbStage& to, const ClimbOptions& options) {
  ClimbPlan plan;
  plan.from_stage = from.index;
  plan.to_stage = to.index;
  plan.min_clearance_m = std::numeric_limits<double>::infinity();
  const int units = static_cast<int>(m.units.size());
  CCBUILD_CHECK(static_cast<int>(from.anchors.size()) == units &&
                    static_cast<int>(to.anchors.size()) == units,
                "a stage has an anchor for every unit");
  const auto began = std::chrono::steady_clock::now();
  std::vector<Anchor> pipes = from.anchors;
  pipes.insert(pipes.end(), to.anchors.begin(), to.anchors.end());
  const Scene scene(m, detail::walls_built(building, from.last, m.gantry.nozzle_width_m), pipes);
  Climber climber(m, scene, options, options.time_limit_s, from.index);
  const machine::Kinematics& robot = *m.robot;

  // Where the climb starts: the units engaged in this stage's pipes, the gantry in the
  // middle of the building with its nozzle at the last layer's top.
  const Eigen::Isometry3d platform(Eigen::Translation3d(0, 0, from.platform_z_m));
  std::vector<double> q = robot.zero();
  const auto& gx = robot.joint_info(m.gantry_joints[0]);
  const auto& gy = robot.joint_info(m.gantry_joints[1]);
  const auto& gz = robot.joint_info(m.gantry_joints[2]);
  q[m.gantry_joints[0]] = 0.5 * (gx.lower + gx.upper);
  q[m.gantry_joints[1]] = 0.5 * (gy.lower + gy.upper);
  // The nozzle has just lifted off the last layer it printed (by a centimetre).
  q[m.gantry_joints[2]] = std::clamp(from.top_m + 0.01 - from.platform_z_m, gz.lower, gz.upper);
  std::vector<Anchor> holding = from.anchors;
  for (int u = 0; u < units; ++u) {
    const PinTarget t = target(m, from.anchors[u]);
    const auto pose = m.unit_ik(u, platform, q, t.foot, t.direction, t.engaged_m);
    CCBUILD_CHECK(pose.has_value(), "stages place anchors the units reach");
    m.set_unit(u, *pose, q);
  }
  auto support_without = [&](const std::vector<int>& moving_units) {
    std::vector<Eigen::Vector2d> points;
    for (int u = 0; u < units; ++u)
      if (std::find(moving_units.begin(), moving_units.end(), u) == moving_units.end())
        points.push_back(holding[u].centre_m.head<2>());
    return points;
  };
  auto fail = [&](ClimbStatus::Code code, const std::string& why) {
    plan.status = {code, why};
    plan.planning_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
    return plan;
  };
  auto joint_names = [&](const std::vector<int>& joints) {
    std::vector<std::string> names;
    for (int j : joints) names.push_back(robot.joint_info(j).name);
    return names;
  };
  // A finished motion becomes a phase; a failed one ends the climb with its reason.
  auto record = [&](ClimbPhase::Kind kind, int unit, const std::vector<int>& joints,
                    const MotionResult& r, const std::vector<double>& q_before,
                    const Eigen::Isometry3d& at, const std::vector<int>& moving,
                    double fixed_duration_s) -> bool {
    ClimbPhase phase;
    phase.kind = kind;
    phase.unit = unit;
    phase.joints = joint_names(joints);
    phase.planning_s = r.planning_s;
    if (!r.verdict.ok) return false;
    phase.path = r.path;
    phase.duration_s = climber.path_time_s(joints, r.path, phase.t_s);
    if (fixed_duration_s > phase.duration_s) {
      // The pin's own time (engaging, locking) stretches its motion.
      const double scale = phase.duration_s > 0 ? fixed_duration_s / phase.duration_s : 0.0;
      for (std::size_t k = 0; k < phase.t_s.size(); ++k)
        phase.t_s[k] = scale > 0 ? phase.t_s[k] * scale
                                 : fixed_duration_s * static_cast<double>(k) /
                                       std::max<std::size_t>(1, phase.t_s.size() - 1);
      phase.duration_s = fixed_duration_s;
    }
    phase.min_clearance_m = climber.clearance(joints, r.path, q_before, at, moving);
    plan.min_clearance_m = std::min(plan.min_clearance_m, phase.min_clearance_m);
    plan.duration_s += phase.duration_s;
    plan.phases.push_back(std::move(phase));
    return true;
  };
  auto blocked = [&](const MotionResult& r) {
    return r.timed_out          ? ClimbStatus::Code::kTimeLimit
           : r.verdict.unstable ? ClimbStatus::Code::kUnstable
                                : ClimbStatus::Code::kBlocked;
  };

  // 1. Park: the nozzle up, clear of the walls.
  {
    const std::vector<int> joints{m.gantry_joints[2]};
    const std::vector<double> before = q;
    const MotionResult r =
        climber.move_joints(joints, {gz.upper}, q, platform, m.gantry_links, support_without({}));
    if (!record(ClimbPhase::Kind::kPark, -1, joints, r, before, platform, m.gantry_links, 0.0))
      return fail(blocked(r), "park: " + r.verdict.why);
  }

  // 2. The units change pipes, units_per_transfer at a time, in their most stable order.
  const detail::Transfers transfers(m, from, to, platform, q);
  if (!transfers.unreachable.empty())
    return fail(ClimbStatus::Code::kNoAnchor, transfers.unreachable);
  const auto& out_old = transfers.out_old;
  const auto& out_new = transfers.out_new;
  const auto& in_new = transfers.in_new;
  const std::vector<int>& order = transfers.order;
  const bool every_order = transfers.every_order;
  std::vector<char> moved(units, 0);
  for (int first = 0; first < units; first += m.units_per_transfer) {
    const std::vector<int> group(order.begin() + first,
                                 order.begin() + std::min(units, first + m.units_per_transfer));
    std::string names;
    for (int u : group) names += (names.empty() ? "" : ", ") + m.units[u].name;
    const auto support = support_without(group);
    // Balance: the gantry, as a counterweight, where the platform stands best on the
    // holding units with the moving ones at either end of their motion.
    {
      const std::vector<int> joints{m.gantry_joints[0], m.gantry_joints[1]};
      const detail::Transfers::Counterweight best =
          transfers.counterweight(group, moved, q, q[joints[0]], q[joints[1]]);
      if (!std::isfinite(best.margin))
        return fail(ClimbStatus::Code::kUnstable,
                    "moving " + names +
                        ": the pins left holding lie in a line, no polygon to "
                        "stand on");
      if (best.margin < m.stability_margin_m)
        return fail(
            ClimbStatus::Code::kUnstable,
            "moving " + names +
                ": with the gantry as counterweight anywhere on its "
                "rails, the centre of mass stays " +
                metres(m.stability_margin_m - best.margin, 2) +
                " short of the margin inside the holding pins' polygon" +
                (every_order ? " (in every order of the units)"
                             : " (the units taken in their most stable order, one by one)"));
      const std::vector<double> before = q;
      const MotionResult r = climber.move_joints(joints, {best.x, best.y}, q, platform,
                                                 m.gantry_links, support_without({}));
      if (!record(ClimbPhase::Kind::kBalance, group.front(), joints, r, before, platform,
                  m.gantry_links, 0.0))
        return fail(blocked(r), "balance for " + names + ": " + r.verdict.why);
    }
    for (std::size_t k = 0; k < group.size(); ++k) {
      const int u = group[k];
      const auto& uj = m.units[u].joints;
      // The pin slides alone (the rest of the unit holds still: it is in its pipe); the
      // transit moves everything but the pin.
      const std::vector<int> pin{uj[4]};
      const std::vector<int> arm{uj[0], uj[1], uj[2], uj[3]};
      const std::vector<int>& moving = m.units[u].links;
      struct Step {
        ClimbPhase::Kind kind;
        const std::vector<int>* joints;
        std::vector<double> goal;
        double fixed_s;
      };
      const machine::UnitPose& b = out_new[u];
      for (const Step& step :
           {Step{ClimbPhase::Kind::kRelease, &pin, {out_old[u][4]}, m.pin_release_s},
            Step{ClimbPhase::Kind::kTransit, &arm, {b[0], b[1], b[2], b[3]}, 0.0},
            Step{ClimbPhase::Kind::kInsert, &pin, {in_new[u][4]}, m.pin_insert_s}}) {
        const std::vector<double> before = q;
        const MotionResult r =
            climber.move_joints(*step.joints, step.goal, q, platform, moving, support);
        if (!record(step.kind, u, *step.joints, r, before, platform, moving, step.fixed_s))
          return fail(blocked(r), to_string(step.kind) + " of unit " + m.units[u].name + " to " +
                                      to.anchors[u].id + ": " + r.verdict.why);
      }
      holding[u] = to.anchors[u];
      moved[u] = 1;
    }
  }

  // 3. Lift: the platform rises on the legs, its units' joints following the pins.
  {
    const double dz = to.platform_z_m - from.platform_z_m;
    MotionProblem p;
    p.lower = {-0.3, -0.3, std::min(from.platform_z_m, to.platform_z_m)};
    p.upper = {0.3, 0.3, std::max(from.platform_z_m, to.platform_z_m)};
    p.start = {0.0, 0.0, from.platform_z_m};
    p.goal = {0.0, 0.0, to.platform_z_m};
    p.seed = mix(options.seed, mix(static_cast<std::uint64_t>(from.index), 1000));
    p.time_s = options.time_limit_s - climber.elapsed_s();
    std::vector<Eigen::Vector2d> support;
    for (const auto& a : to.anchors) support.push_back(a.centre_m.head<2>());
    std::vector<int> all(robot.link_count()), unit_links;
    for (int l = 0; l < robot.link_count(); ++l) all[l] = l;
    for (const auto& unit : m.units)
      unit_links.insert(unit_links.end(), unit.links.begin(), unit.links.end());
    std::vector<double> work = q;
    std::vector<PinTarget> pins;
    for (const auto& a : to.anchors) pins.push_back(target(m, a));
    auto follow = [&](const std::vector<double>& s, std::vector<double>& out) {
      return legs_follow(m, pins, Eigen::Isometry3d(Eigen::Translation3d(s[0], s[1], s[2])), out);
    };
    p.valid = [&](const std::vector<double>& s) {
      Verdict v = follow(s, work);
      if (!v.ok) return v;
      // Rigid parts keep their places on the platform: only the units move against it.
      return scene.check(work, Eigen::Isometry3d(Eigen::Translation3d(s[0], s[1], s[2])), all,
                         unit_links, support);
    };
    const MotionResult r = p.time_s > 0 ? detail::plan_motion(p) : climber.out_of_time();
    ClimbPhase phase;
    phase.kind = ClimbPhase::Kind::kLift;
    phase.joints = {"platform_x", "platform_y", "platform_z"};
    phase.planning_s = r.planning_s;
    if (!r.verdict.ok) return fail(blocked(r), "lift: " + r.verdict.why);
    phase.path = r.path;
    // Under load the legs move at the loaded stroke speed, one cylinder stroke at a time
    // with a reset between strokes: the resets are spread over the path.
    phase.t_s = {0.0};
    for (std::size_t k = 1; k < r.path.size(); ++k) {
      const double d =
          std::hypot(std::hypot(r.path[k][0] - r.path[k - 1][0], r.path[k][1] - r.path[k - 1][1]),
                     r.path[k][2] - r.path[k - 1][2]);
      phase.t_s.push_back(phase.t_s.back() + d / m.stroke_speed_loaded_m_s);
    }
    phase.strokes =
        std::max(1, static_cast<int>(std::ceil(std::abs(dz) / m.lift_per_stroke_m - 1e-9)));
    const double moving_s = phase.t_s.back();
    phase.duration_s = moving_s + (phase.strokes - 1) * m.stroke_reset_s;
    if (moving_s > 0)
      for (double& t : phase.t_s) t *= phase.duration_s / moving_s;
    for (const auto& unit : m.units)
      for (int k = 0; k < 4; ++k)
        phase.following_joints.push_back(robot.joint_info(unit.joints[k]).name);
    double clearance = std::numeric_limits<double>::infinity();
    for (const auto& s : r.path) {
      follow(s, work);
      std::vector<double> legs;
      for (const auto& unit : m.units)
        for (int k = 0; k < 4; ++k) legs.push_back(work[unit.joints[k]]);
      phase.following.push_back(std::move(legs));
      clearance = std::min(
          clearance,
          scene.clearance(work, Eigen::Isometry3d(Eigen::Translation3d(s[0], s[1], s[2])), all));
    }
    phase.min_clearance_m = clearance;
    plan.min_clearance_m = std::min(plan.min_clearance_m, clearance);
    plan.duration_s += phase.duration_s;
    plan.phases.push_back(std::move(phase));
  }
  plan.planning_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  return plan;
}

ClimbStatus verify_climb(const machine::ClimbingMachine& m, const floors::Building& building,
                         const ClimbStage& from, const ClimbStage& to, const ClimbPlan& plan,
                         double step_m, double step_rad) {
  const machine::Kinematics& robot = *m.robot;
  std::vector<Anchor> pipes = from.anchors;
  pipes.insert(pipes.end(), to.anchors.begin(), to.anchors.end());
  const Scene scene(m, detail::walls_built(building, from.last, m.gantry.nozzle_width_m), pipes);
  const int units = static_cast<int>(m.units.size());
  // The machine as the climb starts, from the phases' own first states.
  std::vector<double> q = robot.zero();
  Eigen::Isometry3d platform(Eigen::Translation3d(0, 0, from.platform_z_m));
  std::vector<Anchor> holding = from.anchors;
  for (int u = 0; u < units; ++u) {
    const PinTarget t = target(m, from.anchors[u]);
    const auto pose = m.unit_ik(u, platform, q, t.foot, t.direction, t.engaged_m);
    if (!pose) return {ClimbStatus::Code::kNoAnchor, "unit " + m.units[u].name + " cannot hold"};
    m.set_unit(u, *pose, q);
  }
  std::vector<int> all(robot.link_count());
  for (int l = 0; l < robot.link_count(); ++l) all[l] = l;
  std::vector<PinTarget> lift_pins;
  for (const auto& a : to.anchors) lift_pins.push_back(target(m, a));
  for (std::size_t p = 0; p < plan.phases.size(); ++p) {
    const ClimbPhase& phase = plan.phases[p];
    const std::string where = "phase " + std::to_string(p + 1) + " (" + to_string(phase.kind) + ")";
    if (phase.path.empty()) return {ClimbStatus::Code::kBlocked, where + " has no path"};
    std::vector<int> joints;
    if (phase.kind != ClimbPhase::Kind::kLift)
      for (const auto& name : phase.joints) joints.push_back(robot.joint(name));
    std::vector<Eigen::Vector2d> support;
    std::vector<int> moving = all, self = all;
    if (phase.kind == ClimbPhase::Kind::kLift) {
      for (const auto& a : to.anchors) support.push_back(a.centre_m.head<2>());
      self.clear();
      for (const auto& unit : m.units)
        self.insert(self.end(), unit.links.begin(), unit.links.end());
    } else {
      const bool unit_moves = phase.unit >= 0 && phase.kind != ClimbPhase::Kind::kBalance;
      for (int u = 0; u < units; ++u)
        if (!unit_moves || u != phase.unit) support.push_back(holding[u].centre_m.head<2>());
      moving = unit_moves ? m.units[phase.unit].links : m.gantry_links;
      self = moving;
    }
    for (std::size_t k = 0; k + 1 < phase.path.size(); ++k) {
      const auto& a = phase.path[k];
      const auto& b = phase.path[k + 1];
      int steps = 1;
      for (std::size_t j = 0; j < a.size(); ++j) {
        const bool angular = phase.kind != ClimbPhase::Kind::kLift &&
                             robot.joint_info(joints[j]).type != "prismatic";
        steps = std::max(steps, static_cast<int>(std::ceil(std::abs(b[j] - a[j]) /
                                                           (angular ? step_rad : step_m))));
      }
      for (int i = 0; i <= steps; ++i) {
        const double f = static_cast<double>(i) / steps;
        std::vector<double> s(a.size());
        for (std::size_t j = 0; j < a.size(); ++j) s[j] = a[j] + f * (b[j] - a[j]);
        if (phase.kind == ClimbPhase::Kind::kLift) {
          platform = Eigen::Isometry3d(Eigen::Translation3d(s[0], s[1], s[2]));
          const Verdict v = legs_follow(m, lift_pins, platform, q);
          if (!v.ok) return {ClimbStatus::Code::kBlocked, where + ": " + v.why};
        } else {
          for (std::size_t j = 0; j < joints.size(); ++j) {
            const auto [lower, upper] = m.usable_range(joints[j]);
            if (s[j] < lower - 1e-9 || s[j] > upper + 1e-9)
              return {ClimbStatus::Code::kBlocked,
                      where + ": joint " + robot.joint_info(joints[j]).name + " leaves its limits"};
            q[joints[j]] = s[j];
          }
        }
        const Verdict v = scene.check(q, platform, moving, self, support);
        if (!v.ok)
          return {v.unstable ? ClimbStatus::Code::kUnstable : ClimbStatus::Code::kBlocked,
                  where + ": " + v.why};
      }
    }
    if (phase.kind == ClimbPhase::Kind::kInsert) holding[phase.unit] = to.anchors[phase.unit];
  }
  return {};
}

}  // namespace ccbuild::climb
