// The exports at their boundaries, on schedules made by hand: iCalendar lines folded at
// exactly 75 octets and never inside a UTF-8 character, a task that rounds to an instant
// (no DTEND) and one that rounds across a second; MS Project XML links where a task ends
// exactly when the next starts and where one overlaps it; the formats that need dates.

#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <regex>
#include <set>

#include "ccbuild/common/document.hpp"
#include "ccbuild/common/input_error.hpp"
#include "ccbuild/report/exports.hpp"
#include "ccbuild/report/site_tasks.hpp"
#include "ccbuild/site/site.hpp"
#include "test_support.hpp"

namespace ccbuild::report {
namespace {

using schedule::Event;

schedule::ScheduledLayer layer(int floor, int index, double start_s, double end_s) {
  schedule::ScheduledLayer l;
  l.floor = floor;
  l.layer = index;
  l.start_s = start_s;
  l.end_s = end_s;
  l.plan = "p";
  l.concrete_m3 = 1.0;
  return l;
}

Event event(Event::Kind kind, double start_s, double end_s, int crew, const std::string& detail) {
  Event e;
  e.kind = kind;
  e.start_s = start_s;
  e.end_s = end_s;
  e.crew = crew;
  e.detail = detail;
  return e;
}

ExportDates from_start() {
  ExportDates d;
  d.start_local_s = parse_local_start("2027-03-01 07:00", "--start");
  return d;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t at = 0;
  for (std::size_t end; (end = text.find("\r\n", at)) != std::string::npos; at = end + 2)
    lines.push_back(text.substr(at, end - at));
  return lines;
}

TEST(ICalendar, LinesFoldAtSeventyFiveOctetsNeverInsideACharacter) {
  // "X-WR-CALNAME:" is 13 octets: a 62-octet name makes a line of exactly 75 (kept whole),
  // 63 octets one of 76 (folded); names of "³" (2 octets) put the fold inside one.
  for (const std::string& name :
       {std::string(62, 'a'), std::string(63, 'a'), std::string(61, 'a') + "³", [] {
          std::string s;
          for (int k = 0; k < 100; ++k) s += "³";
          return s;
        }()}) {
    schedule::ScheduleDocument doc;
    doc.inputs.name = name;
    const std::string text = tasks_ical(doc, from_start());
    std::string unfolded;
    std::size_t folds = 0;
    for (const std::string& line : lines_of(text)) {
      EXPECT_LE(line.size(), 75u) << line;
      if (!line.empty() && line[0] == ' ') {
        ++folds;
        ASSERT_GT(line.size(), 1u);
        EXPECT_NE(static_cast<unsigned char>(line[1]) & 0xC0, 0x80) << "a fold inside a character";
        unfolded += line.substr(1);
      } else {
        unfolded += "\n" + line;
      }
    }
    EXPECT_TRUE(testing::contains(unfolded, "\nX-WR-CALNAME:" + name + "\n")) << name;
    if (name.size() + 13 <= 75) {
      EXPECT_EQ(folds, 0u) << name;
    } else {
      EXPECT_GE(folds, 1u) << name;
    }
    if (name.size() + 13 == 76) {
      EXPECT_EQ(folds, 1u);
    }
  }
}

TEST(ICalendar, ATaskThatRoundsToAnInstantHasNoEndAndOneAcrossASecondHasOne) {
  schedule::ScheduleDocument doc;
  doc.inputs.name = "t";
  doc.schedule.layers = {layer(0, 0, 0.0, 100.0)};
  // 100.4 and 100.6 round to 100 and 101; 200.2 and 200.4 both to 200.
  doc.schedule.events = {event(Event::Kind::kLintel, 100.4, 100.6, 2, "lintel a"),
                         event(Event::Kind::kLintel, 200.2, 200.4, 2, "lintel b"),
                         event(Event::Kind::kPurge, 300.0, 420.0, 0, "purge")};
  std::size_t events = 0;
  const std::string text = tasks_ical(doc, from_start(), &events);
  EXPECT_EQ(events, 3u);  // two lintels and the floor's walls finished; the purge has no crew
  const auto block = [&](const std::string& uid) {
    const std::size_t at = text.find("UID:" + uid + "-");
    return text.substr(at, text.find("END:VEVENT", at) - at);
  };
  EXPECT_TRUE(testing::contains(block("E1"), "DTSTART:20270301T070140\r\n"));
  EXPECT_TRUE(testing::contains(block("E1"), "DTEND:20270301T070141\r\n"));
  EXPECT_TRUE(testing::contains(block("E2"), "DTSTART:20270301T070320\r\n"));
  EXPECT_FALSE(testing::contains(block("E2"), "DTEND"));
  EXPECT_FALSE(testing::contains(block("M0"), "DTEND"));
  EXPECT_TRUE(testing::contains(block("M0"), "DTSTART:20270301T070140\r\n"));
  EXPECT_FALSE(testing::contains(text, "UID:E3-"));
  EXPECT_FALSE(testing::contains(text, "VTIMEZONE"));  // floating times
}

// A task's title is made from its fields, never cut out of its words: each event below
// says something else in its detail, and the titles still name the pipe, the lintel, the
// climb and its phases, the pour of the roof and the waits by what they are.
TEST(SiteTasks, TitlesAreMadeFromTheTasksFieldsNotFromTheirWords) {
  schedule::ScheduleDocument doc;
  doc.inputs.unit_names = {"U1", "U2"};
  doc.schedule.layers = {layer(0, 0, 0.0, 100.0), layer(0, 1, 400.0, 500.0)};
  doc.schedule.layers[1].wait_before_s = 50.0;
  Event pipe = event(Event::Kind::kPipe, 100.0, 110.0, 0, "words (that say: other, things)");
  pipe.anchor.emplace();
  pipe.anchor->id = "A7";
  pipe.anchor->unit = 1;
  Event lintel = event(Event::Kind::kLintel, 120.0, 130.0, 2, "x: y, z");
  lintel.lintel.emplace();
  lintel.lintel->opening = "W3";
  lintel.lintel->type = floors::LintelSpec::Type::kPrecast;
  lintel.wait_before_s = 10.0;
  Event up = event(Event::Kind::kClimb, 140.0, 200.0, 0, "not a climb: at all");
  up.climb.emplace();
  up.climb->from_stage = 1;
  up.climb->to_stage = 2;
  up.climb->plan.phases.resize(1);
  up.climb->plan.phases[0].kind = climb::ClimbPhase::Kind::kTransit;
  up.climb->plan.phases[0].unit = 0;
  up.climb->plan.phases[0].duration_s = 60.0;
  Event pour = event(Event::Kind::kPour, 210.0, 300.0, 4, "nothing (here)");
  pour.roof = true;
  doc.schedule.events = {pipe, lintel, up, pour};
  std::map<std::string, std::string> title;
  for (const SiteTask& t : tasks_of(doc)) title[t.id] = title_of(t);
  EXPECT_EQ(title["E1"], "Floor 0: Pipe A7 for unit U2");
  EXPECT_EQ(title["E2"], "Floor 0: Precast lintel over opening W3");
  EXPECT_EQ(title["WE2"], "Wait before precast lintel over opening W3");
  EXPECT_EQ(title["E3"], "Floor 0: Climb from stage 1 to 2");
  EXPECT_EQ(title["E3.1"], "Transit U1");
  EXPECT_EQ(title["E4"], "Floor 0: Pour of the roof over floor 0");
  EXPECT_EQ(title["L0.1"], "Floor 0 layer 1");
  EXPECT_EQ(title["W0.1"], "Wait before floor 0 layer 1");
}

/// The MSPDI file's links: ccbuild id -> ids of its predecessors.
std::map<std::string, std::set<std::string>> links_of(const std::string& xml) {
  std::map<std::string, std::string> id_of_uid;
  std::map<std::string, std::set<std::string>> uid_links;
  const std::regex task(R"(<Task>\s*<UID>(\d+)</UID>[\s\S]*?ccbuild task (\S+) [\s\S]*?</Task>)");
  const std::regex link(R"(<PredecessorUID>(\d+)</PredecessorUID><Type>1</Type>)");
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), task); it != std::sregex_iterator();
       ++it) {
    id_of_uid[(*it)[1]] = (*it)[2];
    const std::string body = (*it)[0];
    for (auto l = std::sregex_iterator(body.begin(), body.end(), link); l != std::sregex_iterator();
         ++l)
      uid_links[(*it)[1]].insert((*l)[1]);
  }
  std::map<std::string, std::set<std::string>> out;
  for (const auto& [uid, id] : id_of_uid) {
    out[id];
    for (const std::string& p : uid_links[uid]) out[id].insert(id_of_uid.at(p));
  }
  return out;
}

