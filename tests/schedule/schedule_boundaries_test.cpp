// The scheduler's rules, each at its boundary, on buildings small enough to time by
// hand: the walls above carried by every older layer, on its floor and the floors below,
// with the safety factor (the wait in seconds from the material's curve), and the
// computed nozzle-count fix that, when applied, makes the schedule feasible while one
// nozzle fewer does not.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "ccbuild/rules/age_clock.hpp"
#include "ccbuild/rules/intervals.hpp"
#include "ccbuild/schedule/project.hpp"
#include "ccbuild/schedule/schedule.hpp"
#include "test_support.hpp"

namespace ccbuild::schedule {
namespace {
using schedule::open_project;
using schedule::Project;
namespace fs = std::filesystem;
using testing::contains;

constexpr double kGravity_m_s2 = 9.80665;

class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name)
      : dir_(fs::temp_directory_path() /
             ("ccbuild_boundaries_" + name + "_" + std::to_string(::getpid()))) {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  ~ScratchDir() { fs::remove_all(dir_); }
  const fs::path& path() const { return dir_; }

 private:
  fs::path dir_;
};

ScheduleOptions quick() {
  ScheduleOptions o;
  o.jobs = 2;
  o.max_kicks = 300;
  return o;
}

/// A material whose strength rises linearly from `s0_mpa` at age 0 to `s1_mpa` at
/// 10 min, then to 6 MPa at a day.
std::string linear_mix(double s0_mpa, double s1_mpa, double safety_factor, double min_s = 10.0,
                       double max_s = 3600.0) {
  std::ostringstream m;
  m.precision(17);
  m << "name: test mix\ndensity_kg_m3: 2200\nmin_layer_interval_s: " << min_s
    << "\nmax_layer_interval_s: " << max_s << "\nsafety_factor: " << safety_factor
    << "\nstrength_curve:\n  - {age_min: 0, strength_mpa: " << s0_mpa
    << "}\n  - {age_min: 10, strength_mpa: " << s1_mpa
    << "}\n  - {age_min: 1440, strength_mpa: 6}\n";
  return m.str();
}

/// A building of one `width_m` x `depth_m` room per floor (floor heights
/// `floor_heights_m`), in 0.25 m layers, no slab stage, with `material` and the bundled
/// gantry (or `machine`).
Project room_building(const fs::path& dir, const std::string& material,
                      const std::vector<double>& floor_heights_m = {0.75}, double width_m = 2.0,
                      double depth_m = 1.0,
                      const std::string& machine = "config/machines/cc-gantry.yaml") {
  std::ofstream(dir / "material.yaml") << material;
  std::ostringstream b;
  b.precision(17);
  b << "units: m\nlayer_height: 0.25\nslab_stage_h: 0\nmaterial: material.yaml\nmachine: "
    << testing::source_path(machine).string() << "\nfloors:\n";
  for (double height_m : floor_heights_m)
    b << "  - height: " << height_m
      << "\n    plan:\n      vertices:\n        - {id: 1, x: 1, y: 1}\n        - {id: 2, x: "
      << 1 + width_m << ", y: 1}\n        - {id: 3, x: " << 1 + width_m << ", y: " << 1 + depth_m
      << "}\n        - {id: 4, x: 1, y: " << 1 + depth_m
      << "}\n      walls:\n        - {id: 1, start: 1, end: 2}\n        - {id: 2, start: 2, end: "
         "3}\n        - {id: 3, start: 3, end: 4}\n        - {id: 4, start: 4, end: 1}\n";
  std::ofstream(dir / "building.yaml") << b.str();
  return open_project(dir / "building.yaml");
}

/// The stress of `height_m` of wall times the safety factor, MPa (density 2200 kg/m3).
double stress_mpa(double height_m, double safety_factor) {
  return safety_factor * 2200.0 * kGravity_m_s2 * 1e-6 * height_m;
}

const WaitReason* reason_of(const ScheduledLayer& l, WaitKind kind) {
  for (const auto& r : l.wait_reasons)
    if (r.kind == kind) return &r;
  return nullptr;
}

TEST(ScheduleBoundaries, AnOlderLayerCarriesTheWallsAboveWithTheSafetyFactor) {
  // Three 0.25 m layers. When layer 2 starts, layer 1 (just below) carries 0.5 m and
  // layer 0 carries 0.75 m: with the factor 1.5, 0.01618 and 0.02427 MPa. The mix has
  // 0.02 MPa at once and gains 0.01 MPa in 10 min: layer 1 is strong enough at any age,
  // layer 0 only (0.02427 - 0.02) / 0.01 x 600 s = 256.3 s after it ends. Without the
  // factor, layer 0 would need no time at all.
  const ScratchDir dir("older_layers");
  const double factor = 1.5;
  const Project p = room_building(dir.path(), linear_mix(0.02, 0.03, factor));
  ASSERT_LT(stress_mpa(0.5, factor), 0.02);
  ASSERT_GT(stress_mpa(0.75, factor), 0.02);
  ASSERT_LE(stress_mpa(0.75, 1.0), 0.02);
  const double age_s = (stress_mpa(0.75, factor) - 0.02) / 0.01 * 600.0;
  EXPECT_NEAR(age_s, 256.28, 0.01);

  const Schedule s = build_schedule(p, quick());
  ASSERT_TRUE(s.feasible) << s.infeasibility->message;
  ASSERT_EQ(s.layers.size(), 3u);
  const ScheduledLayer &l0 = s.layers[0], &l1 = s.layers[1], &l2 = s.layers[2];
  // Layer 1 waits for nothing (layer 0 carries its 0.5 m at once)...
  EXPECT_TRUE(l1.wait_reasons.empty());
  EXPECT_NEAR(l1.wait_before_s, 0.0, 1e-9);
  // ... layer 2 for layer 0's strength: it starts exactly when layer 0 is old enough.
  ASSERT_LT(l1.end_s + l2.move_before_s, l0.end_s + age_s) << "the building is too slow to wait";
  EXPECT_FALSE(l2.purge_before);
  EXPECT_NEAR(l2.start_s, l0.end_s + age_s, 1e-6);
  const WaitReason* why = reason_of(l2, WaitKind::kStrength);
  ASSERT_NE(why, nullptr);
  EXPECT_NEAR(why->required_s, l2.wait_before_s, 1e-6);
  EXPECT_NEAR(l2.wait_before_s, l0.end_s + age_s - (l1.end_s + l2.move_before_s), 1e-6);
  EXPECT_TRUE(contains(why->detail, "floor 0 layer 0 carries 0.750 m"));
  EXPECT_TRUE(contains(why->detail, "safety factor 1.50"));
}

TEST(ScheduleBoundaries, AFloorsFirstLayerLoadsTheLayersOfTheFloorBelow) {
  // Floor 0 has two layers, floor 1 one, with no slab stage between. Floor 1's layer
  // (no layer below it on its floor) puts 0.5 m on floor 0's top layer and 0.75 m on its
  // bottom one. This mix gains strength fast (0.005 MPa at once, 0.5 MPa at 10 min), so
  // the top layer, ended last, is the one to wait for: 0.01618 MPa with the factor,
  // reached (0.01618 - 0.005) / 0.495 x 600 s = 13.6 s after it ended.
  const ScratchDir dir("floor_below");
  const double factor = 1.5;
  const Project p = room_building(dir.path(), linear_mix(0.005, 0.5, factor), {0.5, 0.25});
  const double top_age_s = (stress_mpa(0.5, factor) - 0.005) / 0.495 * 600.0;
  const double bottom_age_s = (stress_mpa(0.75, factor) - 0.005) / 0.495 * 600.0;
  EXPECT_NEAR(top_age_s, 13.55, 0.01);

  const Schedule s = build_schedule(p, quick());
  ASSERT_TRUE(s.feasible) << s.infeasibility->message;
  ASSERT_EQ(s.layers.size(), 3u);
  const ScheduledLayer &bottom = s.layers[0], &top = s.layers[1], &above = s.layers[2];
  ASSERT_EQ(above.floor, 1);
  EXPECT_FALSE(above.interval_s);  // on its slab: no interval to the floor below
  ASSERT_GT(top.end_s + top_age_s, bottom.end_s + bottom_age_s);
  ASSERT_LT(top.end_s + above.move_before_s, top.end_s + top_age_s) << "no wait to measure";
  EXPECT_FALSE(above.purge_before);
  EXPECT_NEAR(above.start_s, top.end_s + top_age_s, 1e-6);
  const WaitReason* why = reason_of(above, WaitKind::kStrength);
  ASSERT_NE(why, nullptr);
  EXPECT_NEAR(why->required_s, above.wait_before_s, 1e-6);
  EXPECT_TRUE(contains(why->detail, "floor 0 layer 1 carries 0.500 m"));
}

/// A one-floor building (three 0.25 m layers) of `rooms` 2 m square rooms in a row along
/// x (the rails), with `material`, on the bundled gantry with `nozzles` nozzles.
Project row_building(const fs::path& dir, const std::string& material, int rooms, int nozzles) {
  std::ofstream(dir / "material.yaml") << material;
  std::ostringstream b;
  b << "units: m\nlayer_height: 0.25\nslab_stage_h: 0\nmaterial: material.yaml\nmachine: "
    << testing::source_path("config/machines/cc-gantry.yaml").string()
    << "\nfloors:\n  - height: 0.75\n    plan:\n      vertices:\n";
  for (int k = 0; k <= rooms; ++k)
    b << "        - {id: " << 2 * k + 1 << ", x: " << 1 + 2 * k << ", y: 1}\n"
      << "        - {id: " << 2 * k + 2 << ", x: " << 1 + 2 * k << ", y: 3}\n";
  b << "      walls:\n";
  // Room k's cross wall is 3k + 1, its two long walls 3k + 2 and 3k + 3.
  for (int k = 0; k <= rooms; ++k) {
    b << "        - {id: " << 3 * k + 1 << ", start: " << 2 * k + 1 << ", end: " << 2 * k + 2
      << "}\n";
    if (k == rooms) break;
    b << "        - {id: " << 3 * k + 2 << ", start: " << 2 * k + 1 << ", end: " << 2 * k + 3
      << "}\n        - {id: " << 3 * k + 3 << ", start: " << 2 * k + 2 << ", end: " << 2 * k + 4
      << "}\n";
  }
  std::ofstream(dir / "building.yaml") << b.str();
  Project p = open_project(dir / "building.yaml");
  auto machine = std::make_shared<machine::MachineModel>(*p.machine);
  machine->nozzles = nozzles;
  p.machine = machine;
  return p;
}

/// A mix strong enough at once for anything in these buildings: only the interval
/// window [10 s, `max_s`] matters.
std::string strong_mix(double max_s) {
  return linear_mix(1.0, 2.0, 1.5, 10.0, max_s);
}

double worst_interval_s(const Schedule& s) {
  double worst_s = 0.0;
  for (const auto& l : s.layers)
    if (l.local_interval_max_s) worst_s = std::max(worst_s, *l.local_interval_max_s);
  return worst_s;
}

TEST(ScheduleBoundaries, TheNozzleFixCountsTheWholeIntervalAndMakesTheScheduleFeasible) {
  // Eight rooms in a row, 16 m along the rails. Their interval with two nozzles (the
  // layer's time, the move up to the next layer, and the piece ends' offsets) is I2.
  // With one nozzle and a maximum of exactly I2 the fix is two nozzles; a millisecond
  // less and it is three, although two nozzles' layer time alone is well within it. The
  // fix, applied, is feasible; one nozzle fewer is not.
  const ScratchDir dir("nozzle_fix");
  const Schedule two = build_schedule(row_building(dir.path(), strong_mix(200.0), 8, 2), quick());
  ASSERT_TRUE(two.feasible);
  ASSERT_EQ(two.layers.size(), 3u);
  for (const auto& l : two.layers) ASSERT_EQ(l.nozzles, 2);
  const double two_s = worst_interval_s(two);
  const double two_layer_s = two.layers[1].end_s - two.layers[1].start_s;
  ASSERT_GT(two_s, two_layer_s + 1.0) << "the move and offsets must count for something";

  auto schedule = [&](double max_s, int nozzles) {
    return build_schedule(row_building(dir.path(), strong_mix(max_s), 8, nozzles), quick());
  };
  {  // At exactly I2: two nozzles, and they do.
    const Schedule one = schedule(two_s, 1);
    ASSERT_FALSE(one.feasible);
    ASSERT_TRUE(one.infeasibility->nozzles_needed);
    EXPECT_EQ(*one.infeasibility->nozzles_needed, 2);
    EXPECT_TRUE(contains(one.infeasibility->fix, "or 2 nozzles (the machine has 1)"));
    EXPECT_TRUE(schedule(two_s, 2).feasible);
  }
  {  // Just under I2: two nozzles' layer time fits, their interval does not.
    const double max_s = two_s - 1e-3;
    ASSERT_LT(two_layer_s, max_s);
    const Schedule one = schedule(max_s, 1);
    ASSERT_FALSE(one.feasible);
    ASSERT_TRUE(one.infeasibility->nozzles_needed);
    const int needed = *one.infeasibility->nozzles_needed;
    EXPECT_EQ(needed, 3);
    const Schedule fixed = schedule(max_s, needed);
    EXPECT_TRUE(fixed.feasible) << fixed.infeasibility->message;
    EXPECT_LE(worst_interval_s(fixed), max_s);
    // From the first layer on: two nozzles' layer time fits, but not with the move up
    // to the next layer, so the run starts with three.
    for (const auto& l : fixed.layers) EXPECT_EQ(l.nozzles, needed);
    const Schedule short_by_one = schedule(max_s, needed - 1);
    EXPECT_FALSE(short_by_one.feasible);
    EXPECT_GT(worst_interval_s(short_by_one), max_s);
  }
}

}  // namespace
}  // namespace ccbuild::schedule

