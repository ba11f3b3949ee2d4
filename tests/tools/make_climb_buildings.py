#!/usr/bin/env python3
"""Writes buildings of several footprints for fitting the climbing machine family to
(tests/CMakeLists.txt), independently of ccbuild: each a building file and its floor plans
in OUT_DIR, in metres, 3 m floors of 0.2 m layers, no anchor points (the default rule), the
machine the family FAMILY.

  box.yaml         12 m x 9 m, two storeys, a cross wall, a door and windows: a new user's
  ell.yaml         L-shaped, 16 m x 12 m less an 8 m x 6 m corner, three storeys
  setback.yaml     20 m x 14 m, four storeys, the top two set back 1.5 m on the east and
                   north sides
  long.yaml        30 m x 7 m, two storeys, cross walls every 5 m
  square.yaml      18 m x 18 m round a 6 m x 6 m courtyard, two storeys
  too_wide.yaml    60 m x 10 m: wider than the family's largest platform
  pinnacle.yaml    20 m x 20 m, then two storeys of a 4 m x 4 m room in its middle: no
                   unit reaches the first of them for the climb onto the second
  pinnacle_low.yaml  its first two storeys (a machine fits: the room is printed from the
                   pipes in the storey below)

Usage: make_climb_buildings.py OUT_DIR FAMILY"""

import os
import sys


class Plan:
    """Vertices and walls from segments, vertices shared where they coincide."""

    def __init__(self):
        self.vertices = {}
        self.walls = []
        self.openings = []

    def vertex(self, x, y):
        key = (round(x, 6), round(y, 6))
        if key not in self.vertices:
            self.vertices[key] = len(self.vertices) + 1
        return self.vertices[key]

    def wall(self, a, b):
        self.walls.append((self.vertex(*a), self.vertex(*b)))
        return len(self.walls)

    def ring(self, points):
        ids = []
        for k in range(len(points)):
            ids.append(self.wall(points[k], points[(k + 1) % len(points)]))
        return ids

    def opening(self, kind, wall, offset, width, sill=None):
        self.openings.append((kind, wall, offset, width, sill))

    def text(self):
        out = ["units: m", "vertices:"]
        for (x, y), i in sorted(self.vertices.items(), key=lambda kv: kv[1]):
            out.append("  - {id: %d, x: %g, y: %g}" % (i, x, y))
        out.append("walls:")
        for k, (a, b) in enumerate(self.walls):
            out.append("  - {id: %d, start: %d, end: %d}" % (k + 1, a, b))
        if self.openings:
            out.append("openings:")
            for k, (kind, wall, offset, width, sill) in enumerate(self.openings):
                extra = ", sill: %g" % sill if sill is not None else ""
                out.append("  - {id: O%d, kind: %s, wall: %d, offset: %g, width: %g%s, head: 2.1}"
                           % (k + 1, kind, wall, offset, width, extra))
        return "\n".join(out) + "\n"


def rectangle(plan, x0, y0, x1, y1):
    return plan.ring([(x0, y0), (x1, y0), (x1, y1), (x0, y1)])


def write_building(out, name, title, floors, family):
    lines = ["# %s (tests/tools/make_climb_buildings.py)" % title, "name: %s" % title,
             "units: m", "layer_height: 0.2", "slab_stage_h: 8",
             "material: %s" % os.path.relpath(
                 os.path.join(os.path.dirname(family), "..", "materials", "standard-mix.yaml"), out),
             "machine: %s" % os.path.relpath(family, out), "floors:"]
    for k, plan in enumerate(floors):
        plan_file = "%s-%d.yaml" % (name, k)
        with open(os.path.join(out, plan_file), "w") as f:
            f.write(plan.text())
        lines += ["  - name: level %d" % k, "    height: 3.0", "    plan: %s" % plan_file]
    with open(os.path.join(out, name + ".yaml"), "w") as f:
        f.write("\n".join(lines) + "\n")


def box():
    p = Plan()
    south, east, north, west = rectangle(p, 0, 0, 12, 9)
    p.wall((6, 0), (6, 9))
    p.opening("door", south, 2.0, 0.9)
    p.opening("window", north, 2.5, 1.2, 0.9)
    p.opening("window", east, 3.0, 1.2, 0.9)
    return p


def ell():
    p = Plan()
    outline = p.ring([(0, 0), (16, 0), (16, 6), (8, 6), (8, 12), (0, 12)])
    p.wall((8, 0), (8, 6))
    p.wall((0, 6), (8, 6))
    p.opening("door", outline[0], 3.0, 0.9)
    p.opening("window", outline[5], 2.0, 1.2, 0.9)
    return p


def setback(top):
    p = Plan()
    x1, y1 = (18.5, 12.5) if top else (20, 14)
    walls = rectangle(p, 0, 0, x1, y1)
    p.wall((10, 0), (10, y1))
    p.wall((0, 7), (10, 7))
    p.opening("window", walls[0], 4.0, 1.5, 0.9)
    return p


def long_block():
    p = Plan()
    walls = rectangle(p, 0, 0, 30, 7)
    for x in range(5, 30, 5):
        p.wall((x, 0), (x, 7))
    p.opening("door", walls[0], 1.5, 0.9)
    return p


def square():
    p = Plan()
    rectangle(p, 0, 0, 18, 18)
    rectangle(p, 6, 6, 12, 12)
    for a, b in [((0, 9), (6, 9)), ((12, 9), (18, 9)), ((9, 0), (9, 6)), ((9, 12), (9, 18))]:
        p.wall(a, b)
    return p


def plain(x1, y1, x0=0, y0=0):
    p = Plan()
    rectangle(p, x0, y0, x1, y1)
    return p


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    out, family = sys.argv[1], os.path.abspath(sys.argv[2])
    os.makedirs(out, exist_ok=True)
    write_building(out, "box", "Box 12 x 9", [box(), box()], family)
    write_building(out, "ell", "L-shaped block", [ell(), ell(), ell()], family)
    write_building(out, "setback", "Set back on two sides",
                   [setback(False), setback(False), setback(True), setback(True)], family)
    write_building(out, "long", "Long narrow block", [long_block(), long_block()], family)
    write_building(out, "square", "Courtyard square", [square(), square()], family)
    write_building(out, "too_wide", "Too wide", [plain(60, 10)], family)
    write_building(out, "pinnacle", "Pinnacle",
                   [plain(20, 20), plain(12, 12, 8, 8), plain(12, 12, 8, 8)], family)
    write_building(out, "pinnacle_low", "Pinnacle, two storeys",
                   [plain(20, 20), plain(12, 12, 8, 8)], family)


if __name__ == "__main__":
    main()
