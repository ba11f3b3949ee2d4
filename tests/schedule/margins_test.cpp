// The margins warned at their thresholds, on schedules made by hand: gantries exactly 50 mm
// apart and 1 mm closer, a climb at 20 mm and under it, an interval at exactly 90%
// of the maximum and over it (a planned joint never), an idle spell at 90% and over, and
// one over the limit (purged, so not a margin).

#include <gtest/gtest.h>

#include <cmath>

#include "ccbuild/schedule/margins.hpp"
#include "test_support.hpp"

namespace ccbuild::schedule {
namespace {

using testing::contains;

struct Case {
  Schedule schedule;
  machine::MachineModel machine;
  floors::MaterialProfile material;
  Case() {
    machine.gantry_width_m = 1.5;
    machine.nozzle_idle_limit_s = 300.0;
    material.max_layer_interval_s = 1000.0;
  }
  ScheduledLayer& add_layer(int floor, int layer, const std::string& plan) {
    ScheduledLayer l;
    l.floor = floor;
    l.layer = layer;
    l.plan = plan;
    schedule.layers.push_back(l);
    return schedule.layers.back();
  }
  std::vector<std::string> warnings() const { return margin_warnings(schedule, machine, material); }
};

TEST(Margins, GantriesWarnedUnderFiftyMillimetresWithTheLayersThatUseThePlan) {
  Case c;
  SchedulePlan wide, tight, single;
  wide.nozzles = tight.nozzles = 2;
  wide.min_gap_m = 1.55;    // exactly 50 mm: not warned
  tight.min_gap_m = 1.549;  // 49 mm
  single.nozzles = 1;
  c.schedule.plans = {{"g1n2", wide}, {"g2n2", tight}, {"g3n1", single}, {"g4n2", tight}};
  for (int k = 0; k < 3; ++k) c.add_layer(0, k, "g1n2");
  for (int k = 3; k < 6; ++k) c.add_layer(0, k, "g2n2");
  c.add_layer(1, 0, "g2n2");
  c.add_layer(1, 1, "g3n1");  // g4n2 is planned but used by no layer: not warned
  const auto w = c.warnings();
  ASSERT_EQ(w.size(), 1u) << (w.empty() ? "" : w[0]);
  EXPECT_TRUE(contains(w[0], "plan g2n2 come within 49 mm"));
  EXPECT_TRUE(contains(w[0], "on floor 0 layers 3-5, floor 1 layer 0; warned under 50 mm"));
}

// At the threshold itself, in binary-exact figures (1.55 - 1.5 is a hair over 0.05): a
// clearance equal to the threshold is not warned, the next double under it is.
TEST(Margins, AGantryClearanceExactlyAtTheThresholdIsNotWarned) {
  Case c;
  SchedulePlan at, under;
  at.nozzles = under.nozzles = 2;
  at.min_gap_m = c.machine.gantry_width_m + 0.0625;
  under.min_gap_m = std::nextafter(at.min_gap_m, 0.0);
  ASSERT_EQ(at.min_gap_m - c.machine.gantry_width_m, 0.0625);
  MarginThresholds t;
  t.gantry_clearance_m = 0.0625;
  c.schedule.plans = {{"g1n2", at}};
  c.add_layer(0, 0, "g1n2");
  EXPECT_TRUE(margin_warnings(c.schedule, c.machine, c.material, t).empty());
  c.schedule.plans = {{"g1n2", under}};
  const auto w = margin_warnings(c.schedule, c.machine, c.material, t);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_TRUE(contains(w[0], "plan g1n2 come within 62 mm")) << w[0];
}

TEST(Margins, ClimbsWarnedUnderTwentyMillimetresNamingTheClosest) {
  Case c;
  for (const double clearance_m : {0.02, 0.019, 0.000256}) {
    Event e;
    e.kind = Event::Kind::kClimb;
    e.climb = ClimbEvent{};
    e.climb->plan.min_clearance_m = clearance_m;
    e.climb->from_stage = static_cast<int>(c.schedule.events.size());
    e.climb->to_stage = e.climb->from_stage + 1;
    c.schedule.events.push_back(e);
  }
  const auto w = c.warnings();
  ASSERT_EQ(w.size(), 1u);
  EXPECT_TRUE(contains(w[0], "2 climbs pass within 20 mm of a wall"));
  EXPECT_TRUE(contains(w[0], "from stage 2 to 3")) << w[0];
  EXPECT_TRUE(contains(w[0], "passes 0.3 mm from it")) << w[0];
}

TEST(Margins, IntervalsOverNinetyPercentOfTheMaximumButNotOnAPlannedJoint) {
  Case c;
  c.add_layer(0, 1, "p").local_interval_max_s = 900.0;  // exactly 90%: not warned
  auto& over = c.add_layer(0, 2, "p");
  over.local_interval_max_s = 900.5;
  over.local_max_at = {5, 4, 1.0, 2.0};
  auto& joint = c.add_layer(0, 3, "p");
  joint.local_interval_max_s = 5000.0;  // a planned joint has no maximum
  joint.planned_joint = true;
  auto& weather = c.add_layer(0, 4, "p");
  weather.local_interval_max_s = 1200.0;  // with weather the equivalent age is what counts
  weather.equivalent_interval_max_s = 880.0;
  const auto w = c.warnings();
  ASSERT_EQ(w.size(), 1u);
  EXPECT_TRUE(contains(w[0], "1 layer cover a piece after more than 90%")) << w[0];
  EXPECT_TRUE(contains(w[0],
                       "floor 0 layer 2, covers wall 5 piece 4 at (1.000, 2.000) m after "
                       "900.5 s (90.0%)"))
      << w[0];
}

TEST(Margins, IdleSpellsOverNinetyPercentOfTheLimitUnlessPurged) {
  Case c;
  c.add_layer(0, 0, "p").max_idle_s = 270.0;  // exactly 90%
  c.add_layer(0, 1, "p").max_idle_s = 290.0;
  c.add_layer(0, 2, "p").max_idle_s = 299.0;
  c.add_layer(0, 3, "p").max_idle_s = 350.0;  // over the limit: purged, not a margin
  const auto w = c.warnings();
  ASSERT_EQ(w.size(), 1u);
  EXPECT_TRUE(contains(w[0],
                       "2 layers leave a nozzle idle for more than 90% of its limit of "
                       "300.0 s"))
      << w[0];
  EXPECT_TRUE(contains(w[0], "floor 0 layer 2, 299.0 s (99.7%)")) << w[0];
}

}  // namespace
}  // namespace ccbuild::schedule
