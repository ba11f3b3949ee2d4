#!/usr/bin/python3
"""Checks `ccbuild export --format ical` against its schedule without ccbuild's code. The
file is read by Debian's python3-icalendar (run with /usr/bin/python3) and, when given, by
ical2html (libical), whose HTML is read back:
- RFC 5545 framing: CRLF line ends, lines folded at 75 octets, a UID and a DTSTAMP in UTC
  on every VEVENT, UIDs unique;
- every crew task (crew > 0, slab stages, pours, climbs) and every floor's walls finished
  appears once, nothing else;
- each starts and ends (a milestone: only starts) at the schedule's own time: in UTC for a
  schedule with a site calendar (the JSON's timestamps), or as floating local times from
  --start;
- the VTIMEZONE gives the offsets of the IANA zone it names (Python's zoneinfo) at every
  event;
- ical2html (libical) finds the same events at the same UTC times.
Usage: check_ical_export.py SCHEDULE.json TASKS.ics [--start T] [--ical2html HTML]
Exit 1 with every problem found."""

import argparse
import datetime
import html
import json
import re
import sys
import zoneinfo

import icalendar

UTC = datetime.timezone.utc


def expected_events(doc):
    """{id: (kind, start_s, end_s or None, start_time, end_time)} from the JSON alone."""
    out = {}
    for k, e in enumerate(doc["events"]):
        if e["crew"] > 0 or e["kind"] in ("slab", "pour", "climb"):
            out["E%d" % (k + 1)] = (e["kind"], e["start_s"], e["end_s"], e.get("start_time"),
                                    e.get("end_time"))
    last = {}
    for l in doc["layers"]:
        last[l["floor"]] = l
    for floor, l in last.items():
        out["M%d" % floor] = ("walls-finished", l["end_s"], None, l.get("end_time"), None)
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("schedule")
    ap.add_argument("ics")
    ap.add_argument("--start")
    ap.add_argument("--ical2html")
    a = ap.parse_args()
    doc = json.load(open(a.schedule))
    raw = open(a.ics, "rb").read()
    problems = []
    lines = raw.split(b"\r\n")
    if lines[-1] != b"" or any(b"\n" in l or b"\r" in l for l in lines):
        problems.append("lines must end in CRLF")
    long_lines = [i + 1 for i, l in enumerate(lines) if len(l) > 75]
    if long_lines:
        problems.append("%d lines longer than 75 octets, the first line %d" % (
            len(long_lines), long_lines[0]))
    cal = icalendar.Calendar.from_ical(raw)
    site = doc["inputs"].get("site")
    zone_name = site["time_zone"] if site else None
    vtz = [c for c in cal.walk("VTIMEZONE")]
    if zone_name and (len(vtz) != 1 or str(vtz[0]["TZID"]) != zone_name):
        problems.append("expected one VTIMEZONE %s, found %r" % (
            zone_name, [str(c.get("TZID")) for c in vtz]))
    if not zone_name and vtz:
        problems.append("a schedule without a site calendar has floating times, not a VTIMEZONE")
    want = expected_events(doc)
    seen = {}
    base = datetime.datetime.fromisoformat(a.start.replace(" ", "T")) if a.start else None
    for ev in cal.walk("VEVENT"):
        uid = str(ev.get("UID", ""))
        tid = uid.split("-")[0]
        if tid in seen:
            problems.append("UID %s twice" % uid)
        seen[tid] = ev
        stamp = ev.get("DTSTAMP")
        if stamp is None or stamp.dt.tzinfo is None or stamp.dt.utcoffset() != datetime.timedelta(0):
            problems.append("%s: DTSTAMP must be in UTC" % uid)
        if tid not in want:
            problems.append("%s: not a crew task or milestone of the schedule" % uid)
            continue
        kind, start_s, end_s, start_time, end_time = want[tid]
        if str(ev.get("CATEGORIES").to_ical().decode()) != kind:
            problems.append("%s: category %r, expected %r" % (uid, ev.get("CATEGORIES"), kind))
        for prop, t_s, stamp_text in (("DTSTART", start_s, start_time), ("DTEND", end_s, end_time)):
            value = ev.get(prop)
            if t_s is None or (prop == "DTEND" and round(end_s) == round(start_s)):
                if value is not None:
                    problems.append("%s: a milestone or an instant has no %s" % (uid, prop))
                continue
            if value is None:
                problems.append("%s: no %s" % (uid, prop))
                continue
            dt = value.dt
            if zone_name:
                expected = datetime.datetime.fromisoformat(stamp_text).astimezone(UTC)
                if dt.tzinfo is None or dt.astimezone(UTC) != expected:
                    problems.append("%s %s: %s, the schedule says %s" % (uid, prop, dt, expected))
                    continue
                # The file's own VTIMEZONE gives the zone's offset there.
                own = vtz[0].to_tz()
                local = dt.replace(tzinfo=None)
                off = own.utcoffset(local) if hasattr(own, "localize") is False else \
                    own.localize(local).utcoffset()
                real = local.replace(tzinfo=zoneinfo.ZoneInfo(zone_name)).utcoffset()
                if off != real:
                    problems.append("%s %s: the VTIMEZONE's offset %s, %s's %s" % (
                        uid, prop, off, zone_name, real))
            else:
                expected = base + datetime.timedelta(seconds=round(t_s))
                if dt.tzinfo is not None or dt != expected:
                    problems.append("%s %s: %s, expected the floating %s" % (uid, prop, dt, expected))
    for tid in want:
        if tid not in seen:
            problems.append("%s (%s) missing" % (tid, want[tid][0]))
    # The second reader: ical2html's HTML, one vevent with its UTC start per task.
    if a.ical2html:
        text = open(a.ical2html, encoding="utf-8", errors="replace").read()
        found = re.findall(r'class="dtstart"\s+title="(\d{8}T\d{6}Z?)".*?ccbuild task ([A-Z][0-9.]+)',
                           text, re.S)
        if len(found) != len(want):
            problems.append("ical2html shows %d events, expected %d" % (len(found), len(want)))
        for when, tid in found:
            if tid not in want:
                problems.append("ical2html: %s is not expected" % tid)
                continue
            kind, start_s, _, start_time, _ = want[tid]
            if zone_name:
                expected = datetime.datetime.fromisoformat(start_time).astimezone(UTC).strftime(
                    "%Y%m%dT%H%M%SZ")
            else:
                expected = (base + datetime.timedelta(seconds=round(start_s))).strftime(
                    "%Y%m%dT%H%M%S")
            if when.rstrip("Z") != expected.rstrip("Z"):
                problems.append("ical2html: %s starts %s, expected %s" % (tid, when, expected))
    print("\n".join(problems) or "%s: OK: %d events (%d milestones) at the schedule's times%s%s" % (
        a.ics, len(seen), sum(1 for t in want if t.startswith("M")),
        " in %s" % zone_name if zone_name else " (floating, from --start)",
        "; ical2html agrees" if a.ical2html else ""))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
