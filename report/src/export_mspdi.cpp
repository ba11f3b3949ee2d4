// The MS Project XML export (MSPDI), the format MS Project, ProjectLibre, GanttProject and
// Primavera import: a summary task per floor, every task with its dates and duration,
// finish-to-start links where the schedule has its order, and the site's calendars.

#include <algorithm>
#include <cmath>
#include <map>

#include "ccbuild/common/format.hpp"
#include "ccbuild/report/exports.hpp"
#include "ccbuild/report/site_tasks.hpp"
#include "ccbuild/site/site.hpp"
#include "svg.hpp"

namespace ccbuild::report {

namespace {

constexpr int kSiteCalendarUid = 1;
constexpr int kAroundTheClockUid = 2;

/// "PT52H3M4S": whole seconds, the form every MSPDI reader takes.
std::string duration_text(long long s) {
  return printf_string("PT%lldH%lldM%lldS", s / 3600, s / 60 % 60, s % 60);
}

/// "2027-03-01T07:00:00" of a local "2027-03-01 07:00:00".
std::string msp_date(std::string local) {
  local[10] = 'T';
  return local;
}

std::string time_of_day(int minutes) {
  return printf_string("%02d:%02d:00", minutes / 60 % 24, minutes % 60);
}

struct Row {
  SiteTask task;
  int uid = 0;
  int level = 2;
  std::string outline;
  bool summary = false;
  std::vector<int> predecessors;  ///< UIDs, finish-to-start
};

/// The task's finish-to-start predecessors on the site's one line of work: each task but
/// a delivery, a milestone and a climb's phase follows the one that ended last at or before
/// its start (the machine and its crew do one task at a time). A climb also follows the
/// pipes it pins into (the last pipe cast before it with each of its anchors' id and unit).
void link(std::vector<Row>& rows, const schedule::ScheduleDocument& schedule) {
  const auto round_s = [](double t) { return std::llround(t); };
  std::vector<Row*> line;
  for (Row& r : rows)
    if (r.task.kind != TaskKind::kFloor && r.task.kind != TaskKind::kDelivery &&
        r.task.kind != TaskKind::kClimbPhase && r.task.kind != TaskKind::kWallsFinished)
      line.push_back(&r);
  std::stable_sort(line.begin(), line.end(),
                   [](const Row* a, const Row* b) { return a->task.start_s < b->task.start_s; });
  for (std::size_t i = 1; i < line.size(); ++i) {
    const Row* before = nullptr;
    for (std::size_t j = i; j-- > 0;) {
      const Row* c = line[j];
      if (round_s(c->task.end_s) > round_s(line[i]->task.start_s)) continue;
      if (!before || c->task.end_s > before->task.end_s) before = c;
    }
    if (before) line[i]->predecessors.push_back(before->uid);
  }
  // The floors' milestones follow their last layer; the climbs follow their anchors' pipes.
  std::map<std::string, int> uid_of;
  for (const Row& r : rows) uid_of[r.task.id] = r.uid;
  for (Row& r : rows)
    if (r.task.kind == TaskKind::kWallsFinished)
      r.predecessors.push_back(uid_of.at(printf_string("L%d.%d", r.task.floor, r.task.layer)));
  const auto& events = schedule.schedule.events;
  const auto& units = schedule.inputs.unit_names;
  for (Row& r : rows) {
    if (r.task.kind != TaskKind::kClimb) continue;
    const std::size_t k = std::stoul(r.task.id.substr(1)) - 1;
    for (const auto& load : events[k].climb->anchors) {
      for (std::size_t p = k; p-- > 0;) {
        const schedule::Event& e = events[p];
        if (e.kind != schedule::Event::Kind::kPipe || !e.anchor || e.anchor->id != load.id)
          continue;
        const int unit = e.anchor->unit;
        if (unit < 0 || unit >= static_cast<int>(units.size()) || units[unit] != load.unit)
          continue;
        const int pipe = uid_of.at(printf_string("E%zu", p + 1));
        if (std::find(r.predecessors.begin(), r.predecessors.end(), pipe) == r.predecessors.end())
          r.predecessors.push_back(pipe);
        break;
      }
    }
  }
}

}  // namespace

std::string tasks_mspdi(const schedule::ScheduleDocument& schedule, const ExportDates& dates,
                        std::size_t* tasks, std::size_t* links) {
  dates.require(schedule, "an MS Project file");
  const auto& calendar = schedule.inputs.calendar;

  // Floors in order, each a summary over its tasks by start; a climb's phases under it.
  std::map<int, std::vector<SiteTask>> by_floor;
  for (SiteTask& t : tasks_of(schedule)) by_floor[t.floor].push_back(std::move(t));
  for (SiteTask& m : milestones_of(schedule)) by_floor[m.floor].push_back(std::move(m));
  std::vector<Row> rows;
  int floor_number = 0;
  for (auto& [floor, list] : by_floor) {
    std::stable_sort(list.begin(), list.end(),
                     [](const SiteTask& a, const SiteTask& b) { return a.start_s < b.start_s; });
    Row summary;
    summary.summary = true;
    summary.level = 1;
    summary.outline = std::to_string(++floor_number);
    summary.task.id = printf_string("F%d", floor);
    summary.task.kind = TaskKind::kFloor;
    summary.task.floor = floor;
    summary.task.start_s = list.front().start_s;
    summary.task.end_s = list.front().end_s;
    for (const SiteTask& t : list) summary.task.end_s = std::max(summary.task.end_s, t.end_s);
    summary.task.detail = printf_string("everything done for floor %d", floor);
    rows.push_back(std::move(summary));
    int child = 0, phase = 0;
    for (SiteTask& t : list) {
      Row r;
      if (t.kind == TaskKind::kClimbPhase) {
        // Under the climb: the row before its first phase (phases follow their climb).
        r.level = 3;
        std::size_t c = rows.size();
        while (rows[c - 1].level == 3) --c;
        r.outline = rows[c - 1].outline + "." + std::to_string(++phase);
        rows[c - 1].summary = true;
      } else {
        r.outline = std::to_string(floor_number) + "." + std::to_string(++child);
        phase = 0;
      }
      r.task = std::move(t);
      rows.push_back(std::move(r));
    }
  }
  for (std::size_t i = 0; i < rows.size(); ++i) rows[i].uid = static_cast<int>(i + 1);
  link(rows, schedule);

  const auto date_at = [&](double t_s) { return msp_date(dates.local(schedule, t_s)); };
  std::string out =
      "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"yes\"?>\n"
      "<Project xmlns=\"http://schemas.microsoft.com/project\">\n"
      "  <SaveVersion>14</SaveVersion>\n";
  out += "  <Title>" + svg::escape(schedule.inputs.name) + "</Title>\n";
  out += "  <ScheduleFromStart>1</ScheduleFromStart>\n";
  out += "  <StartDate>" + date_at(0.0) + "</StartDate>\n";
  double last_s = 0.0;
  for (const Row& r : rows) last_s = std::max(last_s, r.task.end_s);
  out += "  <FinishDate>" + date_at(last_s) + "</FinishDate>\n";
  out += printf_string("  <CalendarUID>%d</CalendarUID>\n",
                       calendar ? kSiteCalendarUid : kAroundTheClockUid);
  out += "  <Calendars>\n";
  if (calendar) {
    const site::SiteProgramme& p = calendar->programme();
    out += printf_string(
        "    <Calendar>\n      <UID>%d</UID>\n      <Name>Site: %s</Name>\n"
        "      <IsBaseCalendar>1</IsBaseCalendar>\n      <WeekDays>\n",
        kSiteCalendarUid, svg::escape(calendar->week_text()).c_str());
    for (int day_type = 1; day_type <= 7; ++day_type) {
      // MSPDI counts from Sunday (1); the programme from Monday.
      const auto& spans = p.week[(day_type + 5) % 7];
      out += printf_string(
          "        <WeekDay>\n          <DayType>%d</DayType>\n"
          "          <DayWorking>%d</DayWorking>\n",
          day_type, spans.empty() ? 0 : 1);
      if (!spans.empty()) {
        out += "          <WorkingTimes>\n";
        for (const site::WorkingHours& h : spans)
          out += "            <WorkingTime><FromTime>" + time_of_day(h.from_min) +
                 "</FromTime><ToTime>" + time_of_day(h.to_min) + "</ToTime></WorkingTime>\n";
        out += "          </WorkingTimes>\n";
      }
      out += "        </WeekDay>\n";
    }
    for (const std::int32_t day : p.holidays) {
      const std::string date = site::local_date_text(day);
      out +=
          "        <WeekDay>\n          <DayType>0</DayType>\n"
          "          <DayWorking>0</DayWorking>\n          <TimePeriod><FromDate>" +
          date + "T00:00:00</FromDate><ToDate>" + date +
          "T23:59:00</ToDate></TimePeriod>\n        </WeekDay>\n";
    }
    out += "      </WeekDays>\n    </Calendar>\n";
  }
  out += printf_string(
      "    <Calendar>\n      <UID>%d</UID>\n      <Name>24 Hours</Name>\n"
      "      <IsBaseCalendar>1</IsBaseCalendar>\n      <WeekDays>\n",
      kAroundTheClockUid);
  for (int day_type = 1; day_type <= 7; ++day_type)
    out += printf_string(
        "        <WeekDay>\n          <DayType>%d</DayType>\n          <DayWorking>1</DayWorking>\n"
        "          <WorkingTimes>\n            <WorkingTime><FromTime>00:00:00</FromTime>"
        "<ToTime>00:00:00</ToTime></WorkingTime>\n          </WorkingTimes>\n"
        "        </WeekDay>\n",
        day_type);
  out += "      </WeekDays>\n    </Calendar>\n  </Calendars>\n  <Tasks>\n";

  std::size_t link_count = 0;
  for (const Row& r : rows) {
    const SiteTask& t = r.task;
    const long long start = std::llround(t.start_s), end = std::llround(t.end_s);
    const bool milestone = !r.summary && end == start;
    // A task within one working window keeps the site's calendar; one through a night, a
    // weekend or a holiday (a wait, an unattended print) runs on the clock.
    const bool on_site_hours = calendar && calendar->within_one_window(t.start_s, t.end_s);
    out += "    <Task>\n";
    out += printf_string("      <UID>%d</UID>\n      <ID>%d</ID>\n", r.uid, r.uid);
    out +=
        "      <Name>" +
        svg::escape(r.summary && t.kind == TaskKind::kFloor ? printf_string("Floor %d", t.floor)
                                                            : title_of(t, shown_unit(schedule))) +
        "</Name>\n";
    out += "      <Type>1</Type>\n      <IsNull>0</IsNull>\n";
    out += "      <WBS>" + r.outline + "</WBS>\n      <OutlineNumber>" + r.outline +
           "</OutlineNumber>\n";
    out += printf_string("      <OutlineLevel>%d</OutlineLevel>\n", r.level);
    out += "      <Start>" + date_at(t.start_s) + "</Start>\n      <Finish>" + date_at(t.end_s) +
           "</Finish>\n";
    out += "      <Duration>" + duration_text(end - start) + "</Duration>\n";
    out += "      <Work>" + duration_text((end - start) * std::max(t.crew, 0)) + "</Work>\n";
    out += printf_string("      <Milestone>%d</Milestone>\n      <Summary>%d</Summary>\n",
                         milestone ? 1 : 0, r.summary ? 1 : 0);
    if (!r.summary)
      // Start no earlier than planned: the links alone would pull a task forward over the
      // waits the schedule keeps for strength and the calendar.
      out += "      <ConstraintType>4</ConstraintType>\n      <ConstraintDate>" +
             date_at(t.start_s) + "</ConstraintDate>\n";
    out += printf_string("      <CalendarUID>%d</CalendarUID>\n",
                         on_site_hours ? kSiteCalendarUid : kAroundTheClockUid);
    out += "      <Notes>" +
           svg::escape("ccbuild task " + t.id + " (" + to_string(t.kind) + "), by " +
                       (t.who.empty() ? std::string("-") : t.who) + ": " + t.detail) +
           "</Notes>\n";
    for (const int p : r.predecessors) {
      out += printf_string(
          "      <PredecessorLink><PredecessorUID>%d</PredecessorUID><Type>1</Type>"
          "<CrossProject>0</CrossProject><LinkLag>0</LinkLag><LagFormat>7</LagFormat>"
          "</PredecessorLink>\n",
          p);
      ++link_count;
    }
    out += "    </Task>\n";
  }
  out += "  </Tasks>\n</Project>\n";
  if (tasks) *tasks = rows.size();
  if (links) *links = link_count;
  return out;
}

}  // namespace ccbuild::report
