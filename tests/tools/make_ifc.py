#!/usr/bin/env python3
"""Writes the IFC models the IFC import tests read (tests/data/ifc/), as plain STEP text,
independently of IFC++.

The building (house_*.ifc): an 8 m x 6 m house of two storeys in millimetres, placed the
way BIM tools place things: the site at the project's origin, the building on the site
turned by 90 degrees and moved to (10 m, 5 m), the storeys on the building at their
elevations, every wall on its storey at its start point, turned along its direction
(RefDirection), every opening on its wall. In the building's own frame (x east, y north):

  ground floor (elevation 0, walls 3000 mm tall)
    W-S  south wall (0,0)->(8,0)      Axis polyline + body rectangle; a door 900 wide at
                                      1000 from its start, 2100 high (the Revit way: the
                                      opening's profile in plan, extruded up)
    W-E  east wall  (8,0)->(8,6)      Axis + body as an arbitrary closed profile
    W-N  north wall (8,6)->(0,6)      Axis + body; a window 1200 wide at 4800 from its
                                      start, sill 900, head 2100 (the ArchiCAD way: the
                                      profile in the wall's elevation, extruded through)
    W-W  west wall  (0,6)->(0,0)      body only (no Axis): the axis is the rectangle's
    W-I  inner wall (4,0.075)->(4,5.925)  its axis stops at the faces of the outer walls, as
                                      architects draw; a door 900 wide at 2000 along its
                                      axis
    a curtain wall (IfcCurtainWall) and a curved wall (IfcWall whose axis is an arc)
  first floor (elevation 3000, walls 2800 mm tall)
    the same outer walls, an inner wall (0,3)->(8,3) and a partition of gypsum board
    (4,3)->(4,6) (a material the default filter leaves out)
  roof (elevation 6000): no walls

Walls are 150 mm thick (one nozzle of the bundled gantry), their material layer set
centred on the axis. The IFC4 file also has a true north and a map conversion.

  house_ifc4.ifc        the house, IFC4, millimetres
                        Its slabs (house_ifc4.ifc only): a ground slab (BASESLAB, top at
                        0, 200 mm, placed at its top and extruded down with a NEGATIVE
                        layer set, as Revit does), a stair landing (LANDING, top at 1.5 m:
                        not a slab the walls carry), the first floor's slab (FLOOR, top
                        at 3.0 m, 200 mm, placed at its underside and extruded up, as
                        ArchiCAD does) and a flat roof (IfcRoof in the roof storey made of
                        a ROOF slab, top at 6.0 m, 200 mm): both floors are 2.8 m of wall
                        under a 0.2 m slab.
  house_ifc2x3.ifc      the same house, IFC2X3, millimetres, without the roof storey and
                        without slabs (the ground floor runs to the first floor's
                        elevation, the first floor's height comes from its walls)
  thick_ifc4.ifc        one storey, outer walls 300 mm whose axis is their outer face (the
                        material layer set offset from it), metres
  feet_ifc2x3.ifc       one storey of four walls in feet (a conversion-based unit)
  layered_ifc4.ifc      one storey of four 300 mm walls without a material layer set, their
                        bodies as Revit exports them: the south and north walls one
                        extrusion per layer (100 + 100 + 100 mm side by side; the north
                        wall also a cornice swept along it), the east and west walls their
                        elevation extruded through them (the west wall's with a gable);
                        millimetres
  truncated.ifc         house_ifc4.ifc cut off in the middle of an entity
  self_placement.ifc    a wall whose placement is placed relative to itself
  nan.ifc               a wall whose placement point is 1.0E999 (not a finite number)
  no_walls.ifc          a storey without walls

Usage: make_ifc.py OUT_DIR"""

import hashlib
import math
import os
import sys


class Step:
    """Entities of one STEP file, numbered in the order they are made."""

    def __init__(self, schema):
        self.schema = schema
        self.lines = []

    def add(self, entity, *args):
        self.lines.append("%s(%s)" % (entity, ",".join(args)))
        return "#%d" % len(self.lines)

    def text(self, name):
        header = ("ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('ViewDefinition [CoordinationView]'),"
                  "'2;1');\nFILE_NAME('%s','2024-01-01T00:00:00',('ccbuild'),('ccbuild'),"
                  "'make_ifc.py','make_ifc.py','');\nFILE_SCHEMA(('%s'));\nENDSEC;\nDATA;\n"
                  % (name, self.schema))
        body = "".join("#%d=%s;\n" % (k + 1, line) for k, line in enumerate(self.lines))
        return header + body + "ENDSEC;\nEND-ISO-10303-21;\n"


