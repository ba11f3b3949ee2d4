#!/usr/bin/env python3
"""A building of N x M square rooms with masonry-thick walls, for timing walls as beads.

Writes DIR/grid-beads-NxM.yaml (one floor of 3 m in 0.5 m layers, so doors are open in
the lower layers and closed above) and its plan: rooms of ROOM m, every wall THICKNESS
thick (0.45 m by default: two skins and a 0.15 m core for the bundled 0.15 m nozzle),
walls split at every junction (L at the corners, T along the sides, X inside), a door in
every wall running along x that is inside the building. Usage:
    make_grid_beads.py DIR N M [--room 4] [--thickness 0.45] [--pattern solid]
"""
import argparse
import os


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dir")
    ap.add_argument("n", type=int)
    ap.add_argument("m", type=int)
    ap.add_argument("--room", type=float, default=4.0)
    ap.add_argument("--thickness", type=float, default=0.45)
    ap.add_argument("--pattern", default="solid")
    a = ap.parse_args()
    os.makedirs(a.dir, exist_ok=True)
    stem = "grid-beads-%dx%d" % (a.n, a.m)
    vid = lambda i, j: j * (a.n + 1) + i + 1
    lines = ["units: m", "vertices:"]
    for j in range(a.m + 1):
        for i in range(a.n + 1):
            lines.append("  - {id: %d, x: %g, y: %g}" % (vid(i, j), i * a.room, j * a.room))
    lines.append("walls:")
    walls, doors = [], []
    for j in range(a.m + 1):
        for i in range(a.n):
            walls.append((vid(i, j), vid(i + 1, j)))
            if 0 < j < a.m:
                doors.append(len(walls))
    for i in range(a.n + 1):
        for j in range(a.m):
            walls.append((vid(i, j), vid(i, j + 1)))
    for k, (s, e) in enumerate(walls, 1):
        lines.append("  - {id: %d, start: %d, end: %d, thickness: %g}" % (k, s, e, a.thickness))
    lines.append("openings:")
    for w in doors:
        lines.append("  - {wall: %d, offset: %g, width: 0.9, sill: 0, head: 2.1}" % (w, a.room / 2 - 0.45))
    with open(os.path.join(a.dir, stem + ".plan.yaml"), "w") as f:
        f.write("\n".join(lines) + "\n")
    config = os.path.relpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "config"), a.dir)
    with open(os.path.join(a.dir, stem + ".yaml"), "w") as f:
        f.write("name: %d x %d rooms, %g m walls as beads\nunits: m\nlayer_height: 0.5\n"
                "wall_pattern: %s\nmaterial: %s/materials/standard-mix.yaml\n"
                "machine: %s/machines/cc-gantry.yaml\nsite: {place: centre}\nfloors:\n"
                "  - {name: ground, height: 3.0, plan: %s.plan.yaml}\n"
                % (a.n, a.m, a.thickness, a.pattern, config, config, stem))
    print(os.path.join(a.dir, stem + ".yaml"))


if __name__ == "__main__":
    main()
