#!/usr/bin/env python3
"""Re-checks ccbuild's climbs (climb --json) from the JSON and the machine's URDF alone.

Independent of ccbuild's code: it reads the JSON (docs/json.md) and the URDF the JSON
names (with Python's own XML parser) and checks that
  - every climb is park, then for each unit exactly once balance, release, transit,
    insert (in that order), then lift; and the climb's duration is the phases' sum;
  - every waypoint's joint values lie within the URDF's limits, the legs' strokes within
    them by the profile's stroke margin, lift waypoints' following legs included;
  - between waypoints no joint moves faster than its URDF velocity limit; time never runs
    backwards and each phase's last waypoint is at its duration; a pin is released and
    inserted in no less than the profile's pin times;
  - the lift goes from the one stage's platform height to the next, in as many strokes as
    the cylinder's stroke needs, at the loaded stroke speed plus a reset between strokes;
  - every joint starts a phase where the previous phase that moved it left it;
  - each stage's pipes are cast in a layer printed before the climb onto them, below the
    platform; stages rise; the totals are the sums.
Collisions are not re-checked here (that needs the walls' geometry; verify_climb in the
tests re-checks every path against FCL at 5 mm).

Usage: check_climbs.py CLIMBS.json            exit 0 when sound, 1 with the problems found
       check_climbs.py --self-test CLIMBS.json  corrupts the climbs in several ways and
                                              exits 0 only when each corruption is caught
"""

import copy
import json
import math
import sys
import xml.etree.ElementTree as ET

POS = 2e-6   # m or rad: the JSON rounds to micrometres
TIME = 2e-6  # s


def read_urdf(path):
    """{joint name: (type, lower, upper, velocity)} from the URDF."""
    joints = {}
    for j in ET.parse(path).getroot().findall("joint"):
        limit = j.find("limit")
        if limit is None:
            joints[j.get("name")] = (j.get("type"), -math.inf, math.inf, math.inf)
        else:
            joints[j.get("name")] = (j.get("type"), float(limit.get("lower", 0)),
                                     float(limit.get("upper", 0)), float(limit.get("velocity")))
    return joints


def check_values(where, names, values, urdf, strokes, margin, problems):
    for name, v in zip(names, values):
        if name.startswith("platform_"):
            continue
        if name not in urdf:
            problems.append("%s: joint %s is not in the URDF" % (where, name))
            continue
        _, lo, hi, _ = urdf[name]
        m = margin if name in strokes else 0.0
        if v < lo + m - POS or v > hi - m + POS:
            problems.append("%s: %s = %g outside [%g, %g]" % (where, name, v, lo + m, hi - m))