def num(v):
    text = repr(float(v))
    if "e" in text or "E" in text:
        return "%.10E" % v
    return text if "." in text else text + "."


def s(text):
    return "'" + text.replace("'", "''") + "'"


def guid(n):
    """A 22-character GlobalId, distinct for each n (IFC's base-64 alphabet)."""
    alphabet = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz_$"
    v = int(hashlib.sha1(b"ccbuild %d" % n).hexdigest(), 16)
    out = ""
    for _ in range(21):
        out = alphabet[v % 64] + out
        v //= 64
    return "3" + out


class Model:
    def __init__(self, schema, unit="mm"):
        self.f = Step(schema)
        self.ifc4 = schema == "IFC4"
        self.n = 0
        f = self.f
        if self.ifc4:
            self.history = "$"
        else:
            person = f.add("IFCPERSON", "$", "$", "''", "$", "$", "$", "$", "$")
            org = f.add("IFCORGANIZATION", "$", "'ccbuild'", "$", "$", "$")
            po = f.add("IFCPERSONANDORGANIZATION", person, org, "$")
            app = f.add("IFCAPPLICATION", org, "'1'", "'make_ifc.py'", "'make_ifc'")
            self.history = f.add("IFCOWNERHISTORY", po, app, "$", ".ADDED.", "$", "$", "$",
                                 "0")
        self.origin = self.point(0, 0, 0)
        self.z = self.direction(0, 0, 1)
        self.x = self.direction(1, 0, 0)
        world = f.add("IFCAXIS2PLACEMENT3D", self.origin, "$", "$")
        north = self.direction(0.5, math.sqrt(3) / 2) if self.ifc4 else "$"
        self.context = f.add("IFCGEOMETRICREPRESENTATIONCONTEXT", "$", "'Model'", "3",
                             "1.0E-5", world, north)
        self.body_context = f.add("IFCGEOMETRICREPRESENTATIONSUBCONTEXT", "'Body'", "'Model'",
                                  "*", "*", "*", "*", self.context, "$", ".MODEL_VIEW.", "$")
        self.axis_context = f.add("IFCGEOMETRICREPRESENTATIONSUBCONTEXT", "'Axis'", "'Model'",
                                  "*", "*", "*", "*", self.context, "$", ".GRAPH_VIEW.", "$")
        if unit == "mm":
            length = f.add("IFCSIUNIT", "*", ".LENGTHUNIT.", ".MILLI.", ".METRE.")
            self.scale = 1000.0
        elif unit == "m":
            length = f.add("IFCSIUNIT", "*", ".LENGTHUNIT.", "$", ".METRE.")
            self.scale = 1.0
        else:  # feet
            metre = f.add("IFCSIUNIT", "*", ".LENGTHUNIT.", "$", ".METRE.")
            dims = f.add("IFCDIMENSIONALEXPONENTS", "1", "0", "0", "0", "0", "0", "0")
            factor = f.add("IFCMEASUREWITHUNIT", "IFCLENGTHMEASURE(0.3048)", metre)
            length = f.add("IFCCONVERSIONBASEDUNIT", dims, ".LENGTHUNIT.", "'FOOT'", factor)
            self.scale = 1 / 0.3048
        angle = f.add("IFCSIUNIT", "*", ".PLANEANGLEUNIT.", "$", ".RADIAN.")
        units = f.add("IFCUNITASSIGNMENT", "(%s,%s)" % (length, angle))
        self.project = f.add("IFCPROJECT", self.id(), self.history, "'ccbuild test house'", "$",
                             "$", "$", "$", "(%s)" % self.context, units)
        if self.ifc4:
            crs = f.add("IFCPROJECTEDCRS", "'EPSG:25832'", "$", "$", "$", "$", "$", "$")
            f.add("IFCMAPCONVERSION", self.context, crs, "458000.", "5438000.", "110.", "$",
                  "$", "$")
        # Site at the origin; the building on it turned by 90 degrees at (10 m, 5 m).
        site_place = self.placement(None, (0, 0, 0))
        self.site = f.add("IFCSITE", self.id(), self.history, "'Site'", "$", "$", site_place,
                          "$", "$", ".ELEMENT.", "$", "$", "$", "$", "$")
        self.building_place = self.placement(site_place, (10, 5, 0), (0, 1))
        self.building = f.add("IFCBUILDING", self.id(), self.history, "'House'", "$", "$",
                              self.building_place, "$", "$", ".ELEMENT.", "$", "$", "$")
        f.add("IFCRELAGGREGATES", self.id(), self.history, "$", "$", self.project,
              "(%s)" % self.site)
        f.add("IFCRELAGGREGATES", self.id(), self.history, "$", "$", self.site,
              "(%s)" % self.building)
        self.storeys = []
        self.materials = {}

    def id(self):
        self.n += 1
        return s(guid(self.n))

    def L(self, metres):
        return num(round(metres * self.scale, 9))

    def point(self, *c):
        return self.f.add("IFCCARTESIANPOINT", "(%s)" % ",".join(num(v) for v in c))

    def mpoint(self, *c):
        return self.f.add("IFCCARTESIANPOINT", "(%s)" % ",".join(self.L(v) for v in c))

    def direction(self, *c):
        return self.f.add("IFCDIRECTION", "(%s)" % ",".join(num(v) for v in c))

    def axis3(self, at, ref=None, axis=None):
        return self.f.add("IFCAXIS2PLACEMENT3D", self.mpoint(*at),
                          self.direction(*axis) if axis else "$",
                          self.direction(*(tuple(ref) + (0,)[:3 - len(ref)]))
                          if ref else "$")

    def placement(self, relative_to, at, ref=None):
        return self.f.add("IFCLOCALPLACEMENT", relative_to or "$", self.axis3(at, ref))

    def storey(self, name, elevation_m):
        place = self.placement(self.building_place, (0, 0, elevation_m))
        st = self.f.add("IFCBUILDINGSTOREY", self.id(), self.history, s(name), "$", "$", place,
                        "$", "$", ".ELEMENT.", self.L(elevation_m))
        self.storeys.append(st)
        self.contained = getattr(self, "contained", {})
        self.contained[st] = []
        return st, place

    def finish(self):
        f = self.f
        f.add("IFCRELAGGREGATES", self.id(), self.history, "$", "$", self.building,
              "(%s)" % ",".join(self.storeys))
        for st in self.storeys:
            if self.contained[st]:
                f.add("IFCRELCONTAINEDINSPATIALSTRUCTURE", self.id(), self.history, "$", "$",
                      "(%s)" % ",".join(self.contained[st]), st)

    def slab(self, storey, name, kind, top_m, thickness_m, style="down", roof=None):
        """A slab over the house's footprint, its top `top_m` above its storey: placed at its
        top and extruded down (Revit's way, its layer set NEGATIVE along AXIS3) or placed at
        its underside and extruded up (ArchiCAD's way). Contained in `storey`, or, with
        `roof` (a name), made part of an IfcRoof contained in it."""
        f = self.f
        st, st_place = storey
        z = top_m if style == "down" else top_m - thickness_m
        place = self.placement(st_place, (0, 0, z))
        solid = self.extrusion(self.rectangle((4, 3), 8.15, 6.15),
                               f.add("IFCAXIS2PLACEMENT3D", self.origin, "$", "$"), thickness_m,
                               (0, 0, -1) if style == "down" else (0, 0, 1))
        rep = f.add("IFCSHAPEREPRESENTATION", self.body_context, "'Body'", "'SweptSolid'",
                    "(%s)" % solid)
        sl = f.add("IFCSLAB", self.id(), self.history, s(name), "$", "$", place,
                   self.shape([rep]), "$", "." + kind + ".")
        f.add("IFCRELASSOCIATESMATERIAL", self.id(), self.history, "$", "$", "(%s)" % sl,
              self.layer_usage("Concrete", thickness_m, 0.0, ".AXIS3.",
                               ".NEGATIVE." if style == "down" else ".POSITIVE."))
        if roof:
            roof_place = self.placement(st_place, (0, 0, 0))
            r = f.add("IFCROOF", self.id(), self.history, s(roof), "$", "$", roof_place, "$",
                      "$", ".FLAT_ROOF.")
            f.add("IFCRELAGGREGATES", self.id(), self.history, "$", "$", r, "(%s)" % sl)
            self.contained[st].append(r)
        else:
            self.contained[st].append(sl)
        return sl

    def layer_usage(self, material, thickness_m, offset_m, axis=".AXIS2.",
                    sense=".POSITIVE."):
        f = self.f
        if material not in self.materials:
            self.materials[material] = f.add("IFCMATERIAL", s(material),
                                             *(("$", "$") if self.ifc4 else ()))
        mat = self.materials[material]
        layer = f.add("IFCMATERIALLAYER", mat, self.L(thickness_m), "$",
                      *(("$", "$", "$", "$") if self.ifc4 else ()))
        lset = f.add("IFCMATERIALLAYERSET", "(%s)" % layer, s(material),
                     *(("$",) if self.ifc4 else ()))
        return f.add("IFCMATERIALLAYERSETUSAGE", lset, axis, sense,
                     self.L(offset_m), *(("$",) if self.ifc4 else ()))

    def extrusion(self, profile, position, depth_m, direction=(0, 0, 1)):
        return self.f.add("IFCEXTRUDEDAREASOLID", profile, position, self.direction(*direction),
                          self.L(depth_m))

    def rectangle(self, centre, xdim, ydim):
        f = self.f
        pos = f.add("IFCAXIS2PLACEMENT2D", self.mpoint(*centre), self.direction(1, 0))
        return f.add("IFCRECTANGLEPROFILEDEF", ".AREA.", "$", pos, self.L(xdim), self.L(ydim))

    def polygon_profile(self, points):
        pts = [self.mpoint(*p) for p in points] + []
        poly = self.f.add("IFCPOLYLINE", "(%s)" % ",".join(pts + [pts[0]]))
        return self.f.add("IFCARBITRARYCLOSEDPROFILEDEF", ".AREA.", "$", poly)

    def shape(self, reps):
        return self.f.add("IFCPRODUCTDEFINITIONSHAPE", "$", "$", "(%s)" % ",".join(reps))

    def wall(self, storey, name, start, end, thickness_m, height_m, axis=True,
             body="rectangle", material="Concrete", entity=None, curve=None):
        """A straight wall from `start` to `end` (metres, storey frame): placed at its
        start, turned along it; returns (wall, its placement, its length)."""
        f = self.f
        st, st_place = storey
        dx, dy = end[0] - start[0], end[1] - start[1]
        length = math.hypot(dx, dy)
        place = self.placement(st_place, (start[0], start[1], 0), (dx / length, dy / length))
        reps = []
        if curve:  # an arc: the axis a trimmed circle
            circle = f.add("IFCCIRCLE", f.add("IFCAXIS2PLACEMENT2D", self.mpoint(0, curve),
                                               "$"), self.L(curve))
            arc = f.add("IFCTRIMMEDCURVE", circle, "(IFCPARAMETERVALUE(270.))",
                        "(IFCPARAMETERVALUE(330.))", ".T.", ".PARAMETER.")
            reps.append(f.add("IFCSHAPEREPRESENTATION", self.axis_context, "'Axis'", "'Curve2D'",
                              "(%s)" % arc))
        elif axis:
            line = f.add("IFCPOLYLINE", "(%s,%s)" % (self.mpoint(0, 0), self.mpoint(length, 0)))
            reps.append(f.add("IFCSHAPEREPRESENTATION", self.axis_context, "'Axis'", "'Curve2D'",
                              "(%s)" % line))
        if body == "rectangle":
            profile = self.rectangle((length / 2, 0), length, thickness_m)
        elif body == "polygon":
            h = thickness_m / 2
            profile = self.polygon_profile([(0, -h), (length, -h), (length, h), (0, h)])
        else:
            profile = None
        if profile:
            solid = self.extrusion(profile, f.add("IFCAXIS2PLACEMENT3D", self.origin, "$", "$"),
                                   height_m)
            reps.append(f.add("IFCSHAPEREPRESENTATION", self.body_context, "'Body'",
                              "'SweptSolid'", "(%s)" % solid))
        entity = entity or ("IFCWALLSTANDARDCASE" if axis and not curve else "IFCWALL")
        extra = ("$",) if self.ifc4 else ()
        w = f.add(entity, self.id(), self.history, s(name), "$", "$", place, self.shape(reps),
                  "$", *extra)
        self.contained[st].append(w)
        if material:
            f.add("IFCRELASSOCIATESMATERIAL", self.id(), self.history, "$", "$", "(%s)" % w,
                  self.layer_usage(material, thickness_m, -thickness_m / 2))
        return w, place, length

    def opening(self, wall, kind, name, along_m, width_m, sill_m, head_m, thickness_m,
                style="plan"):
        """An opening through `wall` (from wall()), filled by a door or window."""
        f = self.f
        w, wall_place, _ = wall
        height = head_m - sill_m
        if style == "plan":  # profile in plan, extruded up from the sill
            place = self.placement(wall_place, (along_m + width_m / 2, 0, sill_m))
            profile = self.rectangle((0, 0), width_m, thickness_m + 0.1)
            solid = self.extrusion(profile, f.add("IFCAXIS2PLACEMENT3D", self.origin, "$", "$"),
                                   height)
        else:  # profile in the wall's elevation, extruded through the wall
            place = self.placement(wall_place, (along_m, 0, sill_m))
            pos = self.axis3((0, thickness_m / 2 + 0.05, 0), ref=(1, 0, 0), axis=(0, -1, 0))
            profile = self.rectangle((width_m / 2, height / 2), width_m, height)
            solid = self.extrusion(profile, pos, thickness_m + 0.1)
        rep = f.add("IFCSHAPEREPRESENTATION", self.body_context, "'Body'", "'SweptSolid'",
                    "(%s)" % solid)
        extra = ("$",) if self.ifc4 else ()
        o = f.add("IFCOPENINGELEMENT", self.id(), self.history, s("Opening for " + name), "$",
                  "$", place, self.shape([rep]), "$", *extra)
        f.add("IFCRELVOIDSELEMENT", self.id(), self.history, "$", "$", w, o)
        filler_place = self.placement(place, (0, 0, 0))
        if self.ifc4:
            filler = f.add(kind, self.id(), self.history, s(name), "$", "$", filler_place, "$",
                           "$", self.L(height), self.L(width_m), "$", "$", "$")
        else:
            filler = f.add(kind, self.id(), self.history, s(name), "$", "$", filler_place, "$",
                           "$", self.L(height), self.L(width_m))
        f.add("IFCRELFILLSELEMENT", self.id(), self.history, "$", "$", o, filler)
        return o


