#!/usr/bin/env python3
"""Writes the DXF drawings the import tests read (tests/data/drawings/), as plain ASCII
DXF, independently of dxflib: two rooms side by side, 6 m x 4 m outside, 0.2 m walls, a
door in the wall between them and a window in the south wall.

  faces_mm.dxf        walls drawn as their two faces (closed polylines), millimetres, with
                      a stray face line that pairs with nothing
  faces_m.dxf         the same in metres
  centrelines_m.dxf   the same walls as centrelines (a polyline and a line), metres
  unitless.dxf        centrelines with $INSUNITS 0
  nan.dxf             a wall line with a NaN coordinate
  truncated.dxf       faces_mm.dxf cut off in the middle of an entity
  long_text.dxf       centrelines_m.dxf with a text of 2,000 characters (dxflib reads lines
                      of at most 1,024 and loops forever on a longer one) and trash after EOF
  binary.dxf          the start of a binary DXF
  gaps_faces_mm.dxf   two rooms with 0.3 m walls drawn as faces (lines) in millimetres, the
                      door and the window left as gaps in the wall lines (closed by jamb
                      lines), a glazing line across the window's gap on layer A-GLAZ
  gaps_m.dxf          the same as centrelines in metres, without jambs
  drafted_mm.dxf      gaps_faces_mm.dxf as drafters draw it: a door block and a window block
                      (SILL and HEAD attributes) inserted in the gaps, no glazing line, and a
                      window block on a wall drawn through
  attributes_m.dxf    centrelines in metres with attributed inserts (INSERT with 66 = 1,
                      ATTRIBs, SEQEND): a door with HEAD 2.3 (the drawing's unit), a window
                      with SILL 1000mm and HEAD 2.2m (tags in any case), a window with only
                      SILL 0.5 (its head the floor's default)
  attribute_not_number.dxf    the same, the window's SILL 'about a metre'
  attribute_out_of_range.dxf  the same, the door's HEAD 2100 (2.1 km in metres)

Usage: make_dxf.py OUT_DIR"""

import os
import sys


class Dxf:
    def __init__(self, insunits):
        self.insunits = insunits
        self.blocks, self.entities = [], []
        self.handle = 0x100

    def next_handle(self):
        self.handle += 1
        return "%X" % self.handle

    @staticmethod
    def pairs(*items):
        return "".join("%d\n%s\n" % (code, value) for code, value in items)

    def line(self, layer, a, b, into=None):
        (self.entities if into is None else into).append(self.pairs(
            (0, "LINE"), (5, self.next_handle()), (8, layer), (10, a[0]), (20, a[1]), (30, 0),
            (11, b[0]), (21, b[1]), (31, 0)))

    def polyline(self, layer, points, closed):
        items = [(0, "LWPOLYLINE"), (5, self.next_handle()), (8, layer), (90, len(points)),
                 (70, 1 if closed else 0)]
        for x, y in points:
            items += [(10, x), (20, y)]
        self.entities.append(self.pairs(*items))

    def block(self, name, width):
        body = [self.pairs((0, "BLOCK"), (5, self.next_handle()), (8, "0"), (2, name), (70, 0),
                           (10, 0), (20, 0), (30, 0), (3, name))]
        self.line("0", (0, 0), (width, 0), into=body)
        body.append(self.pairs((0, "ENDBLK"), (5, self.next_handle()), (8, "0")))
        self.blocks.append("".join(body))

    def insert(self, layer, name, at, angle, attributes=()):
        """An INSERT; with `attributes` ((tag, value), ...), group 66 = 1 and an ATTRIB per
        pair after it, ended by a SEQEND, as AutoCAD writes attributed blocks."""
        handle = self.next_handle()
        items = [(0, "INSERT"), (5, handle), (8, layer)]
        if attributes:
            items.append((66, 1))
        items += [(2, name), (10, at[0]), (20, at[1]), (30, 0), (41, 1), (42, 1), (43, 1),
                  (50, angle)]
        self.entities.append(self.pairs(*items))
        for tag, value in attributes:
            self.entities.append(self.pairs(
                (0, "ATTRIB"), (5, self.next_handle()), (330, handle), (100, "AcDbEntity"),
                (8, layer), (100, "AcDbText"), (10, at[0]), (20, at[1]), (30, 0), (40, 0.1),
                (1, value), (100, "AcDbAttribute"), (2, tag), (70, 0)))
        if attributes:
            self.entities.append(self.pairs((0, "SEQEND"), (5, self.next_handle()),
                                            (330, handle), (8, layer)))
        return handle

    def text(self):
        return (self.pairs((0, "SECTION"), (2, "HEADER"), (9, "$ACADVER"), (1, "AC1015"),
                           (9, "$INSUNITS"), (70, self.insunits), (0, "ENDSEC"))
                + self.pairs((0, "SECTION"), (2, "BLOCKS")) + "".join(self.blocks)
                + self.pairs((0, "ENDSEC"), (0, "SECTION"), (2, "ENTITIES"))
                + "".join(self.entities) + self.pairs((0, "ENDSEC"), (0, "EOF")))


