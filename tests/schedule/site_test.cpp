// The site's programme: its calendar's working windows (holidays, daylight-saving changes,
// back-to-back spans), timestamps, and the scheduler on it at the boundaries: a shift that
// ends exactly at a layer's end, one second before it, a holiday, a DST weekend, a joint
// older than its material allows, a layer longer than any shift. On one straight wall
// whose layers end at known seconds (tests/data/plans/one_wall.yaml).

#include "ccbuild/site/site.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "ccbuild/common/input_error.hpp"
#include "ccbuild/schedule/project.hpp"
#include "ccbuild/schedule/quantities.hpp"
#include "ccbuild/schedule/schedule.hpp"
#include "ccbuild/schedule/schedule_json.hpp"
#include "ccbuild/site/conditions.hpp"
#include "test_support.hpp"

namespace ccbuild::schedule {
namespace {
namespace fs = std::filesystem;
using testing::contains;

constexpr double kTol_s = 1e-6;

fs::path scratch(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("ccbuild_site_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

/// A programme read from YAML text, as a building's `site:` holds it.
site::SiteProgramme programme(const std::string& yaml) {
  const Document doc = parse_yaml(yaml, "site.yaml");
  return *site::read_site_programme(Field::root(doc), {});
}

InputError programme_error(const std::string& yaml) {
  try {
    programme(yaml);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "accepted: " << yaml;
  return InputError("", 0, "", "");
}

// One table of weekday names for the text, the exports and the week's hours: days since
// 1970-01-01 (a Thursday), before it too, and a date the calendar parses.
TEST(SiteCalendar, WeekdaysCountFromAThursday) {
  EXPECT_STREQ(site::weekday_names()[site::weekday_of(0)], "Thu");
  EXPECT_STREQ(site::weekday_names()[site::weekday_of(-1)], "Wed");
  EXPECT_STREQ(site::weekday_names()[site::weekday_of(-7)], "Thu");
  EXPECT_STREQ(site::weekday_names()[site::weekday_of(4)], "Mon");
  EXPECT_STREQ(site::weekday_names()[site::weekday_of(*site::parse_local_date("2027-03-01"))],
               "Mon");
  EXPECT_STREQ(site::weekday_names()[site::weekday_of(*site::parse_local_date("2026-12-06"))],
               "Sun");
  EXPECT_EQ(site::weekday_keys().size(), site::weekday_names().size());
}

TEST(SiteProgramme, DefaultsToMondayToFridaySevenToFive) {
  const site::SiteProgramme p = programme("start: 2027-03-01 07:00\ntime_zone: Europe/Berlin\n");
  for (int d = 0; d < 5; ++d) EXPECT_EQ(p.week[d], (std::vector<site::WorkingHours>{{420, 1020}}));
  EXPECT_TRUE(p.week[5].empty());
  EXPECT_TRUE(p.week[6].empty());
  EXPECT_TRUE(p.printing_attended);
  EXPECT_TRUE(p.pipes_need_crew);
  EXPECT_EQ(site::local_start_text(p.start_local_s), "2027-03-01 07:00");
}

TEST(SiteProgramme, RefusesWhatCannotBeACalendarNamingTheKey) {
  const std::string head = "start: 2027-03-01 07:00\ntime_zone: Europe/Berlin\n";
  struct Case {
    std::string yaml, field, says;
  };
  const Case cases[] = {
      {"start: 2027-02-30 07:00\ntime_zone: Europe/Berlin\n", "start", "YYYY-MM-DD HH:MM"},
      {"start: 2027-03-01 25:00\ntime_zone: Europe/Berlin\n", "start", "YYYY-MM-DD HH:MM"},
      {"start: 2027-03-01 07:00\ntime_zone: Europe/Atlantis\n", "time_zone", "IANA"},
      {"time_zone: Europe/Berlin\n", "", "required key 'start'"},
      {head + "working_hours: {mon-fri: 17:00-07:00}\n", "working_hours.mon-fri", "ends before"},
      {head + "working_hours: {mon: [07:00-12:00, 11:00-17:00]}\n", "working_hours.mon", "overlap"},
      {head + "working_hours: {mon-fri: 07:00-17:00, fri: 07:00-12:00}\n", "working_hours.fri",
       "twice"},
      {head + "working_hours: {weekdays: 07:00-17:00}\n", "working_hours.weekdays", "weekday"},
      {head + "working_hours: {mon-sun: off}\n", "working_hours", "no working hours"},
      {head + "working_hours: {mon: 7-17}\n", "working_hours.mon", "HH:MM-HH:MM"},
      {head + "holidays: [2027-13-01]\n", "holidays[0]", "YYYY-MM-DD"},
      {head + "printing: sometimes\n", "printing", "attended"},
      {head + "pipes: robot\n", "pipes", "crew"},
      {head + "shifts: 2\n", "shifts", "unknown"},
  };
  for (const auto& c : cases) {
    const InputError e = programme_error(c.yaml);
    EXPECT_EQ(e.first().field, c.field) << c.yaml << ": " << e.what();
    EXPECT_TRUE(contains(e.what(), c.says)) << c.yaml << ": " << e.what();
    EXPECT_GT(e.first().line, 0) << c.yaml;
  }
}

TEST(SiteCalendar, WindowsSkipWeekendsAndHolidaysInTheZonesSeconds) {
  // Mon 2027-03-01 07:00 CET; Wednesday a holiday.
  const site::SiteCalendar c(
      programme("start: 2027-03-01 07:00\ntime_zone: Europe/Berlin\nholidays: [2027-03-03]\n"));
  const auto& w = c.windows();
  ASSERT_GE(w.size(), 5u);
  EXPECT_DOUBLE_EQ(w[0].from_s, 0.0);
  EXPECT_DOUBLE_EQ(w[0].to_s, 36000.0);
  EXPECT_DOUBLE_EQ(w[1].from_s, 86400.0);      // Tuesday
  EXPECT_DOUBLE_EQ(w[2].from_s, 3 * 86400.0);  // Thursday: Wednesday is a holiday
  EXPECT_DOUBLE_EQ(w[4].from_s, 7 * 86400.0);  // the next Monday
  EXPECT_EQ(c.timestamp(0.0), "2027-03-01T07:00:00+01:00");
  EXPECT_EQ(c.timestamp(36000.0), "2027-03-01T17:00:00+01:00");
  EXPECT_EQ(c.local_text(3 * 86400.0), "Thu 2027-03-04 07:00");
  EXPECT_EQ(c.week_text(), "Mon-Fri 07:00-17:00");
}

TEST(SiteCalendar, DaylightSavingChangesMoveTheWindowsByAnHour) {
  // Fri 2027-03-26 16:00 CET; clocks go forward on Sunday 28 March: Monday 07:00 CEST is
  // 05:00 UTC, 2 days 14 h after Friday 15:00 UTC (not 2 days 15 h).
  const site::SiteCalendar spring(programme("start: 2027-03-26 16:00\ntime_zone: Europe/Berlin\n"));
  ASSERT_GE(spring.windows().size(), 2u);
  EXPECT_DOUBLE_EQ(spring.windows()[1].from_s, 2 * 86400.0 + 14 * 3600.0);
  EXPECT_EQ(spring.timestamp(spring.windows()[1].from_s), "2027-03-29T07:00:00+02:00");
  // Around the clock on the change days: 23 h on 28 March, 25 h on 31 October, one window.
  const site::SiteCalendar around(programme(
      "start: 2027-03-28 00:00\ntime_zone: Europe/Berlin\nworking_hours: {sun: 00:00-24:00}\n"));
  EXPECT_DOUBLE_EQ(around.windows()[0].to_s - around.windows()[0].from_s, 23 * 3600.0);
  const site::SiteCalendar autumn(programme(
      "start: 2027-10-31 00:00\ntime_zone: Europe/Berlin\nworking_hours: {sun: 00:00-24:00}\n"));
  EXPECT_DOUBLE_EQ(autumn.windows()[0].to_s - autumn.windows()[0].from_s, 25 * 3600.0);
  // A shift starting in the hour that does not exist starts at the change.
  const site::SiteCalendar gap(programme(
      "start: 2027-03-27 12:00\ntime_zone: Europe/Berlin\nworking_hours: {sun: 02:30-06:00}\n"));
  EXPECT_EQ(gap.timestamp(gap.windows()[0].from_s), "2027-03-28T03:00:00+02:00");
}

TEST(SiteCalendar, ZoneOffsetsListTheChangesUpToTheEndAndNoneAfter) {
  // Mon 2027-03-01 07:00 CET (06:00 UTC). Summer time starts Sun 2027-03-28 01:00 UTC,
  // 26 d 19 h later; CET has held since Sun 2026-10-25 01:00 UTC (+02:00 before).
  const site::SiteCalendar c(programme("start: 2027-03-01 07:00\ntime_zone: Europe/Berlin\n"));
  const double change_s = 26 * 86400.0 + 19 * 3600.0;
  const auto before = c.zone_offsets(0.0, change_s - 1.0);
  ASSERT_EQ(before.size(), 1u);
  EXPECT_EQ(before[0].abbreviation, "CET");
  EXPECT_FALSE(before[0].daylight);
  EXPECT_EQ(before[0].offset_s, 3600);
  EXPECT_EQ(before[0].previous_offset_s, 7200);
  EXPECT_EQ(before[0].from_utc_s, 1792890000);  // 2026-10-25T01:00:00Z
  // Ending exactly at the change: the summer offset is not yet in force.
  EXPECT_EQ(c.zone_offsets(0.0, change_s).size(), 1u);
  const auto after = c.zone_offsets(0.0, change_s + 1.0);
  ASSERT_EQ(after.size(), 2u);
  EXPECT_EQ(after[1].abbreviation, "CEST");
  EXPECT_TRUE(after[1].daylight);
  EXPECT_EQ(after[1].from_utc_s, c.utc_of(change_s));
  EXPECT_EQ(after[1].previous_offset_s, 3600);
  EXPECT_EQ(after[1].offset_s, 7200);
  // A zone without changes since before 1970 is said to start then, at its one offset.
  for (const char* zone : {"UTC", "Asia/Tokyo"}) {
    const site::SiteCalendar still(
        programme("start: 2027-03-01 07:00\ntime_zone: " + std::string(zone) + "\n"));
    const auto offsets = still.zone_offsets(0.0, 365 * 86400.0);
    ASSERT_EQ(offsets.size(), 1u) << zone;
    EXPECT_EQ(offsets[0].from_utc_s, 0) << zone;
    EXPECT_EQ(offsets[0].previous_offset_s, offsets[0].offset_s) << zone;
  }
}

TEST(SiteCalendar, SpansThatMeetAtMidnightAreOneWindow) {
  const site::SiteCalendar c(
      programme("start: 2027-03-01 22:00\ntime_zone: UTC\nworking_hours: {mon: [22:00-24:00], tue: "
                "[00:00-06:00]}\n"));
  ASSERT_FALSE(c.windows().empty());
  EXPECT_DOUBLE_EQ(c.windows()[0].from_s, 0.0);
  EXPECT_DOUBLE_EQ(c.windows()[0].to_s, 8 * 3600.0);
  EXPECT_DOUBLE_EQ(c.longest_window_s(), 8 * 3600.0);
}

TEST(SiteCalendar, WorkThatFillsTheRestOfAShiftFitsAndOneSecondMoreWaits) {
  const site::SiteCalendar c(programme("start: 2027-03-01 07:00\ntime_zone: Europe/Berlin\n"));
  EXPECT_DOUBLE_EQ(c.fit_s(30000.0, 6000.0), 30000.0);                  // ends at 17:00 exactly
  EXPECT_DOUBLE_EQ(c.fit_s(30000.0, 6001.0), 86400.0);                  // Tuesday 07:00
  EXPECT_DOUBLE_EQ(c.fit_s(36000.0, 0.0), 36000.0);                     // at the very end
  EXPECT_DOUBLE_EQ(c.fit_s(-5.0, 10.0), 0.0);                           // before the start
  EXPECT_TRUE(std::isinf(c.fit_s(0.0, 36001.0)));                       // longer than any shift
  EXPECT_DOUBLE_EQ(c.fit_s(4 * 86400.0 + 36000.0, 60.0), 7 * 86400.0);  // Friday 17:00: Monday
  EXPECT_TRUE(c.within_one_window(0.0, 36000.0));
  EXPECT_FALSE(c.within_one_window(0.0, 36000.5));
}

// ------------------------------------------------------------------ the scheduler on it

/// The one-wall building (20 layers of 94 s, one every 96.5 s) with `site` as its site.
Schedule one_wall(const fs::path& dir, const std::string& site, const std::string& extra = "",
                  Setup* setup_out = nullptr) {
  const fs::path plan = fs::absolute("tests/data/plans/one_wall.yaml");
  const fs::path mix = fs::absolute("tests/data/materials/quick-bond-mix.yaml");
  const fs::path machine = fs::absolute("config/machines/cc-gantry.yaml");
  // `extra` may name another material.
  const std::string material =
      extra.rfind("material:", 0) == 0 ? "" : "material: " + mix.string() + "\n";
  std::ofstream(dir / "b.yaml") << "name: One wall\nunits: m\nlayer_height: 0.1\n"
                                << material << "machine: " << machine.string() << "\n"
                                << extra << "site:\n"
                                << site << "floors:\n  - {name: ground, height: 2.0, plan: "
                                << plan.string() << "}\n";
  const schedule::Project project = schedule::open_project(dir / "b.yaml");
  ScheduleOptions o;
  o.jobs = 1;
  Schedule s = build_schedule(project, o);
  if (setup_out) *setup_out = project;
  // Whatever it says, its JSON reads back under every rule (read_schedule's own checks).
  const RecordedInputs in = recorded_inputs(project, o);
  try {
    parse_schedule(schedule_json(in, s).dump(1), "one_wall.json");
  } catch (const InputError& e) {
    ADD_FAILURE() << "its JSON does not read back: " << e.what();
  }
  return s;
}

const Event* joint_before(const Schedule& s, const ScheduledLayer& l) {
  for (const auto& e : s.events)
    if (e.kind == Event::Kind::kJoint && e.floor == l.floor && e.layer == l.layer - 1) return &e;
  return nullptr;
}

TEST(SiteSchedule, AShiftEndingExactlyAtALayersEndKeepsThatLayer) {
  const fs::path dir = scratch("exact");
  const Schedule s = one_wall(dir,
                              "  start: 2027-03-01 07:00\n  time_zone: Europe/Berlin\n"
                              "  working_hours: {mon-fri: [07:00-07:08, 08:00-17:00]}\n");
  ASSERT_TRUE(s.feasible) << s.infeasibility->message;
  ASSERT_EQ(s.layers.size(), 20u);
  EXPECT_NEAR(s.layers[4].end_s, 480.0, kTol_s);  // ends with the first span
  EXPECT_FALSE(s.layers[4].planned_joint);
  const ScheduledLayer& next = s.layers[5];
  EXPECT_TRUE(next.planned_joint);
  const Event* joint = joint_before(s, next);
  ASSERT_NE(joint, nullptr);
  EXPECT_NEAR(joint->start_s, 3600.0, kTol_s);  // 08:00: the treatment first
  EXPECT_NEAR(joint->end_s, 3600.0 + 1800.0, kTol_s);
  EXPECT_TRUE(next.purge_before);  // the nozzle idled over its 300 s limit
  EXPECT_NEAR(next.start_s, 3600.0 + 1800.0 + 120.0, kTol_s);
  ASSERT_FALSE(next.wait_reasons.empty());
  EXPECT_EQ(next.wait_reasons.back().kind, WaitKind::kOffShift);
  EXPECT_GT(*next.local_interval_max_s, 200.0);  // over the maximum: a joint, not a failure
  for (std::size_t i = 6; i < s.layers.size(); ++i) EXPECT_FALSE(s.layers[i].planned_joint);
  ASSERT_EQ(s.days.size(), 1u);
  EXPECT_EQ(s.days[0].stop, DayEnd::kFinished);
}

TEST(SiteSchedule, AShiftEndingOneSecondBeforeALayersEndStopsTheLayerBefore) {
  const fs::path dir = scratch("second");
  const Schedule s = one_wall(dir,
                              "  start: 2027-03-01 07:00:01\n  time_zone: Europe/Berlin\n"
                              "  working_hours: {mon-fri: [07:00-07:08, 08:00-17:00]}\n");
  ASSERT_TRUE(s.feasible) << s.infeasibility->message;
  // Layer 4 would end at 07:08:01: it waits for 08:00 on a planned joint.
  EXPECT_NEAR(s.layers[3].end_s, 480.0 - 96.5, kTol_s);
  EXPECT_TRUE(s.layers[4].planned_joint);
  const Event* joint = joint_before(s, s.layers[4]);
  ASSERT_NE(joint, nullptr);
  EXPECT_NEAR(joint->start_s, 3599.0, kTol_s);  // 08:00:00 is 3599 s after 07:00:01
  EXPECT_FALSE(s.layers[5].planned_joint);
}

TEST(SiteSchedule, AHolidayAndAWeekendAreSkippedAndTheJointTreatedAfterThem) {
  const fs::path dir = scratch("holiday");
  // Friday 16:50: 6 layers fit before 17:00 (the seventh would end at 17:01:13).
  const Schedule s = one_wall(dir,
                              "  start: 2027-03-05 16:50\n  time_zone: Europe/Berlin\n"
                              "  holidays: [2027-03-08]\n");
  ASSERT_TRUE(s.feasible) << s.infeasibility->message;
  int stopped = -1;
  for (std::size_t i = 0; i < s.layers.size(); ++i)
    if (s.layers[i].planned_joint) stopped = static_cast<int>(i);
  ASSERT_EQ(stopped, 6);
  const Event* joint = joint_before(s, s.layers[6]);
  ASSERT_NE(joint, nullptr);
  // Tuesday 07:00: 3 days 14 h 10 min after Friday 16:50 (no DST change in between).
  EXPECT_NEAR(joint->start_s, 3 * 86400.0 + 14 * 3600.0 + 600.0, kTol_s);
  const auto& cal = *schedule::open_project(dir / "b.yaml").calendar;
  EXPECT_EQ(cal.local_text(joint->start_s), "Tue 2027-03-09 07:00");
  ASSERT_EQ(s.days.size(), 2u);
  EXPECT_EQ(s.days[0].date, "2027-03-05");
  EXPECT_EQ(s.days[0].layers, 6);
  EXPECT_EQ(s.days[0].stop, DayEnd::kPlannedJoint);
  EXPECT_EQ(s.days[1].date, "2027-03-09");
}

TEST(SiteSchedule, ADaylightSavingWeekendResumesAtSevenLocalTime) {
  const fs::path dir = scratch("dst");
  const Schedule s = one_wall(dir, "  start: 2027-03-26 16:50\n  time_zone: Europe/Berlin\n");
  ASSERT_TRUE(s.feasible) << s.infeasibility->message;
  const Event* joint = joint_before(s, s.layers[6]);
  ASSERT_NE(joint, nullptr);
  // Monday 07:00 CEST is 2 days 13 h 10 min after Friday 16:50 CET, an hour less than the
  // wall clock says.
  EXPECT_NEAR(joint->start_s, 2 * 86400.0 + 13 * 3600.0 + 600.0, kTol_s);
}

TEST(SiteSchedule, AJointOlderThanItsMaterialAllowsIsInfeasible) {
  const fs::path dir = scratch("old_joint");
  // A week of holidays after Friday: the joint would be 11 days old, over 7.
  const Schedule s = one_wall(dir,
                              "  start: 2027-03-05 16:50\n  time_zone: Europe/Berlin\n"
                              "  holidays: [2027-03-08, 2027-03-09, 2027-03-10, 2027-03-11, "
                              "2027-03-12]\n");
  ASSERT_FALSE(s.feasible);
  EXPECT_EQ(s.infeasibility->kind, InfeasibilityKind::kJoint);
  EXPECT_TRUE(contains(s.infeasibility->message, "over the material's 168.0 h"))
      << s.infeasibility->message;
}

TEST(SiteSchedule, UnattendedPrintingRunsThroughTheNight) {
  const fs::path dir = scratch("unattended");
  const Schedule s = one_wall(dir,
                              "  start: 2027-03-05 16:50\n  time_zone: Europe/Berlin\n"
                              "  printing: unattended\n");
  ASSERT_TRUE(s.feasible);
  for (const auto& l : s.layers) EXPECT_FALSE(l.planned_joint);
  EXPECT_NEAR(s.layers.back().end_s, 19 * 96.5 + 94.0, kTol_s);
}

TEST(SiteSchedule, ALayerLongerThanAnyShiftIsInfeasibleWithTheLongestShift) {
  const fs::path dir = scratch("short_shift");
  const Schedule s = one_wall(dir,
                              "  start: 2027-03-01 07:00\n  time_zone: Europe/Berlin\n"
                              "  working_hours: {mon-fri: 07:00-07:01}\n");
  ASSERT_FALSE(s.feasible);
  EXPECT_EQ(s.infeasibility->kind, InfeasibilityKind::kCalendar);
  EXPECT_TRUE(contains(s.infeasibility->message, "the longest is 0.02 h"))
      << s.infeasibility->message;
}

/// The quick-bond mix (tests/data/materials) with `extra` keys, as `material:` for one_wall.
std::string quick_bond_with(const fs::path& dir, const std::string& extra) {
  std::ifstream in("tests/data/materials/quick-bond-mix.yaml");
  std::ofstream(dir / "mix.yaml") << in.rdbuf() << extra;
  return "material: " + (dir / "mix.yaml").string() + "\n";
}

TEST(SiteSchedule, AJointIsTreatedOnceTheLayerBelowIsItsMinimumAgeCountedFromItsEnd) {
  // Layer 4 is deposited from 386 s to 480 s (07:08), the next shift starts at 08:00.
  const std::string site =
      "  start: 2027-03-01 07:00\n  time_zone: Europe/Berlin\n"
      "  working_hours: {mon-fri: [07:00-07:08, 08:00-17:00]}\n";
  for (const double min_age_h : {0.5, 1.0}) {
    SCOPED_TRACE(min_age_h);
    const fs::path dir = scratch("joint_age");
    const Schedule s = one_wall(
        dir, site,
        quick_bond_with(dir, "planned_joint: {min_age_h: " + std::to_string(min_age_h) + "}\n"));
    ASSERT_TRUE(s.feasible) << s.infeasibility->message;
    ASSERT_EQ(s.layers.size(), 20u);
    ASSERT_TRUE(s.layers[5].planned_joint);
    const Event* joint = joint_before(s, s.layers[5]);
    ASSERT_NE(joint, nullptr);
    // Half an hour after 480 s is 07:38, before the shift: at 08:00. An hour after it is
    // 4080 s (08:08), 94 s later than an hour after the layer's start.
    const double treated_s = min_age_h < 1.0 ? 3600.0 : 480.0 + 3600.0;
    EXPECT_NEAR(joint->start_s, treated_s, kTol_s);
    EXPECT_NEAR(s.layers[5].start_s, treated_s + 1800.0 + 120.0, kTol_s);  // treated, purged
    ASSERT_FALSE(s.layers[5].wait_reasons.empty());
    EXPECT_EQ(s.layers[5].wait_reasons.back().kind,
              min_age_h < 1.0 ? WaitKind::kOffShift : WaitKind::kJoint);
  }
}

TEST(SiteSchedule, AJointsTreatmentWaitsForAShiftThatHoldsItWithTheLayer) {
  // After layer 4 (ends 07:08), a 10-minute span from 08:00 holds the layer and its purge
  // (214 s) but not with the joint's 30 min treatment before them (2014 s): the joint is
  // treated at 09:00, and every layer with its purge and joint lies within one span.
  const fs::path dir = scratch("joint_shift");
  const Schedule s = one_wall(dir,
                              "  start: 2027-03-01 07:00\n  time_zone: Europe/Berlin\n"
                              "  working_hours: {mon-fri: [07:00-07:08, 08:00-08:10, "
                              "09:00-17:00]}\n");
  ASSERT_TRUE(s.feasible) << s.infeasibility->message;
  ASSERT_EQ(s.layers.size(), 20u);
  ASSERT_TRUE(s.layers[5].planned_joint);
  const Event* joint = joint_before(s, s.layers[5]);
  ASSERT_NE(joint, nullptr);
  EXPECT_NEAR(joint->start_s, 7200.0, kTol_s);
  EXPECT_NEAR(s.layers[5].start_s, 7200.0 + 1800.0 + 120.0, kTol_s);
  const std::vector<std::pair<double, double>> spans = {
      {0.0, 480.0}, {3600.0, 4200.0}, {7200.0, 36000.0}};
  for (const auto& l : s.layers) {
    const double block_s =
        l.start_s - (l.purge_before ? 120.0 : 0.0) - (l.planned_joint ? 1800.0 : 0.0);
    EXPECT_TRUE(std::any_of(
        spans.begin(), spans.end(),
        [&](const auto& w) { return block_s >= w.first - kTol_s && l.end_s <= w.second + kTol_s; }))
        << "layer " << l.layer << " from " << block_s << " s to " << l.end_s << " s";
  }
}

TEST(SiteSchedule, AStopThatLeavesTheIntervalExactlyAtTheMaximumNeedsNoJoint) {
  // The first span ends at 07:09, after layer 4 (386 s to 480 s after the start) and
  // before layer 5 would end; the next starts at 07:10. From 07:00:14 it is 586 s after
  // the start, exactly the 200 s maximum after layer 4 started: no joint. From 07:00:13 it
  // is 201 s: a planned joint.
  for (const int second : {14, 13}) {
    SCOPED_TRACE(second);
    const fs::path dir = scratch("exact_max");
    const Schedule s =
        one_wall(dir, "  start: 2027-03-01 07:00:" + std::to_string(second) +
                          "\n  time_zone: Europe/Berlin\n"
                          "  working_hours: {mon-fri: [07:00-07:09, 07:10-17:00]}\n");
    ASSERT_TRUE(s.feasible) << s.infeasibility->message;
    ASSERT_EQ(s.layers.size(), 20u);
    EXPECT_NEAR(s.layers[4].start_s, 386.0, kTol_s);
    const ScheduledLayer& next = s.layers[5];
    if (second == 14) {
      EXPECT_FALSE(next.planned_joint);
      EXPECT_NEAR(next.start_s, 586.0, kTol_s);
      ASSERT_TRUE(next.local_interval_max_s.has_value());
      EXPECT_NEAR(*next.local_interval_max_s, 200.0, kTol_s);
      EXPECT_EQ(joint_before(s, next), nullptr);
    } else {
      EXPECT_TRUE(next.planned_joint);
      const Event* joint = joint_before(s, next);
      ASSERT_NE(joint, nullptr);
      EXPECT_NEAR(joint->start_s, 587.0, kTol_s);
    }
  }
}

TEST(SiteSchedule, TheJsonCarriesTimestampsAndTheProgrammeAndReadsBackToTheSameBytes) {
  const fs::path dir = scratch("json");
  schedule::Setup setup;
  const Schedule s =
      one_wall(dir, "  start: 2027-03-01 07:00\n  time_zone: Europe/Berlin\n", "", &setup);
  ScheduleOptions o;
  const RecordedInputs in = recorded_inputs(setup, o);
  const std::string text = schedule_json(in, s).dump(1);
  const auto j = nlohmann::json::parse(text);
  EXPECT_EQ(j["inputs"]["site"]["start"], "2027-03-01T07:00:00+01:00");
  EXPECT_EQ(j["inputs"]["site"]["working_hours"]["mon"][0], "07:00-17:00");
  EXPECT_EQ(j["layers"][0]["start_time"], "2027-03-01T07:00:00+01:00");
  EXPECT_EQ(j["totals"]["finish_time"], j["layers"][19]["end_time"]);
  const ScheduleDocument back = parse_schedule(text, "s.json");
  EXPECT_EQ(schedule_json(back.inputs, back.schedule).dump(1), text);
  // A timestamp that is not its seconds' is refused, at its pointer.
  auto bad = nlohmann::ordered_json::parse(text);
  bad["layers"][0]["start_time"] = "2027-03-01T08:00:00+01:00";
  try {
    parse_schedule(bad.dump(1), "bad.json");
    ADD_FAILURE() << "a wrong timestamp was accepted";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), "/layers/0/start_time")) << e.what();
  }
}

}  // namespace
}  // namespace ccbuild::schedule