def house(schema, roof=True, slabs=False):
    m = Model(schema, "mm")
    t = 0.15
    g = m.storey("Ground floor", 0.0)
    south = m.wall(g, "South wall", (0, 0), (8, 0), t, 3.0)
    m.wall(g, "East wall", (8, 0), (8, 6), t, 3.0, body="polygon")
    north = m.wall(g, "North wall", (8, 6), (0, 6), t, 3.0)
    m.wall(g, "West wall", (0, 6), (0, 0), t, 3.0, axis=False)
    inner = m.wall(g, "Inner wall", (4, t / 2), (4, 6 - t / 2), t, 3.0)
    m.opening(south, "IFCDOOR", "Front door", 1.0, 0.9, 0.0, 2.1, t, "plan")
    m.opening(north, "IFCWINDOW", "Kitchen window", 4.8, 1.2, 0.9, 2.1, t, "elevation")
    m.opening(inner, "IFCDOOR", "Hall door", 2.0, 0.9, 0.0, 2.1, t, "plan")
    m.wall(g, "Glass screen", (8, 6), (10, 6), 0.05, 3.0, entity="IFCCURTAINWALL",
           material="Glass", axis=False)
    m.wall(g, "Curved garden wall", (-3, 0), (-1, 0), t, 1.0, curve=4.0, body=None)
    if slabs:
        m.slab(g, "Ground slab", "BASESLAB", 0.0, 0.2)
        m.slab(g, "Stair landing", "LANDING", 1.5, 0.2)
    f1 = m.storey("First floor", 3.0)
    if slabs:
        m.slab(f1, "First floor slab", "FLOOR", 0.0, 0.2, style="up")
    h1 = 2.8
    m.wall(f1, "South wall", (0, 0), (8, 0), t, h1)
    m.wall(f1, "East wall", (8, 0), (8, 6), t, h1)
    north1 = m.wall(f1, "North wall", (8, 6), (0, 6), t, h1)
    m.wall(f1, "West wall", (0, 6), (0, 0), t, h1)
    m.wall(f1, "Landing wall", (0, 3), (8, 3), t, h1)
    m.wall(f1, "Bedroom partition", (4, 3), (4, 6), 0.1, h1, material="Gypsum board")
    m.opening(north1, "IFCWINDOW", "Bedroom window", 1.0, 1.5, 1.0, 2.2, t, "elevation")
    if roof:
        r = m.storey("Roof", 6.0)
        if slabs:
            m.slab(r, "Roof slab", "ROOF", 0.0, 0.2, roof="Flat roof")
    m.finish()
    return m.f


