#!/usr/bin/env python3
"""Re-checks the lower bound of a layer plan from its certificate alone.

Independent of ccbuild's code: it reads only the certificate that
`ccbuild plan-layer --bound-certificate FILE` writes (docs/json.md) and proves the bound
again from first principles.

The air moves of any tool path of the layer, with its walls, form a closed walk through
every wall (an open path is closed by a free end joined to its start like a wall, at
distance 0 from every point, with exactly one air move there). So for a set S of points:
  - when an odd number of walls leave S, at least one air move crosses it (rhs 1);
  - when no wall leaves S, and walls lie both inside and outside it, at least two do:
    the walk is connected and crosses S an even number of times (rhs 2).
A "moat" is such a set with a width w >= 0. If, for every pair of points, the widths of
the moats holding exactly one of the two sum to no more than their distance, every air
move pays at least the moats it crosses, and each moat is crossed rhs times at least,
so the airtime distance of any path is at least the sum of rhs * w. The free end's
own moat may have a negative width, as its crossing count is exact.

The checker verifies each moat's rhs against the walls, the widths on every pair of
points (pairs that could not be violated are skipped by a sweep in x, which is exact:
both metrics are at least |dx|), and computes the bound; it fails if the certificate
claims more than that. Tiny violations from floating-point sums are repaired by scaling
the widths down, which keeps the proof valid.

Usage: check_bound.py CERT.json [--plan PLAN.json]
           exit 0 when the bound is proven, 1 with the problems found, 2 on a bad file.
           --plan: a plan-layer --json of the same layer; its pieces must be the
           certificate's walls, and its airtime distance at least the bound (the gap is
           printed).
       check_bound.py --self-test CERT.json
           corrupts the certificate in several ways and exits 0 only when each is caught
"""

import copy
import json
import math
import sys

POS = 1e-5  # m: plan JSON rounds points to micrometres
FEASIBLE = 1e-6  # relative excess over a pair's distance repaired by scaling


class BadFile(Exception):
    pass


def need(cond, message):
    if not cond:
        raise BadFile(message)


def nodes_of(cert):
    """(points, walls including the free end's, free end id or None, metric)."""
    for key in ("points_m", "walls", "moats", "metric", "closed", "lower_bound_distance_m"):
        need(key in cert, "missing field '%s'" % key)
    points = cert["points_m"]
    need(isinstance(points, list) and len(points) <= 2_000_000, "points_m: a list expected")
    for i, p in enumerate(points):
        need(isinstance(p, list) and len(p) == 2 and
             all(isinstance(c, (int, float)) and math.isfinite(c) for c in p),
             "points_m[%d]: [x, y] in metres expected" % i)
    need(cert["metric"] in ("euclidean", "rectilinear"), "metric: euclidean or rectilinear")
    n = len(points)
    free = None
    walls = []
    for k, w in enumerate(cert["walls"]):
        need(isinstance(w, list) and len(w) == 2 and
             all(isinstance(a, int) and 0 <= a < n for a in w),
             "walls[%d]: two point ids below %d expected" % (k, n))
        walls.append((w[0], w[1]))
    if not cert["closed"]:
        start = cert.get("start_point")
        need(isinstance(start, int) and 0 <= start < n, "start_point: a point id expected")
        need(cert.get("free_end_point") == n, "free_end_point: %d expected" % n)
        free = n
        walls.append((free, start))
    return points, walls, free, cert["metric"]


def distance(metric, a, b):
    dx, dy = a[0] - b[0], a[1] - b[1]
    return math.hypot(dx, dy) if metric == "euclidean" else abs(dx) + abs(dy)


