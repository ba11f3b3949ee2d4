#!/usr/bin/env python3
"""Checks `ccbuild export --format mspdi` against its schedule without ccbuild's code, on
what GNOME Planner's own stylesheet (msp2planner.xsl, run by xsltproc) made of it, and on
the MSPDI file's calendars (Python's XML parser):
- every task survives: one summary per floor, every layer, wait, event, climb phase,
  delivery and floor milestone once, under its floor (a phase under its climb), with the
  schedule's local start and end and its duration in whole seconds;
- every link survives as finish-to-start, and no link runs backwards in time;
- the schedule's order is in the links: each layer reaches the layer before it through its
  predecessors; every wait, lintel, joint treatment and purge before a layer lies on that
  path; a climb follows the pipes of each of its anchors; a floor's milestone its last layer;
- the site calendar: the working week and the holidays of the schedule's site.
Usage: check_mspdi_export.py SCHEDULE.json PLANNER.xml MSPDI.xml [--start T]
Exit 1 with every problem found."""

import argparse
import datetime
import json
import re
import sys
import xml.etree.ElementTree as ET

NS = {"ms": "http://schemas.microsoft.com/project"}


def local_text(doc_time, t_s, base):
    """'20270301T070000' of a JSON timestamp, or of --start plus the seconds."""
    if doc_time:
        return doc_time[:19].replace("-", "").replace(":", "")
    return (base + datetime.timedelta(seconds=round(t_s))).strftime("%Y%m%dT%H%M%S")


