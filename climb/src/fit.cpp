// Fitting a climbing machine to a building: the platform around the building, then the
// fewest units, mounted where every one reaches solid wall at every stage and every
// transfer keeps the platform stable.

#include "ccbuild/climb/fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "ccbuild/common/format.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/machine/urdf_adapter.hpp"
#include "scene.hpp"
#include "stage_frames.hpp"
#include "statics.hpp"

namespace ccbuild::climb {
namespace {

using machine::UnitMount;
using Beam = machine::UnitMount::Beam;

// A mount position on a beam, and the probe unit (on the same beam) that stands in for it.
struct MountSite {
  Beam beam = Beam::kSouth;
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  double along_m = 0.0;  ///< around the beams' rectangle, from its south-west corner
  int probe_unit = 0;
};

// The member's profile and URDF texts, and the machine loaded from them.
struct Member {
  std::string profile_yaml, urdf_xml;
  machine::MachineProfile profile;
};

Member build_member(const machine::ClimbingFamily& family, const machine::FittedPlatform& p,
                    const FitOptions& options, const std::string& description) {
  Member member;
  member.urdf_xml = machine::climbing_family_urdf(family, p, description);
  const Document doc = machine::fitted_profile_document(family, p, options.urdf_file, description);
  member.profile_yaml =
      to_yaml(doc.root, "A climbing machine fitted by `ccbuild fit`: " + description +
                            "\nFrom the family " + family.source_file +
                            "; fit it again rather than "
                            "edit it.");
  member.profile = machine::load_machine_profile(doc, options.profile_path, &member.urdf_xml);
  if (!member.profile.climbing)
    throw InputError(family.source_file, 0, "climbing",
                     "a family needs a `climbing:` section (its process keys)");
  return member;
}

/// `p` with one unit in the middle of each beam: a member whose loading checks the
/// family's keys as a machine; its units stand in for any mount on their beams.
machine::FittedPlatform probe_platform(machine::FittedPlatform p) {
  const Eigen::Vector2d mid(0.5 * (p.x_min_m + p.x_max_m), 0.5 * (p.y_min_m + p.y_max_m));
  p.units = {machine::mount_on(Beam::kSouth, {mid.x(), p.y_min_m}, "U1"),
             machine::mount_on(Beam::kEast, {p.x_max_m, mid.y()}, "U2"),
             machine::mount_on(Beam::kNorth, {mid.x(), p.y_max_m}, "U3"),
             machine::mount_on(Beam::kWest, {p.x_min_m, mid.y()}, "U4")};
  return p;
}

std::string describe_member(const machine::ClimbingFamily& family, const machine::FittedPlatform& p,
                            floors::LengthUnit unit) {
  std::string units;
  for (const auto& u : p.units)
    units +=
        printf_string("%s%s %s at (%.2f, %.2f)", units.empty() ? "" : ", ", u.name.c_str(),
                      machine::to_string(u.beam).c_str(), floors::length_in(u.position_m.x(), unit),
                      floors::length_in(u.position_m.y(), unit));
  return printf_string("%s x %s platform, %zu units (%s %s), %.0f kg",
                       floors::length_text(p.length_m() + family.beam_section_m, unit, 2).c_str(),
                       floors::length_text(p.width_m() + family.beam_section_m, unit, 2).c_str(),
                       p.units.size(), units.c_str(), floors::to_string(unit).c_str(),
                       p.mass_kg(family));
}

// The point `s` metres around the beams' rectangle (anticlockwise from the south-west).
Eigen::Vector2d around(const machine::FittedPlatform& p, double s) {
  const double w = p.length_m(), h = p.width_m(), perimeter = 2 * (w + h);
  s = std::fmod(std::fmod(s, perimeter) + perimeter, perimeter);
  if (s <= w) return {p.x_min_m + s, p.y_min_m};
  s -= w;
  if (s <= h) return {p.x_max_m, p.y_min_m + s};
  s -= h;
  if (s <= w) return {p.x_max_m - s, p.y_max_m};
  s -= w;
  return {p.x_min_m, p.y_max_m - s};
}

// The stability of the platform while it prints from `stage`: every unit holding, the
// gantry anywhere over the floors it prints (the corners of their footprint, half a metre
// out, bound the centre of mass).
double printing_margin_m(const floors::Building& building, const machine::ClimbingMachine& m,
                         const ClimbStage& stage) {
  std::vector<double> q = detail::parked_on(m, stage);
  if (q.empty()) return -std::numeric_limits<double>::infinity();
  const machine::Kinematics& robot = *m.robot;
  const auto& gx = robot.joint_info(m.gantry_joints[0]);
  const auto& gy = robot.joint_info(m.gantry_joints[1]);
  Eigen::Vector2d low = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d high = -low;
  for (int f = stage.first.floor; f <= stage.last.floor; ++f)
    for (const auto& v : building.floors[f].plan.vertices) {
      low = low.cwiseMin(v.position_m);
      high = high.cwiseMax(v.position_m);
    }
  std::vector<Eigen::Vector2d> pins;
  for (const auto& a : stage.anchors) pins.push_back(a.centre_m.head<2>());
  const Eigen::Isometry3d platform(Eigen::Translation3d(0, 0, stage.platform_z_m));
  double least = std::numeric_limits<double>::infinity();
  for (double x : {low.x() - 0.5, high.x() + 0.5})
    for (double y : {low.y() - 0.5, high.y() + 0.5}) {
      q[m.gantry_joints[0]] = std::clamp(x, gx.lower, gx.upper);
      q[m.gantry_joints[1]] = std::clamp(y, gy.lower, gy.upper);
      least =
          std::min(least, detail::inside_hull_m(
                              robot.centre_of_mass(robot.link_poses(platform, q)).head<2>(), pins));
    }
  return least;
}

// The stages of `m` on the building, and the least stable moment of all: printing from a
// stage or a transfer of a climb. `why` says what fails.
double least_margin_m(const floors::Building& building, const machine::ClimbingMachine& m,
                      const detail::StageFrames& frames, StagePlan& stages, std::string& why) {
  stages = detail::place_anchors(building, m, frames);
  if (!stages.status) {
    why = stages.status.reason();
    return -std::numeric_limits<double>::infinity();
  }
  double least = std::numeric_limits<double>::infinity();
  for (std::size_t s = 0; s < stages.stages.size(); ++s) {
    const ClimbStage& from = stages.stages[s];
    const double printing = printing_margin_m(building, m, from);
    if (printing < least) {
      least = printing;
      why = printf_string("printing from stage %zu, the gantry over a corner of its floors", s);
    }
    if (s + 1 == stages.stages.size()) break;
    const std::vector<double> q = detail::parked_on(m, from);
    const detail::Transfers transfers(
        m, from, stages.stages[s + 1],
        Eigen::Isometry3d(Eigen::Translation3d(0, 0, from.platform_z_m)), q);
    if (!transfers.unreachable.empty()) {
      why = printf_string("climb %zu -> %zu: ", s, s + 1) + transfers.unreachable;
      return -std::numeric_limits<double>::infinity();
    }
    if (transfers.least_margin_m < least) {
      least = transfers.least_margin_m;
      why = printf_string("climb %zu -> %zu, a unit changing pipes", s, s + 1);
    }
  }
  return least;
}

}  // namespace

FitResult fit_climbing_machine(const floors::Building& building,
                               const machine::ClimbingFamily& family, const FitOptions& options) {
  FitResult r;
  auto say = [&](const std::string& what) {
    if (options.progress) options.progress(what);
  };
  // Lengths in messages in the building's unit; the profile written stays in metres.
  auto L = [&](double m) { return floors::length_text(m, building.units, 2); };
  const floors::Envelope env = floors::envelope(building);
  const double clearance = family.beam_clearance_m, section = family.beam_section_m;

  // 1. The platform: beams the clearance outside the outermost walls, grown to the
  // family's smallest platform.
  machine::FittedPlatform p;
  p.x_min_m = env.min_m.x() - clearance;
  p.x_max_m = env.max_m.x() + clearance;
  p.y_min_m = env.min_m.y() - clearance;
  p.y_max_m = env.max_m.y() + clearance;
  for (int axis = 0; axis < 2; ++axis) {
    double& lo = axis == 0 ? p.x_min_m : p.y_min_m;
    double& hi = axis == 0 ? p.x_max_m : p.y_max_m;
    const double smallest = axis == 0 ? family.length_min_m : family.width_min_m;
    const double largest = axis == 0 ? family.length_max_m : family.width_max_m;
    const char* name = axis == 0 ? "length (along x)" : "width (along y)";
    const double outer_m = hi - lo + section;
    if (outer_m > largest + 1e-9) {
      const double extent = env.size_m()[axis];
      r.status = {ClimbStatus::Code::kTooLarge,
                  printf_string("the building is %s along %s; with the beams %s outside "
                                "its outermost walls the platform's %s would be %s, and the "
                                "family's largest is %s",
                                L(extent).c_str(), axis == 0 ? "x" : "y", L(clearance).c_str(),
                                name, L(outer_m).c_str(), L(largest).c_str())};
      r.reasons.push_back(r.status.reason());
      r.nearest_change +=
          std::string(r.nearest_change.empty() ? "" : "; ") +
          printf_string(
              "a family whose platform %s reaches %s (`family.platform.%s`: %.2f), or a "
              "building at most %s along %s",
              name, L(outer_m).c_str(), axis == 0 ? "length_m" : "width_m",
              floors::rounded(outer_m, 2, floors::Towards::kUp),
              floors::length_text(largest - section - 2 * clearance, building.units, 2,
                                  floors::Towards::kDown)
                  .c_str(),
              axis == 0 ? "x" : "y");
    } else if (outer_m < smallest) {
      lo -= 0.5 * (smallest - outer_m);
      hi += 0.5 * (smallest - outer_m);
    }
  }
  if (!r.status) {
    // A key of the family out of its range is bad input whatever the building: checked on
    // the family's largest member before the answer that none fits (exit 1, not 2).
    machine::FittedPlatform largest = p;
    const double half_length = 0.5 * (family.length_max_m - section),
                 half_width = 0.5 * (family.width_max_m - section);
    const Eigen::Vector2d centre(0.5 * (p.x_min_m + p.x_max_m), 0.5 * (p.y_min_m + p.y_max_m));
    largest.x_min_m = centre.x() - half_length;
    largest.x_max_m = centre.x() + half_length;
    largest.y_min_m = centre.y() - half_width;
    largest.y_max_m = centre.y() + half_width;
    largest.gantry_x_min_m = largest.x_min_m;
    largest.gantry_x_max_m = largest.x_max_m;
    largest.gantry_y_min_m = largest.y_min_m;
    largest.gantry_y_max_m = largest.y_max_m;
    build_member(family, probe_platform(largest), options, "probe");
    return r;
  }
  // The gantry reaches half a metre past the outermost walls, within the beams.
  p.gantry_x_min_m = std::max(p.x_min_m, env.min_m.x() - 0.5);
  p.gantry_x_max_m = std::min(p.x_max_m, env.max_m.x() + 0.5);
  p.gantry_y_min_m = std::max(p.y_min_m, env.min_m.y() - 0.5);
  p.gantry_y_max_m = std::min(p.y_max_m, env.max_m.y() + 0.5);
  r.platform = p;

  // 2. A probe: one unit in the middle of each beam. Loading it checks the family's keys
  // as a machine; its units stand in for any mount on their beams.
  const Eigen::Vector2d mid(0.5 * (p.x_min_m + p.x_max_m), 0.5 * (p.y_min_m + p.y_max_m));
  const Member probe = build_member(family, probe_platform(p), options, "probe");
  const machine::ClimbingMachine& pm = *probe.profile.climbing;
  const detail::StageFrames frames = detail::stage_frames(building, pm);
  r.stages = static_cast<int>(frames.frames.size());
  if (!frames.status) {
    r.status = frames.status;
    r.reasons.push_back(frames.status.reason());
    r.nearest_change = "a nozzle that reaches further below the platform (nozzle_reach_below_m)";
    return r;
  }
  for (const auto& f : frames.frames)
    if (f.levels.empty()) {
      r.status = {ClimbStatus::Code::kNoAnchor,
                  printf_string("stage %d: ", f.stage.index) + f.no_level};
      r.reasons.push_back(r.status.reason());
      r.nearest_change = "legs with a longer stroke (`family.units.stroke_m`)";
      return r;
    }

  // 3. Mount sites along the beams, and what each reaches: per stage, at the lowest layer
  // of each floor its pipes may go in (at most three floors).
  std::vector<MountSite> sites;
  const std::vector<Eigen::Vector2d> probe_mounts = {
      {mid.x(), p.y_min_m}, {p.x_max_m, mid.y()}, {mid.x(), p.y_max_m}, {p.x_min_m, mid.y()}};
  {
    const double w = p.length_m(), h = p.width_m();
    struct Side {
      Beam beam;
      int probe;
      double start_s, length_m;
    };
    for (const Side& side : {Side{Beam::kSouth, 0, 0.0, w}, Side{Beam::kEast, 1, w, h},
                             Side{Beam::kNorth, 2, w + h, w}, Side{Beam::kWest, 3, 2 * w + h, h}})
      for (double t = family.mount_end_clearance_m;
           t <= side.length_m - family.mount_end_clearance_m + 1e-9; t += family.mount_step_m)
        sites.push_back({side.beam, around(p, side.start_s + t), side.start_s + t, side.probe});
  }
  r.mounts_considered = static_cast<int>(sites.size());
  say(printf_string("%zu mount positions on the beams, %zu stages", sites.size(),
                    frames.frames.size()));
  const double thickness = pm.gantry.nozzle_width_m;
  const double near_m = family.reach_max_m + 1.0;
  struct Event {
    int stage = 0;
    std::vector<detail::AnchorLevel> levels;
    std::vector<std::vector<detail::Candidate>> candidates;  ///< per level
  };
  std::vector<Event> events;
  for (const auto& f : frames.frames) {
    Event e;
    e.stage = f.stage.index;
    std::set<int> floors_seen;
    for (const auto& level : f.levels) {
      if (!floors_seen.insert(level.floor).second || floors_seen.size() > 3) continue;
      e.levels.push_back(level);
      const int fl = std::max(0, level.floor);
      auto all =
          detail::candidates(building.floors[fl], frames.sliced[fl][std::max(0, level.layer)],
                             thickness, pm.anchor_clearance_m);
      // Every 25 cm is enough to tell whether a unit reaches a wall.
      std::vector<detail::Candidate> thinned;
      for (const auto& c : all)
        if (!c.by_default_rule || thinned.empty() ||
            (thinned.back().point - c.point).norm() > 0.24 || thinned.back().wall_id != c.wall_id)
          thinned.push_back(c);
      e.candidates.push_back(std::move(thinned));
    }
    events.push_back(std::move(e));
  }
  // The probe units' feet at zero, in plan (a site's is its probe's, shifted).
  std::vector<Eigen::Vector2d> probe_feet;
  {
    const auto poses = pm.robot->link_poses(Eigen::Isometry3d::Identity(), pm.robot->zero());
    for (const auto& unit : pm.units)
      probe_feet.push_back(poses[unit.foot_link].translation().head<2>());
  }
  // reaches[site][event]: a bit per level.
  std::vector<std::vector<unsigned>> reaches(sites.size(), std::vector<unsigned>(events.size(), 0));
  for (std::size_t i = 0; i < sites.size(); ++i) {
    const MountSite& site = sites[i];
    const Eigen::Vector2d shift = site.position_m - probe_mounts[site.probe_unit];
    const Eigen::Vector2d foot_at_zero = probe_feet[site.probe_unit] + shift;
    for (std::size_t e = 0; e < events.size(); ++e) {
      const auto& zs = frames.frames[e].platform_zs;
      for (std::size_t l = 0; l < events[e].levels.size(); ++l)
        for (const auto& c : events[e].candidates[l]) {
          if ((c.point - site.position_m).norm() > near_m) continue;
          bool ok = true;
          Eigen::Vector2d n;
          for (double z : zs)
            ok = ok && detail::pin_reaches(
                           pm, site.probe_unit,
                           Eigen::Isometry3d(Eigen::Translation3d(shift.x(), shift.y(), z)),
                           foot_at_zero, c, events[e].levels[l].z_m, n);
          if (ok) {
            reaches[i][e] |= 1u << l;
            break;
          }
        }
    }
  }
  // Per stage, the level most sites reach (ties: the lowest); the sites that reach every
  // stage's.
  std::vector<int> level_of(events.size(), 0);
  std::vector<int> ok_sites;
  for (std::size_t e = 0; e < events.size(); ++e) {
    int best = 0, best_count = -1;
    for (std::size_t l = 0; l < events[e].levels.size(); ++l) {
      int count = 0;
      for (std::size_t i = 0; i < sites.size(); ++i) count += (reaches[i][e] >> l) & 1u;
      if (count > best_count) {
        best = static_cast<int>(l);
        best_count = count;
      }
    }
    level_of[e] = best;
    if (best_count == 0) {
      // Nothing reaches: how far inside the beams is the nearest solid wall?
      const auto& cands = events[e].candidates[best];
      double nearest_m = std::numeric_limits<double>::infinity();
      for (const auto& c : cands)
        nearest_m = std::min({nearest_m, c.point.x() - p.x_min_m, p.x_max_m - c.point.x(),
                              c.point.y() - p.y_min_m, p.y_max_m - c.point.y()});
      const auto& level = events[e].levels[best];
      r.reasons.push_back(
          printf_string(
              "stage %d (pipes at %s, %s): no unit, wherever mounted on the "
              "beams, reaches solid wall",
              events[e].stage, L(level.z_m).c_str(),
              level.floor < 0
                  ? "in the foundation"
                  : printf_string("floor %d layer %d", level.floor, level.layer).c_str()) +
          (std::isfinite(nearest_m)
               ? printf_string(": the nearest is %s inside the beams, and a unit's boom "
                               "reaches %s",
                               L(nearest_m).c_str(), L(family.reach_max_m).c_str())
               : std::string(": that layer has no solid wall clear of ends and openings")));
    }
  }
  if (!r.reasons.empty()) {
    r.status = {ClimbStatus::Code::kNoAnchor, r.reasons.front()};
    r.nearest_change =
        "solid wall (or `anchors:` points) within the units' reach of the beams on those "
        "storeys, or a family with beams closer to the walls (`beam_clearance_m`) or longer "
        "booms (`family.units.reach_m`)";
    return r;
  }
  for (std::size_t i = 0; i < sites.size(); ++i) {
    bool all = true;
    for (std::size_t e = 0; e < events.size() && all; ++e)
      all = (reaches[i][e] >> level_of[e]) & 1u;
    if (all) ok_sites.push_back(static_cast<int>(i));
  }
  r.mounts_reaching = static_cast<int>(ok_sites.size());
  say(printf_string("%d of them reach solid wall at every stage", r.mounts_reaching));

  const int fewest = std::max(family.units_min, pm.units_per_transfer + 3);
  if (fewest > family.units_max) {
    r.status = {ClimbStatus::Code::kUnstable,
                printf_string("the family has at most %d units, and %d must hold the platform "
                              "(3, never in a line) while %d change%s pipes",
                              family.units_max, fewest - pm.units_per_transfer,
                              pm.units_per_transfer, pm.units_per_transfer == 1 ? "s" : "")};
    r.reasons.push_back(r.status.reason());
    r.nearest_change = printf_string("a family of %d units or more (`family.units.count`)", fewest);
    return r;
  }
  // A floor that lists its anchor points needs one per unit at least.
  for (const auto& e : events) {
    const int fl = std::max(0, e.levels[level_of[&e - events.data()]].floor);
    const auto& listed = building.floors[fl].anchors;
    if (!listed.empty() && static_cast<int>(listed.size()) < fewest)
      r.reasons.push_back(printf_string(
          "stage %d: floor '%s' lists %zu anchor point%s, and the machine needs one for each "
          "unit, at least %d",
          e.stage, building.floors[fl].name.c_str(), listed.size(), listed.size() == 1 ? "" : "s",
          fewest));
  }
  if (!r.reasons.empty()) {
    r.status = {ClimbStatus::Code::kNoAnchor, r.reasons.front()};
    r.nearest_change = printf_string(
        "at least %d anchor points on each floor that lists them (`anchors:`), or none, so that "
        "the default rule places them on solid wall",
        fewest);
    return r;
  }

  // 4. The fewest units, spread around the beams; among as few, the most stable.
  const double perimeter = 2 * (p.length_m() + p.width_m());
  std::set<std::vector<int>> tried;
  std::string last_why;
  double last_margin = -std::numeric_limits<double>::infinity();
  std::string blocked_why;
  int blocked_counts = 0;
  for (int k = fewest; k <= family.units_max; ++k) {
    struct Stable {
      machine::FittedPlatform platform;
      double margin_m = 0.0;
      StagePlan stages;
      Member member;  ///< its machine, for planning its climbs
    };
    std::vector<Stable> stable;
    int tried_here = 0;
    for (int j = 0; j < 4; ++j) {
      std::vector<int> chosen;
      // Four units towards the corners (of the beams' rectangle shrunk by 15% more at
      // each try), the others spread evenly around the beams.
      std::vector<Eigen::Vector2d> wants;
      const double shrink = 1.0 - 0.15 * j;
      for (const Eigen::Vector2d& corner :
           {Eigen::Vector2d(p.x_min_m, p.y_min_m), Eigen::Vector2d(p.x_max_m, p.y_min_m),
            Eigen::Vector2d(p.x_max_m, p.y_max_m), Eigen::Vector2d(p.x_min_m, p.y_max_m)})
        wants.push_back(mid + shrink * (corner - mid));
      for (int i = 4; i < k; ++i)
        wants.push_back(around(p, perimeter * (i - 4 + 0.5 + 0.25 * j) / (k - 4)));
      for (const Eigen::Vector2d& want : wants) {
        int pick = -1;
        for (int s : ok_sites) {
          bool spaced = true;
          for (int c : chosen)
            spaced = spaced &&
                     (sites[c].position_m - sites[s].position_m).norm() >= family.mount_spacing_m;
          if (!spaced) continue;
          if (pick < 0 ||
              (sites[s].position_m - want).norm() < (sites[pick].position_m - want).norm() - 1e-12)
            pick = s;
        }
        if (pick >= 0) chosen.push_back(pick);
      }
      if (static_cast<int>(chosen.size()) < k) continue;
      std::sort(chosen.begin(), chosen.end(),
                [&](int a, int b) { return sites[a].along_m < sites[b].along_m; });
      if (!tried.insert(chosen).second) continue;
      machine::FittedPlatform trial = p;
      for (int c : chosen)
        trial.units.push_back(machine::mount_on(sites[c].beam, sites[c].position_m,
                                                "U" + std::to_string(trial.units.size() + 1)));
      const Member member = build_member(family, trial, options, "trial");
      StagePlan stages;
      std::string why;
      const double margin = least_margin_m(building, *member.profile.climbing, frames, stages, why);
      ++r.members_tried;
      ++tried_here;
      say(printf_string("%d units: least margin %s (%s)", k,
                        std::isfinite(margin) ? L(margin).c_str() : "-", why.c_str()));
      if (margin > last_margin || last_why.empty()) {
        last_margin = margin;
        last_why = why;
      }
      if (margin >= pm.stability_margin_m - 1e-9)
        stable.push_back({trial, margin, std::move(stages), member});
    }
    // The most stable first; with options.plan_climbs, the first whose every climb plans.
    std::stable_sort(stable.begin(), stable.end(),
                     [](const Stable& a, const Stable& b) { return a.margin_m > b.margin_m; });
    const Stable* chosen_member = nullptr;
    for (const Stable& candidate : stable) {
      if (!options.plan_climbs) {
        chosen_member = &candidate;
        break;
      }
      const Member& member = candidate.member;
      std::string why;
      const auto& st = candidate.stages.stages;
      for (std::size_t c = 0; c + 1 < st.size() && why.empty(); ++c) {
        const ClimbPlan plan =
            plan_climb(*member.profile.climbing, building, st[c], st[c + 1], options.climb);
        if (!plan.status)
          why = printf_string("climb %zu -> %zu: ", c, c + 1) + plan.status.to_string();
      }
      say(printf_string("%d units, least margin %s: %s", k, L(candidate.margin_m).c_str(),
                        why.empty() ? "every climb planned" : why.c_str()));
      if (why.empty()) {
        chosen_member = &candidate;
        break;
      }
      blocked_why = why;
    }
    if (!chosen_member) {
      // Stable sets whose climbs cannot be planned at two counts: more units crowd the
      // beams more; stop there rather than plan every count's climbs.
      if (!stable.empty() && ++blocked_counts >= 2) break;
      continue;
    }
    const machine::FittedPlatform& best_p = chosen_member->platform;
    const double best_margin = chosen_member->margin_m;
    r.platform = best_p;
    r.least_margin_m = best_margin;
    r.mass_kg = best_p.mass_kg(family);
    r.summary = describe_member(family, best_p, building.units);
    const std::string description =
        "fitted to " + (building.name.empty() ? building.source_file : building.name) + ": " +
        describe_member(family, best_p, floors::LengthUnit::kMeter);
    Member member = build_member(family, best_p, options, description);
    r.profile_yaml = std::move(member.profile_yaml);
    r.urdf_xml = std::move(member.urdf_xml);
    r.urdf_file = options.urdf_file;
    r.profile = std::move(member.profile);
    r.optimised = printf_string(
        "the smallest platform around the building (%s x %s, the beams %s outside "
        "its outermost walls), then the fewest units (%d; %d to %d allowed) that reach solid "
        "wall at all %d stages with every transfer and every printing position stable by the "
        "%s margin%s, then among %d sets of %d the most stable (least margin %s); %.0f kg",
        L(best_p.length_m() + section).c_str(), L(best_p.width_m() + section).c_str(),
        L(clearance).c_str(), k, family.units_min, family.units_max, r.stages,
        L(pm.stability_margin_m).c_str(),
        options.plan_climbs ? " and every climb planned (OMPL)" : "", tried_here, k,
        L(best_margin).c_str(), r.mass_kg);
    return r;
  }
  if (!blocked_why.empty()) {
    r.status = {ClimbStatus::Code::kBlocked,
                "the stable sets of units tried each have a climb that cannot be planned; the "
                "last: " +
                    blocked_why};
    r.reasons.push_back(r.status.reason());
    r.nearest_change =
        "walls clear of the units' paths between the storeys' pipes (a setback within the "
        "booms' reach of the beams), or `anchors:` points the units reach without crossing a "
        "wall";
    return r;
  }
  r.status = {
      ClimbStatus::Code::kUnstable,
      "no set of " + std::to_string(fewest) + " to " + std::to_string(family.units_max) +
          " units on the " + std::to_string(r.mounts_reaching) +
          " mount positions that reach solid wall at every stage keeps the platform "
          "stable by the margin: " +
          (last_why.empty()
               ? std::string("none could be placed")
               : (std::isfinite(last_margin) ? "at best " + L(last_margin) + ", " : std::string()) +
                     last_why)};
  r.reasons.push_back(r.status.reason());
  r.nearest_change =
      "more mount positions that reach wall near the platform's corners (solid wall or "
      "`anchors:` there), a heavier gantry as counterweight, or a smaller stability margin";
  return r;
}

}  // namespace ccbuild::climb