def thick():
    m = Model("IFC4", "m")
    g = m.storey("Ground", 0.0)
    t = 0.3
    # Outer walls drawn along their outer face (an anticlockwise ring): the layer set lies
    # to each wall's left, from the axis inwards.
    corners = [(0, 0), (6, 0), (6, 5), (0, 5)]
    for k in range(4):
        a, b = corners[k], corners[(k + 1) % 4]
        dx, dy = b[0] - a[0], b[1] - a[1]
        length = math.hypot(dx, dy)
        f = m.f
        place = m.placement(g[1], (a[0], a[1], 0), (dx / length, dy / length))
        line = f.add("IFCPOLYLINE", "(%s,%s)" % (m.mpoint(0, 0), m.mpoint(length, 0)))
        axis = f.add("IFCSHAPEREPRESENTATION", m.axis_context, "'Axis'", "'Curve2D'",
                     "(%s)" % line)
        profile = m.polygon_profile([(0, 0), (length, 0), (length - t, t), (t, t)])
        solid = m.extrusion(profile, f.add("IFCAXIS2PLACEMENT3D", m.origin, "$", "$"), 3.0)
        body = f.add("IFCSHAPEREPRESENTATION", m.body_context, "'Body'", "'SweptSolid'",
                     "(%s)" % solid)
        w = f.add("IFCWALL", m.id(), m.history, s("Outer wall %d" % (k + 1)), "$", "$", place,
                  m.shape([axis, body]), "$", "$")
        m.contained[g[0]].append(w)
        f.add("IFCRELASSOCIATESMATERIAL", m.id(), m.history, "$", "$", "(%s)" % w,
              m.layer_usage("Concrete C30/37", t, 0.0))
    # An inner wall of 150 mm meeting the outer ones in T junctions at their inner faces.
    m.wall(g, "Inner wall", (3, 0.3), (3, 4.7), 0.15, 3.0)
    m.finish()
    return m.f