def two_rooms_faces(k):
    """Faces, lengths times k (1000: millimetres)."""
    d = Dxf(4 if k == 1000 else 6)
    s = lambda pts: [(x * k, y * k) for x, y in pts]
    d.polyline("A-WALL", s([(0, 0), (6, 0), (6, 4), (0, 4)]), True)
    d.polyline("A-WALL", s([(0.2, 0.2), (2.9, 0.2), (2.9, 3.8), (0.2, 3.8)]), True)
    d.polyline("A-WALL", s([(3.1, 0.2), (5.8, 0.2), (5.8, 3.8), (3.1, 3.8)]), True)
    d.line("A-ANNO", (0, -1 * k), (6 * k, -1 * k))  # a dimension line: not a wall layer
    d.line("A-WALL", (0, -2 * k), (1 * k, -2 * k))  # a stray face line with no partner
    d.block("DOOR900", 0.9 * k)
    d.block("WIN1200", 1.2 * k)
    d.insert("A-DOOR", "DOOR900", (3.0 * k, 1.0 * k), 90)
    d.insert("A-GLAZ", "WIN1200", (3.8 * k, 0.1 * k), 0)
    return d


def two_rooms_centrelines(insunits=6):
    d = Dxf(insunits)
    d.polyline("WALLS", [(0.1, 0.1), (5.9, 0.1), (5.9, 3.9), (0.1, 3.9)], True)
    d.line("WALLS", (3.0, 0.1), (3.0, 3.9))
    d.block("DOOR900", 0.9)
    d.insert("DOORS", "DOOR900", (3.0, 1.0), 90)
    return d


def two_rooms_gaps_faces():
    """0.3 m walls as face lines, mm; the partition's door (y 1.0-1.9) and the south wall's
    window (x 3.8-5.0) are gaps with jamb lines across the wall at their ends."""
    d = Dxf(4)
    k = 1000
    line = lambda a, b, layer="A-WALL": d.line(layer, (a[0] * k, a[1] * k), (b[0] * k, b[1] * k))
    line((0, 0), (3.8, 0)); line((5.0, 0), (6, 0))                 # south, outer face
    line((6, 0), (6, 4)); line((6, 4), (0, 4)); line((0, 4), (0, 0))
    line((0.3, 0.3), (2.85, 0.3)); line((2.85, 0.3), (2.85, 1.0))  # room 1's inner faces
    line((2.85, 1.9), (2.85, 3.7)); line((2.85, 3.7), (0.3, 3.7)); line((0.3, 3.7), (0.3, 0.3))
    line((3.15, 0.3), (3.8, 0.3)); line((5.0, 0.3), (5.7, 0.3))    # room 2's inner faces
    line((5.7, 0.3), (5.7, 3.7)); line((5.7, 3.7), (3.15, 3.7))
    line((3.15, 3.7), (3.15, 1.9)); line((3.15, 1.0), (3.15, 0.3))
    line((2.85, 1.0), (3.15, 1.0)); line((2.85, 1.9), (3.15, 1.9))  # door jambs
    line((3.8, 0), (3.8, 0.3)); line((5.0, 0), (5.0, 0.3))          # window jambs
    line((3.8, 0.15), (5.0, 0.15), "A-GLAZ")                          # glazing
    return d


