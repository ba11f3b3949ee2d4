// Lintels and slabs: a lintel over every opening before the first layer at or over its head
// (at the boundary: a head exactly at a layer's mid-height), the layers a precast lintel
// lies in cut across its opening and bearings, a stop for lintels leaving a planned joint,
// slabs formed and poured by a crew and cured to a strength before the next floor, the
// roof, crew hours, and the building keys refused at their lines. On small fixtures and on
// the bundled examples.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "ccbuild/common/input_error.hpp"
#include "ccbuild/floors/building.hpp"
#include "ccbuild/floors/slice.hpp"
#include "ccbuild/schedule/project.hpp"
#include "ccbuild/schedule/schedule.hpp"
#include "ccbuild/schedule/schedule_json.hpp"
#include "test_support.hpp"

namespace ccbuild::schedule {
namespace {
namespace fs = std::filesystem;
using testing::contains;

fs::path scratch(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("ccbuild_lintel_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

/// The one-wall building (12.5 m, layers of 0.1 m) with a window on its wall up to
/// `head_m` (none at 0) and `extra` building keys; `floors` floors of 2 m.
fs::path one_wall_building(const fs::path& dir, double head_m, const std::string& extra,
                           int floors = 1, const std::string& plan_file = "one_wall.yaml") {
  const fs::path plan = fs::path(testing::source_path("tests/data/plans/" + plan_file));
  const fs::path mix = fs::path(testing::source_path("tests/data/materials/quick-bond-mix.yaml"));
  const fs::path machine = fs::path(testing::source_path("config/machines/cc-gantry.yaml"));
  std::ofstream out(dir / "b.yaml");
  out << "name: One wall\nunits: m\nlayer_height: 0.1\nmaterial: " << mix.string()
      << "\nmachine: " << machine.string() << "\n"
      << extra << "floors:\n";
  for (int f = 0; f < floors; ++f) {
    out << "  - name: f" << f << "\n    height: 2.0\n    plan: " << plan.string() << "\n";
    if (head_m > 0)
      out << "    openings: [{id: W" << f << ", kind: window, wall: 1, offset: 4.0, width: 1.2, "
          << "sill: 0.6, head: " << head_m << "}]\n";
  }
  return dir / "b.yaml";
}

Schedule schedule_of(const schedule::Project& project) {
  ScheduleOptions o;
  o.jobs = 1;
  Schedule s = build_schedule(project, o);
  // Its JSON reads back under every rule (read_schedule's own checks, lintels and slabs too).
  try {
    parse_schedule(schedule_json(recorded_inputs(project, o), s).dump(1), "lintels.json");
  } catch (const InputError& e) {
    ADD_FAILURE() << "its JSON does not read back: " << e.what();
  }
  return s;
}

std::vector<const Event*> events_of(const Schedule& s, Event::Kind kind) {
  std::vector<const Event*> out;
  for (const auto& e : s.events)
    if (e.kind == kind) out.push_back(&e);
  return out;
}

/// Every lintel: each layer of its floor whose mid-height is at or over the head starts
/// after it, each one under it ends before it. Returns how many it checked.
int check_lintels_precede_layers(const Schedule& s) {
  int checked = 0;
  for (const Event* e : events_of(s, Event::Kind::kLintel)) {
    EXPECT_TRUE(e->lintel.has_value());
    if (!e->lintel) continue;
    ++checked;
    for (const auto& l : s.layers) {
      if (l.floor != e->floor) continue;
      // A mid-height within a micrometre of the head may fall either side of it.
      const double mid_m = 0.5 * (l.z_bottom_m + l.z_top_m);
      if (mid_m >= e->lintel->head_z_m + 1e-6) {
        EXPECT_GE(l.start_s, e->end_s - 1e-9) << "floor " << l.floor << " layer " << l.layer
                                              << " over opening " << e->lintel->opening;
      } else if (mid_m < e->lintel->head_z_m - 1e-6) {
        EXPECT_LE(l.end_s, e->start_s + 1e-9) << "floor " << l.floor << " layer " << l.layer
                                              << " under opening " << e->lintel->opening;
      }
    }
  }
  return checked;
}

TEST(Lintels, ALintelGoesInBeforeTheFirstLayerAtOrOverItsHeadAtTheBoundary) {
  // Head 1.25 m: layer 12 (1.2 to 1.3 m) has its mid-height exactly at the head, so it is
  // the first no longer cut, and the lintel goes in before it; 1 mm higher, before layer 13.
  for (const auto& [head_m, first_over] : {std::pair{1.25, 12}, std::pair{1.251, 13}}) {
    const fs::path dir = scratch("boundary");
    const auto project = schedule::open_project(
        one_wall_building(dir, head_m, "lintels: {place_min: 10, crew: 3}\n"));
    const Schedule s = schedule_of(project);
    ASSERT_TRUE(s.feasible) << s.infeasibility->message;
    const auto lintels = events_of(s, Event::Kind::kLintel);
    ASSERT_EQ(lintels.size(), 1u) << "head " << head_m;
    const Event& e = *lintels[0];
    EXPECT_EQ(e.layer, first_over - 1) << "head " << head_m;  // after the last layer open
    EXPECT_NEAR(e.end_s - e.start_s, 600.0, 1e-9);
    EXPECT_EQ(e.crew, 3);
    EXPECT_EQ(e.lintel->opening, "W0");
    EXPECT_NEAR(e.lintel->from_m, 4.0 - 0.15, 1e-9);  // the bearings
    EXPECT_NEAR(e.lintel->to_m, 5.2 + 0.15, 1e-9);
    EXPECT_EQ(check_lintels_precede_layers(s), 1);
    // The layer over it waits for it; 600 s is over the mix's 200 s maximum, so it starts
    // on a planned joint treated after the lintel.
    const ScheduledLayer& over = s.layers[first_over];
    EXPECT_TRUE(over.planned_joint);
    EXPECT_GE(over.start_s, e.end_s + 1800.0 - 1e-9);
    EXPECT_EQ(events_of(s, Event::Kind::kJoint).size(), 1u);
    EXPECT_NEAR(s.totals.lintels_s, 600.0, 1e-9);
    // Crew hours: the lintel's 3 people for 10 min and the joint's one for 30 min.
    EXPECT_NEAR(s.totals.crew_h, 3 * 600.0 / 3600 + 1800.0 / 3600, 1e-9);
  }
}

TEST(Lintels, AnOpeningUpToTheFloorsTopNeedsNone) {
  const fs::path dir = scratch("full");
  const auto project = schedule::open_project(one_wall_building(dir, 2.0, ""));
  const Schedule s = schedule_of(project);
  EXPECT_TRUE(events_of(s, Event::Kind::kLintel).empty());
  EXPECT_TRUE(events_of(s, Event::Kind::kJoint).empty());
}

TEST(Lintels, APrecastLintelLeavesItsOpeningAndBearingsOutOfTheLayersItLiesIn) {
  const fs::path dir = scratch("precast");
  const auto project = schedule::open_project(one_wall_building(
      dir, 1.2, "lintels: {type: precast, height: 0.2, bearing: 0.25, place_min: 15}\n"));
  const floors::Building& b = project.building;
  const auto layers = floors::slice_floor(b.floors[0], b.layer_height_m);
  ASSERT_EQ(layers.size(), 20u);
  const auto spans = [&](int k) {
    std::vector<std::pair<double, double>> out;  // x of each piece, the wall runs along x
    for (const auto& seg : layers[k].segments)
      out.push_back(
          {std::min(layers[k].points[seg.start_point].x(), layers[k].points[seg.end_point].x()),
           std::max(layers[k].points[seg.start_point].x(), layers[k].points[seg.end_point].x())});
    std::sort(out.begin(), out.end());
    return out;
  };
  // The wall starts at x = 2: the window is x 6 to 7.2, with bearings 5.75 to 7.45.
  using Spans = std::vector<std::pair<double, double>>;
  const auto near = [](const Spans& a, const Spans& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
      if (std::abs(a[i].first - b[i].first) > 1e-6 || std::abs(a[i].second - b[i].second) > 1e-6)
        return false;
    return true;
  };
  EXPECT_TRUE(near(spans(5), (Spans{{2.0, 14.5}})));              // under the sill
  EXPECT_TRUE(near(spans(6), (Spans{{2.0, 6.0}, {7.2, 14.5}})));  // the window
  EXPECT_TRUE(near(spans(11), (Spans{{2.0, 6.0}, {7.2, 14.5}})));
  EXPECT_TRUE(near(spans(12), (Spans{{2.0, 5.75}, {7.45, 14.5}})));  // the lintel's band
  EXPECT_TRUE(near(spans(13), (Spans{{2.0, 5.75}, {7.45, 14.5}})));
  EXPECT_TRUE(near(spans(14), (Spans{{2.0, 14.5}})));  // printed over the lintel
  const Schedule s = schedule_of(project);
  ASSERT_TRUE(s.feasible) << s.infeasibility->message;
  const auto lintels = events_of(s, Event::Kind::kLintel);
  ASSERT_EQ(lintels.size(), 1u);
  EXPECT_EQ(lintels[0]->layer, 11);  // set on the wall's top at the head
  EXPECT_EQ(lintels[0]->lintel->type, floors::LintelSpec::Type::kPrecast);
  EXPECT_EQ(check_lintels_precede_layers(s), 1);
}

// On the examples' golden schedules, read back under every rule: Regression.* schedules each
// example again and holds it to its golden exactly, so this checks what the scheduler makes
// without scheduling the three again (30 s of the suite).
TEST(Lintels, EveryOpeningOfEveryExampleGetsOneBeforeTheFirstLayerOverIt) {
  for (const std::string name : {"house", "apartment", "tower"}) {
    const auto project =
        schedule::open_project(testing::source_path("config/buildings/" + name + ".yaml"));
    const fs::path golden = testing::source_path("tests/regression/" + name + ".schedule.json");
    const Schedule s = parse_schedule(testing::slurp(golden), golden.string(), true).schedule;
    ASSERT_TRUE(s.feasible) << name << ": " << s.infeasibility->message;
    // Openings whose head some printed layer of their floor reaches.
    int want = 0;
    for (const auto& f : project.building.floors)
      for (const auto& o : f.plan.openings)
        for (const auto& l : s.layers)
          if (l.floor == f.index &&
              0.5 * (l.z_bottom_m + l.z_top_m) - f.base_elevation_m >= o.head_m) {
            ++want;
            break;
          }
    EXPECT_GT(want, 0) << name;
    EXPECT_EQ(check_lintels_precede_layers(s), want) << name;
    // The tower's slabs: formed and poured over each floor but the top, and its roof.
    if (!project.building.slabs) continue;
    const int floors = static_cast<int>(project.building.floors.size());
    const auto setups = events_of(s, Event::Kind::kSlab);
    const auto pours = events_of(s, Event::Kind::kPour);
    ASSERT_EQ(static_cast<int>(setups.size()), floors) << name;
    ASSERT_EQ(static_cast<int>(pours.size()), floors) << name;
    for (int f = 0; f < floors; ++f) {
      EXPECT_EQ(pours[f]->floor, f);
      EXPECT_EQ(pours[f]->roof, f + 1 == floors);
      EXPECT_GT(pours[f]->concrete_m3, 0.0);
    }
  }
}

TEST(Lintels, AfterAShortStopAPlanThatKeepsTheIntervalIsPreferredToAJoint) {
  // Two gantries, a mix that needs both, lintels set by the arm in 3 s: over the ground
  // floor's heads a plan following the layer below, a gantry held back, keeps every
  // interval, so no planned joint is made there.
  schedule::ProjectOptions open;
  open.machine_profile = testing::source_path("tests/data/machines/two-gantries.yaml");
  open.material_profile = testing::source_path("tests/data/materials/two-gantry-mix.yaml");
  const auto project = schedule::open_project(
      testing::source_path("tests/data/buildings/house-arm-lintels.yaml"), open);
  const Schedule s = schedule_of(project);
  ASSERT_TRUE(s.feasible) << s.infeasibility->message;
  const auto over = std::find_if(s.layers.begin(), s.layers.end(), [](const ScheduledLayer& l) {
    return l.floor == 0 && l.layer == 21;
  });
  ASSERT_NE(over, s.layers.end());
  EXPECT_FALSE(over->planned_joint);
  EXPECT_NE(over->plan.find('~'), std::string::npos) << over->plan;  // follows the layer below
  EXPECT_LE(*over->local_interval_max_s, project.material.max_layer_interval_s + 1e-6);
  EXPECT_EQ(check_lintels_precede_layers(s), 48);
}

TEST(Slabs, EachFloorsSlabIsFormedPouredAndCuredBeforeTheNextFloorAndTheRoofLast) {
  const fs::path dir = scratch("slabs");
  const auto project = schedule::open_project(
      one_wall_building(dir, 0.0,
                        "slabs: {thickness: 0.25, setup_h: 2, pour_m3_h: 10, ready_mpa: 5, "
                        "concrete: {fcm_mpa: 38, cement_class: N}, crew: 5}\n",
                        2, "two_metre_room.yaml"));
  const Schedule s = schedule_of(project);
  ASSERT_TRUE(s.feasible) << s.infeasibility->message;
  const auto setups = events_of(s, Event::Kind::kSlab);
  const auto pours = events_of(s, Event::Kind::kPour);
  ASSERT_EQ(setups.size(), 2u);  // the slab over floor 0 and the roof
  ASSERT_EQ(pours.size(), 2u);
  EXPECT_FALSE(pours[0]->roof);
  EXPECT_TRUE(pours[1]->roof);
  // 2 m x 2 m x 0.25 m = 1 m³ at 10 m³/h: 360 s.
  EXPECT_NEAR(pours[0]->concrete_m3, 1.0, 1e-9);
  EXPECT_NEAR(pours[0]->end_s - pours[0]->start_s, 360.0, 1e-6);
  EXPECT_NEAR(setups[0]->end_s - setups[0]->start_s, 7200.0, 1e-9);
  EXPECT_NEAR(pours[0]->start_s, setups[0]->end_s, 1e-9);
  EXPECT_EQ(pours[0]->crew, 5);
  // EN 1992-1-1 with s = 0.25: 5 MPa of 38 at t = 28 / (1 - ln(5/38)/0.25)^2 days.
  const double ready_age_s = 28 * 86400.0 / std::pow(1 - std::log(5.0 / 38.0) / 0.25, 2);
  EXPECT_NEAR(ready_age_s / 3600.0, 8.09, 0.01);
  const ScheduledLayer* first_up = nullptr;
  for (const auto& l : s.layers)
    if (l.floor == 1) {
      first_up = &l;
      break;
    }
  ASSERT_NE(first_up, nullptr);
  // It starts (after the purge its nozzle needs, idle since the floor below) at that age.
  const double purge_s = first_up->purge_before ? project.machine->purge_s : 0.0;
  EXPECT_NEAR(first_up->start_s - purge_s, pours[0]->end_s + ready_age_s, 1e-3);
  ASSERT_FALSE(first_up->wait_reasons.empty());
  EXPECT_EQ(first_up->wait_reasons.back().kind, WaitKind::kSlab);
  // The roof after the top floor's last layer, and the makespan its pour's end.
  EXPECT_GE(setups[1]->start_s, s.layers.back().end_s - 1e-9);
  EXPECT_NEAR(s.totals.makespan_s, pours[1]->end_s, 1e-9);
  EXPECT_NEAR(s.totals.slabs_s, 2 * (7200.0 + 360.0), 1e-6);
  EXPECT_NEAR(s.totals.crew_h, 5 * 2 * (7200.0 + 360.0) / 3600.0, 1e-6);
}

/// The two-metre room on two floors of 2 m with `slabs` (a `slabs:` map), the ground
/// floor's own `slab:` thickness when `ground_slab_m` > 0, and `site` (a `site:` block)
/// when given.
schedule::Project two_room_floors(const fs::path& dir, const std::string& slabs,
                                  double ground_slab_m = 0.0, const std::string& site = "",
                                  const std::string& material = "") {
  const std::string plan = testing::source_path("tests/data/plans/two_metre_room.yaml").string();
  std::ofstream out(dir / "b.yaml");
  out << "name: Two rooms\nunits: m\nlayer_height: 0.1\nmaterial: "
      << (material.empty()
              ? testing::source_path("tests/data/materials/quick-bond-mix.yaml").string()
              : material)
      << "\nmachine: " << testing::source_path("config/machines/cc-gantry.yaml").string()
      << "\nslabs: " << slabs << "\n"
      << site << "floors:\n  - {name: f0, height: 2.0, plan: " << plan
      << (ground_slab_m > 0 ? ", slab: " + std::to_string(ground_slab_m) : std::string())
      << "}\n  - {name: f1, height: 2.0, plan: " << plan << "}\n";
  out.close();
  return schedule::open_project(dir / "b.yaml");
}

const ScheduledLayer* first_layer_of(const Schedule& s, int floor) {
  for (const auto& l : s.layers)
    if (l.floor == floor) return &l;
  return nullptr;
}

TEST(Slabs, AFloorsOwnSlabThicknessIsPouredAndTheFloorAboveStandsOnIt) {
  // The ground floor's slab 0.3 m thick, the roof the building's 0.25 m: 2 m x 2 m x 0.3 m =
  // 1.2 m³ at 10 m³/h is 432 s; the roof 1 m³, 360 s.
  const fs::path dir = scratch("own_slab");
  const auto project = two_room_floors(
      dir, "{thickness: 0.25, setup_h: 1, pour_m3_h: 10, ready_mpa: 5, concrete: {fcm_mpa: 38}}",
      0.3);
  const Schedule s = schedule_of(project);
  ASSERT_TRUE(s.feasible) << s.infeasibility->message;
  const auto pours = events_of(s, Event::Kind::kPour);
  ASSERT_EQ(pours.size(), 2u);
  EXPECT_NEAR(pours[0]->concrete_m3, 1.2, 1e-9);
  EXPECT_NEAR(pours[0]->end_s - pours[0]->start_s, 432.0, 1e-6);
  EXPECT_NEAR(pours[1]->concrete_m3, 1.0, 1e-9);
  EXPECT_NEAR(pours[1]->end_s - pours[1]->start_s, 360.0, 1e-6);
  const ScheduledLayer* up = first_layer_of(s, 1);
  ASSERT_NE(up, nullptr);
  EXPECT_NEAR(up->z_bottom_m, 2.0 + 0.3, 1e-9);
}

TEST(Slabs, APourNeedsItsCrewInWorkingHoursThoughPrintingIsUnattended) {
  // Printing runs on through the night; the formwork (9.9 h) waits for Tuesday 07:00 and
  // ends at 16:54. A pour of 1 m³ at 10 m³/h (6 min) ends exactly at 17:00: it follows at
  // once; at 9 m³/h (400 s) it would end at 17:00:40: it waits for Wednesday 07:00.
  for (const double rate_m3_h : {10.0, 9.0}) {
    SCOPED_TRACE(rate_m3_h);
    const fs::path dir = scratch("pour_hours");
    std::ostringstream slabs;
    slabs << "{thickness: 0.25, setup_h: 9.9, pour_m3_h: " << rate_m3_h
          << ", ready_mpa: 5, concrete: {fcm_mpa: 38}}";
    const auto project =
        two_room_floors(dir, slabs.str(), 0.0,
                        "site:\n  start: 2027-03-01 07:00\n  time_zone: Europe/Berlin\n"
                        "  printing: unattended\n");
    const Schedule s = schedule_of(project);
    ASSERT_TRUE(s.feasible) << s.infeasibility->message;
    const auto setups = events_of(s, Event::Kind::kSlab);
    const auto pours = events_of(s, Event::Kind::kPour);
    ASSERT_EQ(setups.size(), 2u);
    ASSERT_EQ(pours.size(), 2u);
    // The ground floor's walls end on Monday, too late for 9.9 h of formwork that day.
    double ground_end_s = 0.0;
    for (const auto& l : s.layers)
      if (l.floor == 0) ground_end_s = std::max(ground_end_s, l.end_s);
    ASSERT_GT(ground_end_s, 360.0);
    ASSERT_LT(ground_end_s, 86400.0);
    EXPECT_NEAR(setups[0]->start_s, 86400.0, 1e-6);          // Tuesday 07:00
    EXPECT_NEAR(setups[0]->end_s, 86400.0 + 35640.0, 1e-6);  // 16:54
    const double shift_end_s = 86400.0 + 36000.0;            // Tuesday 17:00
    if (rate_m3_h == 10.0) {
      EXPECT_NEAR(pours[0]->start_s, setups[0]->end_s, 1e-6);
      EXPECT_NEAR(pours[0]->end_s, shift_end_s, 1e-6);
    } else {
      EXPECT_NEAR(pours[0]->start_s, 2 * 86400.0, 1e-6);  // Wednesday 07:00
      EXPECT_NEAR(pours[0]->end_s - pours[0]->start_s, 400.0, 1e-6);
    }
  }
}

TEST(Slabs, ASlabCuresInTheSitesEquivalentAgeBeforeTheNextFloor) {
  // At a constant 5 °C a Nurse-Saul mix (datum -10 °C) ages at (5 + 10) / 30 = 0.5: the
  // slab's 8.09 h to 5 MPa (EN 1992-1-1, fcm 38 MPa, class N) take twice as long.
  const fs::path dir = scratch("cold_slab");
  std::ofstream(dir / "mix.yaml") << "name: Nurse-Saul test mix\ndensity_kg_m3: 2200\n"
                                     "min_layer_interval_s: 30\nmax_layer_interval_s: 600\n"
                                     "strength_curve:\n  - {age_min: 0, strength_mpa: 0.1}\n"
                                     "  - {age_min: 1440, strength_mpa: 8.0}\n"
                                     "maturity: {function: nurse-saul, datum_temperature_c: -10}\n";
  const auto project = two_room_floors(
      dir,
      "{thickness: 0.25, setup_h: 1, pour_m3_h: 10, ready_mpa: 5, concrete: {fcm_mpa: 38, "
      "cement_class: N}}",
      0.0,
      "site:\n  start: 2027-03-01 07:00\n  time_zone: Europe/Berlin\n  printing: unattended\n"
      "  working_hours: {mon-sun: 00:00-24:00}\n  temperature_c: 5\n",
      (dir / "mix.yaml").string());
  const Schedule s = schedule_of(project);
  ASSERT_TRUE(s.feasible) << s.infeasibility->message;
  const auto pours = events_of(s, Event::Kind::kPour);
  ASSERT_EQ(pours.size(), 2u);
  const double ready_age_s = 28 * 86400.0 / std::pow(1 - std::log(5.0 / 38.0) / 0.25, 2);
  const ScheduledLayer* up = first_layer_of(s, 1);
  ASSERT_NE(up, nullptr);
  const double purge_s = up->purge_before ? project.machine->purge_s : 0.0;
  EXPECT_NEAR(up->start_s - purge_s, pours[0]->end_s + 2.0 * ready_age_s, 1e-3);
  ASSERT_FALSE(up->wait_reasons.empty());
  EXPECT_EQ(up->wait_reasons.back().kind, WaitKind::kSlab);
}

TEST(Slabs, NoRoofIsPouredWhenTheBuildingSaysSo) {
  const fs::path dir = scratch("no_roof");
  const auto project = two_room_floors(
      dir, "{setup_h: 1, pour_m3_h: 10, ready_mpa: 5, concrete: {fcm_mpa: 38}, roof: false}");
  const Schedule s = schedule_of(project);
  ASSERT_TRUE(s.feasible) << s.infeasibility->message;
  const auto pours = events_of(s, Event::Kind::kPour);
  ASSERT_EQ(pours.size(), 1u);  // the slab over the ground floor only
  EXPECT_EQ(pours[0]->floor, 0);
  EXPECT_FALSE(pours[0]->roof);
  EXPECT_EQ(events_of(s, Event::Kind::kSlab).size(), 1u);
  ASSERT_FALSE(s.layers.empty());
  EXPECT_NEAR(s.totals.makespan_s, s.layers.back().end_s, 1e-9);  // the walls end the work
}

TEST(Slabs, TheAreaIsTheConvexHullOfTheFloorsPlan) {
  floors::Floor f;
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{
           {0, 0}, {4, 0}, {4, 2}, {2, 2}, {2, 4}, {0, 4}, {1, 1}})  // an L and a point inside
    f.plan.vertices.push_back(
        {static_cast<std::int64_t>(f.plan.vertices.size() + 1), Eigen::Vector2d(x, y), {}});
  EXPECT_NEAR(floors::slab_area_m2(f), 14.0, 1e-12);  // the L's 12 m² and the corner's 2
  f.plan.vertices.resize(2);
  EXPECT_EQ(floors::slab_area_m2(f), 0.0);
}

TEST(Slabs, ASlabStageAndSlabsTogetherAndBadLintelsAreRefusedAtTheirKeys) {
  struct Case {
    std::string extra, field, says;
  };
  const Case cases[] = {
      {"slab_stage_h: 8\nslabs: {setup_h: 2}\n", "slabs", "not both"},
      {"slabs: {ready_mpa: 60}\n", "slabs.ready_mpa", "never reaches"},
      {"slabs: {pour_m3_h: 0}\n", "slabs.pour_m3_h", ""},
      {"slabs: {crew: 2.5}\n", "slabs.crew", "whole number"},
      {"slabs: {concrete: {fcm_mpa: 38, cement_class: X}}\n", "slabs.concrete.cement_class",
       "R, N or S"},
      {"slabs: {depth: 1}\n", "slabs.depth", ""},
      {"lintels: {type: precast}\n", "lintels", "height"},
      {"lintels: {height: 0.2}\n", "lintels.height", "only a precast"},
      {"lintels: {type: steel}\n", "lintels.type", "precast"},
      {"lintels: {by: arm, crew: 2}\n", "lintels.crew", "no crew"},
      {"lintels: {place_min: 0}\n", "lintels.place_min", ""},
  };
  for (const auto& c : cases) {
    const fs::path dir = scratch("bad");
    const fs::path path = one_wall_building(dir, 1.2, c.extra);
    try {
      schedule::open_project(path);
      ADD_FAILURE() << "accepted: " << c.extra;
    } catch (const InputError& e) {
      EXPECT_EQ(e.first().file, path.string()) << c.extra;
      EXPECT_GT(e.first().line, 0) << c.extra;
      EXPECT_EQ(e.first().field, c.field) << c.extra << ": " << e.what();
      EXPECT_TRUE(contains(e.what(), c.says)) << e.what();
    }
  }
}

}  // namespace
}  // namespace ccbuild::schedule