def check_climb(c, stages, machine, urdf, problems):
    where = "climb %d -> %d" % (c["from_stage"], c["to_stage"])
    if c["status"] != "feasible":
        return
    phases = c["phases"]
    units = [u["name"] for u in machine["units"]]
    strokes = {u["stroke"] for u in machine["units"]}
    kinds = [(p["kind"], p["unit"]) for p in phases]
    seen = [p["unit"] for p in phases if p["kind"] == "transit"]
    if sorted(seen) != sorted(units):
        problems.append("%s: units transferred %s, expected each of %s once" % (where, seen, units))
    # park, then groups (balance for the group's first unit, then release, transit,
    # insert of each of its units), then lift.
    expected = [("park", None)]
    for u in seen:
        if len(expected) < len(kinds) and kinds[len(expected)] == ("balance", u):
            expected.append(("balance", u))
        expected += [("release", u), ("transit", u), ("insert", u)]
        if len(expected) >= len(kinds):
            break
    expected.append(("lift", None))
    if kinds != expected or kinds[1][0] != "balance":
        problems.append("%s: phases %s, expected park, then balance before each group of "
                        "release, transit, insert, then lift" % (where, kinds))
    total = sum(p["duration_s"] for p in phases)
    if abs(total - c["duration_s"]) > TIME * (len(phases) + 1):
        problems.append("%s: duration %g is not its phases' sum %g" % (where, c["duration_s"], total))
    margin = machine["stroke_end_margin_m"]
    last = {}
    for i, p in enumerate(phases):
        pw = "%s phase %d (%s)" % (where, i, p["kind"])
        w = p["waypoints"]
        if len(w) < 2:
            problems.append("%s: fewer than two waypoints" % pw)
            continue
        if abs(w[0]["t_s"]) > TIME or abs(w[-1]["t_s"] - p["duration_s"]) > TIME:
            problems.append("%s: waypoints span %g..%g s, expected 0..%g" %
                            (pw, w[0]["t_s"], w[-1]["t_s"], p["duration_s"]))
        names = p["joints"]
        for k, point in enumerate(w):
            check_values("%s waypoint %d" % (pw, k), names, point["values"], urdf, strokes, margin,
                         problems)
            if p["following_joints"]:
                check_values("%s waypoint %d" % (pw, k), p["following_joints"], point["following"],
                             urdf, strokes, margin, problems)
        for name, v in zip(names, w[0]["values"]):
            if name in last and abs(last[name] - v) > POS:
                problems.append("%s: %s starts at %g, the previous motion left it at %g" %
                                (pw, name, v, last[name]))
        for name, v in zip(names, w[-1]["values"]):
            last[name] = v
        for k in range(len(w) - 1):
            dt = w[k + 1]["t_s"] - w[k]["t_s"]
            if dt < -TIME:
                problems.append("%s: time runs backwards at waypoint %d" % (pw, k))
                continue
            if p["kind"] == "lift":
                continue
            for j, name in enumerate(names):
                speed = urdf.get(name, (None, 0, 0, math.inf))[3]
                d = abs(w[k + 1]["values"][j] - w[k]["values"][j])
                if d > speed * (dt + TIME) + POS:
                    problems.append("%s: %s moves %g in %g s, faster than its %g limit" %
                                    (pw, name, d, dt, speed))
        if p["kind"] == "release" and p["duration_s"] < machine["pin_release_s"] - TIME:
            problems.append("%s: a pin released in %g s, less than %g" %
                            (pw, p["duration_s"], machine["pin_release_s"]))
        if p["kind"] == "insert" and p["duration_s"] < machine["pin_insert_s"] - TIME:
            problems.append("%s: a pin inserted in %g s, less than %g" %
                            (pw, p["duration_s"], machine["pin_insert_s"]))
        if p["kind"] == "lift":
            z0 = stages[c["from_stage"]]["platform_z_m"]
            z1 = stages[c["to_stage"]]["platform_z_m"]
            if abs(w[0]["values"][2] - z0) > POS or abs(w[-1]["values"][2] - z1) > POS:
                problems.append("%s: the platform goes %g -> %g, the stages are at %g -> %g" %
                                (pw, w[0]["values"][2], w[-1]["values"][2], z0, z1))
            strokes = max(1, math.ceil(abs(z1 - z0) / machine["lift_per_stroke_m"] - 1e-9))
            if p["strokes"] != strokes:
                problems.append("%s: %d strokes, %d needed for %g m" %
                                (pw, p["strokes"], strokes, abs(z1 - z0)))
            length = sum(math.dist(w[k]["values"], w[k + 1]["values"]) for k in range(len(w) - 1))
            need = length / machine["stroke_speed_loaded_m_s"] + (strokes - 1) * machine["stroke_reset_s"]
            if abs(p["duration_s"] - need) > 1e-3 * need + TIME:
                problems.append("%s: lasts %g s, the loaded stroke speed and resets give %g s" %
                                (pw, p["duration_s"], need))