def check(cert):
    """(bound proven, claimed bound, problems, pairs checked)."""
    points, walls, free, metric = nodes_of(cert)
    n = len(points)
    nodes = n + (1 if free is not None else 0)
    problems = []
    widths = []
    moats_of = [set() for _ in range(nodes)]
    exact_width = 0.0
    total = 0.0
    for k, m in enumerate(cert["moats"]):
        where = "moats[%d]" % k
        need(isinstance(m, dict) and all(key in m for key in ("points", "rhs", "width_m", "exact")),
             where + ": points, rhs, width_m and exact expected")
        members = m["points"]
        need(isinstance(members, list) and all(isinstance(a, int) and 0 <= a < nodes for a in members),
             where + ".points: node ids below %d expected" % nodes)
        w = m["width_m"]
        need(isinstance(w, (int, float)) and math.isfinite(w), where + ".width_m: a number expected")
        inside = set(members)
        if len(inside) != len(members) or not 0 < len(inside) < nodes:
            problems.append("%s: not a proper set of points (repeated, empty or all)" % where)
            continue
        crossing = sum(1 for a, b in walls if (a in inside) != (b in inside))
        walls_in = any(a in inside for a, b in walls)
        walls_out = any(a not in inside for a, b in walls)
        if m["rhs"] == 1:
            if crossing % 2 == 0:
                problems.append("%s: rhs 1 but %d walls leave it (odd expected)" % (where, crossing))
        elif m["rhs"] == 2:
            if crossing != 0 or not walls_in or not walls_out:
                problems.append("%s: rhs 2 but it is not whole wall-connected parts with walls "
                                "outside it too (%d walls leave it)" % (where, crossing))
        else:
            problems.append("%s: rhs %r (1 or 2 expected)" % (where, m["rhs"]))
        if m["exact"]:
            if free is None or inside != {free} or m["rhs"] != 1:
                problems.append("%s: only the free end's own moat is exact" % where)
            else:
                exact_width += w
            continue
        if w < 0:
            problems.append("%s: negative width %g" % (where, w))
            continue
        total += m["rhs"] * w
        for a in inside:
            moats_of[a].add(len(widths))
        widths.append(w)

    around = [sum(widths[i] for i in moats_of[v]) for v in range(nodes)]

    def separating(u, v):
        shared = sum(widths[i] for i in moats_of[u] & moats_of[v])
        return around[u] + around[v] - 2.0 * shared

    # Every pair of points: the moats between them within their distance.
    order = sorted(range(n), key=lambda v: (points[v][0], v))
    widest = max(around[:n], default=0.0)
    ratio = 1.0
    pairs = 0
    worst = None
    for i, u in enumerate(order):
        pu = points[u]
        reach = around[u] + widest
        for v in order[i + 1:]:
            pv = points[v]
            if pv[0] - pu[0] > reach + 1e-9:
                break
            d = distance(metric, pu, pv)
            if d >= around[u] + around[v]:
                continue
            pairs += 1
            sep = separating(u, v)
            if sep <= d:
                continue
            r = sep / d if d > 0 else math.inf
            if r > ratio:
                ratio, worst = r, (u, v, d, sep)
    if ratio > 1.0 + FEASIBLE:
        u, v, d, sep = worst
        problems.append("points %d and %d: moats of %.9g m between them, %.9g m apart" %
                        (u, v, sep, d))
    scale = 1.0 / ratio
    bound = scale * total
    if free is not None:
        # The free end is at distance 0 from every point: its own moat absorbs the rest.
        load = max((scale * separating(free, v) for v in range(n)), default=0.0)
        bound += min(exact_width, -load)
    # This checker's own sums; and no path is shorter than 0.
    bound = max(0.0, bound - 1e-9 * (1.0 + abs(bound)))
    claimed = cert["lower_bound_distance_m"]
    if claimed > bound + 1e-7 * (1.0 + bound):
        problems.append("the certificate claims %.9f m but its moats prove %.9f m" % (claimed, bound))
    return bound, claimed, problems, pairs


def check_plan(cert, plan, bound):
    problems = []
    points, walls, free, metric = nodes_of(cert)
    pieces = plan.get("pieces", [])
    if plan.get("metric") != metric or plan.get("closed") != cert["closed"]:
        problems.append("the plan's metric or closed/open path differs from the certificate's")
    if len(pieces) != len(cert["walls"]):
        problems.append("the plan has %d pieces, the certificate %d walls" %
                        (len(pieces), len(cert["walls"])))
        return problems
    for k, (piece, (a, b)) in enumerate(zip(pieces, cert["walls"])):
        ends = (piece["start_m"], piece["end_m"])
        if any(abs(e[0] - points[p][0]) > POS or abs(e[1] - points[p][1]) > POS
               for e, p in zip(ends, (a, b))):
            problems.append("piece %d of the plan is not wall %d of the certificate" % (k, k))
    if not cert["closed"]:
        s = points[cert["start_point"]]
        if plan.get("start_m") is None or any(abs(x - y) > POS for x, y in zip(plan["start_m"], s)):
            problems.append("the plan starts elsewhere than the certificate's start point")
    airtime = plan["airtime_distance_m"]
    if airtime < bound - POS * (1 + len(pieces)):
        problems.append("the plan's airtime %.6f m is below the proven bound %.6f m" %
                        (airtime, bound))
    return problems


