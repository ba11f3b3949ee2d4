#!/usr/bin/env python3
"""Checks `ccbuild export --format days` (the work packages by day) against its schedule,
without ccbuild's code: one block per local day with work, in date order, each with its
weekday; per day, the layers started (count and concrete, per floor), the trucks due
(count and m³), every event started that day on a crew or machine line (a line "N × kind"
counts N), and every wait started that day (a layer's with the kinds of its reasons, each
once, in the schedule's order); the local day of a task is the schedule's own
timestamp on a site calendar, else --start plus the schedule seconds.
Usage: check_days_export.py SCHEDULE.json DAYS.txt [--start T]
Exit 1 with every problem found."""

import argparse
import collections
import datetime
import json
import re
import sys
import zoneinfo


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("schedule")
    ap.add_argument("days")
    ap.add_argument("--start")
    a = ap.parse_args()
    doc = json.load(open(a.schedule))
    base = datetime.datetime.fromisoformat(a.start.replace(" ", "T")) if a.start else None

    # Concrete in the building's unit: cubic yards for a building in feet.
    volume_unit = "yd³" if doc["inputs"].get("units") == "ft" else "m³"
    M3_PER = {"m³": 1.0, "yd³": 0.764554857984}

    site = doc["inputs"].get("site")
    if site:
        zone = zoneinfo.ZoneInfo(site["time_zone"])
        origin = datetime.datetime.fromisoformat(site["start"])

    def day_of(t_s):
        """The local date of schedule second t_s (rounded, as the times are written)."""
        if site:
            return (origin + datetime.timedelta(seconds=round(t_s))).astimezone(zone).strftime("%Y-%m-%d")
        return (base + datetime.timedelta(seconds=round(t_s))).strftime("%Y-%m-%d")

    want = collections.defaultdict(collections.Counter)
    reasons = {}  # (floor, layer) -> the kinds of its wait's reasons, as listed
    purge_s = doc["inputs"]["machine"]["purge_s"]
    treatment_s = doc["inputs"]["material"].get("planned_joint", {}).get("treatment_s", 0.0)
    for l in doc["layers"]:
        d = day_of(l["start_s"])
        want[d]["layers"] += 1
        want[d]["m3"] += l["concrete_m3"]
        if l["wait_before_s"] > 0:
            # The wait ends where the layer's joint treatment and purge begin.
            end = l["start_s"] - (purge_s if l["purge_before"] else 0) - \
                (treatment_s if l["planned_joint"] else 0)
            want[day_of(end - l["wait_before_s"])]["waits"] += 1
            # Its reasons, each kind once, in the schedule's order.
            reasons[(l["floor"], l["layer"])] = ", ".join(
                dict.fromkeys(r["kind"] for r in l["wait_reasons"]))
    for dl in doc.get("deliveries", []):
        want[day_of(dl["due_s"])]["trucks"] += 1
        want[day_of(dl["due_s"])]["truck_m3"] += dl["m3"]
    for e in doc["events"]:
        want[day_of(e["start_s"])]["events"] += 1
        if e.get("wait_before_s", 0) > 0:
            want[day_of(e["start_s"] - e["wait_before_s"])]["waits"] += 1
    text = open(a.days, encoding="utf-8").read()
    blocks = re.split(r"\n(?=(?:Mon|Tue|Wed|Thu|Fri|Sat|Sun) \d{4}-\d{2}-\d{2}\n)", text)
    got = {}
    problems = []
    for b in blocks[1:]:
        head, *lines = b.strip("\n").split("\n")
        weekday, day = head.split()
        if datetime.date.fromisoformat(day).strftime("%a") != weekday:
            problems.append("%s is a %s, not a %s" % (day, datetime.date.fromisoformat(day).strftime("%a"), weekday))
        c = collections.Counter()
        label = None
        for line in lines:
            if line[2:9].strip():
                label = line[2:9].strip()
            body = line[9:]
            if label == "print":
                m = re.search(r"\((\d+) layers?\), [0-9.]+ h printing, ([0-9.]+) (m³|yd³)", body)
                c["layers"] += int(m.group(1))
                c["m3"] += float(m.group(2)) * M3_PER[m.group(3)]
                if m.group(3) != volume_unit:
                    problems.append("%s: concrete in %s, the building's unit is %s" % (day, m.group(3), volume_unit))
            elif label == "deliver":
                m = re.search(r"(\d+) trucks?, ([0-9.]+) (m³|yd³)", body)
                c["trucks"] += int(m.group(1))
                c["truck_m3"] += float(m.group(2)) * M3_PER[m.group(3)]
            elif label == "wait":
                c["waits"] += 1
                m = re.search(r"Wait before floor (\d+) layer (\d+) \(([^)]*)\)", body)
                if m and m.group(3) != reasons.get((int(m.group(1)), int(m.group(2)))):
                    problems.append("%s: the wait before floor %s layer %s for '%s', the schedule "
                                    "'%s'" % (day, m.group(1), m.group(2), m.group(3),
                                              reasons.get((int(m.group(1)), int(m.group(2))))))
            elif label in ("crew", "machine"):
                m = re.search(r": (\d+) × ", body)
                c["events"] += int(m.group(1)) if m else 1
        if day in got:
            problems.append("%s twice" % day)
        got[day] = c
    if list(got) != sorted(got):
        problems.append("days not in date order")
    for d in sorted(want):
        g, w = got.get(d, collections.Counter()), want[d]
        if d not in got:
            problems.append("%s: missing" % d)
            continue
        for key, tol in (("layers", 0), ("events", 0), ("trucks", 0), ("waits", 0), ("m3", 0.02),
                         ("truck_m3", 0.02)):
            if abs(g[key] - w[key]) > tol + 1e-9:
                problems.append("%s: %s %s, the schedule %s" % (d, key, g[key], w[key]))
    for d in got:
        if d not in want:
            problems.append("%s: a day without work in the schedule" % d)
    print("\n".join(problems) or "%s: OK: %d days; layers, concrete, trucks and events per day "
          "agree with the schedule" % (a.days, len(got)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