namespace ccbuild::schedule {
namespace {

std::vector<WaitReason> bound(std::vector<WaitReason> reasons) {
  bind_wait_reasons(reasons);
  return reasons;
}

// A climb held by its anchors until 5 h, then by the night until 14 h, then by the wind
// until 16.5 h: each hour goes to the cause that held it then, 5 + 9 + 2.5 h.
TEST(WaitCauses, ANightThenTheWindAfterTheAnchorsEachBindTheirOwnHours) {
  const double h = 3600.0;
  const auto r = bound({{WaitKind::kAnchorStrength, 5 * h, "anchors", 0.0},
                        {WaitKind::kOffShift, 14 * h, "night", 5 * h},
                        {WaitKind::kWind, 16.5 * h, "wind", 14 * h}});
  EXPECT_DOUBLE_EQ(r[0].binding_s, 5 * h);
  EXPECT_DOUBLE_EQ(r[1].binding_s, 9 * h);
  EXPECT_DOUBLE_EQ(r[2].binding_s, 2.5 * h);
  EXPECT_DOUBLE_EQ(binding_s(r, WaitKind::kAnchorStrength), 5 * h);
  EXPECT_DOUBLE_EQ(binding_s(r, WaitKind::kStrength), 0.0);
}

// Two anchors (strong at 3 h and at 20 h) and a night found at 20 h, until 30 h: the
// younger anchor holds the first 20 h alone, though the other anchor and a night in
// between held too; a reason another outlasts never binds.
TEST(WaitCauses, AReasonOutlastedByAnotherHoldingThenBindsNothing) {
  const double h = 3600.0;
  const auto r = bound({{WaitKind::kAnchorStrength, 3 * h, "older anchor", 0.0},
                        {WaitKind::kAnchorStrength, 20 * h, "younger anchor", 0.0},
                        {WaitKind::kOffShift, 30 * h, "night", 20 * h}});
  EXPECT_DOUBLE_EQ(r[0].binding_s, 0.0);
  EXPECT_DOUBLE_EQ(r[1].binding_s, 20 * h);
  EXPECT_DOUBLE_EQ(r[2].binding_s, 10 * h);
  EXPECT_DOUBLE_EQ(binding_s(r, WaitKind::kAnchorStrength), 20 * h);
}

// Boundaries: equal reasons (the first binds), one that ends where it starts (none), and
// a moment no reason holds (bound by none: the binding times fall short of the wait).
TEST(WaitCauses, TiesEmptyReasonsAndGapsAtTheirBoundaries) {
  auto tie =
      bound({{WaitKind::kMinInterval, 100.0, "a", 0.0}, {WaitKind::kStrength, 100.0, "b", 0.0}});
  EXPECT_DOUBLE_EQ(tie[0].binding_s, 100.0);
  EXPECT_DOUBLE_EQ(tie[1].binding_s, 0.0);
  auto empty = bound({{WaitKind::kOffShift, 50.0, "a", 50.0}, {WaitKind::kCold, 50.0, "b", 0.0}});
  EXPECT_DOUBLE_EQ(empty[0].binding_s, 0.0);
  EXPECT_DOUBLE_EQ(empty[1].binding_s, 50.0);
  auto gap =
      bound({{WaitKind::kMinInterval, 10.0, "a", 0.0}, {WaitKind::kOffShift, 30.0, "b", 20.0}});
  EXPECT_DOUBLE_EQ(gap[0].binding_s, 10.0);
  EXPECT_DOUBLE_EQ(gap[1].binding_s, 10.0);
  // Held from the start, the later one outlasts: it binds it all.
  auto concurrent =
      bound({{WaitKind::kMinInterval, 100.0, "a", 0.0}, {WaitKind::kStrength, 120.0, "b", 0.0}});
  EXPECT_DOUBLE_EQ(concurrent[0].binding_s, 0.0);
  EXPECT_DOUBLE_EQ(concurrent[1].binding_s, 120.0);
}

}  // namespace
}  // namespace ccbuild::schedule

