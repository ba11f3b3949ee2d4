#!/usr/bin/env python3
"""A large DXF floor plan for the import bench: NX x NY rooms of 4 m x 3 m (centre to
centre) with 0.2 m walls, written as face lines in millimetres (each room a closed
polyline, the outside one more) or as centrelines in metres (one line per wall between
two junctions), a door block inserted in every wall between two rooms along x.

Usage: make_grid_dxf.py NX NY faces|centrelines OUT.dxf"""

import sys


def pairs(*items):
    return "".join("%d\n%s\n" % (code, value) for code, value in items)


def main():
    nx, ny, how, out = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3], sys.argv[4]
    faces = how == "faces"
    k = 1000.0 if faces else 1.0  # millimetres for faces, metres for centrelines
    w, h, t = 4.0, 3.0, 0.2
    handle = [0x100]

    def next_handle():
        handle[0] += 1
        return "%X" % handle[0]

    entities = []

    def polyline(points):
        items = [(0, "LWPOLYLINE"), (5, next_handle()), (8, "A-WALL"), (90, len(points)), (70, 1)]
        for x, y in points:
            items += [(10, "%.6f" % (x * k)), (20, "%.6f" % (y * k))]
        entities.append(pairs(*items))

    def line(a, b):
        entities.append(pairs((0, "LINE"), (5, next_handle()), (8, "A-WALL"), (10, a[0] * k),
                              (20, a[1] * k), (30, 0), (11, b[0] * k), (21, b[1] * k), (31, 0)))

    if faces:
        polyline([(-t / 2, -t / 2), (nx * w + t / 2, -t / 2), (nx * w + t / 2, ny * h + t / 2),
                  (-t / 2, ny * h + t / 2)])
        for i in range(nx):
            for j in range(ny):
                x0, y0 = i * w + t / 2, j * h + t / 2
                polyline([(x0, y0), (x0 + w - t, y0), (x0 + w - t, y0 + h - t), (x0, y0 + h - t)])
    else:
        for j in range(ny + 1):
            for i in range(nx):
                line((i * w, j * h), ((i + 1) * w, j * h))
        for i in range(nx + 1):
            for j in range(ny):
                line((i * w, j * h), (i * w, (j + 1) * h))
    for i in range(1, nx):
        for j in range(ny):
            entities.append(pairs((0, "INSERT"), (5, next_handle()), (8, "A-DOOR"), (2, "DOOR900"),
                                  (10, i * w * k), (20, (j * h + 1.0) * k), (30, 0), (41, 1),
                                  (42, 1), (43, 1), (50, 90)))
    block = (pairs((0, "BLOCK"), (5, next_handle()), (8, "0"), (2, "DOOR900"), (70, 0), (10, 0),
                   (20, 0), (30, 0), (3, "DOOR900"))
             + pairs((0, "LINE"), (5, next_handle()), (8, "0"), (10, 0), (20, 0), (30, 0),
                     (11, 0.9 * k), (21, 0), (31, 0))
             + pairs((0, "ENDBLK"), (5, next_handle()), (8, "0")))
    text = (pairs((0, "SECTION"), (2, "HEADER"), (9, "$INSUNITS"), (70, 4 if faces else 6),
                  (0, "ENDSEC"), (0, "SECTION"), (2, "BLOCKS")) + block
            + pairs((0, "ENDSEC"), (0, "SECTION"), (2, "ENTITIES")) + "".join(entities)
            + pairs((0, "ENDSEC"), (0, "EOF")))
    with open(out, "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()