TEST(Mspdi, EachTaskFollowsTheOneThatEndedLastAtOrBeforeItsStart) {
  schedule::ScheduleDocument doc;
  doc.inputs.name = "t";
  // L0.0 [0, 100]; a lintel [100, 160] ends exactly when L0.1 starts; a slab [150, 400]
  // overlaps L0.1 [160, 260] and ends exactly when L0.2 starts [400, 500]; a second slab
  // [399, 600] starts 1 s before the first slab ends, so follows L0.1 instead.
  doc.schedule.layers = {layer(0, 0, 0.0, 100.0), layer(0, 1, 160.0, 260.0),
                         layer(0, 2, 400.0, 500.0)};
  doc.schedule.events = {event(Event::Kind::kLintel, 100.0, 160.0, 2, "lintel"),
                         event(Event::Kind::kSlab, 150.0, 400.0, 4, "slab"),
                         event(Event::Kind::kSlab, 399.0, 600.0, 4, "second slab")};
  std::size_t tasks = 0, links = 0;
  const std::string xml = tasks_mspdi(doc, from_start(), &tasks, &links);
  const auto by = links_of(xml);
  EXPECT_EQ(by.at("L0.0"), std::set<std::string>{});
  EXPECT_EQ(by.at("E1"), std::set<std::string>{"L0.0"});  // ended at 100, its start
  EXPECT_EQ(by.at("E2"), std::set<std::string>{"L0.0"});  // the lintel ends after 150
  EXPECT_EQ(by.at("L0.1"), std::set<std::string>{"E1"});  // at 160; the slab runs on
  EXPECT_EQ(by.at("L0.2"), std::set<std::string>{"E2"});  // at 400, later than L0.1
  EXPECT_EQ(by.at("E3"), std::set<std::string>{"L0.1"});  // E2 ends 1 s after 399
  EXPECT_EQ(by.at("M0"), std::set<std::string>{"L0.2"});  // the walls finished
  EXPECT_EQ(by.at("F0"), std::set<std::string>{});
  EXPECT_EQ(tasks, 1u + 3u + 3u + 1u);  // the floor, 3 layers, 3 events, the milestone
  EXPECT_EQ(links, 6u);
  // Durations in whole seconds, a milestone of none.
  EXPECT_TRUE(testing::contains(xml, "<Duration>PT0H4M10S</Duration>"));  // the slab, 250 s
  EXPECT_TRUE(testing::contains(xml, "<Milestone>1</Milestone>"));
}

