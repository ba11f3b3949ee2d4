// The whole-building schedule, checked from its outcome: every piece of every layer
// deposited once, every local interval in the material's window (or the run says
// infeasible, with its fix), every wait no longer than its reason needs, no climb before
// its anchors are strong, the gantries apart, and the same schedule whatever --jobs.
// On the examples and on generated buildings.

#include "ccbuild/schedule/schedule.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "ccbuild/common/format.hpp"
#include "ccbuild/floors/generate.hpp"
#include "ccbuild/schedule/project.hpp"
#include "ccbuild/schedule/schedule_diff.hpp"
#include "ccbuild/schedule/schedule_json.hpp"
#include "scheduler.hpp"
#include "test_support.hpp"

namespace ccbuild::schedule {
namespace {
using schedule::open_project;
using schedule::Project;
namespace fs = std::filesystem;
using testing::contains;

constexpr double kTol_s = 1e-6;

fs::path scratch_dir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("ccbuild_schedule_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

ScheduleOptions quick(int jobs = 2) {
  ScheduleOptions o;
  o.jobs = jobs;
  o.max_kicks = 300;
  return o;
}

/// Every extruding span of a plan lies on a piece of its layer, and the spans of each
/// piece add up to its length: each piece deposited exactly once.
void expect_every_piece_once(const SchedulePlan& plan) {
  std::map<std::pair<std::int64_t, int>, double> deposited_m;
  for (const auto& path : plan.waypoints)
    for (std::size_t k = 0; k + 1 < path.size(); ++k)
      if (path[k].extruding)
        deposited_m[{path[k].wall, path[k].piece}] +=
            (path[k + 1].position_m - path[k].position_m).norm();
  ASSERT_EQ(deposited_m.size(), plan.layer.segments.size()) << plan.key;
  for (const auto& s : plan.layer.segments) {
    const auto it = deposited_m.find({s.wall_id, s.piece + 1});
    ASSERT_NE(it, deposited_m.end()) << plan.key << " wall " << s.wall_id;
    EXPECT_NEAR(it->second, s.length_m, 2e-3) << plan.key << " wall " << s.wall_id;
  }
}

/// The rules every schedule keeps, whatever the building.
void expect_schedule_rules(const Project& project, const Schedule& s) {
  const auto& m = project.material;
  ASSERT_FALSE(s.layers.empty());
  for (const auto& [key, plan] : s.plans) {
    SCOPED_TRACE(key);
    expect_every_piece_once(plan);
    // Gantries on common rails: never closer than the gantry width.
    if (plan.nozzles > 1) {
      EXPECT_GE(plan.min_gap_m, project.machine->gantry_width_m - 1e-9);
    }
  }
  double machine_free_s = 0.0;
  for (std::size_t i = 0; i < s.layers.size(); ++i) {
    const ScheduledLayer& l = s.layers[i];
    SCOPED_TRACE("floor " + std::to_string(l.floor) + " layer " + std::to_string(l.layer));
    ASSERT_TRUE(s.plans.count(l.plan));
    EXPECT_NEAR(l.end_s - l.start_s, s.plans.at(l.plan).layer_time_s, kTol_s);
    EXPECT_GE(l.start_s, machine_free_s + l.move_before_s - kTol_s);  // one layer at a time
    machine_free_s = l.end_s;
    // A wait has reasons, and is exactly as long as the most demanding one.
    double most_s = 0.0;
    for (const auto& r : l.wait_reasons) {
      EXPECT_FALSE(r.detail.empty());
      most_s = std::max(most_s, r.required_s);
    }
    EXPECT_NEAR(l.wait_before_s, most_s, kTol_s);
    // The layer below on the same floor: the intervals of every piece end.
    const bool has_below = i > 0 && s.layers[i - 1].floor == l.floor;
    EXPECT_EQ(l.interval_s.has_value(), has_below);
    if (!has_below || !l.local_interval_max_s) continue;
    EXPECT_NEAR(*l.interval_s, l.start_s - s.layers[i - 1].start_s, kTol_s);
    EXPECT_GE(*l.local_interval_min_s, m.min_layer_interval_s - kTol_s);
    // The layer below carries the walls from its bottom to this layer's top, piece by
    // piece: each is at least as old as its strength needs when it is covered.
    const double stress_mpa = m.safety_factor * m.density_kg_m3 * 9.80665 * 1e-6 *
                              (l.z_top_m - s.layers[i - 1].z_bottom_m);
    EXPECT_GE(*l.local_interval_min_s, m.age_for_strength_s(stress_mpa) - kTol_s);
    if (s.feasible && !l.planned_joint) {
      EXPECT_LE(*l.local_interval_max_s, m.max_layer_interval_s + kTol_s);
    }
    // No longer than needed: a layer that waited for its minimum interval starts when
    // the tightest piece reaches it, not later.
    bool only_min_interval = !l.wait_reasons.empty() && !l.purge_before;
    for (const auto& r : l.wait_reasons)
      only_min_interval = only_min_interval && r.kind == WaitKind::kMinInterval;
    if (only_min_interval) {
      EXPECT_NEAR(*l.local_interval_min_s, m.min_layer_interval_s, 1e-6);
    }
  }
  if (!s.feasible) {
    ASSERT_TRUE(s.infeasibility);
    EXPECT_FALSE(s.infeasibility->fix.empty());
  }
}

TEST(Schedule, TheHouseIsFeasibleAndKeepsEveryRule) {
  const Project house = open_project(testing::source_path("config/buildings/house.yaml"));
  const Schedule s = build_schedule(house, quick());
  EXPECT_TRUE(s.feasible);
  EXPECT_EQ(s.layers.size(), 60u);
  expect_schedule_rules(house, s);
  // A fixed gantry: no stages, no pipes, no climbs; one slab between the two floors.
  EXPECT_TRUE(s.stages.empty());
  int slabs = 0;
  for (const auto& e : s.events) {
    EXPECT_NE(e.kind, Event::Kind::kClimb);
    EXPECT_NE(e.kind, Event::Kind::kPipe);
    if (e.kind == Event::Kind::kSlab) {
      ++slabs;
      EXPECT_NEAR(e.end_s - e.start_s, house.building.slab_stage_s, kTol_s);
    }
  }
  EXPECT_EQ(slabs, 1);
  // The next floor starts on the slab: after it, with nothing required of the floor below.
  const auto first_upper =
      std::find_if(s.layers.begin(), s.layers.end(), [](const auto& l) { return l.floor == 1; });
  ASSERT_NE(first_upper, s.layers.end());
  EXPECT_FALSE(first_upper->interval_s);
  EXPECT_GE(first_upper->start_s, std::prev(first_upper)->end_s + house.building.slab_stage_s);
}

// The schedule's quantities are each floor's as floor_quantities slices it (the text and
// the JSON read them there rather than slice the building again), floor by floor.
TEST(Schedule, ItsQuantitiesAreEachFloorsAsSliced) {
  const Project house = open_project(testing::source_path("config/buildings/house.yaml"));
  const Schedule s = build_schedule(house, quick());
  const floors::Building& b = house.building;
  ASSERT_EQ(s.quantities.size(), b.floors.size());
  ASSERT_GE(b.floors.size(), 2u);
  double concrete_m3 = 0.0;
  for (std::size_t f = 0; f < b.floors.size(); ++f) {
    SCOPED_TRACE(f);
    const floors::FloorQuantities q =
        floors::floor_quantities(b.floors[f], b.layer_height_m, house.machine->nozzle_width_m);
    EXPECT_GT(q.printed_m3, 0.0);
    EXPECT_DOUBLE_EQ(s.quantities[f].printed_m3, q.printed_m3);
    EXPECT_EQ(s.quantities[f].walls_unmodelled, q.walls_unmodelled);
    concrete_m3 += q.printed_m3;
  }
  EXPECT_NEAR(concrete_m3, s.totals.concrete_m3, 0.01);
}

TEST(Schedule, TheSameWhateverTheJobs) {
  const Project house = open_project(testing::source_path("config/buildings/house.yaml"));
  const auto one = schedule_json(house, quick(1), build_schedule(house, quick(1))).dump();
  const auto two = schedule_json(house, quick(2), build_schedule(house, quick(2))).dump();
  EXPECT_EQ(one, two);
  const auto again = schedule_json(house, quick(2), build_schedule(house, quick(2))).dump();
  EXPECT_EQ(two, again);
  EXPECT_FALSE(
      diff_schedules(parse_schedule(one, "one"), parse_schedule(two, "two"), {}).differs());
  // Equal bytes are what the regression tests compare with `diff` and no tolerance: that
  // comparison is exact, a layer started a millisecond later differs and is named.
  ScheduleDocument later = parse_schedule(two, "two");
  auto& layer = later.schedule.layers[10];
  layer.start_s += 1e-3;
  layer.end_s += 1e-3;
  const ScheduleDiff moved = diff_schedules(parse_schedule(one, "one"), later, {});
  EXPECT_TRUE(moved.differs());
  EXPECT_EQ(moved.differing_layers, 1);
  std::string changes;
  for (const auto& c : moved.changes) changes += c + "\n";
  EXPECT_TRUE(contains(changes, "floor 0 layer 10")) << changes;
}

// A memo shared between schedules of the house changes none of their bytes; the same
// options plan nothing again, another objective only the counts not yet planned, and a
// gantry opened again (another object) or another seed plans everything again.
TEST(Schedule, APlanMemoChangesNothingAndPlansNothingTwice) {
  const Project house = open_project(testing::source_path("config/buildings/house.yaml"));
  const auto bytes = [&](const ScheduleOptions& o, const Schedule& s) {
    ScheduleOptions recorded = o;
    recorded.memo = nullptr;
    return schedule_json(house, recorded, s).dump();
  };
  ScheduleOptions with = quick();
  with.memo = make_plan_memo();
  const Schedule first = build_schedule(house, with);
  ASSERT_GT(first.plans_computed, 0);
  EXPECT_EQ(bytes(with, first), bytes(quick(), build_schedule(house, quick())));
  const Schedule again = build_schedule(house, with);
  EXPECT_EQ(again.plans_computed, 0);
  EXPECT_EQ(bytes(with, again), bytes(with, first));

  ScheduleOptions shortest = with, plain_shortest = quick();
  shortest.objective = plain_shortest.objective = Objective::kShortest;
  const Schedule memo_shortest = build_schedule(house, shortest);
  const Schedule fresh_shortest = build_schedule(house, plain_shortest);
  EXPECT_LT(memo_shortest.plans_computed, fresh_shortest.plans_computed);
  EXPECT_EQ(bytes(shortest, memo_shortest), bytes(plain_shortest, fresh_shortest));

  const Project reopened = open_project(testing::source_path("config/buildings/house.yaml"));
  EXPECT_EQ(build_schedule(reopened, with).plans_computed, first.plans_computed);
  // The same gantry object and the same floors and layers, the walls 50 mm to the east.
  Project moved = house;
  for (auto& f : moved.building.floors)
    for (auto& v : f.plan.vertices) v.position_m.x() += 0.05;
  EXPECT_EQ(build_schedule(moved, with).plans_computed, first.plans_computed);
  ScheduleOptions seed2 = with;
  seed2.seed = 2;
  EXPECT_EQ(build_schedule(house, seed2).plans_computed, build_schedule(house,
                                                                        [] {
                                                                          ScheduleOptions o =
                                                                              quick();
                                                                          o.seed = 2;
                                                                          return o;
                                                                        }())
                                                             .plans_computed);
}

// A two-floor building of generated plans (seeded) with `material` and the bundled gantry.
std::string generated_building(const fs::path& dir, std::uint64_t seed,
                               const std::string& material) {
  for (int f = 0; f < 2; ++f) {
    floors::PlanGeneratorOptions g;
    g.rooms = 5 + f;
    g.seed = seed * 10 + f;
    const floors::FloorPlan plan = floors::generate_plan(g);
    std::ofstream out(dir / ("floor" + std::to_string(f) + ".yaml"));
    out.precision(17);
    out << "units: m\nvertices:\n";
    for (const auto& v : plan.vertices)
      out << "  - {id: " << v.id << ", x: " << v.position_m.x() << ", y: " << v.position_m.y()
          << "}\n";
    out << "walls:\n";
    for (const auto& w : plan.walls)
      out << "  - {id: " << w.id << ", start: " << w.start_vertex << ", end: " << w.end_vertex
          << "}\n";
    if (!plan.openings.empty()) out << "openings:\n";
    for (const auto& o : plan.openings)
      out << "  - {wall: " << o.wall_id << ", offset: " << o.offset_m << ", width: " << o.width_m
          << ", sill: " << o.sill_m << ", head: " << o.head_m << "}\n";
  }
  std::ofstream(dir / "material.yaml") << material;
  std::ofstream(dir / "building.yaml")
      << "units: m\nlayer_height: 0.25\nslab_stage_h: 2\nmaterial: material.yaml\nmachine: "
      << testing::source_path("config/machines/cc-gantry.yaml").string()
      << "\nfloors:\n  - {height: 2.5, plan: floor0.yaml}\n  - {height: 2.5, plan: floor1.yaml}\n";
  return (dir / "building.yaml").string();
}

std::string material(double min_s, double max_s) {
  std::ostringstream m;
  m.precision(17);
  m << "name: test mix\ndensity_kg_m3: 2200\nmin_layer_interval_s: " << min_s
    << "\nmax_layer_interval_s: " << max_s
    << "\nstrength_curve:\n  - {age_min: 0, strength_mpa: 0.005}\n"
       "  - {age_min: 15, strength_mpa: 0.02}\n  - {age_min: 60, strength_mpa: 0.08}\n"
       "  - {age_min: 1440, strength_mpa: 6}\n";
  return m.str();
}

TEST(Schedule, GeneratedBuildingsKeepEveryRule) {
  const fs::path dir = scratch_dir("generated");
  for (std::uint64_t seed : {1, 2, 3}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    // A window wide enough, and one so tight that the minimum forces waits.
    for (double min_s : {30.0, 400.0}) {
      const Project p = open_project(generated_building(dir, seed, material(min_s, 3600)));
      const Schedule s = build_schedule(p, quick());
      expect_schedule_rules(p, s);
      EXPECT_TRUE(s.feasible) << (s.infeasibility ? s.infeasibility->message : "");
      if (min_s == 400.0) {  // layers here take under 400 s
        EXPECT_GT(s.totals.waits_s, 0.0);
      }
    }
  }
  fs::remove_all(dir);
}

TEST(Schedule, AMaximumNoNozzleCountMeetsIsInfeasibleWithItsFix) {
  const fs::path dir = scratch_dir("infeasible");
  const Project p = open_project(generated_building(dir, 1, material(10, 60)));
  const Schedule s = build_schedule(p, quick());
  EXPECT_FALSE(s.feasible);
  ASSERT_TRUE(s.infeasibility);
  const Infeasibility& inf = *s.infeasibility;
  EXPECT_EQ(inf.kind, InfeasibilityKind::kMaxInterval);
  EXPECT_EQ(inf.floor, 0);
  EXPECT_EQ(inf.layer, 1);  // the first layer with a layer below
  EXPECT_NEAR(inf.required_s, 60.0, kTol_s);
  EXPECT_GT(inf.achieved_s, 60.0);
  // The computed fixes: the maximum that would do is at least the interval achieved.
  ASSERT_TRUE(inf.max_interval_needed_s);
  EXPECT_GE(*inf.max_interval_needed_s, inf.achieved_s);
  EXPECT_TRUE(contains(inf.message, "over the material's maximum interval of 60.0 s"));
  EXPECT_TRUE(contains(inf.fix, "a maximum layer interval of at least"));
  // Still a whole schedule, so that the report can show it.
  expect_schedule_rules(p, s);
  // The figure said, applied as written, schedules: proven by scheduling with it (the
  // first failing layer's interval alone, 791 s, falls short on layer 4, which needs 810 s).
  EXPECT_TRUE(
      contains(inf.fix, ccbuild::printf_string("at least %.0f s", *inf.max_interval_needed_s)))
      << inf.fix;
  EXPECT_TRUE(contains(inf.message, "; fix: " + inf.fix)) << inf.message;
  EXPECT_GT(*inf.max_interval_needed_s, inf.achieved_s + 1.0);
  const Project fixed =
      open_project(generated_building(dir, 1, material(10, *inf.max_interval_needed_s)));
  const Schedule applied = build_schedule(fixed, quick());
  EXPECT_TRUE(applied.feasible) << (applied.infeasibility ? applied.infeasibility->message : "");
  fs::remove_all(dir);
}

TEST(Schedule, TheMaximumHoldsAtEqualityAndNotBeyond) {
  // Find the largest local interval with a roomy window, then make it the maximum
  // exactly (feasible), and a microsecond less (the layer needs more than this plan).
  // Layers on a planned joint (after a stop for lintels) may exceed any maximum.
  const fs::path dir = scratch_dir("boundary");
  const Project roomy = open_project(generated_building(dir, 2, material(10, 7200)));
  const Schedule s = build_schedule(roomy, quick());
  double worst_s = 0.0;
  for (const auto& l : s.layers)
    if (l.local_interval_max_s && !l.planned_joint)
      worst_s = std::max(worst_s, *l.local_interval_max_s);
  ASSERT_GT(worst_s, 10.0);
  const Project exact = open_project(generated_building(dir, 2, material(10, worst_s)));
  const Schedule at = build_schedule(exact, quick());
  EXPECT_TRUE(at.feasible);
  EXPECT_EQ(schedule_json(roomy, quick(), s)["layers"].dump(),
            schedule_json(exact, quick(), at)["layers"].dump());
  const Project tight = open_project(generated_building(dir, 2, material(10, worst_s - 1e-3)));
  const Schedule below = build_schedule(tight, quick());
  bool changed = !below.feasible;
  for (std::size_t i = 0; i < below.layers.size() && !changed; ++i)
    changed = below.layers[i].plan != s.layers[i].plan;
  EXPECT_TRUE(changed) << "a maximum just under the worst interval must change the schedule";
  fs::remove_all(dir);
}

// The plans and climbs of the tower's schedule.
const std::shared_ptr<PlanMemo>& tower_memo() {
  static const std::shared_ptr<PlanMemo> memo = make_plan_memo();
  return memo;
}

// The tower on the climbing machine, scheduled once for the tests that read it.
const std::pair<Project, Schedule>& tower() {
  static const auto cached = [] {
    Project p = open_project(testing::source_path("config/buildings/tower.yaml"));
    ScheduleOptions o;
    o.memo = tower_memo();
    Schedule s = build_schedule(p, o);
    return std::make_pair(std::move(p), std::move(s));
  }();
  return cached;
}

TEST(Schedule, TheTowerClimbsOnlyOnStrongAnchors) {
  const auto& [p, s] = tower();
  ASSERT_TRUE(p.climber);
  EXPECT_TRUE(s.feasible) << (s.infeasibility ? s.infeasibility->message : "");
  expect_schedule_rules(p, s);
  // One climb per floor boundary, each after the slab; stages end at floor tops.
  ASSERT_EQ(s.stages.size(), 10u);
  std::map<std::string, double> cast_s;  // the latest cast of each anchor id, so far
  int climbs = 0;
  for (const auto& e : s.events) {
    if (e.kind == Event::Kind::kPipe) cast_s[e.anchor->id] = e.end_s;
    if (e.kind != Event::Kind::kClimb) continue;
    ++climbs;
    const ClimbEvent& c = *e.climb;
    EXPECT_TRUE(c.plan.status) << c.plan.status.to_string();
    EXPECT_NEAR(e.end_s - e.start_s, c.plan.duration_s, kTol_s);
    ASSERT_EQ(c.anchors.size(), s.stages[c.to_stage].anchors.size());
    for (const auto& a : c.anchors) {
      ASSERT_TRUE(cast_s.count(a.id)) << a.id;
      const double age_s = e.start_s - cast_s[a.id];
      EXPECT_NEAR(a.age_s, age_s, 1e-6);
      EXPECT_GE(p.material.strength_at_mpa(age_s), p.climber->anchor_strength_mpa - 1e-9);
    }
    // Not later than the youngest anchor needs: a climb that waited starts when it is ready.
    double ready_s = 0.0;
    for (const auto& a : c.anchors)
      ready_s = std::max(
          ready_s, cast_s[a.id] + p.material.age_for_strength_s(p.climber->anchor_strength_mpa));
    EXPECT_LE(ready_s, e.start_s + 1e-6);
    if (c.wait_before_s > 1e-9) {
      EXPECT_NEAR(e.start_s, ready_s, 1e-6);
    }
    // The layers after the climb start after it.
    for (const auto& l : s.layers)
      if (l.floor == e.floor + 1 && l.layer == 0) {
        EXPECT_GE(l.start_s, e.end_s);
      }
  }
  EXPECT_EQ(climbs, 9);
  // The ground floor needs two nozzles; the top floors manage with one.
  int ground = 0, top = 9;
  for (const auto& l : s.layers) {
    if (l.floor == 0) ground = std::max(ground, l.nozzles);
    if (l.floor == 9) top = std::min(top, l.nozzles);
  }
  EXPECT_EQ(ground, 2);
  EXPECT_EQ(top, 1);
  // The other objective with the climbs of the first from the memo: none planned again,
  // the same bytes as planned afresh (one test: the tower is scheduled once per process).
  {
    const Schedule& first = s;
    ASSERT_GE(std::count_if(first.events.begin(), first.events.end(),
                            [](const Event& e) { return e.kind == Event::Kind::kClimb; }),
              2);
    EXPECT_GT(first.climb_planning_s, 0.0);
    ScheduleOptions shortest, plain;
    shortest.memo = tower_memo();
    shortest.objective = plain.objective = Objective::kShortest;
    const Schedule reused = build_schedule(p, shortest);
    EXPECT_EQ(reused.climb_planning_s, 0.0);
    EXPECT_EQ(schedule_json(p, plain, reused).dump(),
              schedule_json(p, plain, build_schedule(p, plain)).dump());
  }
}

TEST(Schedule, AgeForStrengthInvertsTheCurve) {
  const Project house = open_project(testing::source_path("config/buildings/house.yaml"));
  auto m = house.material;
  m.en1992.reset();  // the curve alone (the Eurocode's part: Material.StandardMix...)
  EXPECT_EQ(m.age_for_strength_s(0.0), 0.0);
  EXPECT_EQ(m.age_for_strength_s(m.strength_curve.front().strength_mpa), 0.0);
  for (std::size_t k = 1; k < m.strength_curve.size(); ++k) {
    const auto& q = m.strength_curve[k];
    EXPECT_NEAR(m.age_for_strength_s(q.strength_mpa), q.age_s, 1e-6);  // at a point
    const double mid_mpa = 0.5 * (q.strength_mpa + m.strength_curve[k - 1].strength_mpa);
    EXPECT_NEAR(m.strength_at_mpa(m.age_for_strength_s(mid_mpa)), mid_mpa, 1e-9);
  }
  EXPECT_TRUE(std::isinf(m.age_for_strength_s(m.strength_curve.back().strength_mpa + 1e-6)));
}

// Pipes cast after a layer lengthen the interval that ends at the next layer of its floor:
// the run holding that next layer is given the time, the run holding the layer itself is
// not (unless the pipes fall inside it), and pipes after a floor's top delay nothing.
TEST(PipeTime, PipesDelayTheRunOfTheLayerAfterThemAndNothingAfterAFloorsTop) {
  using detail::LayerOrder;
  // Floor 0: layers 0-1 solid (geometry 0), 2-4 with a window (geometry 1); floor 1:
  // layers 0-2 solid (geometry 0).
  const std::vector<LayerOrder> order = {{0, 0, 0}, {0, 1, 0}, {0, 2, 1}, {0, 3, 1},
                                         {0, 4, 1}, {1, 0, 0}, {1, 1, 0}, {1, 2, 0}};
  constexpr double kPipe_s = 120.0;
  // Two pipes after floor 0's layer 1 (the solid run's last), one after its top layer.
  std::vector<double> s = detail::pipe_time_in_runs_s(order, {{{0, 1}, 2}, {{0, 4}, 1}}, kPipe_s);
  EXPECT_EQ(s, (std::vector<double>{0, 0, 240, 240, 240, 0, 0, 0}));
  // Inside a run: its most, not their sum; the next floor's first run is not given the
  // time of pipes after the floor below's top.
  s = detail::pipe_time_in_runs_s(order, {{{0, 2}, 1}, {{0, 3}, 3}, {{1, 0}, 1}}, kPipe_s);
  EXPECT_EQ(s, (std::vector<double>{0, 0, 360, 360, 360, 120, 120, 120}));
  // Pipes after the first layer of the building.
  s = detail::pipe_time_in_runs_s(order, {{{0, 0}, 1}}, kPipe_s);
  EXPECT_EQ(s, (std::vector<double>{120, 120, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(detail::pipe_time_in_runs_s({}, {{{0, 0}, 1}}, kPipe_s), std::vector<double>{});
}

// The count of nozzles a run takes: the fewest whose interval fits (at exactly the maximum
// too), else the fastest usable (the fewer of two equally fast). A count whose share of
// the deposition alone cannot fit is planned only when it could still be the fastest: at a
// share equal to the fastest so far it is, above it it is not; one nozzle too.
TEST(NozzleCount, TheFewestThatFitElseTheFastestPlanningOnlyCountsThatCouldBeEither) {
  using detail::CountPlan;
  EXPECT_EQ(detail::deposition_share_s(90.0, 3), 30.0);
  constexpr double kBetween_s = 5.0;
  // Plans by count (index 0 unused); interval = layer time + 5 s.
  const auto choose = [&](std::vector<CountPlan> plans, double deposition_s, double max_s,
                          std::set<int>* planned) {
    for (auto& p : plans) p.interval_s = p.layer_time_s + kBetween_s;
    return detail::fewest_fitting_count(
        static_cast<int>(plans.size()) - 1, deposition_s, kBetween_s, max_s,
        [&](int n) { return planned->count(n) > 0; },
        [&](int n) {
          planned->insert(n);
          return plans.at(n);
        });
  };
  const std::vector<CountPlan> three = {{}, {true, 100}, {true, 50}, {true, 35}};
  std::set<int> planned;
  // One nozzle's deposition with the 5 s between (95 s) cannot fit 55 s: not planned.
  EXPECT_EQ(choose(three, 90.0, 55.0, &planned), 2);  // 50 + 5 = 55: fits exactly
  EXPECT_EQ(planned, (std::set<int>{2}));
  planned.clear();
  // ... and at exactly the maximum it could: planned (and it fits).
  EXPECT_EQ(choose(three, 90.0, 95.0, &planned), 2);
  EXPECT_EQ(planned, (std::set<int>{1, 2}));
  planned.clear();
  EXPECT_EQ(choose(three, 90.0, 105.0, &planned), 1);  // 100 + 5 = 105
  EXPECT_EQ(planned, (std::set<int>{1}));
  planned.clear();
  EXPECT_EQ(choose(three, 90.0, 54.999, &planned), 3);
  planned.clear();
  // Two nozzles' share (45 s) with the 5 s between cannot fit 40 s: not planned.
  EXPECT_EQ(choose(three, 90.0, 40.0, &planned), 3);
  EXPECT_EQ(planned, (std::set<int>{3}));
  planned.clear();
  // None fits; the three nozzles' plan is the fastest and two nozzles' share (45 s) cannot
  // beat its 35 s: not planned.
  EXPECT_EQ(choose(three, 90.0, 10.0, &planned), 3);
  EXPECT_EQ(planned, (std::set<int>{3}));
  planned.clear();
  // None fits, three nozzles cannot work: two nozzles, unplanned in the first pass, are;
  // one nozzle's deposition (90 s) cannot beat their 50 s.
  EXPECT_EQ(choose({{}, {true, 100}, {true, 50}, {false, 0}}, 90.0, 10.0, &planned), 2);
  EXPECT_EQ(planned, (std::set<int>{2, 3}));
  planned.clear();
  // ... and where no more nozzles can work, one is planned and taken.
  EXPECT_EQ(choose({{}, {true, 100}, {false, 0}, {false, 0}}, 90.0, 10.0, &planned), 1);
  EXPECT_EQ(planned, (std::set<int>{1, 2, 3}));
  planned.clear();
  // One nozzle whose deposition equals the fastest so far is planned, and wins the tie.
  EXPECT_EQ(choose({{}, {true, 35}, {true, 50}, {true, 35}}, 35.0, 10.0, &planned), 1);
  EXPECT_EQ(planned, (std::set<int>{1, 2, 3}));
  planned.clear();
  // A share equal to the fastest so far is planned, and the fewer of two equally fast wins.
  EXPECT_EQ(choose({{}, {true, 100}, {true, 35}, {true, 35}}, 70.0, 10.0, &planned), 2);
  EXPECT_EQ(planned, (std::set<int>{2, 3}));
  planned.clear();
  // Nothing usable: one nozzle.
  EXPECT_EQ(choose({{}, {false, 0}, {false, 0}}, 0.0, 10.0, &planned), 1);
}

// The counts a schedule plans ahead, in parallel (next_count_to_plan asked until it names
// none, from none planned), are exactly those fewest_fitting_count plans one at a time,
// whatever the plans; and it then plans nothing more and gives the same count.
TEST(NozzleCount, PlanningAheadPlansWhatTheChoiceWouldAndNothingElse) {
  using detail::CountPlan;
  constexpr double kBetween_s = 5.0;
  struct Case {
    std::vector<CountPlan> plans;  // by count, index 0 unused; interval = layer time + 5 s
    double deposition_s, max_s;
  };
  const std::vector<Case> cases = {
      {{{}, {true, 100}, {true, 50}, {true, 35}}, 90.0, 55.0},    // two fit exactly
      {{{}, {true, 100}, {true, 50}, {true, 35}}, 90.0, 54.999},  // three, two planned
      {{{}, {true, 100}, {true, 50}, {true, 35}}, 90.0, 40.0},    // two's share cannot fit
      {{{}, {true, 100}, {true, 50}, {true, 35}}, 90.0, 10.0},    // none fits: the fastest
      {{{}, {true, 100}, {true, 50}, {false, 0}}, 90.0, 10.0},    // three unusable
      {{{}, {true, 100}, {true, 35}, {true, 35}}, 70.0, 10.0},    // equally fast
      {{{}, {true, 100}, {false, 0}, {true, 60}, {true, 45}}, 120.0, 10.0},
      {{{}, {false, 0}, {false, 0}}, 0.0, 10.0},
  };
  for (std::size_t c = 0; c < cases.size(); ++c) {
    SCOPED_TRACE(c);
    std::vector<CountPlan> plans = cases[c].plans;
    for (auto& p : plans) p.interval_s = p.layer_time_s + kBetween_s;
    const int max_count = static_cast<int>(plans.size()) - 1;
    const auto choose = [&](std::set<int>& planned) {
      return detail::fewest_fitting_count(
          max_count, cases[c].deposition_s, kBetween_s, cases[c].max_s,
          [&](int n) { return planned.count(n) > 0; },
          [&](int n) {
            planned.insert(n);
            return plans.at(n);
          });
    };
    std::set<int> one_at_a_time;
    const int chosen = choose(one_at_a_time);
    std::set<int> ahead;
    for (int round = 0; round < 10; ++round) {
      const auto next =
          detail::next_count_to_plan(max_count, cases[c].deposition_s, kBetween_s, cases[c].max_s,
                                     [&](int n) -> std::optional<CountPlan> {
                                       if (!ahead.count(n)) return std::nullopt;
                                       return plans.at(n);
                                     });
      if (!next) break;
      EXPECT_FALSE(ahead.count(*next)) << *next;
      ahead.insert(*next);
    }
    EXPECT_EQ(ahead, one_at_a_time);
    std::set<int> after = ahead;
    EXPECT_EQ(choose(after), chosen);
    EXPECT_EQ(after, ahead);  // nothing more planned
  }
}

}  // namespace
}  // namespace ccbuild::schedule