def expected_tasks(doc, base):
    """{id: (kind, floor, start, end, duration_s, parent id)} from the JSON alone."""
    out = {}

    def add(tid, kind, floor, s, e, st, et, parent):
        out[tid] = (kind, floor, local_text(st, s, base), local_text(et, e, base),
                    round(e) - round(s), parent)

    for l in doc["layers"]:
        key = "%d.%d" % (l["floor"], l["layer"])
        add("L" + key, "layer", l["floor"], l["start_s"], l["end_s"], l.get("start_time"),
            l.get("end_time"), "F%d" % l["floor"])
        if l["wait_before_s"] > 0:
            out["W" + key] = ("wait", l["floor"], None, None, None, "F%d" % l["floor"])
    for k, e in enumerate(doc["events"]):
        tid = "E%d" % (k + 1)
        add(tid, e["kind"], e["floor"], e["start_s"], e["end_s"], e.get("start_time"),
            e.get("end_time"), "F%d" % e["floor"])
        waited = e.get("wait_before_s", 0)  # a climb's is its own wait
        if waited > 0:
            out["W" + tid] = ("wait", e["floor"], None, None, None, "F%d" % e["floor"])
        if "climb" in e:
            for p in range(len(e["climb"]["phases"])):
                out["%s.%d" % (tid, p + 1)] = ("climb-phase", e["floor"], None, None, None, tid)
    for k, d in enumerate(doc.get("deliveries", [])):
        add("D%d" % (k + 1), "delivery", d["floor"], d["due_s"], d["due_s"], d.get("due_time"),
            d.get("due_time"), "F%d" % d["floor"])
    last = {}
    for l in doc["layers"]:
        last[l["floor"]] = l
    for floor, l in last.items():
        add("M%d" % floor, "walls-finished", floor, l["end_s"], l["end_s"], l.get("end_time"),
            l.get("end_time"), "F%d" % floor)
        out["F%d" % floor] = ("floor", floor, None, None, None, None)
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("schedule")
    ap.add_argument("planner")
    ap.add_argument("mspdi")
    ap.add_argument("--start")
    a = ap.parse_args()
    doc = json.load(open(a.schedule))
    base = datetime.datetime.fromisoformat(a.start.replace(" ", "T")) if a.start else None
    want = expected_tasks(doc, base)
    problems = []

    # The Planner file: nested <task> elements.
    tasks = {}    # ccbuild id -> attributes (+ parent id, predecessor planner ids)
    by_pid = {}   # planner id -> ccbuild id

    def walk(el, parent):
        for t in el.findall("task"):
            m = re.match(r"ccbuild task (\S+) \(([a-z-]+)\)", t.get("note", ""))
            if not m:
                problems.append("task %s (%s): no ccbuild id in its note" % (t.get("id"), t.get("name")))
                continue
            tid = m.group(1)
            if tid in tasks:
                problems.append("%s twice" % tid)
            tasks[tid] = dict(t.attrib, kind=m.group(2), parent=parent,
                              preds=[(p.get("predecessor-id"), p.get("type"), p.get("lag"))
                                     for p in t.findall("predecessors/predecessor")])
            by_pid[t.get("id")] = tid
            walk(t, tid)

    walk(ET.parse(a.planner).getroot().find("tasks"), None)
    for tid, w in want.items():
        t = tasks.get(tid)
        if t is None:
            problems.append("%s (%s) did not survive" % (tid, w[0]))
            continue
        kind, floor, start, end, duration, parent = w
        if t["kind"] != kind or t["parent"] != parent:
            problems.append("%s: %s under %s, expected %s under %s" % (
                tid, t["kind"], t["parent"], kind, parent))
        if start is not None and (t["start"].rstrip("Z") != start or t["end"].rstrip("Z") != end):
            problems.append("%s: %s to %s, the schedule says %s to %s" % (
                tid, t["start"], t["end"], start, end))
        if duration is not None and float(t["duration"]) != duration:
            problems.append("%s: duration %s s, expected %d s" % (tid, t["duration"], duration))
        if kind in ("delivery", "walls-finished") and t["type"] != "milestone":
            problems.append("%s: a %s is a milestone" % (tid, kind))
    for tid in tasks:
        if tid not in want:
            problems.append("%s: not a task of the schedule" % tid)

    # Links: finish-to-start, forwards in time.
    links = 0
    preds = {}
    for tid, t in tasks.items():
        preds[tid] = []
        for pid, typ, lag in t["preds"]:
            links += 1
            p = by_pid.get(pid)
            if p is None or typ != "FS" or float(lag) != 0:
                problems.append("%s: link %s %s lag %s" % (tid, pid, typ, lag))
                continue
            preds[tid].append(p)
            if tasks[p]["end"] > t["start"]:
                problems.append("%s starts %s, before its predecessor %s ends %s" % (
                    tid, t["start"], p, tasks[p]["end"]))

    # The schedule's order: back from each layer to the layer before it.
    layers = ["L%d.%d" % (l["floor"], l["layer"]) for l in doc["layers"]]
    on_path = {}
    for before, layer in zip(layers, layers[1:]):
        path, at = [], layer
        while True:
            ps = preds.get(at, [])
            if not ps:
                problems.append("%s: its predecessors end at %s, not at %s" % (layer, at, before))
                break
            at = ps[0]
            if at == before:
                break
            if at.startswith("L"):
                problems.append("%s reaches %s before %s" % (layer, at, before))
                break
            path.append(at)
        on_path[layer] = set(path)
    for l in doc["layers"]:
        key = "L%d.%d" % (l["floor"], l["layer"])
        if l["wait_before_s"] > 0 and key != layers[0] and "W" + key[1:] not in on_path.get(key, ()):
            problems.append("%s: its wait is not between it and the layer before" % key)
    for k, e in enumerate(doc["events"]):
        m = re.search(r"before floor (\d+) layer (\d+)", e["detail"])
        if e["kind"] in ("lintel", "joint", "purge") and m:
            key = "L%s.%s" % m.groups()
            if "E%d" % (k + 1) not in on_path.get(key, ()):
                problems.append("E%d (%s) does not lead to %s" % (k + 1, e["kind"], key))
        if e["kind"] == "climb":
            for anchor in e["anchors"]:
                pipes = [j for j in range(k) if doc["events"][j]["kind"] == "pipe" and
                         doc["events"][j]["anchor"]["id"] == anchor["id"] and
                         doc["events"][j]["anchor"]["unit"] == anchor["unit"]]
                if pipes and "E%d" % (pipes[-1] + 1) not in preds.get("E%d" % (k + 1), []):
                    problems.append("climb E%d does not follow pipe E%d (anchor %s)" % (
                        k + 1, pipes[-1] + 1, anchor["id"]))
    last = {}
    for l in doc["layers"]:
        last[l["floor"]] = "L%d.%d" % (l["floor"], l["layer"])
    for floor, key in last.items():
        if key not in preds.get("M%d" % floor, []):
            problems.append("M%d does not follow %s" % (floor, key))

    # The calendars, in the MSPDI file itself.
    root = ET.parse(a.mspdi).getroot()
    cals = {c.findtext("ms:UID", namespaces=NS): c for c in root.findall("ms:Calendars/ms:Calendar", NS)}
    site = doc["inputs"].get("site")
    if site:
        cal = cals.get(root.findtext("ms:CalendarUID", namespaces=NS))
        names = ["sun", "mon", "tue", "wed", "thu", "fri", "sat"]
        week, holidays = {}, []
        for d in cal.findall("ms:WeekDays/ms:WeekDay", NS):
            day_type = int(d.findtext("ms:DayType", namespaces=NS))
            if day_type == 0:
                holidays.append(d.findtext("ms:TimePeriod/ms:FromDate", namespaces=NS)[:10])
                continue
            week[names[day_type - 1]] = [
                "%s-%s" % (w.findtext("ms:FromTime", namespaces=NS)[:5],
                           w.findtext("ms:ToTime", namespaces=NS)[:5].replace("00:00", "24:00")
                           if w.findtext("ms:ToTime", namespaces=NS)[:5] == "00:00"
                           else w.findtext("ms:ToTime", namespaces=NS)[:5])
                for w in d.findall("ms:WorkingTimes/ms:WorkingTime", NS)]
        if week != site["working_hours"]:
            problems.append("calendar week %r, the site's %r" % (week, site["working_hours"]))
        if sorted(holidays) != sorted(site.get("holidays", [])):
            problems.append("calendar holidays %r, the site's %r" % (holidays, site.get("holidays")))
    print("\n".join(problems) or
          "%s: OK: %d tasks (%d layers) and %d links survive msp2planner.xsl; the order, the "
          "anchors and the calendar hold" % (a.mspdi, len(tasks), len(layers), links))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