def two_rooms_drafted():
    """As drafters draw it (AIA layers, millimetres): gaps_faces_mm's walls broken at the
    door and the window, with jambs, no glazing line; a door block (A-DOOR) inserted in the
    partition's gap, a window block (A-GLAZ) in the south wall's gap with SILL 1000 and HEAD
    2200 (the drawing's millimetres), and a window block on the north wall drawn through
    (x 1.0-2.2 m; its sill and head the defaults)."""
    d = two_rooms_gaps_faces()
    d.entities.pop()  # the glazing line: the blocks say which opening is which
    d.block("DOOR900", 900)
    d.block("WIN1200", 1200)
    d.insert("A-DOOR", "DOOR900", (3000, 1000), 90)
    d.insert("A-GLAZ", "WIN1200", (3800, 150), 0, (("SILL", "1000"), ("HEAD", "2200")))
    d.insert("A-GLAZ", "WIN1200", (1000, 3850), 0)
    return d


def two_rooms_gaps_centrelines():
    d = Dxf(6)
    d.line("WALLS", (0.15, 0.15), (3.8, 0.15)); d.line("WALLS", (5.0, 0.15), (5.85, 0.15))
    d.polyline("WALLS", [(5.85, 0.15), (5.85, 3.85), (0.15, 3.85), (0.15, 0.15)], False)
    d.line("WALLS", (3.0, 0.15), (3.0, 1.0)); d.line("WALLS", (3.0, 1.9), (3.0, 3.85))
    d.line("GLAZING", (3.8, 0.15), (5.0, 0.15))
    return d


def two_rooms_attributes(door_attributes=(("head", "2.3"),),
                         window_attributes=(("SILL", "1000mm"), ("Head", "2.2m"))):
    """The centrelines (metres) with a door whose HEAD attribute is 2.3 (the drawing's
    unit), a window in the south wall with SILL 1000mm and HEAD 2.2m, and a window in the
    north wall with only a SILL of 0.5 (its head the floor's default)."""
    d = two_rooms_centrelines()
    d.entities.clear()
    d.blocks.clear()
    d.polyline("WALLS", [(0.1, 0.1), (5.9, 0.1), (5.9, 3.9), (0.1, 3.9)], True)
    d.line("WALLS", (3.0, 0.1), (3.0, 3.9))
    d.block("DOOR900", 0.9)
    d.block("WIN1200", 1.2)
    d.insert("DOORS", "DOOR900", (3.0, 1.0), 90, door_attributes)
    d.insert("WINDOWS", "WIN1200", (3.8, 0.1), 0, window_attributes)
    d.insert("WINDOWS", "WIN1200", (1.0, 3.9), 0, (("sill", "0.5"),))
    return d


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    faces = two_rooms_faces(1000).text()
    files = {
        "faces_mm.dxf": faces,
        "faces_m.dxf": two_rooms_faces(1).text(),
        "centrelines_m.dxf": two_rooms_centrelines().text(),
        "unitless.dxf": two_rooms_centrelines(0).text(),
        "truncated.dxf": faces[: len(faces) // 2],
        "gaps_faces_mm.dxf": two_rooms_gaps_faces().text(),
        "gaps_m.dxf": two_rooms_gaps_centrelines().text(),
        "drafted_mm.dxf": two_rooms_drafted().text(),
    }
    files["attributes_m.dxf"] = two_rooms_attributes().text()
    files["attribute_not_number.dxf"] = two_rooms_attributes(
        window_attributes=(("SILL", "about a metre"),)).text()
    files["attribute_out_of_range.dxf"] = two_rooms_attributes(
        door_attributes=(("HEAD", "2100"),)).text()  # millimetres in a drawing in metres
    nan = two_rooms_centrelines()
    nan.line("WALLS", (1.0, 1.0), ("nan", 2.0))
    files["nan.dxf"] = nan.text()
    long_text = two_rooms_centrelines()
    long_text.entities.append(Dxf.pairs((0, "TEXT"), (5, long_text.next_handle()), (8, "NOTES"),
                                        (10, 0), (20, 0), (30, 0), (40, 0.2), (1, "x" * 2000)))
    files["long_text.dxf"] = long_text.text() + "trash after the end\n"
    files["binary.dxf"] = "AutoCAD Binary DXF\r\n\x1a\x00"
    for name, text in files.items():
        with open(os.path.join(out, name), "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