namespace ccbuild::schedule {
namespace {

// ------------------------------------------------------------------ weather and maturity

site::SiteConditions readings(std::vector<site::WeatherReading> r) {
  site::SiteConditions c;
  c.readings = std::move(r);
  return c;
}

TEST(EquivalentAge, NurseSaulAgesByHandComputedRates) {
  // 20 °C for an hour, 0 °C for an hour, then 30 °C; datum -10 °C: rates 1, 1/3, 4/3.
  const site::SiteConditions c =
      readings({{0.0, 20.0, 0.0}, {3600.0, 0.0, 0.0}, {7200.0, 30.0, 0.0}});
  floors::MaturityFunction f;
  f.kind = floors::MaturityFunction::Kind::kNurseSaul;
  f.datum_temperature_c = -10.0;
  const site::EquivalentAge e(c, f);
  EXPECT_NEAR(e.at(3600.0), 3600.0, 1e-9);
  EXPECT_NEAR(e.at(7200.0), 4800.0, 1e-9);
  EXPECT_NEAR(e.at(9000.0), 7200.0, 1e-9);
  EXPECT_NEAR(e.after(0.0, 4800.0), 7200.0, 1e-9);
  EXPECT_NEAR(e.after(3600.0, 1200.0), 7200.0, 1e-9);  // the cold hour ages it 20 min
  EXPECT_NEAR(e.after(5400.0, 1000.0), 7200.0 + 400.0 / (4.0 / 3.0), 1e-9);
  // Below the datum it does not age at all.
  const site::SiteConditions frost = readings({{0.0, -15.0, 0.0}, {3600.0, 20.0, 0.0}});
  const site::EquivalentAge f2(frost, f);
  EXPECT_NEAR(f2.at(3600.0), 0.0, 1e-9);
  EXPECT_NEAR(f2.after(0.0, 60.0), 3660.0, 1e-9);
}

TEST(EquivalentAge, ArrheniusAgesByHandComputedRates) {
  // E = 40 kJ/mol: exp(-E/R (1/T - 1/293.15 K)) is 0.300709 at 0 °C, 1.718325 at 30 °C.
  const site::SiteConditions c = readings({{0.0, 0.0, 0.0}, {3600.0, 30.0, 0.0}});
  const site::EquivalentAge e(c, floors::MaturityFunction{});
  EXPECT_NEAR(e.at(3600.0), 3600.0 * 0.300709, 0.01);
  EXPECT_NEAR(e.at(7200.0), 3600.0 * (0.300709 + 1.718325), 0.01);
  // At 20 °C the rate is exactly 1: equivalent age is age.
  const site::SiteConditions twenty = readings({{0.0, 20.0, 0.0}});
  const site::EquivalentAge t(twenty, floors::MaturityFunction{});
  EXPECT_DOUBLE_EQ(t.after(123.0, 456.0), 579.0);
}

TEST(EquivalentAge, WeatherFitsFindTheFirstSpellThatHoldsTheWork) {
  const site::SiteConditions c =
      readings({{0.0, 10.0, 5.0}, {3600.0, 10.0, 20.0}, {7200.0, 10.0, 5.0}, {10800.0, 4.0, 5.0}});
  const site::EquivalentAge e(c, floors::MaturityFunction{});
  const auto calm = [](const site::WeatherReading& r) { return r.wind_m_s <= 15.0; };
  EXPECT_DOUBLE_EQ(e.fit_s(0.0, 3600.0, calm), 0.0);     // ends as the gale starts
  EXPECT_DOUBLE_EQ(e.fit_s(0.0, 3601.0, calm), 7200.0);  // one second into it: after it
  const auto warm = [](const site::WeatherReading& r) { return r.temperature_c >= 5.0; };
  EXPECT_TRUE(std::isinf(e.fit_s(9000.0, 3600.0, warm)));  // the cold holds for ever
  const auto at_limit = [](const site::WeatherReading& r) { return r.temperature_c >= 10.0; };
  EXPECT_DOUBLE_EQ(e.fit_s(0.0, 600.0, at_limit), 0.0);  // exactly at the limit is allowed
}

TEST(Weather, ReadsAnHourlyCsvAndRefusesBadRowsByLineAndColumn) {
  const fs::path dir = scratch("weather");
  const site::SiteCalendar cal(programme("start: 2027-03-01 07:00\ntime_zone: Europe/Berlin\n"));
  std::ofstream(dir / "ok.csv") << "timestamp,temperature_c,wind_m_s\n2027-03-01T06:00:00Z,4,3\n"
                                   "2027-03-01 08:00,6.5,12\n";
  const site::SiteConditions c = site::read_weather_csv(dir / "ok.csv", cal);
  ASSERT_EQ(c.readings.size(), 2u);
  EXPECT_DOUBLE_EQ(c.readings[0].t_s, 0.0);  // 06:00 UTC is 07:00 in Berlin
  EXPECT_DOUBLE_EQ(c.readings[1].t_s, 3600.0);
  EXPECT_DOUBLE_EQ(c.readings[1].wind_m_s, 12.0);
  struct Case {
    std::string body, column, says;
    int line;
  };
  const Case cases[] = {
      {"time,t,w\n", "header", "timestamp,temperature_c,wind_m_s", 1},
      {"timestamp,temperature_c,wind_m_s\nyesterday,4,3\n", "timestamp", "ISO 8601", 2},
      {"timestamp,temperature_c,wind_m_s\n2027-03-01 08:00,95,3\n", "temperature_c", "95", 2},
      {"timestamp,temperature_c,wind_m_s\n2027-03-01 08:00,5,-1\n", "wind_m_s", "-1", 2},
      {"timestamp,temperature_c,wind_m_s\n2027-03-01 08:00,5,1\n2027-03-01 07:00,5,1\n",
       "timestamp", "increase", 3},
      {"timestamp,temperature_c,wind_m_s\n2027-03-01 08:00,5\n", "", "3 values", 2},
  };
  for (const auto& k : cases) {
    std::ofstream(dir / "bad.csv") << k.body;
    try {
      site::read_weather_csv(dir / "bad.csv", cal);
      ADD_FAILURE() << "accepted: " << k.body;
    } catch (const InputError& e) {
      EXPECT_EQ(e.first().field, k.column) << e.what();
      EXPECT_EQ(e.first().line, k.line) << e.what();
      EXPECT_TRUE(contains(e.what(), k.says)) << e.what();
    }
  }
}

/// A mix like the quick-bond one whose window is in equivalent age (Nurse-Saul, datum
/// -10 °C: rate (T + 10) / 30).
fs::path nurse_saul_mix(const fs::path& dir, double min_s, double max_s) {
  std::ofstream(dir / "mix.yaml") << "name: Nurse-Saul test mix\ndensity_kg_m3: 2200\n"
                                  << "min_layer_interval_s: " << min_s
                                  << "\nmax_layer_interval_s: " << max_s
                                  << "\nstrength_curve:\n  - {age_min: 0, strength_mpa: 0.1}\n"
                                     "  - {age_min: 1440, strength_mpa: 8.0}\n"
                                     "maturity: {function: nurse-saul, datum_temperature_c: -10}\n";
  return dir / "mix.yaml";
}

TEST(SiteSchedule, ACold5DegreeSiteHalvesTheAgeAndTheLayersWaitForTheMinimum) {
  // At 5 °C the rate is 0.5: a 60 s minimum in equivalent age takes 120 s, where the
  // layers follow each other every 96.5 s at 20 °C.
  const fs::path dir = scratch("cold_site");
  const Schedule s = one_wall(dir,
                              "  start: 2027-03-01 07:00\n  time_zone: Europe/Berlin\n"
                              "  printing: unattended\n  temperature_c: 5\n",
                              "material: " + nurse_saul_mix(dir, 60, 600).string() + "\n");
  ASSERT_TRUE(s.feasible) << s.infeasibility->message;
  for (std::size_t i = 1; i < s.layers.size(); ++i) {
    const ScheduledLayer& l = s.layers[i];
    EXPECT_NEAR(l.start_s - s.layers[i - 1].start_s, 120.0, kTol_s) << i;
    ASSERT_TRUE(l.equivalent_interval_min_s.has_value());
    EXPECT_NEAR(*l.equivalent_interval_min_s, 60.0, kTol_s) << i;
    EXPECT_NEAR(*l.equivalent_interval_max_s, 0.5 * *l.local_interval_max_s, kTol_s) << i;
    ASSERT_FALSE(l.wait_reasons.empty());
    EXPECT_EQ(l.wait_reasons[0].kind, WaitKind::kMinInterval);
    EXPECT_NEAR(l.wait_reasons[0].required_s, 23.5, kTol_s) << i;
  }
}

TEST(SiteSchedule, AHotSiteShortensTheWindowBeyondWhatTheLayersKeep) {
  // At 35 °C the rate is 1.5: 96.5 s between layers is 144.75 s of equivalent age, over a
  // 120 s maximum that 20 °C keeps.
  const fs::path dir = scratch("hot_site");
  const std::string site =
      "  start: 2027-03-01 07:00\n  time_zone: Europe/Berlin\n  printing: unattended\n";
  const std::string mix = "material: " + nurse_saul_mix(dir, 30, 120).string() + "\n";
  EXPECT_TRUE(one_wall(dir, site + "  temperature_c: 20\n", mix).feasible);
  const Schedule hot = one_wall(dir, site + "  temperature_c: 35\n", mix);
  ASSERT_FALSE(hot.feasible);
  EXPECT_EQ(hot.infeasibility->kind, InfeasibilityKind::kMaxInterval);
  ASSERT_GE(hot.layers.size(), 2u);
  EXPECT_NEAR(*hot.layers[1].equivalent_interval_max_s, 1.5 * *hot.layers[1].local_interval_max_s,
              kTol_s);
}

TEST(SiteSchedule, PrintingStopsInTheColdAndResumesAtThePlacingLimit) {
  const fs::path dir = scratch("frost");
  // 07:00 start; from 07:05 to 08:00 it is 4.9 °C, from 08:00 exactly 5.0 °C (the limit).
  std::ofstream(dir / "w.csv") << "timestamp,temperature_c,wind_m_s\n2027-03-01 07:00,8,1\n"
                                  "2027-03-01 07:05,4.9,1\n2027-03-01 08:00,5.0,1\n";
  const Schedule s = one_wall(dir,
                              "  start: 2027-03-01 07:00\n  time_zone: Europe/Berlin\n"
                              "  weather: " +
                                  (dir / "w.csv").string() + "\n");
  ASSERT_TRUE(s.feasible) << s.infeasibility->message;
  // Layers 0-2 end by 07:05 (layer 2 at 287 s); layer 3 would run into the frost.
  EXPECT_LE(s.layers[2].end_s, 300.0 + kTol_s);
  EXPECT_TRUE(s.layers[3].planned_joint);
  const Event* joint = joint_before(s, s.layers[3]);
  ASSERT_NE(joint, nullptr);
  EXPECT_NEAR(joint->start_s, 3600.0, kTol_s);  // at 08:00, 5.0 °C
  EXPECT_EQ(s.layers[3].wait_reasons.back().kind, WaitKind::kCold);
}

/// Every layer of `s`, from its block's start (its joint's treatment, its purge) to its
/// end, in air within [min_c, max_c] by the hourly `readings` (time, °C), each in force
/// until the next.
void expect_printed_within(const Schedule& s,
                           const std::vector<std::pair<double, double>>& readings, double min_c,
                           double max_c) {
  for (const auto& l : s.layers) {
    const double block_s =
        l.start_s - (l.purge_before ? 120.0 : 0.0) - (l.planned_joint ? 1800.0 : 0.0);
    for (std::size_t k = 0; k < readings.size(); ++k) {
      const double from_s = readings[k].first;
      const double to_s = k + 1 < readings.size() ? readings[k + 1].first : INFINITY;
      if (to_s <= block_s + kTol_s || from_s >= l.end_s - kTol_s) continue;
      EXPECT_GE(readings[k].second, min_c) << "layer " << l.layer << " at " << from_s << " s";
      EXPECT_LE(readings[k].second, max_c) << "layer " << l.layer << " at " << from_s << " s";
    }
  }
}

TEST(SiteSchedule, PrintingRunsAtExactlyThePlacingMaximumAndStopsATenthOfADegreeOver) {
  // A mix placed from 5 to 25 °C (at 25 °C it ages 1.32 times as fast: 127 s of the
  // 200 s maximum between layers).
  const fs::path dir = scratch("heat");
  const std::string mix = quick_bond_with(dir, "placing_temperature_c: [5, 25]\n");
  const std::string site = "  start: 2027-03-01 07:00\n  time_zone: Europe/Berlin\n  weather: " +
                           (dir / "w.csv").string() + "\n";
  // 25.0 °C all day: printed straight through.
  std::ofstream(dir / "w.csv") << "timestamp,temperature_c,wind_m_s\n2027-03-01 07:00,25.0,1\n";
  const Schedule at_max = one_wall(dir, site, mix);
  ASSERT_TRUE(at_max.feasible) << at_max.infeasibility->message;
  for (const auto& l : at_max.layers) EXPECT_FALSE(l.planned_joint);
  EXPECT_NEAR(at_max.layers.back().end_s, 19 * 96.5 + 94.0, kTol_s);
  // 25.1 °C from 07:05 to 08:00: layer 3 waits for 08:00 on a planned joint.
  std::ofstream(dir / "w.csv") << "timestamp,temperature_c,wind_m_s\n2027-03-01 07:00,20,1\n"
                                  "2027-03-01 07:05,25.1,1\n2027-03-01 08:00,25.0,1\n";
  const Schedule hot = one_wall(dir, site, mix);
  ASSERT_TRUE(hot.feasible) << hot.infeasibility->message;
  ASSERT_EQ(hot.layers.size(), 20u);
  EXPECT_TRUE(hot.layers[3].planned_joint);
  const Event* joint = joint_before(hot, hot.layers[3]);
  ASSERT_NE(joint, nullptr);
  EXPECT_NEAR(joint->start_s, 3600.0, kTol_s);
  ASSERT_FALSE(hot.layers[3].wait_reasons.empty());
  EXPECT_EQ(hot.layers[3].wait_reasons.back().kind, WaitKind::kCold);  // out of range
  expect_printed_within(hot, {{0.0, 20.0}, {300.0, 25.1}, {3600.0, 25.0}}, 5.0, 25.0);
}

TEST(SiteSchedule, TheJointsTreatmentAndPurgeAreInThePlacingWindowWithTheLayer) {
  // After layer 4 (ends 07:08), the next shift at 08:00; 4 °C from 08:30 to 09:00. From
  // 08:00 the layer and its purge (214 s) would end before the frost, but with the joint's
  // 30 min treatment first (2014 s) they run into it: the joint is treated at 09:00.
  const fs::path dir = scratch("cold_joint");
  std::ofstream(dir / "w.csv") << "timestamp,temperature_c,wind_m_s\n2027-03-01 07:00,20,1\n"
                                  "2027-03-01 08:30,4,1\n2027-03-01 09:00,20,1\n";
  const Schedule s = one_wall(dir,
                              "  start: 2027-03-01 07:00\n  time_zone: Europe/Berlin\n"
                              "  working_hours: {mon-fri: [07:00-07:08, 08:00-17:00]}\n"
                              "  weather: " +
                                  (dir / "w.csv").string() + "\n");
  ASSERT_TRUE(s.feasible) << s.infeasibility->message;
  ASSERT_EQ(s.layers.size(), 20u);
  ASSERT_TRUE(s.layers[5].planned_joint);
  const Event* joint = joint_before(s, s.layers[5]);
  ASSERT_NE(joint, nullptr);
  EXPECT_NEAR(joint->start_s, 7200.0, kTol_s);
  ASSERT_FALSE(s.layers[5].wait_reasons.empty());
  EXPECT_EQ(s.layers[5].wait_reasons.back().kind, WaitKind::kCold);
  expect_printed_within(s, {{0.0, 20.0}, {5400.0, 4.0}, {7200.0, 20.0}}, 5.0, 35.0);
}

TEST(SiteSchedule, AJointsTreatmentCountsTowardsTheNozzlesIdleTimeBeforeItsPurge) {
  // A mix placed from 5 to 25 °C; 26 °C from 07:05 to 07:08: layer 3 waits from 287 s
  // (layer 2's end) to 480 s, 193 s idle, under the nozzle's 300 s limit. The heat ages
  // layer 2 faster (Arrhenius: 1.39 at 26 °C), over the 200 s maximum in equivalent age:
  // a planned joint, whose 30 min treatment comes first. The nozzle then idles 1993 s,
  // and is purged.
  const fs::path dir = scratch("short_heat");
  std::ofstream(dir / "w.csv") << "timestamp,temperature_c,wind_m_s\n2027-03-01 07:00,20,1\n"
                                  "2027-03-01 07:05,26,1\n2027-03-01 07:08,20,1\n";
  const Schedule s = one_wall(dir,
                              "  start: 2027-03-01 07:00\n  time_zone: Europe/Berlin\n"
                              "  weather: " +
                                  (dir / "w.csv").string() + "\n",
                              quick_bond_with(dir, "placing_temperature_c: [5, 25]\n"));
  ASSERT_TRUE(s.feasible) << s.infeasibility->message;
  ASSERT_EQ(s.layers.size(), 20u);
  EXPECT_NEAR(s.layers[2].end_s, 287.0, kTol_s);
  ASSERT_TRUE(s.layers[3].planned_joint);
  const Event* joint = joint_before(s, s.layers[3]);
  ASSERT_NE(joint, nullptr);
  EXPECT_NEAR(joint->start_s, 480.0, kTol_s);
  EXPECT_TRUE(s.layers[3].purge_before);
  EXPECT_NEAR(s.layers[3].start_s, 480.0 + 1800.0 + 120.0, kTol_s);
}

TEST(SiteSchedule, AClimbWaitsForTheWindToDropUnderTheMachinesLimit) {
  // The tower at a constant 20 °C: where its first climb starts; then a gale over that
  // hour: the climb waits until it has passed, and climbs in the wind after it, exactly at
  // the machine's 15 m/s limit (at the limit is calm enough; the last reading holds, so a
  // climb refused there would never start).
  const fs::path dir = scratch("gale");
  std::ofstream(dir / "site.yaml") << "start: 2027-03-01 07:00\ntime_zone: Europe/Berlin\n"
                                      "printing: unattended\npipes: unattended\n"
                                      "working_hours: {mon-sun: 00:00-24:00}\n";
  schedule::ProjectOptions po;
  po.site_file = dir / "site.yaml";
  ScheduleOptions o;
  o.jobs = 2;
  const auto first_climb = [](const Schedule& s) -> const Event* {
    for (const auto& e : s.events)
      if (e.kind == Event::Kind::kClimb) return &e;
    return nullptr;
  };
  std::ofstream(dir / "calm.csv") << "timestamp,temperature_c,wind_m_s\n2027-03-01 07:00,20,2\n";
  std::ofstream(dir / "site.yaml", std::ios::app) << "weather: calm.csv\n";
  // One project and one plan memo for both: only the weather differs, so the second
  // schedule plans nothing again (the tower takes a while to plan).
  schedule::Project tower = schedule::open_project("config/buildings/tower.yaml", po);
  o.memo = make_plan_memo();
  const Schedule calm = build_schedule(tower, o);
  const Event* c0 = first_climb(calm);
  ASSERT_NE(c0, nullptr);
  const double gale_from_s = std::floor(c0->start_s / 3600.0) * 3600.0;
  const site::SiteCalendar& cal = *tower.calendar;
  const auto local = [&](double t_s) { return cal.timestamp(t_s); };
  std::ofstream(dir / "calm.csv") << "timestamp,temperature_c,wind_m_s\n"
                                  << local(0.0) << ",20,2\n"
                                  << local(gale_from_s) << ",20,22\n"
                                  << local(gale_from_s + 3 * 3600.0) << ",20,15\n";
  tower.conditions =
      std::make_shared<const site::SiteConditions>(site::read_weather_csv(dir / "calm.csv", cal));
  const Schedule windy = build_schedule(tower, o);
  const Event* c1 = first_climb(windy);
  ASSERT_NE(c1, nullptr);
  EXPECT_NEAR(c1->start_s, gale_from_s + 3 * 3600.0, kTol_s);
  ASSERT_TRUE(c1->climb.has_value());
  EXPECT_EQ(c1->climb->wait_reasons.back().kind, WaitKind::kWind);
}

}  // namespace
}  // namespace ccbuild::schedule