def self_test(cert):
    """Each corruption must be caught: (the ones that were not, how many were tried)."""
    missed = []
    base_bound, _, base_problems, _ = check(cert)
    if base_problems:
        return ["the certificate itself: " + p for p in base_problems], 0
    ordinary = [k for k, m in enumerate(cert["moats"]) if not m["exact"] and m["width_m"] > 0]
    cases = []

    # Only corruptions that apply: a certificate without moats (a layer that needs no
    # air move) has no width to widen.
    def widened(c):  # every width 1% wider: a pair the optimum uses breaks
        for m in c["moats"]:
            if not m["exact"]:
                m["width_m"] *= 1.01
        c["lower_bound_distance_m"] = base_bound * 1.01
    if ordinary:
        cases.append(("widths 1% wider", widened))

    def overclaimed(c):
        c["lower_bound_distance_m"] = base_bound * 1.001 + 1e-3
    cases.append(("a claim above the proof", overclaimed))

    singles = [k for k in ordinary if len(cert["moats"][k]["points"]) == 1]
    if singles:
        def rhs_two(c):
            c["moats"][singles[0]]["rhs"] = 2
        cases.append(("rhs 2 on an odd point", rhs_two))
        degree = {}
        for a, b in cert["walls"]:
            degree[a] = degree.get(a, 0) + 1
            degree[b] = degree.get(b, 0) + 1
        even = [p for p, d in degree.items() if d % 2 == 0 and p != cert.get("start_point")]
        if even:
            def moved(c):
                c["moats"][singles[0]]["points"] = [even[0]]
            cases.append(("rhs 1 on an even point", moved))

        def negative(c):
            c["moats"][singles[0]]["width_m"] = -0.01
        cases.append(("a negative width", negative))

        def exact(c):
            c["moats"][singles[0]]["exact"] = True
        cases.append(("an exact moat that is not the free end", exact))

    # A wall that leaves a moat of rhs 1: without it, an even number leave.
    crossing = [w for w, (a, b) in enumerate(cert["walls"])
                if any(m["rhs"] == 1 and (a in set(m["points"])) != (b in set(m["points"]))
                       for m in cert["moats"][:50])]
    if crossing:
        def wall_dropped(c):
            del c["walls"][crossing[0]]
        cases.append(("a wall left out", wall_dropped))

    for name, corrupt in cases:
        c = copy.deepcopy(cert)
        corrupt(c)
        try:
            problems = check(c)[2]
        except BadFile:
            problems = ["bad file"]
        if not problems:
            missed.append(name)
    return missed, len(cases)


def load(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        raise BadFile("cannot read %s: %s" % (path, e))


def main(argv):
    args = argv[1:]
    if not args or args[0] in ("-h", "--help"):
        print(__doc__)
        return 0 if args else 2
    try:
        if args[0] == "--self-test":
            need(len(args) == 2, "usage: check_bound.py --self-test CERT.json")
            missed, tried = self_test(load(args[1]))
            for m in missed:
                print("check_bound: self-test: not caught: %s" % m)
            print("check_bound: self-test: %d of %d corruptions caught" %
                  (tried - len(missed), tried))
            return 1 if missed else 0
        plan_path = None
        if "--plan" in args:
            i = args.index("--plan")
            need(i + 1 < len(args), "--plan needs a file")
            plan_path = args[i + 1]
            del args[i:i + 2]
        need(len(args) == 1, "usage: check_bound.py CERT.json [--plan PLAN.json]")
        cert = load(args[0])
        need(isinstance(cert, dict) and cert.get("format") == "ccbuild-bound-certificate-1",
             "%s: not a ccbuild bound certificate (format ccbuild-bound-certificate-1)" % args[0])
        bound, claimed, problems, pairs = check(cert)
        if plan_path:
            plan = load(plan_path)
            need(isinstance(plan, dict) and "airtime_distance_m" in plan,
                 "%s: not a plan-layer --json of one nozzle" % plan_path)
            problems += check_plan(cert, plan, bound)
    except BadFile as e:
        print("check_bound: %s" % e, file=sys.stderr)
        return 2
    for p in problems:
        print("check_bound: %s" % p)
    if problems:
        return 1
    print("check_bound: proven: every path is at least %.6f m in the air (claimed %.6f m; "
          "%d moats, %d pairs of points checked closely)" %
          (bound, claimed, len(cert["moats"]), pairs))
    if plan_path:
        airtime = plan["airtime_distance_m"]
        print("check_bound: the plan's %.6f m is %.4f%% above it" %
              (airtime, 100.0 * (airtime / bound - 1.0) if bound > 0 else 0.0))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