namespace ccbuild::rules {
namespace {

// Half speed from t = 0 (a cold spell), full speed from t = 1000 s (E = 500 s there).
AgeClock cold_then_mild() {
  return AgeClock({{0.0, 0.0, 0.5}, {1000.0, 500.0, 1.0}});
}

TEST(AgeClock, AgesAndTheirInverseByHand) {
  const AgeClock c = cold_then_mild();
  EXPECT_DOUBLE_EQ(c.age(200.0, 600.0), 200.0);        // 400 s at half speed
  EXPECT_DOUBLE_EQ(c.age(800.0, 1200.0), 300.0);       // 200 s at half, 200 at full
  EXPECT_DOUBLE_EQ(c.after(800.0, 300.0), 1200.0);     // and back
  EXPECT_DOUBLE_EQ(c.after(800.0, 100.0), 1000.0);     // exactly at the breakpoint
  EXPECT_DOUBLE_EQ(AgeClock().after(5.0, 7.0), 12.0);  // real time
  // Frozen for ever: never that old.
  EXPECT_TRUE(std::isinf(AgeClock({{0.0, 0.0, 0.0}}).after(1.0, 1.0)));
}

TEST(AgeClock, ItsTextRoundTripsAndABadLineIsNamed) {
  const AgeClock c = cold_then_mild();
  const AgeClock back = AgeClock::parse(c.text());
  ASSERT_EQ(back.breakpoints().size(), 2u);
  EXPECT_EQ(back.at(1234.5), c.at(1234.5));
  for (const char* bad :
       {"0 0 0.5\n10 5\n", "0 0 -1\n", "10 0 1\n5 0 1\n", "0 0 1 x\n", "0 nan 1\n"}) {
    try {
      AgeClock::parse(bad);
      ADD_FAILURE() << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_TRUE(std::string(e.what()).find("line ") == 0) << e.what();
    }
  }
}

// One stretch laid below from t = 100 to 300 s, covered from 50 to 150 s after the upper
// layer's start, with a 100-600 s window. On the cold clock the newest end is 100 s old
// at 500 s and the oldest 600 s old at 1150 s: the layer starts in [450, 1000]; on real
// time, in [350, 550].
TEST(AgeClock, TheStartWindowIsOneOfEquivalentAge) {
  IntervalOffsets o;
  o.each.push_back({50.0, 150.0, 100.0, 300.0, {}});
  o.ends = 1;
  const AgeClock cold = cold_then_mild();
  const StartWindow w = start_window(o, 100.0, 600.0, &cold);
  EXPECT_DOUBLE_EQ(w.earliest_s, 500.0 - 50.0);
  EXPECT_DOUBLE_EQ(w.latest_s, 1150.0 - 150.0);
  const StartWindow r = start_window(o, 100.0, 600.0);
  EXPECT_DOUBLE_EQ(r.earliest_s, 400.0 - 50.0);
  EXPECT_DOUBLE_EQ(r.latest_s, 700.0 - 150.0);
}

}  // namespace
}  // namespace ccbuild::rules