def feet():
    m = Model("IFC2X3", "ft")
    g = m.storey("Ground", 0.0)
    t = 0.5 * 0.3048  # half a foot
    w, d = 20 * 0.3048, 15 * 0.3048
    corners = [(0, 0), (w, 0), (w, d), (0, d)]
    for k in range(4):
        m.wall(g, "Wall %d" % (k + 1), corners[k], corners[(k + 1) % 4], t, 10 * 0.3048)
    m.finish()
    return m.f


def layered():
    m = Model("IFC4", "mm")
    g = m.storey("Ground", 0.0)
    f = m.f
    t, h = 0.3, 3.0
    brick = f.add("IFCMATERIAL", s("Brick"), "$", "$")
    corners = [(0, 0), (6, 0), (6, 4), (0, 4)]
    for k, name in enumerate(["South wall", "East wall", "North wall", "West wall"]):
        a, b = corners[k], corners[(k + 1) % 4]
        dx, dy = b[0] - a[0], b[1] - a[1]
        length = math.hypot(dx, dy)
        place = m.placement(g[1], (a[0], a[1], 0), (dx / length, dy / length))
        line = f.add("IFCPOLYLINE", "(%s,%s)" % (m.mpoint(0, 0), m.mpoint(length, 0)))
        axis = f.add("IFCSHAPEREPRESENTATION", m.axis_context, "'Axis'", "'Curve2D'",
                     "(%s)" % line)
        solids = []
        if k % 2 == 0:  # three layers side by side, each its own extrusion
            for y in (-0.1, 0.0, 0.1):
                solids.append(m.extrusion(m.rectangle((length / 2, y), length, 0.1),
                                          f.add("IFCAXIS2PLACEMENT3D", m.origin, "$", "$"), h))
            if k == 2:  # a cornice on the north wall's outer face, swept along it
                pos = m.axis3((0, 0, 0), ref=(0, 1, 0), axis=(1, 0, 0))
                cornice = m.rectangle((-0.175, 2.8), 0.05, 0.1)
                solids.append(m.extrusion(cornice, pos, length))
        else:  # the elevation (x along the wall, y up), extruded through the wall
            top = [(length, h), (0, h)] if k == 1 else [(length, h), (length / 2, h + 0.5),
                                                        (0, h)]
            profile = m.polygon_profile([(0, 0), (length, 0)] + top)
            pos = m.axis3((0, t / 2, 0), ref=(1, 0, 0), axis=(0, -1, 0))
            solids.append(m.extrusion(profile, pos, t))
        body = f.add("IFCSHAPEREPRESENTATION", m.body_context, "'Body'", "'SweptSolid'",
                     "(%s)" % ",".join(solids))
        w = f.add("IFCWALL", m.id(), m.history, s(name), "$", "$", place,
                  m.shape([axis, body]), "$", "$")
        m.contained[g[0]].append(w)
        f.add("IFCRELASSOCIATESMATERIAL", m.id(), m.history, "$", "$", "(%s)" % w, brick)
    m.finish()
    return m.f


