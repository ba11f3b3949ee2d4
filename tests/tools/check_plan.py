#!/usr/bin/env python3
"""Re-checks a ccbuild layer plan (plan-layer --json) from its waypoints alone.

Independent of ccbuild's code: it reads only the JSON (docs/json.md) and checks that
  - every wall piece of the layer is deposited over its whole length, exactly once
    (a piece may be deposited in parts, e.g. by two nozzles either side of a border);
  - every stretch between two waypoints respects the machine's limits: deposition at the
    deposition speed, air moves within the travel speed (per axis, one axis at a time,
    for the rectilinear metric), z within the z axis speed, turns within the rotation
    speed, the cumulative heading within the stopper;
  - time never runs backwards, and the paths end within the layer time;
  - the nozzle never travels through a wall it has already built at nozzle height: an
    air move that crosses one is lifted above the layer (touching a wall only at the
    move's own ends is not crossing);
  - adjacent gantries on common rails stay at least a gantry width apart at every
    breakpoint of either path (both are piecewise linear, so that is exact).

Usage: check_plan.py PLAN.json            exit 0 when sound, 1 with the problems found
       check_plan.py --self-test PLAN.json  corrupts the plan in several ways and exits 0
                                            only when each corruption is caught
"""

import copy
import json
import math
import sys

POS = 1e-5   # m: the JSON rounds to micrometres
TIME = 2e-6  # s: and to microseconds
ANGLE = 1e-5  # rad


def paths_of(plan):
    """(stage index, nozzle number, waypoints) for every nozzle of every stage."""
    if plan.get("nozzles", 1) == 1:
        return [(0, 1, plan["waypoints"])]
    out = []
    for s, stage in enumerate(plan["stages"]):
        for n in stage["nozzles"]:
            out.append((s, n["nozzle"], n["waypoints"]))
    return out


def check_limits(plan, problems):
    m = plan["machine"]
    metric = plan.get("metric", "euclidean")
    for stage, nozzle, w in paths_of(plan):
        where = "stage %d nozzle %d" % (stage + 1, nozzle)
        for k in range(len(w) - 1):
            a, b = w[k], w[k + 1]
            dt = b["t_s"] - a["t_s"]
            if dt < -TIME:
                problems.append("%s: time runs backwards at waypoint %d" % (where, k))
                continue
            dx, dy = b["x_m"] - a["x_m"], b["y_m"] - a["y_m"]
            d = math.hypot(dx, dy)
            slack = dt + TIME
            if abs(b["z_m"] - a["z_m"]) > m["z_speed_m_s"] * slack + POS:
                problems.append("%s: z faster than the z axis at waypoint %d" % (where, k))
            if abs(b["heading_rad"] - a["heading_rad"]) > m["rotation_speed_rad_s"] * slack + ANGLE:
                problems.append("%s: turning faster than the nozzle can at waypoint %d" % (where, k))
            if m["stopper_min_rad"] is not None:
                h = b["heading_rad"]
                if h < m["stopper_min_rad"] - ANGLE or h > m["stopper_max_rad"] + ANGLE:
                    problems.append("%s: heading %.6f past the stopper at waypoint %d" % (where, h, k + 1))
            if a["extruding"]:
                v = m["deposition_speed_m_s"]
                if abs(d - v * dt) > v * TIME + 2 * POS:
                    problems.append("%s: wall %d not deposited at the deposition speed (%.6f m in %.6f s)"
                                    % (where, a["wall"], d, dt))
                if abs(b["z_m"] - a["z_m"]) > POS:
                    problems.append("%s: the nozzle changes height while depositing at %d" % (where, k))
            elif metric == "rectilinear":
                if abs(dx) > POS and abs(dy) > POS:
                    problems.append("%s: a rectilinear move runs diagonally at waypoint %d" % (where, k))
                if abs(dx) > m["x_speed_m_s"] * slack + 2 * POS or abs(dy) > m["y_speed_m_s"] * slack + 2 * POS:
                    problems.append("%s: faster than an axis allows at waypoint %d" % (where, k))
            elif d > m["travel_speed_m_s"] * slack + 2 * POS:
                problems.append("%s: air move faster than the travel speed at waypoint %d (%.6f m in %.6f s)"
                                % (where, k, d, dt))
        if w and plan.get("layer_time_s") is not None and w[-1]["t_s"] > plan["layer_time_s"] + TIME:
            problems.append("%s: ends at %.6f s, after the layer time %.6f s" % (where, w[-1]["t_s"], plan["layer_time_s"]))
        if w and w[-1]["extruding"]:
            problems.append("%s: the last waypoint still extrudes" % where)