def check(doc):
    problems = []
    if doc.get("format") != "ccbuild-climbs-1":
        return ["not a ccbuild-climbs-1 document"]
    machine = doc["machine"]
    if machine["kind"] != "climbing":
        if doc["stages"] or doc["climbs"]:
            problems.append("a fixed gantry with stages or climbs")
        return problems
    if machine.get("urdf") is None:
        return ["the climbs were planned on a machine family fitted on the fly, whose URDF was "
                "never written: fit it with `ccbuild fit BUILDING --machine FAMILY -o fitted.yaml` "
                "and plan the climbs on fitted.yaml"]
    urdf = read_urdf(machine["urdf"])
    stages = doc["stages"]
    for k, s in enumerate(stages):
        if s["stage"] != k:
            problems.append("stage %d is numbered %d" % (k, s["stage"]))
        if k > 0 and s["platform_z_m"] <= stages[k - 1]["platform_z_m"]:
            problems.append("stage %d is not above stage %d" % (k, k - 1))
        if len(s["anchors"]) != len(machine["units"]):
            problems.append("stage %d holds %d pins, the machine has %d units" %
                            (k, len(s["anchors"]), len(machine["units"])))
        for a in s["anchors"]:
            if a["z_m"] >= s["platform_z_m"]:
                problems.append("stage %d: pipe %s is not below the platform" % (k, a["id"]))
            if k == 0 or a["floor"] is None:
                continue
            cast = (a["floor"], a["after_layer"])
            printed = (stages[k - 1]["last"]["floor"], stages[k - 1]["last"]["layer"])
            if cast > printed:
                problems.append("stage %d: pipe %s cast after floor %d layer %d, not printed "
                                "before the climb (stage %d ends at floor %d layer %d)" %
                                (k, a["id"], cast[0], cast[1], k - 1, printed[0], printed[1]))
    for c in doc["climbs"]:
        if c["to_stage"] != c["from_stage"] + 1 or c["to_stage"] >= len(stages):
            problems.append("climb %d -> %d does not join two stages" % (c["from_stage"], c["to_stage"]))
            continue
        check_climb(c, stages, machine, urdf, problems)
    t = sum(c["duration_s"] for c in doc["climbs"])
    if abs(t - doc["totals"]["climb_time_s"]) > TIME * (len(doc["climbs"]) + 1) * 20:
        problems.append("total climb time %g is not the climbs' sum %g" % (doc["totals"]["climb_time_s"], t))
    if doc["status"] == "feasible" and any(c["status"] != "feasible" for c in doc["climbs"]):
        problems.append("feasible, with an infeasible climb")
    return problems


def self_test(doc):
    """Each corruption of a sound document must be caught."""
    climbs = [c for c in doc["climbs"] if c["status"] == "feasible"]
    if not climbs:
        return ["no feasible climb to corrupt"]

    def first(d, kind):
        return next(p for p in d["climbs"][0]["phases"] if p["kind"] == kind)

    def hurried(d):
        t = first(d, "transit")
        t["waypoints"][-1]["t_s"] /= 10
        t["duration_s"] /= 10

    def over_limit(d):
        first(d, "transit")["waypoints"][1]["values"][1] = 99.0

    def stroke_to_its_end(d):
        lift = first(d, "lift")
        names = lift["following_joints"]
        stroke = d["machine"]["units"][0]["stroke"]
        k = names.index(stroke)
        lo, hi = URDF_CACHE[names[k]][1:3]
        lift["waypoints"][0]["following"][k] = hi - 0.005

    def skipped_unit(d):
        phases = d["climbs"][0]["phases"]
        k = next(i for i, p in enumerate(phases) if p["kind"] == "transit")
        del phases[k]

    def jump(d):
        first(d, "insert")["waypoints"][0]["values"][0] += 0.05

    def quick_pin(d):
        first(d, "release")["duration_s"] = 1.0
        first(d, "release")["waypoints"][-1]["t_s"] = 1.0

    def one_stroke(d):
        first(d, "lift")["strokes"] = 1

    def pipe_too_late(d):
        k = d["climbs"][0]["to_stage"]
        last = d["stages"][k - 1]["last"]
        d["stages"][k]["anchors"][0]["floor"] = last["floor"]
        d["stages"][k]["anchors"][0]["after_layer"] = last["layer"] + 1

    def wrong_sum(d):
        d["climbs"][0]["duration_s"] += 1.0

    problems = []
    for corrupt in (hurried, over_limit, stroke_to_its_end, skipped_unit, jump, quick_pin,
                    one_stroke, pipe_too_late, wrong_sum):
        bad = copy.deepcopy(doc)
        corrupt(bad)
        if not check(bad):
            problems.append("the corruption '%s' went unnoticed" % corrupt.__name__)
    return problems


URDF_CACHE = {}


def main(argv):
    if len(argv) == 3 and argv[1] == "--self-test":
        doc = json.load(open(argv[2]))
        if doc["machine"]["kind"] != "climbing":
            bad = copy.deepcopy(doc)
            bad["stages"].append({})
            problems = check(doc) or (["a fixed gantry's stage went unnoticed"] if not check(bad) else [])
        else:
            URDF_CACHE.update(read_urdf(doc["machine"]["urdf"]))
            problems = check(doc) or self_test(doc)
    elif len(argv) == 2:
        problems = check(json.load(open(argv[1])))
    else:
        print(__doc__, file=sys.stderr)
        return 2
    for p in problems[:30]:
        print("check_climbs: " + p, file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