namespace ccbuild::schedule {
namespace {

TEST(Quantities, APumpTooSmallForANozzleRefusesItsPlanSayingSo) {
  // One nozzle draws 0.2 m/s x 0.15 m x 0.1 m = 10.8 m³/h; a 5 m³/h pump cannot feed it.
  const fs::path dir = scratch("pump");
  std::ifstream in("config/machines/cc-gantry.yaml");
  std::string profile((std::istreambuf_iterator<char>(in)), {});
  const std::string urdf = "urdf: cc_gantry.urdf";
  profile.replace(profile.find(urdf), urdf.size(),
                  "urdf: " + fs::absolute("config/machines/cc_gantry.urdf").string());
  for (const double pump_m3_h : {5.0, 10.8, 11.0}) {
    std::ofstream(dir / "m.yaml") << profile << "pump_capacity_m3_h: " << pump_m3_h << "\n";
    std::ofstream(dir / "b.yaml")
        << "units: m\nlayer_height: 0.1\nmaterial: "
        << fs::absolute("tests/data/materials/quick-bond-mix.yaml").string()
        << "\nmachine: " << (dir / "m.yaml").string()
        << "\nfloors:\n  - {name: g, height: 0.5, plan: "
        << fs::absolute("tests/data/plans/one_wall.yaml").string() << "}\n";
    const Schedule s = build_schedule(schedule::open_project(dir / "b.yaml"));
    ASSERT_FALSE(s.layers.empty() && pump_m3_h > 10.0);
    if (pump_m3_h < 10.8) {
      ASSERT_FALSE(s.feasible);
      EXPECT_EQ(s.infeasibility->kind, InfeasibilityKind::kNoPlan);
      EXPECT_TRUE(contains(s.infeasibility->message, "more than the pump's 5.00 m³/h"))
          << s.infeasibility->message;
    } else {  // exactly the nozzle's flow is enough
      EXPECT_TRUE(s.feasible) << pump_m3_h;
      EXPECT_NEAR(s.layers[0].peak_flow_m3_s * 3600.0, 10.8, 1e-9);
      EXPECT_NEAR(s.layers[0].concrete_m3, 12.5 * 0.15 * 0.1, 1e-6);
    }
  }
}

TEST(Quantities, ANozzleHandingOverToAnotherAtOneInstantIsNotCountedTwice) {
  // Each nozzle lays 2 m in 10 s at 0.15 m x 0.1 m: 0.2 x 0.15 x 0.1 = 0.003 m³/s. The
  // second nozzle (listed first) stops at 10 s, exactly when the first starts: one nozzle's
  // flow at every instant. Stopping a second later, both draw for that second.
  const auto span = [](double from_s, double to_s, double x_m) {
    planner::Waypoint a, b;
    a.t_s = from_s;
    a.position_m = Eigen::Vector2d(x_m, 0.0);
    a.extruding = true;
    a.wall = 1;
    a.piece = 1;
    b.t_s = to_s;
    b.position_m = Eigen::Vector2d(x_m + 0.2 * (to_s - from_s), 0.0);
    return std::vector<planner::Waypoint>{a, b};
  };
  const floors::Layer layer;
  EXPECT_NEAR(peak_flow_m3_s({span(10.0, 20.0, 0.0), span(0.0, 10.0, 5.0)}, layer, 0.15, 0.1),
              0.003, 1e-12);
  EXPECT_NEAR(peak_flow_m3_s({span(10.0, 20.0, 0.0), span(0.0, 11.0, 5.0)}, layer, 0.15, 0.1),
              0.006, 1e-12);
}

TEST(Quantities, DeliveriesAreDueWhenTheConcreteUsedReachesEachBatch) {
  // Three layers of 3 m³ over 100 s each, batches of 4 m³: 9 m³ need three trucks, due at
  // 0 m³ (the start), at 4 m³ (a third into the second layer) and at 8 m³ (two thirds
  // into the third); the last brings the 1 m³ left.
  std::vector<ScheduledLayer> layers(3);
  for (int k = 0; k < 3; ++k) {
    layers[k].layer = k;
    layers[k].start_s = 200.0 * k;
    layers[k].end_s = 200.0 * k + 100.0;
    layers[k].concrete_m3 = 3.0;
  }
  const auto d = deliveries_of(layers, 4.0);
  ASSERT_EQ(d.size(), 3u);
  EXPECT_DOUBLE_EQ(d[0].due_s, 0.0);
  EXPECT_NEAR(d[1].due_s, 200.0 + 100.0 / 3.0, 1e-9);
  EXPECT_EQ(d[1].layer, 1);
  EXPECT_NEAR(d[2].due_s, 400.0 + 200.0 / 3.0, 1e-9);
  EXPECT_DOUBLE_EQ(d[2].m3, 1.0);
  // A batch boundary exactly at a layer's end: due then, with that layer.
  const auto even = deliveries_of(layers, 3.0);
  ASSERT_EQ(even.size(), 3u);
  EXPECT_DOUBLE_EQ(even[1].due_s, 100.0);
  EXPECT_EQ(even[1].layer, 0);
  EXPECT_DOUBLE_EQ(even[2].m3, 3.0);
}

}  // namespace
}  // namespace ccbuild::schedule