def check_coverage(plan, problems):
    """Each piece's length is covered by the extruding stretches along it, once."""
    covered = {}  # piece index -> [(s0, s1)] along the piece
    pieces = plan["pieces"]
    for stage, nozzle, w in paths_of(plan):
        for k in range(len(w) - 1):
            a, b = w[k], w[k + 1]
            if not a["extruding"]:
                continue
            p0, p1 = (a["x_m"], a["y_m"]), (b["x_m"], b["y_m"])
            home = None
            for i, piece in enumerate(pieces):
                if piece["wall"] != a["wall"]:
                    continue
                (sx, sy), (ex, ey) = piece["start_m"], piece["end_m"]
                length = math.hypot(ex - sx, ey - sy)
                ux, uy = (ex - sx) / length, (ey - sy) / length
                along = []
                fits = True
                for (px, py) in (p0, p1):
                    t = (px - sx) * ux + (py - sy) * uy
                    off = abs(-(px - sx) * uy + (py - sy) * ux)
                    if off > 2 * POS or t < -2 * POS or t > length + 2 * POS:
                        fits = False
                    along.append(t)
                if fits:
                    home = (i, min(along), max(along))
                    break
            if home is None:
                problems.append("stage %d nozzle %d: extrudes wall %d where the layer has no such wall "
                                "(waypoint %d)" % (stage + 1, nozzle, a["wall"], k))
                continue
            covered.setdefault(home[0], []).append((home[1], home[2]))
    for i, piece in enumerate(pieces):
        spans = sorted(covered.get(i, []))
        name = "wall %d piece %d" % (piece["wall"], piece["piece"])
        if not spans:
            problems.append("%s is never deposited" % name)
            continue
        at = 0.0
        for s0, s1 in spans:
            if s0 > at + 2 * POS:
                problems.append("%s: %.6f m to %.6f m is never deposited" % (name, at, s0))
            if s0 < at - 2 * POS:
                problems.append("%s: %.6f m to %.6f m is deposited twice" % (name, s0, min(at, s1)))
            at = max(at, s1)
        if at < piece["length_m"] - 2 * POS:
            problems.append("%s: %.6f m to its end (%.6f m) is never deposited" % (name, at, piece["length_m"]))


def cross(ox, oy, ax, ay, bx, by):
    return (ax - ox) * (by - oy) - (ay - oy) * (bx - ox)


def passes_through(p, q, c, d, eps=1e-6):
    """Does the travel p -> q meet the wall c - d anywhere but within eps of p or q?"""
    (px, py), (qx, qy), (cx, cy), (dx, dy) = p, q, c, d
    length = math.hypot(qx - px, qy - py)
    if length <= eps:
        return False
    ux, uy = (qx - px) / length, (qy - py) / length
    # The wall's end points and any crossing, as distances along the travel.
    def along(x, y):
        return (x - px) * ux + (y - py) * uy

    def off(x, y):
        return abs(-(x - px) * uy + (y - py) * ux)
    hits = []
    for (x, y) in ((cx, cy), (dx, dy)):
        if off(x, y) <= eps:
            hits.append(along(x, y))
    wx, wy = dx - cx, dy - cy
    denominator = (qx - px) * wy - (qy - py) * wx
    if abs(denominator) > 1e-12:
        t = ((cx - px) * wy - (cy - py) * wx) / denominator
        u = ((cx - px) * (qy - py) - (cy - py) * (qx - px)) / denominator
        if -1e-9 <= u <= 1 + 1e-9:
            hits.append(t * length)
    elif off(cx, cy) <= eps:  # collinear: overlapping runs
        lo, hi = sorted((along(cx, cy), along(dx, dy)))
        if hi > eps and lo < length - eps:
            return True
    return any(eps < h < length - eps for h in hits)


