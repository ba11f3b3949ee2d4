#!/usr/bin/env python3
"""Writes an IFC4 model of a grid of NX x NY rooms (4 m x 3 m, 150 mm concrete walls, a door
in every wall between two rooms along x) on STOREYS storeys of 3 m, in millimetres, placed
like tests/tools/make_ifc.py's house (the building turned on its site): for timing the IFC
import (bench/README.md).

With --mixed, the lines of walls take four thicknesses in turn (0.15, 0.20, 0.24 and 0.27 m,
each line one thickness) and the top storey's walls across the rooms (along y) are gables
from 2.0 m at their ends to a 3.0 m ridge in their middle (issue 50's benchmark).

Usage: make_grid_ifc.py NX NY STOREYS OUT.ifc [--mixed]"""

import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests",
                                "tools"))
import make_ifc  # noqa: E402


def main():
    nx, ny, storeys, out = int(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
    mixed = "--mixed" in sys.argv[5:]
    m = make_ifc.Model("IFC4", "mm")
    kinds = (0.15, 0.20, 0.24, 0.27) if mixed else (0.15,)
    for s in range(storeys):
        st = m.storey("Storey %d" % s, 3.0 * s)
        gables = mixed and s == storeys - 1
        # Lines along x (y = const) broken at every room, then along y.
        for j in range(ny + 1):
            t = kinds[j % len(kinds)]
            for i in range(nx):
                m.wall(st, "X %d %d %d" % (s, i, j), (4 * i, 3 * j), (4 * i + 4, 3 * j), t,
                       2.0 if gables else 3.0)
        for i in range(nx + 1):
            t = kinds[i % len(kinds)]
            for j in range(ny):
                if gables:
                    w = m.wall(st, "Y %d %d %d" % (s, i, j), (4 * i, 3 * j), (4 * i, 3 * j + 3),
                               t, 2.0, ridge_m=3.0)
                else:
                    w = m.wall(st, "Y %d %d %d" % (s, i, j), (4 * i, 3 * j), (4 * i, 3 * j + 3),
                               t, 3.0)
                if 0 < i < nx:
                    m.opening(w, "IFCDOOR", "Door %d %d %d" % (s, i, j), 1.0, 0.9, 0.0, 2.1, t)
    m.finish()
    with open(out, "w", newline="\n") as fh:
        fh.write(m.f.text(os.path.basename(out)))


if __name__ == "__main__":
    main()