namespace ccbuild::schedule {
namespace {

TEST(Objective, ShortestEndsNoLaterAndUsesMoreNozzlesWhereThatFinishesSooner) {
  schedule::ProjectOptions po;
  po.site_file = "config/sites/weekdays-berlin-2027.yaml";
  const schedule::Project house = schedule::open_project("config/buildings/house.yaml", po);
  ScheduleOptions fewest;
  fewest.jobs = 2;
  ScheduleOptions shortest = fewest;
  shortest.objective = Objective::kShortest;
  const Schedule a = build_schedule(house, fewest);
  const Schedule b = build_schedule(house, shortest);
  ASSERT_TRUE(a.feasible && b.feasible);
  EXPECT_LE(b.totals.makespan_s, a.totals.makespan_s + 1e-6);
  int more = 0;
  for (std::size_t i = 0; i < a.layers.size(); ++i)
    more += b.layers[i].nozzles > a.layers[i].nozzles;
  EXPECT_GT(more, 0);  // the house's layers end sooner on more nozzles
  const auto j = schedule_json(recorded_inputs(house, shortest), b);
  EXPECT_EQ(j["inputs"]["objective"], "shortest");
  EXPECT_FALSE(schedule_json(recorded_inputs(house, fewest), a)["inputs"].contains("objective"));
}

}  // namespace
}  // namespace ccbuild::schedule