def check_walls_cleared(plan, problems):
    top = plan["z_top_m"]
    for stage, nozzle, w in paths_of(plan):
        built = []
        for k in range(len(w) - 1):
            a, b = w[k], w[k + 1]
            p, q = (a["x_m"], a["y_m"]), (b["x_m"], b["y_m"])
            if a["extruding"]:
                built.append((p, q, a["wall"]))
                continue
            if a["z_m"] > top + POS and b["z_m"] > top + POS:
                continue  # lifted above the walls
            for c, d, wall in built:
                if passes_through(p, q, c, d):
                    problems.append("stage %d nozzle %d: travels through built wall %d at nozzle height "
                                    "(waypoints %d-%d)" % (stage + 1, nozzle, wall, k, k + 1))
                    break


def rail(w, axis):
    return w["x_m"] if axis == "x" else w["y_m"]


def position_at(w, t, axis):
    """The rail coordinate at time t: linear between waypoints, held before and after."""
    if t <= w[0]["t_s"]:
        return rail(w[0], axis)
    for k in range(len(w) - 1):
        a, b = w[k], w[k + 1]
        if t <= b["t_s"]:
            if b["t_s"] - a["t_s"] <= 1e-12:
                return rail(b, axis)
            f = (t - a["t_s"]) / (b["t_s"] - a["t_s"])
            return rail(a, axis) + f * (rail(b, axis) - rail(a, axis))
    return rail(w[-1], axis)


def check_gaps(plan, problems):
    if plan.get("nozzles", 1) == 1 or plan.get("status") != "solved":
        return
    width, axis = plan["gantry_width_m"], plan["rail_axis"]
    smallest = math.inf
    for s, stage in enumerate(plan["stages"]):
        nozzles = sorted(stage["nozzles"], key=lambda n: n["nozzle"])
        for left, right in zip(nozzles, nozzles[1:]):
            times = sorted({w["t_s"] for w in left["waypoints"]} | {w["t_s"] for w in right["waypoints"]})
            for t in times:
                gap = position_at(right["waypoints"], t, axis) - position_at(left["waypoints"], t, axis)
                smallest = min(smallest, gap)
                if gap < width - 2 * POS:
                    problems.append("stage %d: nozzles %d and %d are %.6f m apart at t = %.6f s (gantry width %.6f m)"
                                    % (s + 1, left["nozzle"], right["nozzle"], gap, t, width))
                    break
    if plan.get("min_gap_m") is not None and math.isfinite(smallest):
        if abs(smallest - plan["min_gap_m"]) > 4 * POS:
            problems.append("the closest gap is %.6f m, the plan says %.6f m" % (smallest, plan["min_gap_m"]))


def check(plan):
    problems = []
    if plan.get("nozzles", 1) > 1 and plan.get("status") != "solved":
        return problems  # no plan to check: the JSON says why
    check_limits(plan, problems)
    check_coverage(plan, problems)
    check_walls_cleared(plan, problems)
    check_gaps(plan, problems)
    return problems


