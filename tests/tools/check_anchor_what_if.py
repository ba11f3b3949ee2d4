#!/usr/bin/env python3
"""Checks `ccbuild schedule --what-if anchors` on the tower against schedules of the changes
made by hand, outside ccbuild: the earlier-pipes change is listed with its makespan, and
scheduling the tower on a copy of the climber whose URDF legs are that much longer (edited
here with Python's XML parser) gives the same makespan, with each climb's pipes cast in the
storey below the one they were cast in before; every change listed shortens the build; the
lower anchor strength leaves no climb waiting. The what-if schedule itself is re-checked by
check_schedule.py and its report (a strength curve per climb, the what-ifs' table) by
check_report.py in headless Chromium.

Usage: check_anchor_what_if.py CCBUILD SOURCE_DIR"""

import json
import os
import re
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET


def run(args, cwd):
    r = subprocess.run(args, cwd=cwd, capture_output=True, text=True, timeout=600)
    if r.returncode not in (0, 1):
        sys.exit("%s: exit %d\n%s" % (" ".join(args), r.returncode, r.stderr))
    return r


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    ccbuild, source = sys.argv[1], sys.argv[2]
    tower = os.path.join(source, "config/buildings/tower.yaml")
    # A mix whose anchors are slow to strengthen: every climb then waits for them.
    mix = ["--material", os.path.join(source, "tests/data/materials/slow-anchor-mix.yaml")]
    with tempfile.TemporaryDirectory() as tmp:
        base = run([ccbuild, "schedule", tower, "--quiet", "--what-if", "anchors"] + mix + [
                    "-o", os.path.join(tmp, "base.json"), "--report", os.path.join(tmp, "base.html")],
                   tmp)
        here = os.path.dirname(os.path.abspath(__file__))
        for checker, target in (("check_schedule.py", "base.json"), ("check_report.py", "base.html")):
            r = subprocess.run([sys.executable, os.path.join(here, checker), os.path.join(tmp, target)],
                               capture_output=True, text=True, timeout=600)
            print(r.stdout, end="")
            if r.returncode != 0:
                sys.exit("%s %s: exit %d\n%s" % (checker, target, r.returncode, r.stderr))
        out = base.stdout
        base_doc = json.load(open(os.path.join(tmp, "base.json")))
        base_makespan = base_doc["totals"]["makespan_s"]
        changes = re.findall(r"^  (.*): [0-9.]+ [a-z]+ \(([0-9]+) s\)( NOT feasible)?,", out, re.M)
        if len(changes) < 3:
            sys.exit("expected at least three what-if changes, got:\n" + out)
        for text, makespan, infeasible in changes:
            if infeasible or float(makespan) >= base_makespan:
                sys.exit("a change that does not shorten the build: %s (%s s against %.0f s)"
                         % (text, makespan, base_makespan))
        # The lower strength is the youngest anchor's when its climb is ready: no climb waits.
        lower = re.search(r"^  load the anchors from .*, anchor waits (.*)$", out, re.M)
        # (The column's unit is that of its largest value: zero may read "0.00 h".)
        if not lower or not re.fullmatch(r"0(\.0+)? (s|min|h|d)", lower.group(1)):
            sys.exit("the lower anchor strength still leaves anchor waits: %s"
                     % (lower.group(0) if lower else "not listed"))
        earlier = [c for c in changes if "a storey earlier" in c[0]]
        if not earlier:
            sys.exit("the earlier-pipes change is not listed:\n" + out)
        # In the building's unit (the tower is drawn in feet); the URDF is in metres.
        longer = re.search(r"legs reach ([0-9.]+) (m|ft) longer", earlier[0][0])
        extra = float(longer.group(1)) * (0.3048 if longer.group(2) == "ft" else 1.0)
        listed = float(earlier[0][1])

        # The variant by hand: the climber's URDF with every leg's stroke `extra` longer.
        machines = os.path.join(source, "config/machines")
        tree = ET.parse(os.path.join(machines, "cc_climber.urdf"))
        legs = 0
        for joint in tree.getroot().findall("joint"):
            if joint.get("name").endswith("_stroke"):
                limit = joint.find("limit")
                limit.set("upper", repr(float(limit.get("upper")) + extra))
                legs += 1
        if legs < 3:
            sys.exit("the climber's URDF has %d legs" % legs)
        tree.write(os.path.join(tmp, "longer.urdf"))
        profile = open(os.path.join(machines, "cc-climber.yaml")).read()
        profile = profile.replace("urdf: cc_climber.urdf", "urdf: longer.urdf")
        open(os.path.join(tmp, "longer.yaml"), "w").write(profile)
        run([ccbuild, "schedule", tower, "--quiet", "--no-compare", "--machine", os.path.join(tmp, "longer.yaml"),
             "-o", os.path.join(tmp, "longer.json")] + mix, tmp)
        doc = json.load(open(os.path.join(tmp, "longer.json")))
        if not doc["feasible"]:
            sys.exit("the tower on the longer legs is not feasible")
        got = doc["totals"]["makespan_s"]
        if abs(got - listed) > 1.0:
            sys.exit("the what-if said %.0f s, scheduling the variant gives %.3f s" % (listed, got))
        # Each climb's pipes, once the legs reach, in the storey below where they were.
        before = {s["stage"]: s["anchors"] for s in base_doc["stages"]}
        moved = 0
        for stage in doc["stages"]:
            was = before[stage["stage"]]
            for a, b in zip(stage["anchors"], was):
                if a["floor"] is not None and b["floor"] is not None and b["floor"] >= 1:
                    if a["floor"] != b["floor"] - 1:
                        sys.exit("stage %d: pipe %s cast in floor %d, expected %d"
                                 % (stage["stage"], a["id"], a["floor"], b["floor"] - 1))
                    moved += 1
        if moved == 0:
            sys.exit("no pipe moved a storey down")
        print("what-if anchors: %d changes, each shorter than %.0f s; the earlier pipes (legs "
              "%.2f m longer) give %.0f s, and so does the variant scheduled by hand; %d pipes "
              "cast a storey earlier" % (len(changes), base_makespan, extra, got, moved))


if __name__ == "__main__":
    main()
