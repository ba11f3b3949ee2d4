// The iCalendar export (RFC 5545): the crew's tasks and the milestones, for a site's
// shared calendar.

#include <algorithm>
#include <cstdlib>

#include "ccbuild/common/format.hpp"
#include "ccbuild/report/exports.hpp"
#include "ccbuild/report/site_tasks.hpp"
#include "ccbuild/site/site.hpp"

namespace ccbuild::report {

namespace {

/// TEXT escaped (RFC 5545, 3.3.11): backslash, semicolon, comma and line breaks.
std::string ical_text(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '\\' || c == ';' || c == ',') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    if (c != '\r') out += c;
  }
  return out;
}

/// Appends a content line folded at 75 octets (3.1), never inside a UTF-8 sequence.
void add_line(std::string& out, const std::string& line) {
  std::size_t at = 0, limit = 75;
  while (line.size() - at > limit) {
    std::size_t cut = at + limit;
    while (cut > at + 1 && (static_cast<unsigned char>(line[cut]) & 0xC0) == 0x80) --cut;
    out.append(line, at, cut - at);
    out += "\r\n ";  // a continuation line starts with one space, which it also counts
    at = cut;
    limit = 74;
  }
  out.append(line, at, std::string::npos);
  out += "\r\n";
}

/// "2027-03-01 07:00:00" as "20270301T070000".
std::string compact(const std::string& local) {
  std::string out;
  for (char c : local) {
    if (c == ' ')
      out += 'T';
    else if (c != '-' && c != ':')
      out += c;
  }
  return out;
}

/// "+0100" of an offset in seconds.
std::string offset_text(int offset_s) {
  const int minutes = std::abs(offset_s) / 60;
  return printf_string("%c%02d%02d", offset_s < 0 ? '-' : '+', minutes / 60, minutes % 60);
}

bool on_the_calendar(const SiteTask& t) {
  return t.crew > 0 || t.kind == TaskKind::kSlab || t.kind == TaskKind::kPour ||
         t.kind == TaskKind::kClimb;
}

}  // namespace

std::string tasks_ical(const schedule::ScheduleDocument& schedule, const ExportDates& dates,
                       std::size_t* events) {
  dates.require(schedule, "an iCalendar file");
  std::vector<SiteTask> chosen;
  for (SiteTask& t : tasks_of(schedule))
    if (on_the_calendar(t)) chosen.push_back(std::move(t));
  for (SiteTask& m : milestones_of(schedule)) chosen.push_back(std::move(m));
  std::stable_sort(chosen.begin(), chosen.end(),
                   [](const SiteTask& a, const SiteTask& b) { return a.start_s < b.start_s; });
  if (events) *events = chosen.size();

  const auto& calendar = schedule.inputs.calendar;
  const std::string zone = calendar ? calendar->programme().time_zone : "";
  // A stable UID across exports of the same schedule, distinct between buildings.
  const std::string uid_tail =
      (schedule.inputs.files.empty() ? std::string("schedule")
                                     : schedule.inputs.files.front().sha256.substr(0, 12)) +
      "@ccbuild";
  // DTSTAMP must be UTC; the schedule's own start keeps the file the same on every export.
  const std::string stamp = calendar ? compact(civil_text(calendar->utc_of(0.0))) + "Z"
                                     : compact(civil_text(*dates.start_local_s)) + "Z";
  const auto when = [&](const char* name, double t_s) {
    const std::string local = compact(dates.local(schedule, t_s));
    return zone.empty() ? std::string(name) + ":" + local
                        : std::string(name) + ";TZID=" + zone + ":" + local;
  };

  std::string out;
  add_line(out, "BEGIN:VCALENDAR");
  add_line(out, "VERSION:2.0");
  add_line(out, "PRODID:-//ccbuild//ccbuild " + schedule.inputs.ccbuild_version + "//EN");
  add_line(out, "CALSCALE:GREGORIAN");
  add_line(out, "X-WR-CALNAME:" + ical_text(schedule.inputs.name));
  if (calendar) {
    add_line(out, "X-WR-TIMEZONE:" + zone);
    double last_s = 0.0;
    for (const SiteTask& t : chosen) last_s = std::max(last_s, t.end_s);
    add_line(out, "BEGIN:VTIMEZONE");
    add_line(out, "TZID:" + zone);
    for (const site::ZoneOffset& z : calendar->zone_offsets(0.0, last_s)) {
      const char* part = z.daylight ? "DAYLIGHT" : "STANDARD";
      add_line(out, std::string("BEGIN:") + part);
      // The onset in the local time of the offset before it (RFC 5545, 3.6.5).
      add_line(out, "DTSTART:" + compact(civil_text(z.from_utc_s + z.previous_offset_s)));
      add_line(out, "TZOFFSETFROM:" + offset_text(z.previous_offset_s));
      add_line(out, "TZOFFSETTO:" + offset_text(z.offset_s));
      add_line(out, "TZNAME:" + ical_text(z.abbreviation));
      add_line(out, std::string("END:") + part);
    }
    add_line(out, "END:VTIMEZONE");
  }
  for (const SiteTask& t : chosen) {
    add_line(out, "BEGIN:VEVENT");
    add_line(out, "UID:" + t.id + "-" + uid_tail);
    add_line(out, "DTSTAMP:" + stamp);
    add_line(out, when("DTSTART", t.start_s));
    // A milestone, or a task shorter than the second the times are rounded to, has no
    // DTEND: it ends where it starts (RFC 5545, 3.6.1).
    if (std::llround(t.end_s) > std::llround(t.start_s)) add_line(out, when("DTEND", t.end_s));
    add_line(out, "SUMMARY:" + ical_text(title_of(t, shown_unit(schedule))));
    std::string description = t.detail + "\nby: " + t.who + "\nccbuild task " + t.id;
    if (t.layer >= 0) description += printf_string(" (floor %d, layer %d)", t.floor, t.layer);
    add_line(out, "DESCRIPTION:" + ical_text(description));
    add_line(out, "CATEGORIES:" + ical_text(to_string(t.kind)));
    add_line(out, "END:VEVENT");
  }
  add_line(out, "END:VCALENDAR");
  return out;
}

}  // namespace ccbuild::report