def self_test(plan):
    """Each corruption must be caught: a checker that cannot fail proves nothing."""
    paths = paths_of(plan)
    _, _, w = max(paths, key=lambda p: len(p[2]))
    extruding = [k for k, p in enumerate(w[:-1]) if p["extruding"]]
    moving = [k for k, p in enumerate(w[:-1]) if not p["extruding"] and
              math.hypot(w[k + 1]["x_m"] - p["x_m"], w[k + 1]["y_m"] - p["y_m"]) > 0.1]
    corruptions = {}

    def corrupt(name, change):
        bad = copy.deepcopy(plan)
        _, _, bw = max(paths_of(bad), key=lambda p: len(p[2]))
        change(bad, bw)
        corruptions[name] = bad

    k = extruding[len(extruding) // 2]
    corrupt("a wall left out", lambda p, bw: bw[k].update(extruding=False))
    corrupt("depositing too fast", lambda p, bw: [q.update(t_s=q["t_s"] - 0.5 * (bw[k + 1]["t_s"] - bw[k]["t_s"]))
                                                 for q in bw[k + 1:]])
    if moving:
        j = moving[len(moving) // 2]
        corrupt("travelling too fast", lambda p, bw: [q.update(t_s=q["t_s"] - 0.9 * (bw[j + 1]["t_s"] - bw[j]["t_s"]))
                                                     for q in bw[j + 1:]])
    lifted = [j for j in range(len(w) - 1) if w[j]["z_m"] > plan["z_top_m"] + POS and
              w[j + 1]["z_m"] > plan["z_top_m"] + POS and
              math.hypot(w[j + 1]["x_m"] - w[j]["x_m"], w[j + 1]["y_m"] - w[j]["y_m"]) > 0.1]
    if lifted:
        j2 = lifted[0]

        def unlifted(p, bw):
            for q in bw:  # no lift anywhere: the crossing now happens at nozzle height
                q["z_m"] = p["z_top_m"]
        corrupt("no lift over a built wall", unlifted)
    corrupt("turning past the stopper", lambda p, bw: bw[-1].update(heading_rad=bw[-1]["heading_rad"] + 40.0))

    def twice(p, bw):
        # The same stretch again at the end (after a long, slow air move to it).
        dt = bw[k + 1]["t_s"] - bw[k]["t_s"]
        end = bw[-1]["t_s"]
        bw.append(dict(bw[k], t_s=end + 1e4))
        bw.append(dict(bw[k + 1], t_s=end + 1e4 + dt, extruding=False, wall=0, piece=0))
        if p.get("layer_time_s") is not None:
            p["layer_time_s"] = end + 1e4 + dt
    corrupt("a wall deposited twice", twice)
    if plan.get("nozzles", 1) > 1:
        def collide(p, bw):
            stage = p["stages"][0]
            a, b = stage["nozzles"][0]["waypoints"], stage["nozzles"][1]["waypoints"]
            axis = "x_m" if p["rail_axis"] == "x" else "y_m"
            b[0][axis] = a[0][axis]
        corruptions["two gantries too close"] = copy.deepcopy(plan)
        collide(corruptions["two gantries too close"], None)
    missed = [name for name, bad in corruptions.items() if not check(bad)]
    for name in missed:
        print("self-test: the checker missed: " + name)
    print("self-test: %d of %d corruptions caught" % (len(corruptions) - len(missed), len(corruptions)))
    return not missed


def main(argv):
    if len(argv) == 3 and argv[1] == "--self-test":
        with open(argv[2]) as f:
            plan = json.load(f)
        if check(plan):
            print("self-test: the plan itself does not pass")
            return 1
        return 0 if self_test(plan) else 1
    if len(argv) != 2:
        print(__doc__)
        return 2
    with open(argv[1]) as f:
        plan = json.load(f)
    problems = check(plan)
    for p in problems[:50]:
        print("problem: " + p)
    if problems:
        print("%d problem(s) in %s" % (len(problems), argv[1]))
        return 1
    if plan.get("nozzles", 1) > 1 and plan.get("status") != "solved":
        print("OK: %s: no plan to check (%s: %s)" % (argv[1], plan["status"], plan["status_reason"]))
        return 0
    paths = paths_of(plan)
    print("OK: %s: %d piece(s) covered once, %d path(s), %d waypoints within the machine's limits%s"
          % (argv[1], len(plan["pieces"]), len(paths), sum(len(p[2]) for p in paths),
             ", gantries a width apart" if plan.get("nozzles", 1) > 1 else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
