#!/usr/bin/env python3
"""Checks `ccbuild export --format csv` against its schedule, read by Python's csv module
(RFC 4180), without ccbuild's code: every layer and event once with the schedule's times,
every climb's phases back to back over its climb, rows in order of start, the columns
re-summed to the schedule's totals (concrete, waits, crew hours, slabs, lintels, joints,
pipes, purges, climbs, deliveries), and the local dates: the schedule's own timestamps on a
site calendar, else --start plus the schedule seconds.
Usage: check_csv_export.py SCHEDULE.json TASKS.csv [--start "2027-03-01 07:00"]
Exit 1 with every problem found."""

import argparse
import csv
import datetime
import json
import sys

HEADER = ["id", "kind", "floor", "layer", "start", "end", "start_s", "end_s", "duration_s",
          "who", "crew", "concrete_m3", "detail"]
T = 2e-6  # s: times written to the microsecond


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("schedule")
    ap.add_argument("csv")
    ap.add_argument("--start")
    a = ap.parse_args()
    doc = json.load(open(a.schedule))
    with open(a.csv, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    problems = []
    if not rows or rows[0] != HEADER:
        print("%s: header %r, expected %r" % (a.csv, rows[0] if rows else None, HEADER))
        return 1
    tasks = [dict(zip(HEADER, r)) for r in rows[1:]]
    for t in tasks:
        if len(t) != len(HEADER):
            problems.append("row %s: %d fields" % (t.get("id"), len(t)))
        for k in ("start_s", "end_s", "duration_s", "concrete_m3"):
            t[k] = float(t[k])
        t["crew"] = int(t["crew"])
        if not t["who"]:
            problems.append("%s: no one named in who" % t["id"])
        if abs(t["end_s"] - t["start_s"] - t["duration_s"]) > 3 * T:
            problems.append("%s: duration %.6f, end - start %.6f" % (
                t["id"], t["duration_s"], t["end_s"] - t["start_s"]))
    ids = [t["id"] for t in tasks]
    if len(set(ids)) != len(ids):
        problems.append("ids repeat")
    starts = [t["start_s"] for t in tasks]
    if starts != sorted(starts):
        problems.append("rows not in order of start")
    # Every layer and event once, with its times.
    by_id = {t["id"]: t for t in tasks}
    layers = [t for t in tasks if t["kind"] == "layer"]
    if len(layers) != len(doc["layers"]):
        problems.append("%d layer rows, the schedule has %d layers" % (len(layers), len(doc["layers"])))
    for l in doc["layers"]:
        t = by_id.get("L%d.%d" % (l["floor"], l["layer"]))
        if t is None or t["kind"] != "layer" or abs(t["start_s"] - l["start_s"]) > T or \
                abs(t["end_s"] - l["end_s"]) > T or abs(t["concrete_m3"] - l["concrete_m3"]) > 1e-6:
            problems.append("floor %d layer %d: row %r" % (l["floor"], l["layer"], t))
    for k, e in enumerate(doc["events"]):
        t = by_id.get("E%d" % (k + 1))
        if t is None or t["kind"] != e["kind"] or abs(t["start_s"] - e["start_s"]) > T or \
                abs(t["end_s"] - e["end_s"]) > T or t["crew"] != e["crew"]:
            problems.append("event %d (%s): row %r" % (k + 1, e["kind"], t))
            continue
        if e["kind"] == "climb":
            phases = sorted((t2 for t2 in tasks if t2["id"].startswith("E%d." % (k + 1))),
                            key=lambda p: int(p["id"].split(".")[1]))
            at = e["start_s"]
            for p in phases:
                if abs(p["start_s"] - at) > 1e-3 or p["kind"] != "climb-phase":
                    problems.append("%s starts at %.6f, the phase before ends at %.6f" % (
                        p["id"], p["start_s"], at))
                at = p["end_s"]
            if not phases or abs(at - e["end_s"]) > 1e-3:
                problems.append("climb %d: its %d phases end at %.6f, the climb at %.6f" % (
                    k + 1, len(phases), at, e["end_s"]))
    # Re-summed to the totals.
    tot = doc["totals"]
    n = len(tasks)

    def total(kinds, what=lambda t: t["duration_s"]):
        return sum(what(t) for t in tasks if t["kind"] in kinds)

    checks = [
        ("concrete_m3", total({"layer"}, lambda t: t["concrete_m3"]), tot["concrete_m3"], 1e-5 * n),
        ("waits_s", total({"wait"}), tot["waits_s"], 1e-5 * n),
        ("slabs_s", total({"slab", "pour"}), tot["slabs_s"], 1e-5 * n),
        ("lintels_s", total({"lintel"}), tot["lintels_s"], 1e-5 * n),
        ("joints_s", total({"joint"}), tot["joints_s"], 1e-5 * n),
        ("pipes_s", total({"pipe"}), tot["pipes_s"], 1e-5 * n),
        ("purges_s", total({"purge"}), tot["purges_s"], 1e-5 * n),
        ("climbs_s", total({"climb"}), tot["climbs_s"], 1e-5 * n),
        ("crew_h", sum(t["crew"] * t["duration_s"] for t in tasks
                       if t["kind"] not in ("wait", "climb-phase", "layer")) / 3600.0,
         tot["crew_h"], 1e-5 * n),
        ("deliveries m3", total({"delivery"}, lambda t: t["concrete_m3"]),
         sum(d["m3"] for d in doc.get("deliveries", [])), 1e-5 * n),
        ("makespan_s", max(t["end_s"] for t in tasks), tot["makespan_s"], 1e-5),
    ]
    for name, got, want, tol in checks:
        if abs(got - want) > tol:
            problems.append("%s re-summed from the rows %.6f, the schedule's totals %.6f" % (
                name, got, want))
    # Local dates.
    dated = 0
    for l in doc["layers"]:
        t = by_id.get("L%d.%d" % (l["floor"], l["layer"]))
        if t is None:
            continue
        if l.get("start_time"):
            want = l["start_time"][:19].replace("T", " ")
        elif a.start:
            base = datetime.datetime.fromisoformat(a.start.replace(" ", "T"))
            want = (base + datetime.timedelta(seconds=round(l["start_s"]))).strftime("%Y-%m-%d %H:%M:%S")
        else:
            want = ""
        dated += want != ""
        if t["start"] != want:
            problems.append("floor %d layer %d starts at %r, expected %r" % (
                l["floor"], l["layer"], t["start"], want))
    print("\n".join(problems) or
          "%s: OK: %d rows (%d layers, %d events, %d deliveries) re-summed to the totals; %d "
          "layer starts dated" % (a.csv, n, len(layers), len(doc["events"]),
                                 len(doc.get("deliveries", [])), dated))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