def small(schema="IFC4"):
    """One storey, one wall: the base of the hostile files."""
    m = Model(schema, "mm")
    g = m.storey("Ground", 0.0)
    w = m.wall(g, "Only wall", (0, 0), (4, 0), 0.15, 3.0)
    m.finish()
    return m, w


def args(line):
    """The top-level arguments of an entity's line ("IFCX(#1,#2)" -> ["#1", "#2"])."""
    return line[line.index("(") + 1:-1].split(",")


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    os.makedirs(out, exist_ok=True)

    def write(name, text):
        with open(os.path.join(out, name), "w", newline="\n") as fh:
            fh.write(text)

    write("house_ifc4.ifc", house("IFC4", slabs=True).text("house_ifc4.ifc"))
    write("house_ifc2x3.ifc", house("IFC2X3", roof=False).text("house_ifc2x3.ifc"))
    write("thick_ifc4.ifc", thick().text("thick_ifc4.ifc"))
    write("feet_ifc2x3.ifc", feet().text("feet_ifc2x3.ifc"))
    write("layered_ifc4.ifc", layered().text("layered_ifc4.ifc"))
    text = house("IFC4").text("truncated.ifc")
    write("truncated.ifc", text[: int(len(text) * 0.6)])
    # A wall's placement relative to itself.
    m, (wall, place, _) = small()
    k = int(place[1:]) - 1
    relative_to, axis = args(m.f.lines[k])
    m.f.lines[k] = "IFCLOCALPLACEMENT(%s,%s)" % (place, axis)
    write("self_placement.ifc", m.f.text("self_placement.ifc"))
    # A wall's placement point not a finite number.
    m, (wall, place, _) = small()
    relative_to, axis = args(m.f.lines[int(place[1:]) - 1])
    point = args(m.f.lines[int(axis[1:]) - 1])[0]
    m.f.lines[int(point[1:]) - 1] = "IFCCARTESIANPOINT((1.0E999,0.,0.))"
    write("nan.ifc", m.f.text("nan.ifc"))
    # A storey without walls.
    m = Model("IFC4", "mm")
    m.storey("Empty", 0.0)
    m.finish()
    write("no_walls.ifc", m.f.text("no_walls.ifc"))


if __name__ == "__main__":
    main()