/// The `<Task>` element of ccbuild task `id` in an MSPDI file ("" when there is none).
std::string task_of(const std::string& xml, const std::string& id) {
  const std::size_t at = xml.find("ccbuild task " + id + " ");
  if (at == std::string::npos) return "";
  const std::size_t from = xml.rfind("<Task>", at);
  return xml.substr(from, xml.find("</Task>", at) - from);
}

TEST(Mspdi, DurationsInWholeHoursWorkTimesTheCrewAndTheSiteWeekFromSunday) {
  // Mon 2027-03-01 07:00 in Berlin; Monday to Friday 07:00-17:00, Saturday 07:00-12:00.
  const Document site = parse_yaml(
      "start: 2027-03-01 07:00\ntime_zone: Europe/Berlin\n"
      "working_hours: {mon-fri: 07:00-17:00, sat: 07:00-12:00}\n",
      "site.yaml");
  schedule::ScheduleDocument doc;
  doc.inputs.name = "t";
  doc.inputs.calendar =
      std::make_shared<const site::SiteCalendar>(*site::read_site_programme(Field::root(site), {}));
  // L0.0 in Monday's shift; L0.1 from 16:50 to 17:10, across its end (printed unattended);
  // a slab stage of 25 h (by 4) and a pour of 250 s (by 4) after them.
  doc.schedule.layers = {layer(0, 0, 0.0, 3600.0), layer(0, 1, 35400.0, 36600.0)};
  doc.schedule.events = {event(Event::Kind::kSlab, 86400.0, 86400.0 + 90000.0, 4, "slab"),
                         event(Event::Kind::kPour, 176400.0, 176650.0, 4, "pour")};
  const std::string xml = tasks_mspdi(doc, ExportDates{});
  const std::string slab = task_of(xml, "E1"), pour = task_of(xml, "E2");
  ASSERT_FALSE(slab.empty());
  ASSERT_FALSE(pour.empty());
  EXPECT_TRUE(testing::contains(slab, "<Duration>PT25H0M0S</Duration>")) << slab;
  EXPECT_TRUE(testing::contains(slab, "<Work>PT100H0M0S</Work>")) << slab;
  EXPECT_TRUE(testing::contains(pour, "<Duration>PT0H4M10S</Duration>")) << pour;
  EXPECT_TRUE(testing::contains(pour, "<Work>PT0H16M40S</Work>")) << pour;  // 4 x 250 s
  // Within one shift a task keeps the site's calendar (1); across a shift's end it runs on
  // the clock (2).
  const std::string in_shift = task_of(xml, "L0.0"), across = task_of(xml, "L0.1");
  ASSERT_FALSE(in_shift.empty());
  ASSERT_FALSE(across.empty());
  EXPECT_TRUE(testing::contains(in_shift, "<CalendarUID>1</CalendarUID>")) << in_shift;
  EXPECT_TRUE(testing::contains(across, "<CalendarUID>2</CalendarUID>")) << across;
  // The site calendar's week: MSPDI's day 1 is Sunday, 7 Saturday.
  const std::size_t site_from = xml.find("<Name>Site: ");
  ASSERT_NE(site_from, std::string::npos);
  const std::string week = xml.substr(site_from, xml.find("</Calendar>", site_from) - site_from);
  const auto day = [&](int type) {
    const std::size_t at = week.find("<DayType>" + std::to_string(type) + "</DayType>");
    return at == std::string::npos ? std::string()
                                   : week.substr(at, week.find("</WeekDay>", at) - at);
  };
  EXPECT_TRUE(testing::contains(day(1), "<DayWorking>0</DayWorking>")) << day(1);  // Sunday
  EXPECT_TRUE(testing::contains(day(2), "<FromTime>07:00:00</FromTime><ToTime>17:00:00</ToTime>"))
      << day(2);                                                                  // Monday
  EXPECT_TRUE(testing::contains(day(6), "<ToTime>17:00:00</ToTime>")) << day(6);  // Friday
  EXPECT_TRUE(testing::contains(day(7), "<FromTime>07:00:00</FromTime><ToTime>12:00:00</ToTime>"))
      << day(7);  // Saturday
}

TEST(Exports, ACalendarAProjectAndTheDaysNeedDatesACsvDoesNot) {
  schedule::ScheduleDocument doc;
  doc.schedule.layers = {layer(0, 0, 0.0, 100.0)};
  const ExportDates none;
  for (const auto& write : std::vector<std::function<void()>>{
           [&] { tasks_ical(doc, none); }, [&] { tasks_mspdi(doc, none); },
           [&] { work_packages_text(doc, none); }}) {
    const InputError e = testing::expect_input_error(write);
    EXPECT_EQ(e.first().field, "--start");
  }
  EXPECT_TRUE(testing::contains(tasks_csv(doc, none), "\r\nL0.0,layer,0,0,,,"));
}

}  // namespace
}  // namespace ccbuild::report