namespace ccbuild::schedule {
namespace {

// How a day ends is a kind with one name each and one wording (schedule_model.cpp): the
// days' detail and the day packages' "stop" line are both day_end_text, never cut out of
// each other's words.
TEST(SiteSchedule, ADaysEndIsAKindWithOneNameAndOneWording) {
  for (DayEnd end :
       {DayEnd::kPlannedJoint, DayEnd::kFloorTop, DayEnd::kFinished, DayEnd::kContinues})
    EXPECT_EQ(day_end_named(to_string(end)), end);
  EXPECT_FALSE(day_end_named("lunch").has_value());
  EXPECT_EQ(day_end_names(), "planned-joint, floor-top, finished, continues");
  EXPECT_EQ(day_end_text(DayEnd::kFloorTop, 0, 20, 1, 0, true),
            "stopped at the top of floor 0 (floor 0 layer 20); floor 1 starts on its slab");
  EXPECT_EQ(day_end_text(DayEnd::kFloorTop, 0, 20, 1, 0, false),
            "at the top of floor 0 (floor 0 layer 20); floor 1 starts on its slab");
  EXPECT_EQ(day_end_text(DayEnd::kPlannedJoint, 2, 5, 2, 6, true),
            "stopped at the end of floor 2 layer 5; floor 2 layer 6 starts on a planned joint");
  EXPECT_EQ(day_end_text(DayEnd::kContinues, 2, 5, 2, 6, true),
            "floor 2 layer 5 ends the day; floor 2 layer 6 follows within its interval");
  EXPECT_EQ(day_end_text(DayEnd::kFinished, 3, 9, 3, 9, true),
            "the building's walls are finished with floor 3 layer 9");
}

}  // namespace
}  // namespace ccbuild::schedule
