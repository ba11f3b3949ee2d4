#!/usr/bin/env python3
"""Re-checks a ccbuild schedule (ccbuild schedule -o) from its JSON alone.

Independent of ccbuild's code: it reads only the document (docs/schedule.md) and
recomputes what it checks from the waypoints, the inputs and the events; the document's
derived numbers (layer times, intervals, totals, ...) are compared with the recomputed
ones, never used to compute them. It checks:
  1. structure: the keys and types; layers in building order; each layer's plan exists
     and has the layer's nozzle count;
  2. coverage: every wall piece of every plan deposited exactly once (the extruding
     spans labelled with it lie on it and cover its length once), no span on a piece
     the plan does not have;
  3. timing: time never runs backwards, deposition at the deposition speed, air moves
     within the axes' and the travel speed, z within the z speed, turns within the
     rotation speed, the heading within the stopper; the plan's layer time is its
     last waypoint's;
  4. gantries: adjacent nozzles (rail order) a gantry width apart at every breakpoint
     of either (the paths are piecewise linear, so that is exact);
  5. layers: each lasts its plan's layer time (and its nozzle times and longest idle
     are its plan's, the idle within the machine's limit), none overlaps the previous
     one or its move, the wait is the largest of its reasons, start-to-start intervals;
     the time between two layers is the events', the climbs' waits, the move and the
     wait, the pipes' as pipes_before_s; a purge exactly when the nozzle idled longer
     than its limit;
  6. local intervals: at each piece's ends and where a bead of either layer starts or
     ends along it (each side of such a point with the beads on that side), the time
     between the layer below depositing that point of the wall and this layer
     depositing it, compared with the document and
     with the material's minimum and maximum (an infeasible schedule must say so and
     may exceed the maximum); local_interval_min_at and _max_at must name a piece end
     where the recomputed interval is that minimum or maximum;
  7. strength: the layer below is old enough, at every piece end, to carry the walls
     from its bottom to this layer's top (density, g, safety factor, strength curve);
     so is every older layer, of this floor and of the floors below, aged from its end.
     Each min-interval and strength reason is the wait recomputed for it from the
     earliest start (the start less the wait and, when a purge preceded the layer, less
     the purge, which follows the wait): the layer below's strength and the older
     layers' (the longest any of them needs) are separate reasons; a needed wait has
     its reason. A load the material never carries is a problem, or, in a schedule
     marked infeasible, a note (no wait helps) at or after the place it names;
  8. events: in time order, outside every layer, each after the layer it names; pipes
     name their anchor; purges before the layers that say so; a climb starts only when
     every anchor of its stage has reached the anchor strength, counted from the end
     of the latest placement of that pipe (and its anchor-strength reasons are those
     waits); it follows its stage's last layer; its duration is its phases' sum.
  9. beads (walls thicker than one bead, and passes of another width than the nozzle's):
     each bead piece names its kind (pass, skin, core, tie) and a width; a pass, skin or
     tie lies within the machine's bead widths (bead_width_m, else the nozzle's width; a
     poured core is as wide as the skins leave); no two beads' footprints (the piece
     widened by half its width each side) overlap, except beads that meet end to end,
     which must not double back along each other, and two passes (one-pass walls meet
     on their middle lines);
 10. totals: makespan, layer count, nozzle times, moves, waits, pipes, purges, climbs,
     slabs, joints and machine time are what the layers and events add up to; each
     layer's concrete its plan's pieces x bead widths x its height, and where the model
     states its walls' volumes (inputs.provenance[].quantities), each floor's printed
     volume the sum of its layers' pieces; each wall's concrete recomputed from the
     nozzles' timed paths (every extruding span x its bead's width x its layer's height)
     is what its pieces hold, and a floor's what it prints against the model.
 11. site calendar (inputs.site): the working windows recomputed with Python's zoneinfo;
     every timestamp the local time of its seconds; attended printing, climbs, joints'
     treatments and crew-placed pipes each within one working window; an off-shift wait
     ending at the earliest window that holds the work; a planned joint only after
     off-shift hours, treated (a joint event) within the material's ages, and every
     layer over the maximum interval a planned joint; the days as the layers make them.

Usage: check_schedule.py SCHEDULE.json              exit 0 when sound, 1 with the problems
       check_schedule.py SCHEDULE.json --self-test  corrupts the document in many ways
                                                    and exits 0 only when each is caught
The self-test's corruptions that need a feature the document lacks (several nozzles, a
climb, a strength wait, a purge, a layer whose intervals differ) are left out; CTest's
feasible schedules (tests/CMakeLists.txt) between them have every feature but those of
an infeasible schedule.
Exit 2: not a schedule (unreadable, not JSON, another format or schema version).
"""

import argparse
import bisect
import datetime
import json
import math
import sys
import time

G = 9.80665        # m/s²
T_DOC = 1e-3       # s: a time the document states, against the recomputed one
ON_SPAN = 2e-3     # m: a point on a span, a span on its piece
COVER = 1e-3       # m: the spans' lengths against the piece's
ROUND_P = 2e-6     # m: two coordinates, each rounded to micrometres
ROUND_T = 2e-6     # s: two times, each rounded to microseconds
ROUND_A = 2e-6     # rad: two headings, each rounded to microradians
INTERVAL = 2.5e-6  # s: an interval from four times rounded to microseconds, against the bounds


def interval_tolerance(doc):
    """s: an interval against the bounds, at a point inside two paths' spans (a gable's
    piece ending mid-wall): each time is interpolated along a span whose ends' coordinates
    are rounded to micrometres, so is off by up to 2 x 0.5e-6 m over the deposition speed."""
    speed = doc["inputs"]["machine"].get("deposition_speed_m_s") or 0.0
    return INTERVAL + (2 * 2 * 0.5e-6 / speed if speed > 0 else 0.0)
WAIT_KINDS = ("min-interval", "strength", "anchor-strength", "slab", "off-shift", "joint", "cold",
              "wind")
EVENT_KINDS = ("pipe", "slab", "purge", "climb", "joint", "lintel", "pour")
MAX_SHOWN = 20


class NotASchedule(Exception):
    pass


# ---------------------------------------------------------------- 1. structure

NUM, INT, STR, BOOL, LIST, OBJ, NULL, POINT = "number", "integer", "string", "boolean", \
    "list", "object", "null", "point"

TOP = {"format": STR, "schema_version": INT, "inputs": OBJ, "feasible": BOOL,
       "infeasibility": (OBJ, NULL), "totals": OBJ, "layers": LIST, "plans": OBJ,
       "stages": LIST, "events": LIST, "warnings": LIST}
INPUTS = {"building": STR, "layer_height_m": NUM, "slab_stage_s": NUM, "machine": OBJ,
          "material": OBJ, "files": LIST}
MACHINE = {"deposition_speed_m_s": NUM, "travel_speed_m_s": NUM, "x_speed_m_s": NUM,
           "y_speed_m_s": NUM, "z_speed_m_s": NUM, "rotation_speed_rad_s": NUM,
           "stopper_min_rad": (NUM, NULL), "stopper_max_rad": (NUM, NULL), "nozzles": INT,
           "gantry_width_m": NUM, "rail_axis": STR, "purge_s": NUM, "kind": STR}
CLIMBING = {"anchor_strength_mpa": NUM, "pipe_embed_s": NUM}
MATERIAL = {"density_kg_m3": NUM, "min_layer_interval_s": NUM, "max_layer_interval_s": NUM,
            "safety_factor": NUM, "strength_curve": LIST}
CURVE_POINT = {"age_s": NUM, "strength_mpa": NUM}
TOTALS = {"makespan_s": NUM, "layers": INT, "deposition_s": NUM, "airtime_s": NUM,
          "moves_s": NUM, "waits_s": NUM, "pipes_s": NUM, "purges_s": NUM, "climbs_s": NUM,
          "slabs_s": NUM, "machine_s": NUM}
LAYER = {"floor": INT, "layer": INT, "z_m": NUM, "z_bottom_m": NUM, "geometry": INT,
         "plan": STR, "nozzles": INT, "method": STR, "start_s": NUM, "end_s": NUM,
         "deposition_s": NUM, "airtime_s": NUM, "max_idle_s": NUM, "move_before_s": NUM,
         "pipes_before_s": NUM, "wait_before_s": NUM, "wait_reasons": LIST,
         "purge_before": BOOL, "interval_s": (NUM, NULL), "local_interval_min_s": (NUM, NULL),
         "local_interval_max_s": (NUM, NULL), "local_interval_min_at": (OBJ, NULL),
         "local_interval_max_at": (OBJ, NULL), "piece_ends_checked": INT}
PIECE_END = {"wall": INT, "piece": INT, "x_m": NUM, "y_m": NUM}
REASON = {"kind": STR, "required_s": NUM, "from_s": NUM, "binding_s": NUM, "detail": STR}
PLAN = {"geometry": INT, "nozzles_used": INT, "method": STR, "z_top_m": NUM,
        "layer_time_s": NUM, "pieces": LIST, "nozzles": LIST}
PIECE = {"wall": INT, "piece": INT, "piece_count": INT, "start_m": POINT, "end_m": POINT,
         "length_m": NUM}
NOZZLE = {"nozzle": INT, "waypoints": LIST}
WAYPOINT = {"t_s": NUM, "x_m": NUM, "y_m": NUM, "z_m": NUM, "heading_rad": NUM,
            "extruding": BOOL, "wall": INT, "piece": INT}
EVENT = {"kind": STR, "start_s": NUM, "end_s": NUM, "floor": (INT, NULL),
         "after_layer": (INT, NULL), "detail": STR}
PIPE = {"anchor": OBJ}
CLIMB = {"from_stage": INT, "to_stage": INT, "wait_before_s": NUM, "wait_reasons": LIST,
         "anchors": LIST, "climb": OBJ}
CLIMB_ANCHOR = {"id": STR, "age_s": NUM, "strength_mpa": NUM, "required_mpa": NUM}
CLIMB_BODY = {"duration_s": NUM, "phases": LIST}
STAGE = {"stage": INT, "anchors": LIST}
# With a site calendar (inputs.site): timestamps beside the seconds, planned joints, days.
SITE = {"start": STR, "start_local": STR, "time_zone": STR, "working_hours": OBJ,
        "holidays": LIST, "printing": STR, "pipes": STR}
SITE_LAYER = {"start_time": STR, "end_time": STR, "planned_joint": BOOL}
SITE_EVENT = {"start_time": STR, "end_time": STR}
SITE_TOTALS = {"joints_s": NUM, "start_time": STR, "finish_time": STR}
JOINT = {"treatment_s": NUM, "min_age_s": NUM, "max_age_s": NUM}
LINTEL = {"opening": STR, "wall": INT, "from_m": NUM, "to_m": NUM, "sill_m": NUM, "head_m": NUM,
          "head_z_m": NUM, "type": STR, "by": STR}
DAY = {"date": STR, "layers": INT, "first": LIST, "last": LIST, "printing_s": NUM, "stop": STR,
       "detail": STR}


def type_ok(v, t):
    if isinstance(t, tuple):
        return any(type_ok(v, u) for u in t)
    if t == NUM:
        return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
    if t == INT:
        return isinstance(v, int) and not isinstance(v, bool)
    if t == POINT:
        return isinstance(v, list) and len(v) == 2 and all(type_ok(c, NUM) for c in v)
    return {STR: str, BOOL: bool, LIST: list, OBJ: dict, NULL: type(None)}[t] is type(v)


def keys_ok(obj, schema, where, problems):
    if not isinstance(obj, dict):
        problems.append("%s: not an object" % where)
        return False
    good = True
    for key, t in schema.items():
        if key not in obj:
            problems.append("%s: no `%s`" % (where, key))
            good = False
        elif not type_ok(obj[key], t):
            problems.append("%s: `%s` is %r, expected %s" % (where, key, obj[key],
                                                              t if isinstance(t, str) else " or ".join(t)))
            good = False
    return good


def check_structure(doc, problems):
    """Keys and types, so that the other checks can read the document."""
    if not keys_ok(doc, TOP, "document", problems):
        return
    inputs = doc["inputs"]
    if keys_ok(inputs, INPUTS, "inputs", problems):
        m = inputs["machine"]
        if keys_ok(m, MACHINE, "inputs.machine", problems):
            if m["rail_axis"] not in ("x", "y"):
                problems.append("inputs.machine: rail_axis %r is neither x nor y" % m["rail_axis"])
            if m["kind"] == "climbing":
                keys_ok(m, CLIMBING, "inputs.machine (climbing)", problems)
        if keys_ok(inputs["material"], MATERIAL, "inputs.material", problems):
            curve = inputs["material"]["strength_curve"]
            if not curve:
                problems.append("inputs.material: an empty strength curve")
            for i, p in enumerate(curve):
                if keys_ok(p, CURVE_POINT, "strength_curve[%d]" % i, problems) and i and \
                        type_ok(curve[i - 1], OBJ) and p["age_s"] <= curve[i - 1].get("age_s", -math.inf):
                    problems.append("strength_curve[%d]: ages not increasing" % i)
    keys_ok(doc["totals"], TOTALS, "totals", problems)
    site = inputs.get("site") if isinstance(inputs, dict) else None
    if site is not None:
        if keys_ok(site, SITE, "inputs.site", problems):
            keys_ok(site["working_hours"], {d: LIST for d in WEEKDAYS}, "inputs.site.working_hours",
                    problems)
        keys_ok(inputs["material"], {"planned_joint": OBJ}, "inputs.material", problems) and \
            keys_ok(inputs["material"]["planned_joint"], JOINT, "inputs.material.planned_joint", problems)
        keys_ok(doc["totals"], SITE_TOTALS, "totals", problems)
        if keys_ok(doc, {"days": LIST}, "document", problems):
            for i, d in enumerate(doc["days"]):
                keys_ok(d, DAY, "days[%d]" % i, problems)
    if any(isinstance(l, dict) and l.get("planned_joint") for l in doc["layers"]):
        keys_ok(inputs["material"], {"planned_joint": OBJ}, "inputs.material", problems) and \
            keys_ok(inputs["material"]["planned_joint"], JOINT, "inputs.material.planned_joint", problems)
    for i, e in enumerate(doc["events"]):
        if isinstance(e, dict) and e.get("kind") == "lintel":
            keys_ok(e, {"lintel": OBJ}, "event %d" % i, problems) and \
                keys_ok(e["lintel"], LINTEL, "event %d lintel" % i, problems)
        if isinstance(e, dict) and e.get("kind") == "pour":
            keys_ok(e, {"concrete_m3": NUM, "roof": BOOL}, "event %d" % i, problems)
    for i, layer in enumerate(doc["layers"]):
        where = "layers[%d]" % i
        if site is not None:
            keys_ok(layer, SITE_LAYER, where, problems)
        if keys_ok(layer, LAYER, where, problems):
            where = "floor %d layer %d" % (layer["floor"], layer["layer"])
            for j, r in enumerate(layer["wait_reasons"]):
                keys_ok(r, REASON, "%s wait_reasons[%d]" % (where, j), problems)
            for name in ("min", "max"):
                at = layer["local_interval_%s_at" % name]
                if at is not None:
                    keys_ok(at, PIECE_END, "%s local_interval_%s_at" % (where, name), problems)
    for key, plan in doc["plans"].items():
        where = "plan %s" % key
        if not keys_ok(plan, PLAN, where, problems):
            continue
        for j, piece in enumerate(plan["pieces"]):
            keys_ok(piece, PIECE, "%s pieces[%d]" % (where, j), problems)
        if not plan["nozzles"]:
            problems.append("%s: no nozzles" % where)
        for j, n in enumerate(plan["nozzles"]):
            if not keys_ok(n, NOZZLE, "%s nozzles[%d]" % (where, j), problems):
                continue
            if not n["waypoints"]:
                problems.append("%s nozzle %d: no waypoints" % (where, n["nozzle"]))
            for k, w in enumerate(n["waypoints"]):
                if not keys_ok(w, WAYPOINT, "%s nozzle %d waypoint %d" % (where, n["nozzle"], k),
                               problems):
                    break
    for i, s in enumerate(doc["stages"]):
        keys_ok(s, STAGE, "stages[%d]" % i, problems)
    for i, e in enumerate(doc["events"]):
        where = "event %d" % i
        if not keys_ok(e, EVENT, where, problems):
            continue
        if site is not None:
            keys_ok(e, SITE_EVENT, where, problems)
        where = "event %d (%s)" % (i, e["kind"])
        if e["kind"] not in EVENT_KINDS:
            problems.append("%s: unknown kind" % where)
        if e["kind"] == "pipe" and keys_ok(e, PIPE, where, problems):
            if not isinstance(e["anchor"].get("id"), str):
                problems.append("%s: its anchor has no id" % where)
        if e["kind"] == "climb" and keys_ok(e, CLIMB, where, problems):
            for j, a in enumerate(e["anchors"]):
                keys_ok(a, CLIMB_ANCHOR, "%s anchors[%d]" % (where, j), problems)
            for j, r in enumerate(e["wait_reasons"]):
                keys_ok(r, REASON, "%s wait_reasons[%d]" % (where, j), problems)
            if keys_ok(e["climb"], CLIMB_BODY, "%s climb" % where, problems):
                for j, p in enumerate(e["climb"]["phases"]):
                    keys_ok(p, {"duration_s": NUM}, "%s phase %d" % (where, j), problems)


def check_layer_order(doc, problems):
    """Building order, plans that exist with the layer's nozzles, the layer's height."""
    layers, plans = doc["layers"], doc["plans"]
    previous = None
    for layer in layers:
        where = "floor %d layer %d" % (layer["floor"], layer["layer"])
        here = (layer["floor"], layer["layer"])
        expected = [(0, 0)] if previous is None else [(previous[0], previous[1] + 1),
                                                      (previous[0] + 1, 0)]
        if here not in expected:
            problems.append("%s: out of building order (after %s)" % (
                where, "the start" if previous is None else "floor %d layer %d" % previous))
        previous = here
        plan = plans.get(layer["plan"])
        if plan is None:
            problems.append("%s: plan %s is not in plans" % (where, layer["plan"]))
            continue
        if not layer["nozzles"] == len(plan["nozzles"]) == plan["nozzles_used"]:
            problems.append("%s: %d nozzles, plan %s has %d nozzle paths and says %d used" % (
                where, layer["nozzles"], layer["plan"], len(plan["nozzles"]), plan["nozzles_used"]))
        if layer["method"] != plan["method"] or layer["geometry"] != plan["geometry"]:
            problems.append("%s: method %s geometry %d, plan %s has %s geometry %d" % (
                where, layer["method"], layer["geometry"], layer["plan"], plan["method"],
                plan["geometry"]))
        if layer["z_m"] <= layer["z_bottom_m"]:
            problems.append("%s: top %.6f m not above its bottom %.6f m" % (
                where, layer["z_m"], layer["z_bottom_m"]))
    if len(layers) != len({(l["floor"], l["layer"]) for l in layers}):
        problems.append("a layer is listed twice")


# ---------------------------------------------------------------- plans (2, 3, 4)

class Plan:
    """What the checks need of one plan, computed once for every layer that uses it."""

    def __init__(self, key, plan):
        self.key = key
        self.end_t = max(n["waypoints"][-1]["t_s"] for n in plan["nozzles"])
        self.deposition = self.airtime = self.max_idle = 0.0
        self.by_wall = {}       # wall -> [(x0, y0, x1, y1, t0, t1)] of the extruding spans
        self.waypoints = 0
        for n in plan["nozzles"]:
            w = n["waypoints"]
            self.waypoints += len(w)
            idle = 0.0          # the current run of air time between two depositions
            for a, b in zip(w, w[1:]):
                dt = b["t_s"] - a["t_s"]
                if a["extruding"]:
                    self.max_idle = max(self.max_idle, idle)
                    idle = 0.0
                    self.deposition += dt
                    self.by_wall.setdefault(a["wall"], []).append(
                        (a["x_m"], a["y_m"], b["x_m"], b["y_m"], a["t_s"], b["t_s"]))
                else:
                    self.airtime += dt
                    idle += dt
            self.max_idle = max(self.max_idle, idle)
        # Every piece: (wall, piece, start, end).
        self.pieces = [(p["wall"], p["piece"], p["start_m"], p["end_m"]) for p in plan["pieces"]]
        self.breakpoints = 0    # gantry breakpoints checked
        self.min_gap = None

    def times_at(self, wall, x, y):
        """The times an extruding span of `wall` passes within ON_SPAN of (x, y)."""
        out = []
        for x0, y0, x1, y1, t0, t1 in self.by_wall.get(wall, ()):
            dx, dy = x1 - x0, y1 - y0
            length2 = dx * dx + dy * dy
            f = 0.0 if length2 <= 1e-18 else min(1.0, max(0.0, ((x - x0) * dx + (y - y0) * dy) / length2))
            if math.hypot(x - x0 - f * dx, y - y0 - f * dy) <= ON_SPAN:
                out.append(t0 + f * (t1 - t0))
        return out


def check_coverage(key, plan, problems):
    """Every piece deposited once; no span off the plan's pieces."""
    pieces = {}
    counts = {}
    for piece in plan["pieces"]:
        label = (piece["wall"], piece["piece"])
        if label in pieces:
            problems.append("plan %s: wall %d piece %d listed twice" % ((key,) + label))
        pieces[label] = piece
        counts.setdefault(piece["wall"], []).append(piece)
    for wall, ps in counts.items():
        numbers = sorted(p["piece"] for p in ps)
        if numbers != list(range(1, len(ps) + 1)) or any(p["piece_count"] != len(ps) for p in ps):
            problems.append("plan %s: wall %d has pieces %s, its piece_count says %s" % (
                key, wall, numbers, sorted({p["piece_count"] for p in ps})))
    spans = {}                  # label -> [(from, to along the piece, length)]
    for n in plan["nozzles"]:
        w = n["waypoints"]
        for k in range(len(w) - 1):
            a, b = w[k], w[k + 1]
            if not a["extruding"]:
                continue
            where = "plan %s nozzle %d waypoint %d" % (key, n["nozzle"], k)
            label = (a["wall"], a["piece"])
            piece = pieces.get(label)
            if piece is None:
                problems.append("%s: extrudes wall %d piece %d, not a piece of the plan" % ((where,) + label))
                continue
            (sx, sy), (ex, ey) = piece["start_m"], piece["end_m"]
            length = math.hypot(ex - sx, ey - sy)
            ux, uy = ((ex - sx) / length, (ey - sy) / length) if length > 0 else (1.0, 0.0)
            along = []
            for q in (a, b):
                px, py = q["x_m"] - sx, q["y_m"] - sy
                t, off = px * ux + py * uy, abs(py * ux - px * uy)
                if off > ON_SPAN or t < -ON_SPAN or t > length + ON_SPAN:
                    problems.append("%s: the span on wall %d piece %d leaves the piece "
                                    "(%.4f, %.4f) m is %.4f m off it" % (
                                        where, label[0], label[1], q["x_m"], q["y_m"],
                                        max(off, -t, t - length)))
                    break
                along.append(t)
            else:
                spans.setdefault(label, []).append(
                    (min(along), max(along), math.hypot(b["x_m"] - a["x_m"], b["y_m"] - a["y_m"])))
    for label, piece in pieces.items():
        where = "plan %s wall %d piece %d" % ((key,) + label)
        (sx, sy), (ex, ey) = piece["start_m"], piece["end_m"]
        length = math.hypot(ex - sx, ey - sy)
        if abs(length - piece["length_m"]) > ROUND_P * 2:
            problems.append("%s: length_m %.6f, its ends are %.6f m apart" % (where, piece["length_m"], length))
        got = sorted(spans.get(label, []))
        if not got:
            problems.append("%s: never deposited" % where)
            continue
        total = sum(s[2] for s in got)
        if abs(total - piece["length_m"]) > COVER + 1e-6 * piece["length_m"]:
            problems.append("%s: its spans add up to %.6f m, the piece is %.6f m" % (where, total, piece["length_m"]))
        at = 0.0
        for s0, s1, _ in got:
            if s0 > at + ON_SPAN:
                problems.append("%s: %.4f m to %.4f m along it never deposited" % (where, at, s0))
            elif s0 < at - ON_SPAN:
                problems.append("%s: %.4f m to %.4f m along it deposited twice" % (where, s0, min(at, s1)))
            at = max(at, s1)
        if at < length - ON_SPAN:
            problems.append("%s: %.4f m to its end (%.4f m) never deposited" % (where, at, length))


BEAD_KINDS = ("pass", "skin", "core", "tie")
OVERLAP = 1e-6    # m: beads may overlap by a micrometre (the JSON rounds to one)


def footprint(a, b, width):
    """The piece widened by half its width each side, as 4 corners anticlockwise."""
    dx, dy = b[0] - a[0], b[1] - a[1]
    n = math.hypot(dx, dy)
    hx, hy = -dy / n * width / 2, dx / n * width / 2
    return [(a[0] - hx, a[1] - hy), (b[0] - hx, b[1] - hy), (b[0] + hx, b[1] + hy), (a[0] + hx, a[1] + hy)]


def clip_area(subject, clip):
    """Area common to two convex anticlockwise polygons (Sutherland-Hodgman)."""
    out = subject
    for i in range(len(clip)):
        if not out:
            return 0.0
        (ax, ay), (bx, by) = clip[i], clip[(i + 1) % len(clip)]
        side = lambda p: (bx - ax) * (p[1] - ay) - (by - ay) * (p[0] - ax)
        inp, out = out, []
        for j in range(len(inp)):
            p, q = inp[j], inp[(j + 1) % len(inp)]
            sp, sq = side(p), side(q)
            if sp >= 0:
                out.append(p)
            if (sp >= 0) != (sq >= 0):
                t = sp / (sp - sq)
                out.append((p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])))
    return abs(sum(out[i][0] * out[(i + 1) % len(out)][1] - out[(i + 1) % len(out)][0] * out[i][1]
                   for i in range(len(out)))) / 2 if len(out) >= 3 else 0.0


def check_beads(key, plan, machine, problems):
    """Beads name their kind and width, within the machine's range; no two overlap unless
    they meet end to end or both are passes."""
    narrowest, widest = machine.get("bead_width_m") or [machine["nozzle_width_m"]] * 2
    beads = []
    for piece in plan["pieces"]:
        if "bead" not in piece and "width_m" not in piece:
            continue
        label = "plan %s: wall %s piece %s" % (key, piece["wall"], piece["piece"])
        if piece.get("bead") not in BEAD_KINDS:
            problems.append("%s: bead kind %r is none of %s" % (label, piece.get("bead"), BEAD_KINDS))
            continue
        width = piece.get("width_m")
        if not isinstance(width, (int, float)) or isinstance(width, bool) or not 0 < width <= 10:
            problems.append("%s: bead width %r is not a width" % (label, width))
            continue
        if piece["bead"] != "core" and not narrowest - 1e-6 <= width <= widest + 1e-6:
            problems.append("%s: a %s %.6f m wide, outside the machine's bead widths %g to %g m"
                            % (label, piece["bead"], width, narrowest, widest))
        a, b = tuple(piece["start_m"]), tuple(piece["end_m"])
        if math.hypot(b[0] - a[0], b[1] - a[1]) <= 0:
            continue
        fp = footprint(a, b, width)
        box = (min(p[0] for p in fp), min(p[1] for p in fp), max(p[0] for p in fp), max(p[1] for p in fp))
        beads.append((label, a, b, width, fp, box, piece["bead"] == "pass"))
    beads.sort(key=lambda x: x[5][0])
    close = lambda p, q: math.hypot(p[0] - q[0], p[1] - q[1]) <= 1e-6
    for i, (li, ai, bi, wi, fi, xi, pi) in enumerate(beads):
        for lj, aj, bj, wj, fj, xj, pj in beads[i + 1:]:
            if xj[0] > xi[2]:
                break
            if xj[1] > xi[3] or xj[3] < xi[1] or (pi and pj):
                continue
            if any(close(p, q) for p in (ai, bi) for q in (aj, bj)):
                ux, uy = bi[0] - ai[0], bi[1] - ai[1]
                vx, vy = bj[0] - aj[0], bj[1] - aj[1]
                cross = ux * vy - uy * vx
                if abs(cross) <= 1e-9 * math.hypot(ux, uy) * math.hypot(vx, vy) and ux * vx + uy * vy != 0:
                    # collinear and meeting: they must continue, not double back
                    if not (close(bi, aj) or close(ai, bj)) or (close(ai, aj) or close(bi, bj)):
                        problems.append("%s and %s double back along each other" % (li, lj))
                continue
            area = clip_area(fi, fj)
            if area > OVERLAP * max(wi, wj):
                problems.append("%s and %s overlap (%.2g m2 of footprint in common)" % (li, lj, area))


def check_motion(key, plan, machine, info, problems):
    """Time, speeds, turns and the stopper along every nozzle's path; the layer time."""
    v_dep, v_travel = machine["deposition_speed_m_s"], machine["travel_speed_m_s"]
    vx, vy, vz = machine["x_speed_m_s"], machine["y_speed_m_s"], machine["z_speed_m_s"]
    rot = machine["rotation_speed_rad_s"]
    lo, hi = machine["stopper_min_rad"], machine["stopper_max_rad"]
    travel = {"x": machine["x_range_m"], "y": machine["y_range_m"]}
    for n in plan["nozzles"]:
        w = n["waypoints"]
        where = "plan %s nozzle %d" % (key, n["nozzle"])
        if w[0]["t_s"] < -ROUND_T:
            problems.append("%s: starts at t = %.6f s, before the layer's start" % (where, w[0]["t_s"]))
        if w[-1]["extruding"]:
            problems.append("%s: the last waypoint still extrudes" % where)
        for k, q in enumerate(w):
            # Coordinates are the machine's (the building placed, inputs.placement).
            for axis, (t0, t1) in travel.items():
                v = q[axis + "_m"]
                if v < t0 - ROUND_P or v > t1 + ROUND_P:
                    problems.append("%s waypoint %d: %s = %.6f m outside the machine's %s travel "
                                    "[%g, %g]" % (where, k, axis, v, axis, t0, t1))
            h = q["heading_rad"]
            if (lo is not None and h < lo - ROUND_A) or (hi is not None and h > hi + ROUND_A):
                problems.append("%s waypoint %d: heading %.6f rad past the stopper [%s, %s]" % (
                    where, k, h, lo, hi))
        for k in range(len(w) - 1):
            a, b = w[k], w[k + 1]
            at = "%s waypoint %d" % (where, k)
            dt = b["t_s"] - a["t_s"]
            if dt < -1e-9:
                problems.append("%s: time runs backwards (%.6f s -> %.6f s)" % (at, a["t_s"], b["t_s"]))
                continue
            dx, dy, dz = abs(b["x_m"] - a["x_m"]), abs(b["y_m"] - a["y_m"]), abs(b["z_m"] - a["z_m"])
            d = math.hypot(dx, dy)
            if dz > vz * (dt + ROUND_T) + ROUND_P:
                problems.append("%s: z changes %.6f m in %.6f s, over the z speed" % (at, dz, dt))
            turn = abs(b["heading_rad"] - a["heading_rad"])
            if turn > rot * (dt + ROUND_T) + ROUND_A:
                problems.append("%s: turns %.6f rad in %.6f s, over the rotation speed" % (at, turn, dt))
            if a["extruding"]:
                if abs(d - v_dep * dt) > 1e-3 * v_dep * dt + ROUND_P + v_dep * ROUND_T:
                    problems.append("%s: wall %d piece %d deposited at %s m/s (%.6f m in %.6f s), "
                                    "not the deposition speed %g" % (
                                        at, a["wall"], a["piece"],
                                        "%.4f" % (d / dt) if dt > 0 else "inf", d, dt, v_dep))
            else:
                fast = [name for name, dist, v in (("x", dx, vx), ("y", dy, vy), ("travel", d, v_travel))
                        if dist > v * dt * (1 + 1e-6) + ROUND_P + v * ROUND_T]
                if fast:
                    problems.append("%s: air move of %.6f m (x %.6f, y %.6f) in %.6f s, faster than "
                                    "the %s speed" % (at, d, dx, dy, dt, " and ".join(fast)))
    if abs(info.end_t - plan["layer_time_s"]) > T_DOC:
        problems.append("plan %s: layer_time_s %.6f, its paths end at %.6f s" % (
            key, plan["layer_time_s"], info.end_t))


def interpolate(track, times, t):
    """A piecewise linear coordinate at t, held before its first and after its last time."""
    j = bisect.bisect_right(times, t)
    if j == 0:
        return track[0][1]
    if j == len(track):
        return track[-1][1]
    (t0, p0), (t1, p1) = track[j - 1], track[j]
    return p0 if t1 <= t0 else p0 + (t - t0) / (t1 - t0) * (p1 - p0)


def check_gantries(key, plan, machine, info, problems):
    """Adjacent nozzles on common rails, a gantry width apart at every breakpoint; on fewer
    gantries than the machine has, room for the idle ones at the far end of the rails."""
    axis = machine["rail_axis"] + "_m"
    width = machine["gantry_width_m"]
    idle = machine.get("nozzles", 1) - len(plan["nozzles"])
    if idle > 0 and all("waypoints" in n for n in plan["nozzles"]):
        reach = max((q[axis] for n in plan["nozzles"] for q in n["waypoints"]), default=-math.inf)
        room = machine[machine["rail_axis"] + "_range_m"][1] - idle * width
        if reach > room + 1e-6:
            problems.append("plan %s: on %d of the machine's %d gantries the path reaches %.6f m "
                            "along %s, where the idle ones leave room only up to %.6f m" % (
                                key, len(plan["nozzles"]), machine["nozzles"], reach,
                                machine["rail_axis"], room))
    if len(plan["nozzles"]) < 2:
        return
    tracks = [[(q["t_s"], q[axis]) for q in n["waypoints"]] for n in plan["nozzles"]]
    smallest = math.inf
    for i in range(len(tracks) - 1):
        left, right = tracks[i], tracks[i + 1]
        lt, rt = [t for t, _ in left], [t for t, _ in right]
        worst = None
        # At each breakpoint, the nozzle's own waypoint against the other interpolated.
        for t, p in left:
            gap = interpolate(right, rt, t) - p
            if worst is None or gap < worst[0]:
                worst = (gap, t)
        for t, p in right:
            gap = p - interpolate(left, lt, t)
            if gap < worst[0]:
                worst = (gap, t)
        info.breakpoints += len(left) + len(right)
        smallest = min(smallest, worst[0])
        if worst[0] < width - 1e-6:
            problems.append("plan %s: nozzles %d and %d are %.6f m apart along %s at t = %.6f s, "
                            "under the gantry width %.6f m" % (
                                key, plan["nozzles"][i]["nozzle"], plan["nozzles"][i + 1]["nozzle"],
                                worst[0], machine["rail_axis"], worst[1], width))
    info.min_gap = smallest
    if plan.get("min_gap_m") is not None and abs(plan["min_gap_m"] - smallest) > 1e-5:
        problems.append("plan %s: min_gap_m %.6f, the closest the gantries come is %.6f m" % (
            key, plan["min_gap_m"], smallest))


# ---------------------------------------------------------------- layers (5, 6, 7)

class StrengthModel:
    """The material's strength against (equivalent) age: its curve (tested strengths)
    up to the curve's last age t1 (strength f1); from there on, where it states
    `strength_en1992`, the larger of f1 and the smaller of two estimates: EN 1992-1-1
    §3.1.2's fcm b(t) (from its `from_s` on) and f1 b(t) / b(t1), where
    b(t) = exp(s (1 - sqrt(28 days / t)))."""

    def __init__(self, material):
        self.points = [(p["age_s"], p["strength_mpa"]) for p in material["strength_curve"]]
        self.en = material.get("strength_en1992")

    def beta(self, age):
        return math.exp(self.en["s"] * (1 - math.sqrt(28 * 86400.0 / age))) if age > 0 else 0.0

    def eurocode(self, age):
        en = self.en
        if en is None or age <= 0:
            return 0.0
        stated = en["fcm_mpa"] * self.beta(age) if age >= en["from_s"] else 0.0
        t1, f1 = self.points[-1]
        return min(stated, f1 * self.beta(age) / self.beta(t1)) if t1 > 0 else stated

    def eurocode_age(self, mpa):
        en = self.en
        if en is None:
            return math.inf
        if mpa <= 0:
            return 0.0

        def reaching(fcm, from_s):
            if fcm <= 0:
                return math.inf
            ratio = math.log(mpa / fcm) / en["s"]
            return math.inf if ratio >= 1 else max(from_s, 28 * 86400.0 / (1 - ratio) ** 2)
        t1, f1 = self.points[-1]
        age = reaching(en["fcm_mpa"], en["from_s"])
        return max(age, reaching(f1 / self.beta(t1), 0.0)) if t1 > 0 else age


def strength_at(curve, age):
    """The strength curve at an age: linear between its points, flat outside them (and
    past its last point the Eurocode's, where the material states it and it is larger)."""
    if isinstance(curve, StrengthModel):
        table = strength_at(curve.points, age)
        return table if age < curve.points[-1][0] else max(table, curve.eurocode(age))
    if age <= curve[0][0]:
        return curve[0][1]
    for (a0, s0), (a1, s1) in zip(curve, curve[1:]):
        if age <= a1:
            return s0 + (s1 - s0) * (age - a0) / (a1 - a0)
    return curve[-1][1]


def age_reaching(curve, mpa):
    """The first age at which the curve reaches `mpa` (inf when it never does)."""
    if isinstance(curve, StrengthModel):
        tested = age_reaching(curve.points, mpa)
        return tested if tested < math.inf else max(curve.points[-1][0], curve.eurocode_age(mpa))
    if curve[0][1] >= mpa:
        return 0.0
    for (a0, s0), (a1, s1) in zip(curve, curve[1:]):
        if s1 >= mpa:
            return a0 + (a1 - a0) * (mpa - s0) / (s1 - s0)
    return math.inf


def check_binding(where, reasons, wait, problems):
    """Each reason's binding_s: how long, of the wait, it held (from from_s to required_s)
    and was the one of those holding that held the longest; together the whole wait."""
    cuts = sorted({max(0.0, r["from_s"]) for r in reasons} | {max(0.0, r["required_s"]) for r in reasons})
    bound = [0.0] * len(reasons)
    for a, b in zip(cuts, cuts[1:]):
        holding = [k for k, r in enumerate(reasons) if r["from_s"] <= a and r["required_s"] >= b]
        if holding:
            k = max(holding, key=lambda k: (reasons[k]["required_s"], -k))
            bound[k] += b - a
    for k, r in enumerate(reasons):
        if abs(r["binding_s"] - bound[k]) > T_DOC * (len(reasons) + 1):
            problems.append("%s wait reason %d (%s): binding_s %.6f, it was the binding one for "
                            "%.6f s" % (where, k, r["kind"], r["binding_s"], bound[k]))
    if reasons and abs(sum(r["binding_s"] for r in reasons) - wait) > T_DOC * (len(reasons) + 1):
        problems.append("%s: its reasons bind %.6f s of the %.6f s wait" % (
            where, sum(r["binding_s"] for r in reasons), wait))


def check_layers(doc, infos, problems):
    """Durations, order in time, waits, start-to-start intervals, nozzle times."""
    layers = doc["layers"]
    from_plan = {}              # (plan, what) -> [first problem, how many layers]
    limit = doc["inputs"]["machine"].get("nozzle_idle_limit_s")

    def per_plan(what, text):
        """A plan's number wrong in every layer using it: reported once, with a count."""
        key = (layer["plan"], what)
        if key in from_plan:
            from_plan[key][1] += 1
        else:
            from_plan[key] = [len(problems), 1]
            problems.append(text)
    for i, layer in enumerate(layers):
        where = "floor %d layer %d" % (layer["floor"], layer["layer"])
        info = infos[layer["plan"]]
        if abs(layer["end_s"] - layer["start_s"] - info.end_t) > T_DOC:
            problems.append("%s: lasts %.6f s (start %.6f, end %.6f), plan %s takes %.6f s" % (
                where, layer["end_s"] - layer["start_s"], layer["start_s"], layer["end_s"],
                layer["plan"], info.end_t))
        for name, value in (("deposition_s", info.deposition), ("airtime_s", info.airtime),
                            ("max_idle_s", info.max_idle)):
            if abs(layer[name] - value) > T_DOC:
                per_plan(name, "%s: %s %.6f, plan %s's paths give %.6f s" % (
                    where, name, layer[name], layer["plan"], value))
        if isinstance(limit, (int, float)) and info.max_idle > limit + T_DOC:
            per_plan("idle", "%s: plan %s idles a nozzle %.6f s between depositions, over the idle "
                     "limit %g s" % (where, layer["plan"], info.max_idle, limit))
        if i == 0:
            if layer["start_s"] < -T_DOC:
                problems.append("%s: starts at %.6f s, before 0" % (where, layer["start_s"]))
        else:
            prev = layers[i - 1]
            earliest = prev["end_s"] + layer["move_before_s"]
            if layer["start_s"] < earliest - T_DOC:
                problems.append("%s: starts at %.6f s, before the previous layer's end %.6f s and "
                                "the move %.6f s" % (where, layer["start_s"], prev["end_s"],
                                                     layer["move_before_s"]))
        reasons = layer["wait_reasons"]
        for j, r in enumerate(reasons):
            if r["kind"] not in WAIT_KINDS or not r["detail"].strip():
                problems.append("%s wait reason %d: kind %r, detail %r" % (where, j, r["kind"], r["detail"]))
        longest = max([r["required_s"] for r in reasons], default=0.0)
        if abs(layer["wait_before_s"] - longest) > T_DOC:
            problems.append("%s: wait_before_s %.6f, its reasons need %.6f s" % (
                where, layer["wait_before_s"], longest))
        check_binding(where, reasons, layer["wait_before_s"], problems)
        below = layers[i - 1] if i and layers[i - 1]["floor"] == layer["floor"] and \
            layers[i - 1]["layer"] == layer["layer"] - 1 else None
        if below is None:
            if layer["interval_s"] is not None:
                problems.append("%s: interval_s %.6f without a layer below on its floor" % (
                    where, layer["interval_s"]))
        else:
            if layer["interval_s"] is None or \
                    abs(layer["interval_s"] - (layer["start_s"] - below["start_s"])) > T_DOC:
                problems.append("%s: interval_s %s, start to start is %.6f s" % (
                    where, layer["interval_s"], layer["start_s"] - below["start_s"]))
            if abs(layer["z_bottom_m"] - below["z_m"]) > ROUND_P:
                problems.append("%s: bottom %.6f m, the layer below's top is %.6f m" % (
                    where, layer["z_bottom_m"], below["z_m"]))
    for index, count in from_plan.values():
        if count > 1:
            problems[index] += " (and in %d more layers using the plan)" % (count - 1)


def spans_along(plan, wall, ax, ay, ex, ey, length):
    """The spans of `plan` on `wall` along the piece from (ax, ay) in direction (ex, ey)
    over `length`: both ends within ON_SPAN of its line and more than a point of it
    covered. Each as (u at its start, u at its end, t at its start, t at its end), u in m
    from the piece's start."""
    out = []
    for x0, y0, x1, y1, t0, t1 in plan.by_wall.get(wall, ()):
        if abs((y0 - ay) * ex - (x0 - ax) * ey) > ON_SPAN or abs((y1 - ay) * ex - (x1 - ax) * ey) > ON_SPAN:
            continue
        ua, ub = (x0 - ax) * ex + (y0 - ay) * ey, (x1 - ax) * ex + (y1 - ay) * ey
        if min(ua, ub) > length - ON_SPAN or max(ua, ub) < ON_SPAN:
            continue
        out.append((ua, ub, t0, t1))
    return out


def time_along(span, u):
    ua, ub, ta, tb = span
    if abs(ub - ua) < 1e-12:
        return ta
    return ta + min(1.0, max(0.0, (u - ua) / (ub - ua))) * (tb - ta)


def checked_points(this, below):
    """Where the local intervals of this plan over the plan below are taken: along each
    piece, each layer's time is linear between the points where one of its spans starts
    or ends; at both ends of every stretch between such points (and the piece's ends)
    that both plans cover, with the spans that cover that stretch (a point where beads
    meet is taken once from each side). Yields (wall, piece, x, y, this plan's times
    there, the plan below's)."""
    for wall, piece, (ax, ay), (bx, by) in this.pieces:
        length = math.hypot(bx - ax, by - ay)
        if length < 1e-12:
            continue
        ex, ey = (bx - ax) / length, (by - ay) / length
        up = spans_along(this, wall, ax, ay, ex, ey, length)
        low = spans_along(below, wall, ax, ay, ex, ey, length)
        if not up or not low:
            continue
        cuts = sorted(min(length, max(0.0, u)) for s in up + low for u in s[:2])
        kept = [0.0]
        for u in cuts:
            if u - kept[-1] > ON_SPAN and length - u > ON_SPAN:
                kept.append(u)
        kept.append(length)
        for u0, u1 in zip(kept, kept[1:]):
            def covers(s):
                return min(s[0], s[1]) <= u0 + ON_SPAN and max(s[0], s[1]) >= u1 - ON_SPAN
            cu, cl = [s for s in up if covers(s)], [s for s in low if covers(s)]
            if not cu or not cl:
                continue
            for u in (u0, u1):
                yield (wall, piece, ax + u * ex, ay + u * ey, [time_along(s, u) for s in cu],
                       [time_along(s, u) for s in cl])


def pair_intervals(this, below):
    """The points of this plan's pieces over walls the plan below deposits where the
    intervals are taken (checked_points), with their intervals in plan times (this time -
    below time; where a point is passed more than once, the smallest difference counts
    for the minimum and the largest for the maximum).
    Returns (count, ends, low, high): ends maps (wall, piece) to [(x, y, smallest,
    largest)], low and high are (interval, wall, piece, x, y) at the extremes.
    Computed once per pair of plans."""
    count, ends, low, high = 0, {}, None, None
    for wall, piece, x, y, own, under in checked_points(this, below):
        count += 1
        lo = min(own) - max(under)
        hi = max(own) - min(under)
        ends.setdefault((wall, piece), []).append((x, y, lo, hi))
        if low is None or lo < low[0]:
            low = (lo, wall, piece, x, y)
        if high is None or hi > high[0]:
            high = (hi, wall, piece, x, y)
    return count, ends, low, high


class Maturity:
    """Equivalent age at 20 °C from the site's readings (each holds until the next) and the
    material's age function (ASTM C1074: Nurse-Saul or Arrhenius), counted from 0 s."""

    def __init__(self, doc):
        fn = doc["inputs"]["material"]["maturity"]
        readings = doc["inputs"]["site"]["conditions"]["readings"]
        if fn["function"] == "arrhenius":
            e = fn["activation_energy_j_mol"]

            def rate(T):
                return math.exp(-e / 8.314462618 * (1.0 / (T + 273.15) - 1.0 / 293.15))
        else:
            t0 = fn["datum_temperature_c"]

            def rate(T):
                return max(0.0, T - t0) / (20.0 - t0)
        self.readings = readings
        self.t = [r[0] for r in readings]
        self.rate = [rate(r[1]) for r in readings]
        f = [0.0]
        for i in range(1, len(self.t)):
            f.append(f[-1] + self.rate[i - 1] * (self.t[i] - self.t[i - 1]))
        self.f = f
        self.memo = {}
        zero = self.at(0.0)
        self.f = [v - zero for v in f]
        self.memo = {}

    def index(self, t):
        return max(bisect.bisect_right(self.t, t) - 1, 0)

    def at(self, t):
        # The same ends and starts are asked about for every layer above them.
        v = self.memo.get(t)
        if v is None:
            i = self.index(t)
            v = self.memo[t] = self.f[i] + self.rate[i] * (t - self.t[i])
        return v

    def age(self, a, b):
        return self.at(b) - self.at(a)

    def after(self, start, age):
        if age <= 0:
            return start
        if math.isinf(age):
            return math.inf
        target = self.at(start) + age
        i = bisect.bisect_left(self.f, target)
        seg = max(i - 1, 0)
        if self.rate[seg] <= 0:
            return start if i == 0 else math.inf
        return max(start, self.t[seg] + (target - self.f[seg]) / self.rate[seg])

    def all_ok(self, a, b, ok):
        """Whether every reading in force over [a, b) is ok."""
        i = self.index(a)
        while i < len(self.t) and (i == self.index(a) or self.t[i] < b - 1e-9):
            if not ok(self.readings[i]):
                return False
            i += 1
        return True


def maturity_of(doc):
    site = doc["inputs"].get("site")
    return Maturity(doc) if site is not None and site.get("conditions") is not None else None


def raw_ends(this, below):
    """Per point of checked_points: (this plan's earliest and latest time there, the plan
    below's earliest and latest), each in its own plan's time."""
    return [(min(own), max(own), min(under), max(under))
            for _, _, _, _, own, under in checked_points(this, below)]


def index_of(layers, floor, layer):
    """The index of floor `floor` layer `layer` in layers, or None."""
    return next((i for i, l in enumerate(layers) if (l["floor"], l["layer"]) == (floor, layer)), None)


def layer_below(layers, i):
    """The layer just below layers[i] on its floor; None for a floor's first layer, which
    stands on the slab."""
    if i and layers[i - 1]["floor"] == layers[i]["floor"] and \
            layers[i - 1]["layer"] == layers[i]["layer"] - 1:
        return layers[i - 1]
    return None


def earliest_start(layer, purge_s, joint_s=0.0):
    """When the layer could have started had nothing held it back: its start less its
    wait and, when the nozzle was purged before it, less the purge, and, on a planned
    joint, less the joint's treatment (`joint_s`), both of which follow the wait
    (docs/schedule.md, Waits). Every wait reason is counted from there."""
    return layer["start_s"] - layer["wait_before_s"] - (purge_s if layer["purge_before"] else 0.0) - \
        (joint_s if layer.get("planned_joint") else 0.0)


def joint_treatment_s(doc):
    """The planned joint's treatment, s (0 where the material states none)."""
    joint = doc["inputs"]["material"].get("planned_joint")
    return joint["treatment_s"] if joint else 0.0


def slab_ready_age_s(slabs):
    """The age at which a slab's concrete reaches its `ready_mpa` (EN 1992-1-1 §3.1.2:
    fcm exp(s (1 - sqrt(28 d / t))) solved for t), s."""
    c = slabs["concrete"]
    ratio = math.log(slabs["ready_mpa"] / c["fcm_mpa"]) / c["s"]
    return math.inf if ratio >= 1 else 28 * 86400.0 / (1 - ratio) ** 2


def older_layers(layers, i, has_below, curve, rho_g_sf, earliest, feasible, where, problems, notes,
                 mat=None):
    """Every layer under layers[i] but the one just below it (that one is checked piece
    by piece), on its floor and on the floors below, must carry the walls from its
    bottom to this layer's top at its age counted from its end, at this layer's start.
    Returns ((wait, that layer), never): the longest wait any of them needs from the
    earliest start (None when there is no such layer), and whether one of them carries
    more than the material ever reaches.
    In a document marked infeasible, a load the material never carries is the answer,
    not a bug: no wait can help, so the layer's older-layer shortfalls are notes and it
    needs no older-layer wait."""
    layer = layers[i]
    worst, short, never = None, [], False
    for j in range(i - 2 if has_below else i - 1, -1, -1):
        old = layers[j]
        load = rho_g_sf * (layer["z_m"] - old["z_bottom_m"])
        age = age_reaching(curve, load)
        never = never or math.isinf(age)
        old_age = mat.age(old["end_s"], layer["start_s"]) if mat else layer["start_s"] - old["end_s"]
        if old_age < age - T_DOC:
            short.append("%s: floor %d layer %d is %.6f s old at its start, it needs %.6f s to "
                         "carry %.6f MPa" % (where, old["floor"], old["layer"], old_age, age, load))
        need = (mat.after(old["end_s"], age) - earliest) if mat else age - (earliest - old["end_s"])
        if worst is None or need > worst[0]:
            worst = (need, old)
    if never and not feasible:
        notes.extend(short)
        return None, never
    problems.extend(short)
    return worst, never


def check_reasons(where, layer, min_need, below_need, older, problems):
    """Each min-interval and strength reason is the wait recomputed for it; a wait that
    is needed has its reason. Strength has two: the layer just below (piece by piece)
    and the older layers (the longest wait any of them needs)."""
    reasons = layer["wait_reasons"]
    by_kind = {}
    for r in reasons:
        by_kind.setdefault(r["kind"], []).append(r["required_s"])
    mins = by_kind.get("min-interval", [])
    if min_need is not None:
        if min_need > T_DOC and not mins:
            problems.append("%s: needs a %.6f s wait for the minimum interval, no min-interval "
                            "reason" % (where, min_need))
        for got in mins:
            if abs(got - min_need) > T_DOC:
                problems.append("%s: min-interval reason requires %.6f s, recomputed %.6f s" % (
                    where, got, min_need))
    elif mins:
        problems.append("%s: a min-interval reason without a layer below" % where)
    needs = []                  # (who, the wait it needs)
    if below_need is not None:
        needs.append(("the layer below", below_need))
    if older is not None:
        needs.append(("floor %d layer %d" % (older[1]["floor"], older[1]["layer"]), older[0]))
    strengths = by_kind.get("strength", [])
    recomputed = ", ".join("%s %.6f s" % n for n in needs) or "no layer under it"
    for got in strengths:
        if not any(abs(got - n) <= T_DOC for _, n in needs):
            problems.append("%s: strength reason requires %.6f s, recomputed: %s" % (
                where, got, recomputed))
    for who, need in needs:
        if need > T_DOC and not any(abs(got - need) <= T_DOC for got in strengths):
            problems.append("%s: %s needs a %.6f s wait for its strength, the strength reasons "
                            "say %s" % (where, who, need,
                                        ", ".join("%.6f s" % s for s in strengths) or "none"))


def check_at(where, layer, name, extreme, shift, ends, problems):
    """local_interval_<name>_at names a piece end of this layer's plan over a wall of the
    layer below whose recomputed interval is the extreme (any of them on a tie)."""
    key = "local_interval_%s_at" % name
    at = layer[key]
    if at is None:
        problems.append("%s: %s is null, the %s is %.6f s" % (where, key, name, extreme))
        return
    there = [e for e in ends.get((at["wall"], at["piece"]), ())
             if abs(e[0] - at["x_m"]) <= ROUND_P and abs(e[1] - at["y_m"]) <= ROUND_P]
    if not there:
        problems.append("%s: %s names wall %d piece %d at (%.6f, %.6f) m, not an end of a piece of "
                        "plan %s over a wall deposited below" % (
                            where, key, at["wall"], at["piece"], at["x_m"], at["y_m"], layer["plan"]))
        return
    value = shift + (min(e[2] for e in there) if name == "min" else max(e[3] for e in there))
    if abs(value - extreme) > T_DOC:
        problems.append("%s: %s names wall %d piece %d at (%.4f, %.4f) m, covered %.6f s after the "
                        "layer below there; the %s is %.6f s" % (
                            where, key, at["wall"], at["piece"], at["x_m"], at["y_m"], value, name,
                            extreme))


def check_intervals(doc, infos, problems, notes, stats):
    """Local intervals per piece end, against the document and the material; strength."""
    layers = doc["layers"]
    material = doc["inputs"]["material"]
    tolerance = interval_tolerance(doc)
    curve = StrengthModel(material)
    lo_bound, hi_bound = material["min_layer_interval_s"], material["max_layer_interval_s"]
    rho_g_sf = material["density_kg_m3"] * G * material["safety_factor"] * 1e-6
    purge_s = doc["inputs"]["machine"]["purge_s"]
    joint_s = joint_treatment_s(doc)
    mat = maturity_of(doc)
    feasible = doc["feasible"]
    cache, raw_cache = {}, {}
    overs = []                  # (layer, interval) over the maximum, when infeasible
    first_never = None          # the first layer some layer under it can never carry
    # Where a layer waits for strength (layer index -> the wait and what needs it), for
    # the self-test's choice of what to corrupt.
    stats["strength_waits"] = {}
    for i, layer in enumerate(layers):
        where = "floor %d layer %d" % (layer["floor"], layer["layer"])
        below = layer_below(layers, i)
        earliest = earliest_start(layer, purge_s, joint_s)
        older, never = older_layers(layers, i, below is not None, curve, rho_g_sf, earliest,
                                    feasible, where, problems, notes, mat)
        if never and first_never is None:
            first_never = i
        if older is not None and older[0] > T_DOC:
            stats["strength_waits"][i] = (older[0], older[1])
        claimed = ["local_interval_%s" % k for k in ("min_s", "max_s", "min_at", "max_at")
                   if layer["local_interval_%s" % k] is not None]
        if below is None:
            if claimed:
                problems.append("%s: %s without a layer below on its floor" % (where, ", ".join(claimed)))
            check_reasons(where, layer, None, None, older, problems)
            continue
        pair = (layer["plan"], below["plan"])
        if pair not in cache:
            cache[pair] = pair_intervals(infos[pair[0]], infos[pair[1]])
        count, ends, low, high = cache[pair]
        stats["ends"] += count
        shift = layer["start_s"] - below["start_s"]
        if count != layer["piece_ends_checked"]:
            problems.append("%s: piece_ends_checked %d, %d piece ends of plan %s lie on a wall "
                            "plan %s deposits below" % (where, layer["piece_ends_checked"], count,
                                                         pair[0], pair[1]))
        if count == 0:
            if claimed:
                problems.append("%s: %s, no piece end has a wall under it" % (where, ", ".join(claimed)))
            check_reasons(where, layer, None, None, older, problems)
            continue
        stats["layers"] += 1
        smallest, largest = shift + low[0], shift + high[0]
        for name, value, at in (("min", smallest, low), ("max", largest, high)):
            said = layer["local_interval_%s_s" % name]
            if said is None or abs(said - value) > T_DOC:
                problems.append("%s: local_interval_%s_s %s, recomputed %.6f s (wall %d piece %d at "
                                "(%.4f, %.4f) m)" % ((where, name, said, value) + at[1:]))
            check_at(where, layer, name, value, shift, ends, problems)
        if mat is not None:
            # With the site's weather the window and the strength are in equivalent age,
            # piece end by piece end.
            if pair not in raw_cache:
                raw_cache[pair] = raw_ends(infos[pair[0]], infos[pair[1]])
            raw = raw_cache[pair]
            s0, b0 = layer["start_s"], below["start_s"]
            smallest = min(mat.age(b0 + r[3], s0 + r[0]) for r in raw)
            largest = max(mat.age(b0 + r[2], s0 + r[1]) for r in raw)
            for name, value in (("min", smallest), ("max", largest)):
                said = layer.get("equivalent_interval_%s_s" % name)
                if said is None or abs(said - value) > T_DOC:
                    problems.append("%s: equivalent_interval_%s_s %s, recomputed %.6f s from the paths "
                                    "and the weather" % (where, name, said, value))
        if smallest < lo_bound - tolerance:
            problems.append("%s: wall %d piece %d at (%.4f, %.4f) m covered %.6f s after the layer "
                            "below, under the minimum interval %g s" % ((where,) + low[1:] + (smallest, lo_bound)))
        stats.setdefault("largest", {})[i] = largest
        if largest > hi_bound + tolerance and layer.get("planned_joint"):
            pass                # a planned joint: checked with the site's calendar (11)
        elif largest > hi_bound + tolerance:
            text = "%s: wall %d piece %d at (%.4f, %.4f) m covered %.6f s after the layer below, " \
                   "over the maximum interval %g s" % ((where,) + high[1:] + (largest, hi_bound))
            if feasible:
                problems.append(text)
            else:
                notes.append(text)
                overs.append((layer, largest))
        # 7. The layer below carries the walls from its bottom to this layer's top.
        load = rho_g_sf * (layer["z_m"] - below["z_bottom_m"])
        age = age_reaching(curve, load)
        # What the report draws of it: the strength at that age, and the load.
        if "below_strength_mpa" in layer:
            for key, want in (("below_strength_mpa", strength_at(curve, smallest)),
                              ("below_required_mpa", load)):
                if layer[key] is None or abs(layer[key] - want) > 1e-5:
                    problems.append("%s: %s %s, recomputed %.6f MPa" % (where, key, layer[key], want))
        if smallest < age - T_DOC:
            # As for the older layers: a load never carried is a note when infeasible.
            (notes if math.isinf(age) and not feasible else problems).append(
                "%s: wall %d piece %d at (%.4f, %.4f) m of the layer below is %.6f s old, it "
                "needs %.6f s to carry %.6f MPa" % ((where,) + low[1:] + (smallest, age, load)))
        # The waits as they would be recomputed: had the layer started at its earliest
        # start, its smallest interval would have been this much shorter.
        early = smallest - (layer["start_s"] - earliest)
        if math.isinf(age) and first_never is None:
            first_never = i
        below_need = None if math.isinf(age) and not feasible else age - early
        min_need = lo_bound - early
        if mat is not None:
            # Each end may be covered once the concrete deposited there last is old enough.
            b0 = below["start_s"]
            min_need = max(mat.after(b0 + r[3], lo_bound) - r[0] for r in raw) - earliest
            if below_need is not None:
                below_need = max(mat.after(b0 + r[3], age) - r[0] for r in raw) - earliest
        check_reasons(where, layer, min_need, below_need, older, problems)
        if below_need is not None and below_need > T_DOC and (
                i not in stats["strength_waits"] or below_need > stats["strength_waits"][i][0]):
            stats["strength_waits"][i] = (below_need, below)
    stats["pairs"] = len(cache)
    stats["overs"] = len(overs)
    stats["first_never"] = first_never
    bad = doc["infeasibility"]
    if first_never is not None and not feasible and isinstance(bad, dict):
        # The first place the schedule cannot be built is the one its infeasibility names.
        at = index_of(layers, bad.get("floor"), bad.get("layer"))
        if at is not None and at > first_never:
            problems.append("floor %d layer %d: a layer under it carries more than the material ever "
                            "reaches, before floor %s layer %s that the infeasibility names" % (
                                layers[first_never]["floor"], layers[first_never]["layer"],
                                bad.get("floor"), bad.get("layer")))
    if not feasible:
        bad = doc["infeasibility"]
        if not isinstance(bad, dict) or not str(bad.get("message", "")).strip() or \
                not isinstance(bad.get("fix"), dict) or not str(bad["fix"].get("text", "")).strip():
            problems.append("infeasible, and infeasibility has no message or no fix.text: %r" % (bad,))
        elif overs and bad.get("kind") == "max-interval":
            layer, largest = overs[0]
            if (bad.get("floor"), bad.get("layer")) != (layer["floor"], layer["layer"]) or \
                    not isinstance(bad.get("achieved_s"), (int, float)) or \
                    abs(bad["achieved_s"] - largest) > T_DOC:
                problems.append("infeasibility names floor %s layer %s, achieved %s s; the first layer "
                                "over the maximum is floor %d layer %d at %.6f s" % (
                                    bad.get("floor"), bad.get("layer"), bad.get("achieved_s"),
                                    layer["floor"], layer["layer"], largest))
            warned = " ".join(str(w) for w in doc["warnings"])
            # ccbuild names the next few and then says there are more; those beyond
            # the named ones are then listed by their local_interval_max_s alone.
            named = [w for w in doc["warnings"] if str(w).startswith("also infeasible: floor")]
            more = any(str(w).startswith("also infeasible: more layers") for w in doc["warnings"])
            for n, (layer, largest) in enumerate(overs[1:]):
                name = "floor %d layer %d" % (layer["floor"], layer["layer"])
                if more and n >= len(named):
                    continue
                if name + ":" not in warned:
                    problems.append("%s: over the maximum interval (%.6f s), not in warnings" % (name, largest))
        elif bad.get("kind") == "max-interval":
            problems.append("infeasible over the maximum interval at floor %s layer %s, no layer's "
                            "recomputed interval is over it" % (bad.get("floor"), bad.get("layer")))
    elif doc["infeasibility"] is not None:
        problems.append("feasible, with an infeasibility")


# ---------------------------------------------------------------- 8. events

def check_events(doc, problems, stats):
    layers, events = doc["layers"], doc["events"]
    machine = doc["inputs"]["machine"]
    curve = StrengthModel(doc["inputs"]["material"])
    starts = [l["start_s"] for l in layers]
    index = {(l["floor"], l["layer"]): i for i, l in enumerate(layers)}
    slabs, lintels = doc["inputs"].get("slabs"), doc["inputs"].get("lintels")
    duration = {"purge": machine["purge_s"],
                "slab": slabs["setup_s"] if slabs else doc["inputs"]["slab_stage_s"],
                "pipe": machine.get("pipe_embed_s"), "joint": joint_treatment_s(doc),
                "lintel": lintels["place_s"] if lintels else None}
    mat = maturity_of(doc)
    purges_end = []
    for i, e in enumerate(events):
        where = "event %d (%s)" % (i, e["kind"])
        if i and e["start_s"] < events[i - 1]["start_s"]:
            problems.append("%s: starts at %.6f s, before event %d (%.6f s): not sorted" % (
                where, e["start_s"], i - 1, events[i - 1]["start_s"]))
        if e["end_s"] < e["start_s"]:
            problems.append("%s: ends at %.6f s, before its start %.6f s" % (where, e["end_s"], e["start_s"]))
        if not e["detail"].strip():
            problems.append("%s: no detail" % where)
        want = duration.get(e["kind"])
        if want is not None and abs(e["end_s"] - e["start_s"] - want) > T_DOC:
            problems.append("%s: lasts %.6f s, the inputs say %g s" % (where, e["end_s"] - e["start_s"], want))
        j = bisect.bisect_left(starts, e["end_s"] - ROUND_T) - 1
        if j >= 0 and layers[j]["end_s"] > e["start_s"] + ROUND_T and e["end_s"] > e["start_s"]:
            problems.append("%s: %.6f..%.6f s overlaps floor %d layer %d (%.6f..%.6f s)" % (
                where, e["start_s"], e["end_s"], layers[j]["floor"], layers[j]["layer"],
                layers[j]["start_s"], layers[j]["end_s"]))
        after = index.get((e["floor"], e["after_layer"]))
        if e["kind"] == "purge":
            purges_end.append(e["end_s"])
        if after is None:
            problems.append("%s: after floor %s layer %s, which is not in layers" % (
                where, e["floor"], e["after_layer"]))
        elif after >= 0:
            nxt = layers[after + 1]["start_s"] if after + 1 < len(layers) else math.inf
            if e["start_s"] < layers[after]["end_s"] - T_DOC or e["end_s"] > nxt + T_DOC:
                problems.append("%s: %.6f..%.6f s is not between floor %d layer %d's end %.6f s and "
                                "the next layer's start %.6f s" % (
                                    where, e["start_s"], e["end_s"], e["floor"], e["after_layer"],
                                    layers[after]["end_s"], nxt))
        if e["kind"] == "pipe" and (e["anchor"].get("floor"), e["anchor"].get("after_layer")) != \
                (e["floor"], e["after_layer"]):
            problems.append("%s: cast after floor %s layer %s, its anchor says floor %s layer %s" % (
                where, e["floor"], e["after_layer"], e["anchor"].get("floor"), e["anchor"].get("after_layer")))
        if e["kind"] == "slab" and after is not None and after + 1 < len(layers) and \
                layers[after + 1]["floor"] == e["floor"]:
            problems.append("%s: a slab over floor %d before its top layer" % (where, e["floor"]))
        if e["kind"] == "climb":
            check_climb(doc, i, e, curve, problems, stats)
        if e["kind"] == "lintel":
            # Every layer of its floor at or over the head after it, every one under it before.
            lt = e["lintel"]
            for l in layers:
                if l["floor"] != e["floor"]:
                    continue
                mid = 0.5 * (l["z_bottom_m"] + l["z_m"])   # within rounding of the head: either side
                over, under = mid >= lt["head_z_m"] + ROUND_P, mid < lt["head_z_m"] - ROUND_P
                if over and l["start_s"] < e["end_s"] - T_DOC:
                    problems.append("%s: the lintel over opening %s is set until %.6f s, but floor %d layer %d, "
                                    "over its head at %.4f m, starts at %.6f s" % (
                                        where, lt["opening"], e["end_s"], l["floor"], l["layer"], lt["head_z_m"],
                                        l["start_s"]))
                if under and l["end_s"] > e["start_s"] + T_DOC:
                    problems.append("%s: the lintel over opening %s is set from %.6f s, before floor %d layer %d, "
                                    "under its head, ends at %.6f s" % (
                                        where, lt["opening"], e["start_s"], l["floor"], l["layer"], l["end_s"]))
            stats["lintels"] = stats.get("lintels", 0) + 1
        if e["kind"] == "pour":
            if slabs is None:
                problems.append("%s: a pour, but the inputs have no slabs" % where)
                continue
            want = e["concrete_m3"] / (slabs["pour_m3_h"] / 3600.0)
            if abs(e["end_s"] - e["start_s"] - want) > T_DOC + 1e-9 * want:
                problems.append("%s: pours %.6f m3 in %.6f s; at %g m3/h that takes %.6f s" % (
                    where, e["concrete_m3"], e["end_s"] - e["start_s"], slabs["pour_m3_h"], want))
            if not e["roof"]:
                age = slab_ready_age_s(slabs)
                ready = mat.after(e["end_s"], age) if mat is not None else e["end_s"] + age
                nxt = next((l for l in layers if l["floor"] > e["floor"]), None)
                if nxt is not None and nxt["start_s"] < ready - T_DOC:
                    problems.append("%s: floor %d layer %d starts at %.6f s, before the slab reaches %g MPa "
                                    "(at %.6f s)" % (where, nxt["floor"], nxt["layer"], nxt["start_s"],
                                                     slabs["ready_mpa"], ready))
            stats["pours"] = stats.get("pours", 0) + 1
    # A purge ends at the start of each layer that says so, and only there.
    purges_end.sort()
    for l in layers:
        k = bisect.bisect_left(purges_end, l["start_s"] - T_DOC)
        has = k < len(purges_end) and abs(purges_end[k] - l["start_s"]) <= T_DOC
        if has != l["purge_before"]:
            problems.append("floor %d layer %d: purge_before %s, %s purge event ends at its start" % (
                l["floor"], l["layer"], l["purge_before"], "a" if has else "no"))
    check_between(doc, problems)
    if sum(1 for l in layers if l["purge_before"]) != len(purges_end):
        problems.append("%d purge events, %d layers with purge_before" % (
            len(purges_end), sum(1 for l in layers if l["purge_before"])))


def check_between(doc, problems):
    """Between two layers every second is the events', the climbs' waits, the move's or
    the wait's; pipes_before_s is the pipes'; a purge exactly when the nozzle idled
    longer than its limit."""
    layers = doc["layers"]
    events = sorted(doc["events"], key=lambda e: e["start_s"])
    starts = [e["start_s"] for e in events]
    limit = doc["inputs"]["machine"].get("nozzle_idle_limit_s")
    for k in range(1, len(events)):
        if events[k]["start_s"] < events[k - 1]["end_s"] - T_DOC:
            problems.append("events at %.6f s (%s) and %.6f s (%s) overlap" % (
                events[k - 1]["start_s"], events[k - 1]["kind"], events[k]["start_s"], events[k]["kind"]))
    for i in range(1, len(layers)):
        prev, layer = layers[i - 1], layers[i]
        where = "floor %d layer %d" % (layer["floor"], layer["layer"])
        j = bisect.bisect_left(starts, prev["end_s"] - T_DOC)
        between = []
        while j < len(events) and events[j]["start_s"] <= layer["start_s"] + T_DOC:
            if events[j]["end_s"] <= layer["start_s"] + T_DOC:
                between.append(events[j])
            j += 1
        busy = sum(e["end_s"] - e["start_s"] for e in between)
        waits = sum(e.get("wait_before_s", 0.0) for e in between)   # climbs' and crew tasks' waits
        gap = layer["start_s"] - prev["end_s"]
        if abs(gap - busy - waits - layer["move_before_s"] - layer["wait_before_s"]) > T_DOC:
            problems.append("%s: %.6f s since the previous layer's end; its events (%.6f s), climbs' "
                            "waits (%.6f s), move (%.6f s) and wait (%.6f s) account for %.6f s" % (
                                where, gap, busy, waits, layer["move_before_s"], layer["wait_before_s"],
                                busy + waits + layer["move_before_s"] + layer["wait_before_s"]))
        pipes = sum(e["end_s"] - e["start_s"] for e in between if e["kind"] == "pipe")
        if abs(pipes - layer["pipes_before_s"]) > T_DOC:
            problems.append("%s: pipes_before_s %.6f, the pipe events before it last %.6f s" % (
                where, layer["pipes_before_s"], pipes))
        if isinstance(limit, (int, float)):
            purge = [e for e in between if e["kind"] == "purge"]
            idle = (purge[-1]["start_s"] if purge else layer["start_s"]) - prev["end_s"]
            if layer["purge_before"] and idle < limit - T_DOC:
                problems.append("%s: a purge after the nozzle idled %.6f s, under its limit %g s" % (
                    where, idle, limit))
            if not layer["purge_before"] and idle > limit + T_DOC:
                problems.append("%s: the nozzle idled %.6f s, over its limit %g s, and no purge" % (
                    where, idle, limit))


def check_climb(doc, i, e, curve, problems, stats):
    """Anchors old enough, recomputed from the pipes' placements; the climb's durations."""
    where = "event %d (climb %d -> %d)" % (i, e["from_stage"], e["to_stage"])
    required = doc["inputs"]["machine"].get("anchor_strength_mpa")
    stats["climbs"] += 1
    pipes = {}
    for p in doc["events"]:
        if p["kind"] == "pipe" and p["end_s"] <= e["start_s"] + ROUND_T:
            pipes[p["anchor"]["id"]] = max(pipes.get(p["anchor"]["id"], -math.inf), p["end_s"])
    stages = doc["stages"]
    if e["to_stage"] != e["from_stage"] + 1:
        problems.append("%s: does not climb to the next stage" % where)
    elif 0 <= e["from_stage"] < len(stages):
        last = stages[e["from_stage"]].get("last") or {}
        if (last.get("floor"), last.get("layer")) != (e["floor"], e["after_layer"]):
            problems.append("%s: after floor %s layer %s, stage %d ends at floor %s layer %s" % (
                where, e["floor"], e["after_layer"], e["from_stage"], last.get("floor"), last.get("layer")))
    if 0 <= e["to_stage"] < len(stages):
        ids = sorted(a.get("id") for a in stages[e["to_stage"]]["anchors"])
        if sorted(a["id"] for a in e["anchors"]) != ids:
            problems.append("%s: anchors %s, stage %d holds %s" % (
                where, sorted(a["id"] for a in e["anchors"]), e["to_stage"], ids))
    else:
        problems.append("%s: stage %d is not in stages" % (where, e["to_stage"]))
    earliest = e["start_s"] - e["wait_before_s"]
    needs = []                  # the wait each anchor needs from the earliest start
    for a in e["anchors"]:
        stats["anchors"] += 1
        at = "%s anchor %s" % (where, a["id"])
        if required is None or abs(a["required_mpa"] - required) > 1e-6:
            problems.append("%s: required_mpa %g, the machine's anchor strength is %s" % (
                at, a["required_mpa"], required))
        cast = pipes.get(a["id"])
        if cast is None:
            problems.append("%s: no pipe event places it before the climb" % at)
            continue
        age = e["start_s"] - cast
        mat = maturity_of(doc)
        equivalent = mat.age(cast, e["start_s"]) if mat else age
        mpa = strength_at(curve, equivalent)
        if required is not None:
            needs.append((mat.after(cast, age_reaching(curve, required)) if mat else
                          cast + age_reaching(curve, required)) - earliest)
        if abs(a["age_s"] - age) > T_DOC:
            problems.append("%s: age_s %.6f, the climb starts %.6f s after its pipe's placement" % (
                at, a["age_s"], age))
        if mat and abs(a.get("equivalent_age_s", math.nan) - equivalent) > T_DOC:
            problems.append("%s: equivalent_age_s %s, recomputed %.6f s from the weather" % (
                at, a.get("equivalent_age_s"), equivalent))
        if abs(a["strength_mpa"] - mpa) > 1e-5:
            problems.append("%s: strength_mpa %.6f, the curve gives %.6f at %.6f s" % (
                at, a["strength_mpa"], mpa, equivalent))
        if mpa < (required if required is not None else a["required_mpa"]) - 1e-6:
            problems.append("%s: %.6f MPa at %.6f s, under the anchor strength %g MPa (needs %.6f s)" % (
                at, mpa, equivalent, required, age_reaching(curve, required)))
    # The youngest anchor's strength the report draws: from its casting to the climb, in
    # equal steps, each at its (equivalent) age then.
    points = e.get("youngest_anchor_strength")
    if points is not None and e["anchors"]:
        young = min(e["anchors"], key=lambda a: a["age_s"])
        cast = e["start_s"] - young["age_s"]
        mat = maturity_of(doc)
        if len(points) < 2:
            problems.append("%s: youngest_anchor_strength has %d points" % (where, len(points)))
        for k, (t, mpa) in enumerate(points):
            want_t = cast + young["age_s"] * k / (len(points) - 1) if len(points) > 1 else cast
            want = strength_at(curve, mat.age(cast, want_t) if mat else want_t - cast)
            if abs(t - want_t) > T_DOC or abs(mpa - want) > 1e-5:
                problems.append("%s: youngest_anchor_strength point %d is [%.6f, %.6f], "
                                "recomputed [%.6f, %.6f]" % (where, k, t, mpa, want_t, want))
                break
    longest = max([r["required_s"] for r in e["wait_reasons"]], default=0.0)
    check_binding(where, e["wait_reasons"], e["wait_before_s"], problems)
    if abs(e["wait_before_s"] - longest) > T_DOC:
        problems.append("%s: wait_before_s %.6f, its reasons need %.6f s" % (where, e["wait_before_s"], longest))
    for j, r in enumerate(e["wait_reasons"]):
        if r["kind"] not in WAIT_KINDS or not r["detail"].strip():
            problems.append("%s wait reason %d: kind %r, detail %r" % (where, j, r["kind"], r["detail"]))
        elif r["kind"] == "anchor-strength" and not any(abs(r["required_s"] - n) <= T_DOC for n in needs):
            problems.append("%s wait reason %d: requires %.6f s, no anchor needs that (%s)" % (
                where, j, r["required_s"], ", ".join("%.3f" % n for n in needs)))
    got = [r["required_s"] for r in e["wait_reasons"] if r["kind"] == "anchor-strength"]
    for n in needs:
        if n > T_DOC and not any(abs(g - n) <= T_DOC for g in got):
            problems.append("%s: an anchor needs a %.6f s wait, no anchor-strength reason says so" % (where, n))
    body = e["climb"]
    phases = sum(p["duration_s"] for p in body["phases"])
    if abs(e["end_s"] - e["start_s"] - body["duration_s"]) > T_DOC or abs(phases - body["duration_s"]) > T_DOC:
        problems.append("%s: lasts %.6f s, climb.duration_s %.6f, its phases %.6f s" % (
            where, e["end_s"] - e["start_s"], body["duration_s"], phases))


# ---------------------------------------------------------------- 9. totals

def check_totals(doc, infos, problems):
    layers, events, totals = doc["layers"], doc["events"], doc["totals"]

    def span(kind):
        return sum(e["end_s"] - e["start_s"] for e in events if e["kind"] == kind)
    pieces = {
        "makespan_s": max([l["end_s"] for l in layers] + [e["end_s"] for e in events], default=0.0),
        "deposition_s": sum(infos[l["plan"]].deposition for l in layers),
        "airtime_s": sum(infos[l["plan"]].airtime for l in layers),
        "moves_s": sum(l["move_before_s"] for l in layers),
        "waits_s": sum(l["wait_before_s"] for l in layers) +
        sum(e.get("wait_before_s", 0.0) for e in events),
        "pipes_s": span("pipe"), "purges_s": span("purge"), "climbs_s": span("climb"),
        "slabs_s": span("slab") + span("pour"),
    }
    for key, kind in (("joints_s", "joint"), ("lintels_s", "lintel")):
        if key in totals or doc["inputs"].get("site") is not None:
            pieces[key] = span(kind)
    if "crew_h" in totals:
        pieces["crew_h"] = sum(e.get("crew", 0) * (e["end_s"] - e["start_s"]) for e in events) / 3600.0
    pieces["machine_s"] = sum(infos[l["plan"]].end_t for l in layers) + pieces["moves_s"] + \
        pieces["pipes_s"] + pieces["purges_s"] + pieces["climbs_s"]
    if totals["layers"] != len(layers):
        problems.append("totals: layers %d, the document lists %d" % (totals["layers"], len(layers)))
    for name, value in pieces.items():
        if abs(totals[name] - value) > T_DOC + 1e-9 * abs(value):
            problems.append("totals: %s %.6f, the layers and events add up to %.6f" % (name, totals[name], value))


# ---------------------------------------------------------------- 11. the site's calendar

WEEKDAYS = ("mon", "tue", "wed", "thu", "fri", "sat", "sun")


class Calendar:
    """The site's working windows in the schedule's seconds, computed here from the
    programme with Python's zoneinfo (the system's tzdata): a local time that does not
    exist (spring forward) is the moment of the change, one that occurs twice is the
    first."""

    def __init__(self, site, until_s):
        from zoneinfo import ZoneInfo
        self.zone = ZoneInfo(site["time_zone"])
        text = site["start_local"].replace("T", " ")
        start_local = datetime.datetime.strptime(text, "%Y-%m-%d %H:%M:%S" if text.count(":") == 2
                                                 else "%Y-%m-%d %H:%M")
        self.start = self.utc(start_local)
        holidays = {datetime.date.fromisoformat(h) for h in site["holidays"]}
        hours = {d: [tuple(self.minutes(t) for t in span.split("-")) for span in site["working_hours"][d]]
                 for d in WEEKDAYS}
        self.windows = []
        day = start_local.date()
        last = (self.start + datetime.timedelta(seconds=until_s + 3 * 86400)).astimezone(self.zone).date()
        while day <= last:
            if day not in holidays:
                for lo, hi in hours[WEEKDAYS[day.weekday()]]:
                    midnight = datetime.datetime.combine(day, datetime.time())
                    a = self.seconds(self.utc(midnight + datetime.timedelta(minutes=lo)))
                    b = self.seconds(self.utc(midnight + datetime.timedelta(minutes=hi)))
                    if b <= 0 or b <= a:
                        continue
                    a = max(a, 0.0)
                    if self.windows and self.windows[-1][1] >= a:
                        self.windows[-1][1] = max(self.windows[-1][1], b)
                    else:
                        self.windows.append([a, b])
            day += datetime.timedelta(days=1)
        self.ends = [w[1] for w in self.windows]

    @staticmethod
    def minutes(text):
        h, m = text.split(":")
        return int(h) * 60 + int(m)

    def utc(self, local):
        aware = local.replace(tzinfo=self.zone, fold=0)
        at = aware.astimezone(datetime.timezone.utc)
        if at.astimezone(self.zone).replace(tzinfo=None) == local:
            return at
        # In a spring-forward gap: the first instant with the later offset.
        lo = local.replace(tzinfo=self.zone, fold=1).astimezone(datetime.timezone.utc)
        later = lo.astimezone(self.zone).utcoffset()
        hi = at
        while (hi - lo).total_seconds() > 1:
            mid = lo + (hi - lo) / 2
            if mid.astimezone(self.zone).utcoffset() == later:
                hi = mid
            else:
                lo = mid
        return hi.replace(microsecond=0)

    def seconds(self, utc):
        return (utc - self.start).total_seconds()

    def timestamp(self, t_s):
        if not math.isfinite(t_s):
            return "never"
        at = self.start + datetime.timedelta(seconds=math.floor(t_s + 0.5))
        return at.astimezone(self.zone).isoformat()

    def date(self, t_s):
        return self.timestamp(t_s)[:10]

    def within(self, a, b):
        k = bisect.bisect_left(self.ends, a + 1e-6)
        return k < len(self.windows) and self.windows[k][0] <= a + 1e-6 and b <= self.windows[k][1] + 1e-6

    def fit(self, t, length):
        """The earliest start from t at which `length` seconds fit in one window."""
        k = bisect.bisect_right(self.ends, t + 1e-6)
        for a, b in self.windows[k:]:
            start = max(t, a)
            if start + length <= b + 1e-6:
                return start
        return math.inf


def check_joint(doc, where, l, below, block, stopped, problems, stats):
    """A planned joint under layer `l`, whose block (treatment, purge, layer) starts at
    `block`: on a layer of its floor, where work stopped (`stopped`: off-shift hours or
    cold; or lintels set in between), treated by a joint event within the material's ages."""
    joint = doc["inputs"]["material"]["planned_joint"]
    if below is None:
        problems.append("%s: a planned joint on a floor's first layer, which stands on its slab" % where)
        return
    lintels = any(e["kind"] == "lintel" and e["start_s"] >= below["end_s"] - T_DOC and e["end_s"] <= block + T_DOC
                  for e in doc["events"])
    if not stopped and not lintels:
        problems.append("%s: a planned joint, but no off-shift hours, cold or lintels lie between the layer below's "
                        "end (%.6f s) and the joint (%.6f s)" % (where, below["end_s"], block))
    age = block - below["end_s"]
    if age < joint["min_age_s"] - T_DOC or (doc["feasible"] and age > joint["max_age_s"] + T_DOC):
        problems.append("%s: the joint is treated %.1f s after the layer below ended, outside the "
                        "material's %g..%g s" % (where, age, joint["min_age_s"], joint["max_age_s"]))
    if not any(e["kind"] == "joint" and (e["floor"], e["after_layer"]) == (below["floor"], below["layer"]) and
               abs(e["start_s"] - block) <= T_DOC for e in doc["events"]):
        problems.append("%s: a planned joint, and no joint event after floor %d layer %d at %.6f s" % (
            where, below["floor"], below["layer"], block))
    stats["joints"] = stats.get("joints", 0) + 1


def check_joints_off_site(doc, problems, stats):
    """Without a site calendar, a planned joint only where lintels stopped the work."""
    if doc["inputs"].get("site") is not None:
        return
    layers = doc["layers"]
    purge_s, treat = doc["inputs"]["machine"]["purge_s"], joint_treatment_s(doc)
    for i, l in enumerate(layers):
        if not l.get("planned_joint"):
            continue
        below = layers[i - 1] if i and layers[i - 1]["floor"] == l["floor"] else None
        block = l["start_s"] - (purge_s if l["purge_before"] else 0.0) - treat
        check_joint(doc, "floor %d layer %d" % (l["floor"], l["layer"]), l, below, block, False, problems, stats)


def check_site(doc, problems, stats):
    """On a site calendar: the timestamps are the seconds' local times; attended printing,
    climbs, joints' treatments and (when the crew places them) pipes lie within one
    working window each; an off-shift wait ends at the earliest window that holds the
    work; a planned joint only where off-shift hours passed since the layer below ended,
    treated within the material's ages, and every layer over the maximum interval is
    one; the days sum up the layers as they are."""
    site = doc["inputs"].get("site")
    if site is None:
        return
    layers, events = doc["layers"], doc["events"]
    machine, material = doc["inputs"]["machine"], doc["inputs"]["material"]
    joint = material["planned_joint"]
    cal = Calendar(site, doc["totals"]["makespan_s"])
    stats["windows"] = len(cal.windows)
    if cal.timestamp(0.0) != site["start"]:
        problems.append("inputs.site.start %s, but %s in %s is %s" % (
            site["start"], site["start_local"], site["time_zone"], cal.timestamp(0.0)))
    stamped = [("totals", doc["totals"], 0.0, "start_time"),
               ("totals", doc["totals"], doc["totals"]["makespan_s"], "finish_time")]
    for l in layers:
        name = "floor %d layer %d" % (l["floor"], l["layer"])
        stamped += [(name, l, l["start_s"], "start_time"), (name, l, l["end_s"], "end_time")]
    for i, e in enumerate(events):
        name = "event %d (%s)" % (i, e["kind"])
        stamped += [(name, e, e["start_s"], "start_time"), (name, e, e["end_s"], "end_time")]
    for name, obj, t, key in stamped:
        if obj[key] != cal.timestamp(t):
            problems.append("%s: %s %s, but %.6f s from the start is %s" % (name, key, obj[key], t, cal.timestamp(t)))
    attended = site["printing"] == "attended"
    purge_s = machine["purge_s"]
    mat = maturity_of(doc)
    lo_c, hi_c = material.get("placing_temperature_c", [-math.inf, math.inf])

    def warm(r):
        return lo_c - 1e-9 <= r[1] <= hi_c + 1e-9

    def fit(t, crew, whole, ok):
        """The earliest start from t at which `crew` s lie in one working window and the
        weather is ok over `whole` s (the calendar and the weather each as strict as the
        work needs)."""
        for _ in range(10000):
            u = cal.fit(t, crew) if crew > 0 else t
            if mat is not None and math.isfinite(u) and not mat.all_ok(u, u + whole, ok):
                k = mat.index(u)
                while k < len(mat.t) and (k == mat.index(u) or mat.t[k] < u + whole) and ok(mat.readings[k]):
                    k += 1
                u = mat.t[k + 1] if k + 1 < len(mat.t) else math.inf
            if not math.isfinite(u) or abs(u - t) <= 1e-9:
                return u
            t = u
        return math.inf
    largest = stats.get("largest", {})
    for i, l in enumerate(layers):
        where = "floor %d layer %d" % (l["floor"], l["layer"])
        treat = joint["treatment_s"] if l["planned_joint"] else 0.0
        block = l["start_s"] - (purge_s if l["purge_before"] else 0.0) - treat
        length = l["end_s"] - block
        if attended and not cal.within(block, l["end_s"]):
            problems.append("%s: printing is attended, but it (with its purge and joint) runs %s to %s, "
                            "outside one working window" % (where, cal.timestamp(block), cal.timestamp(l["end_s"])))
        if mat is not None and not mat.all_ok(block, l["end_s"], warm):
            problems.append("%s: printed from %s to %s, when the air was outside the material's placing "
                            "range %g..%g °C" % (where, cal.timestamp(block), cal.timestamp(l["end_s"]), lo_c, hi_c))
        earliest = block - l["wait_before_s"]
        rules = earliest + max([r["required_s"] for r in l["wait_reasons"]
                                if r["kind"] not in ("off-shift", "joint", "cold")], default=0.0)
        for r in l["wait_reasons"]:
            if r["kind"] in ("off-shift", "cold"):
                crew = length if attended else treat
                want = fit(rules, crew, length, warm)
                if abs(want - block) > T_DOC:
                    problems.append("%s: waits off-shift until %s; the earliest working window that holds "
                                    "its %.1f s from %s starts the work at %s" % (
                                        where, cal.timestamp(block), crew, cal.timestamp(rules), cal.timestamp(want)))
                if abs(r["required_s"] - (block - earliest)) > T_DOC:
                    problems.append("%s: off-shift reason requires %.6f s, the wait to %s is %.6f s" % (
                        where, r["required_s"], cal.timestamp(block), block - earliest))
        below = layers[i - 1] if i and layers[i - 1]["floor"] == l["floor"] else None
        if l["planned_joint"]:
            stopped = below is not None and (not cal.within(below["end_s"], block) or (
                mat is not None and not mat.all_ok(below["end_s"], block, warm)))
            check_joint(doc, where, l, below, block, stopped, problems, stats)
        elif i in largest and largest[i] > material["max_layer_interval_s"] + interval_tolerance(doc) and doc["feasible"]:
            problems.append("%s: covered %.6f s after the layer below, over the maximum interval %g s, "
                            "and not a planned joint" % (where, largest[i], material["max_layer_interval_s"]))
    for i, e in enumerate(events):
        lintel_crew = e["kind"] == "lintel" and (e["lintel"]["by"] == "crew" or attended)
        slab_crew = e["kind"] == "pour" or (e["kind"] == "slab" and doc["inputs"].get("slabs") is not None)
        crew = e["kind"] in ("climb", "joint") or (e["kind"] == "pipe" and site["pipes"] == "crew") or \
            lintel_crew or slab_crew
        if crew and not cal.within(e["start_s"], e["end_s"]):
            problems.append("event %d (%s): needs a crew, but runs %s to %s, outside one working window" % (
                i, e["kind"], cal.timestamp(e["start_s"]), cal.timestamp(e["end_s"])))
        limit = machine.get("climb_wind_limit_m_s", math.inf)

        def calm(r):
            return r[2] <= limit + 1e-9
        if e["kind"] == "climb" and mat is not None and not mat.all_ok(e["start_s"], e["end_s"], calm):
            problems.append("event %d (climb): from %s to %s the wind exceeds the machine's climbing "
                            "limit %g m/s" % (i, cal.timestamp(e["start_s"]), cal.timestamp(e["end_s"]), limit))
        for r in e.get("wait_reasons", []):
            if r["kind"] in ("off-shift", "wind"):
                ready = e["start_s"] - e["wait_before_s"] + max(
                    [q["required_s"] for q in e["wait_reasons"] if q["kind"] not in ("off-shift", "wind")],
                    default=0.0)
                span = e["end_s"] - e["start_s"]
                want = fit(ready, span, span, calm)
                if abs(want - e["start_s"]) > T_DOC:
                    problems.append("event %d (%s): starts %s; the earliest working window that holds it from "
                                    "%s starts it at %s" % (i, e["kind"], cal.timestamp(e["start_s"]),
                                                            cal.timestamp(ready), cal.timestamp(want)))
    # The days: layers grouped by the local date they start on.
    days = []
    for i, l in enumerate(layers):
        date = cal.date(l["start_s"])
        if not days or days[-1]["date"] != date:
            days.append({"date": date, "layers": 0, "first": [l["floor"], l["layer"]], "printing_s": 0.0,
                         "concrete_m3": 0.0})
        d = days[-1]
        d["layers"] += 1
        d["concrete_m3"] += l.get("concrete_m3", 0.0)
        d["last"] = [l["floor"], l["layer"]]
        d["printing_s"] += l["end_s"] - l["start_s"]
        nxt = layers[i + 1] if i + 1 < len(layers) else None
        d["stop"] = "finished" if nxt is None else "floor-top" if nxt["floor"] != l["floor"] else \
            "planned-joint" if nxt["planned_joint"] else "continues"
    if len(days) != len(doc["days"]):
        problems.append("days: %d listed, the layers start on %d local days" % (len(doc["days"]), len(days)))
    for want, got in zip(days, doc["days"]):
        for key in ("date", "layers", "first", "last", "stop"):
            if want[key] != got[key]:
                problems.append("days %s: %s %r, recomputed %r" % (got["date"], key, got[key], want[key]))
        if "concrete_m3" in got and abs(want["concrete_m3"] - got["concrete_m3"]) > 1e-5:
            problems.append("days %s: concrete_m3 %.6f, its layers hold %.6f" % (
                got["date"], got["concrete_m3"], want["concrete_m3"]))
        if "deliveries" in got:
            due = sum(1 for t in doc.get("deliveries", []) if cal.date(t["due_s"]) == got["date"])
            if due != got["deliveries"]:
                problems.append("days %s: deliveries %d, %d are due that day" % (got["date"], got["deliveries"], due))
        if "crew_h" in got:
            crew_h = sum(e.get("crew", 0) * (e["end_s"] - e["start_s"]) for e in events
                         if cal.date(e["start_s"]) == got["date"]) / 3600.0
            if abs(crew_h - got["crew_h"]) > 1e-5:
                problems.append("days %s: crew_h %.6f, its crew tasks add up to %.6f person-hours" % (
                    got["date"], got["crew_h"], crew_h))
        if abs(want["printing_s"] - got["printing_s"]) > T_DOC:
            problems.append("days %s: printing_s %.6f, its layers last %.6f s" % (
                got["date"], got["printing_s"], want["printing_s"]))
    stats["days"] = len(days)


# ---------------------------------------------------------------- 12. quantities

def check_quantities(doc, problems, stats):
    """Each layer's concrete is its plan's pieces' length x bead width (the nozzle's for a
    one-pass wall) x its height; its peak flow the most its nozzles deposit at once (swept
    over the extruding spans); the total their sum; the deliveries the material's batches,
    truck k due when the concrete used (evenly over each layer) reaches k batches; each
    day's concrete and deliveries. Schedules written before quantities have none."""
    if "deliveries" not in doc:
        return
    layers, plans = doc["layers"], doc["plans"]
    nozzle_w = doc["inputs"]["machine"]["nozzle_width_m"]
    flows, by_floor = {}, {}
    for l in layers:
        where = "floor %d layer %d" % (l["floor"], l["layer"])
        plan = plans[l["plan"]]
        height = l["z_m"] - l["z_bottom_m"]
        width = {(p["wall"], p["piece"]): p.get("width_m") or nozzle_w for p in plan["pieces"]}
        volume = sum(p["length_m"] * width[(p["wall"], p["piece"])] * height for p in plan["pieces"])
        by_floor[l["floor"]] = by_floor.get(l["floor"], 0.0) + volume
        if abs(l["concrete_m3"] - volume) > 2e-6 + 1e-6 * volume:
            problems.append("%s: concrete_m3 %.6f, its pieces hold %.6f m3" % (where, l["concrete_m3"], volume))
        if l["plan"] not in flows and all("waypoints" in n for n in plan["nozzles"]):
            changes = []
            for n in plan["nozzles"]:
                w = n["waypoints"]
                for a, b in zip(w, w[1:]):
                    dt = b["t_s"] - a["t_s"]
                    if a["extruding"] and dt > 0:
                        f = math.hypot(b["x_m"] - a["x_m"], b["y_m"] - a["y_m"]) / dt * \
                            width.get((a["wall"], a["piece"]), nozzle_w) * height
                        changes += [(a["t_s"], f), (b["t_s"], -f)]
            flow = peak = 0.0
            for _, d in sorted(changes):
                flow += d
                peak = max(peak, flow)
            flows[l["plan"]] = peak * 3600.0
        if l["plan"] in flows and abs(l["peak_flow_m3_h"] - flows[l["plan"]]) > 1e-4 * max(1.0, flows[l["plan"]]):
            problems.append("%s: peak_flow_m3_h %.6f, its nozzles draw at most %.6f m3/h" % (
                where, l["peak_flow_m3_h"], flows[l["plan"]]))
        cap = doc["inputs"]["machine"].get("pump_capacity_m3_h")
        if cap is not None and l["peak_flow_m3_h"] > cap * (1 + 1e-6):
            problems.append("%s: its nozzles draw %.3f m3/h, more than the pump's %g m3/h" % (
                where, l["peak_flow_m3_h"], cap))
    check_wall_volumes_from_paths(doc, problems, stats)
    total = sum(l["concrete_m3"] for l in layers)
    if abs(doc["totals"]["concrete_m3"] - total) > 1e-5:
        problems.append("totals: concrete_m3 %.6f, the layers hold %.6f" % (doc["totals"]["concrete_m3"], total))
    batch = doc["inputs"]["material"]["delivery_batch_m3"]
    want, used = [], 0.0
    count = math.ceil(total / batch - 1e-9) if total > 0 else 0
    for l in layers:
        while len(want) < count and len(want) * batch <= used + l["concrete_m3"] + 1e-12:
            k = len(want)
            share = min(max((k * batch - used) / l["concrete_m3"], 0.0), 1.0) if l["concrete_m3"] > 0 else 0.0
            want.append((l["start_s"] + share * (l["end_s"] - l["start_s"]), min(batch, total - k * batch)))
        used += l["concrete_m3"]
    got = doc["deliveries"]
    if len(got) != len(want):
        problems.append("deliveries: %d listed; %.6f m3 in batches of %g m3 make %d" % (len(got), total, batch, len(want)))
    for k, ((due, m3), d) in enumerate(zip(want, got)):
        if abs(d["due_s"] - due) > T_DOC or abs(d["m3"] - m3) > 1e-5:
            problems.append("delivery %d: %.6f m3 due at %.6f s, recomputed %.6f m3 at %.6f s" % (
                k, d["m3"], d["due_s"], m3, due))
    stats["concrete_m3"] = total
    stats["deliveries"] = len(got)
    # A model's own volumes (inputs.provenance[].quantities): what the floor prints is what
    # its layers' pieces hold, recomputed above; the share of it on the walls the model
    # states a volume of is no more than that.
    for f in doc["inputs"].get("provenance") or []:
        q = f.get("quantities")
        if q is None:
            continue
        held = by_floor.get(f["floor"], 0.0)
        if abs(q["printed_m3"] - held) > 1e-5 + 1e-6 * held:
            problems.append("provenance floor %d: quantities.printed_m3 %.6f, its layers' pieces "
                            "hold %.6f m3" % (f["floor"], q["printed_m3"], held))
        if q["printed_modelled_m3"] > q["printed_m3"] + 1e-6:
            problems.append("provenance floor %d: quantities.printed_modelled_m3 %.6f, more than "
                            "the floor prints (%.6f m3)" % (f["floor"], q["printed_modelled_m3"],
                                                            q["printed_m3"]))
        if (q["walls_modelled"] > 0) != (q["model_volume_m3"] > 0):
            problems.append("provenance floor %d: %d walls state %.6f m3" % (
                f["floor"], q["walls_modelled"], q["model_volume_m3"]))
        stats["modelled_floors"] = stats.get("modelled_floors", 0) + 1


def check_wall_volumes_from_paths(doc, problems, stats):
    """Each wall's concrete from the nozzles' timed paths, not from the pieces: every
    extruding span's length x its bead's width (the nozzle's for a one-pass wall) x its
    layer's height, summed per wall over the building. It must be what the wall's pieces
    hold (the paths lay each bead once, end to end), and per floor what the floor prints
    against the model (inputs.provenance[].quantities.printed_m3)."""
    layers, plans = doc["layers"], doc["plans"]
    if not all("waypoints" in n for l in layers for n in plans[l["plan"]]["nozzles"]):
        return
    nozzle_w = doc["inputs"]["machine"]["nozzle_width_m"]
    laid, held, floor_laid = {}, {}, {}  # by (floor, wall); by floor
    for l in layers:
        plan = plans[l["plan"]]
        height = l["z_m"] - l["z_bottom_m"]
        width = {(p["wall"], p["piece"]): p.get("width_m") or nozzle_w for p in plan["pieces"]}
        for p in plan["pieces"]:
            key = (l["floor"], p["wall"])
            held[key] = held.get(key, 0.0) + p["length_m"] * width[(p["wall"], p["piece"])] * height
        for n in plan["nozzles"]:
            w = n["waypoints"]
            for a, b in zip(w, w[1:]):
                if not a["extruding"]:
                    continue
                m3 = math.hypot(b["x_m"] - a["x_m"], b["y_m"] - a["y_m"]) * \
                    width.get((a["wall"], a["piece"]), nozzle_w) * height
                key = (l["floor"], a["wall"])
                laid[key] = laid.get(key, 0.0) + m3
                floor_laid[l["floor"]] = floor_laid.get(l["floor"], 0.0) + m3
    off = []
    for key in sorted(set(laid) | set(held)):
        got, want = laid.get(key, 0.0), held.get(key, 0.0)
        # Coordinates are written to the micrometre: a span's length to about 2 um.
        if abs(got - want) > 1e-5 + 1e-6 * want:
            off.append("floor %d wall %d: its paths lay %.6f m3, its pieces hold %.6f m3" % (
                key[0], key[1], got, want))
    problems.extend(off[:10])
    if len(off) > 10:
        problems.append("... and %d more walls whose paths do not lay their pieces" % (len(off) - 10))
    for f in doc["inputs"].get("provenance") or []:
        q = f.get("quantities")
        if q is not None:
            got = floor_laid.get(f["floor"], 0.0)
            if abs(q["printed_m3"] - got) > 1e-4 + 1e-6 * got:
                problems.append("provenance floor %d: quantities.printed_m3 %.6f, its nozzles' "
                                "paths lay %.6f m3" % (f["floor"], q["printed_m3"], got))
    stats["walls_volume_from_paths"] = len(laid)


# ---------------------------------------------------------------- driver

def guarded(name, fn, problems, *args):
    """A check that trips over a corrupt document reports that, not a traceback."""
    try:
        fn(*args)
    except (KeyError, TypeError, ValueError, IndexError, ZeroDivisionError, AttributeError,
            OverflowError) as x:
        problems.append("the %s check could not run: %s: %s" % (name, type(x).__name__, x))


def check(doc, problems=None):
    """(problems, notes, stats). Raises NotASchedule for another document. `problems`: the
    list to append to (the self-test's stops at the problem it waits for)."""
    if not isinstance(doc, dict) or doc.get("format") != "ccbuild-schedule":
        raise NotASchedule("format is %r, not \"ccbuild-schedule\"" % (
            doc.get("format") if isinstance(doc, dict) else type(doc).__name__))
    if doc.get("schema_version") != 2 or isinstance(doc.get("schema_version"), bool):
        raise NotASchedule("schema_version is %r, this checker reads 2" % doc.get("schema_version"))
    problems, notes = ([] if problems is None else problems), []
    stats = {"ends": 0, "layers": 0, "pairs": 0, "climbs": 0, "anchors": 0}
    check_structure(doc, problems)
    if problems:
        return problems, notes, stats
    guarded("layer order", check_layer_order, problems, doc, problems)
    if problems:
        return problems, notes, stats
    machine = doc["inputs"]["machine"]
    infos = {}
    for key, plan in doc["plans"].items():
        info = infos[key] = Plan(key, plan)
        guarded("coverage", check_coverage, problems, key, plan, problems)
        guarded("beads", check_beads, problems, key, plan, machine, problems)
        guarded("motion", check_motion, problems, key, plan, machine, info, problems)
        guarded("gantry", check_gantries, problems, key, plan, machine, info, problems)
    stats["infos"] = infos
    guarded("layer", check_layers, problems, doc, infos, problems)
    # The intervals after the checks that read nothing they find: they take most of the
    # time (every piece end of every layer). The site's check reads their largest.
    guarded("event", check_events, problems, doc, problems, stats)
    guarded("totals", check_totals, problems, doc, infos, problems)
    guarded("quantities", check_quantities, problems, doc, problems, stats)
    guarded("interval", check_intervals, problems, doc, infos, problems, notes, stats)
    guarded("site calendar", check_site, problems, doc, problems, stats)
    guarded("planned joints", check_joints_off_site, problems, doc, problems, stats)
    return problems, notes, stats


def summary(doc, stats):
    infos = stats["infos"]
    multi = [i for i in infos.values() if i.min_gap is not None]
    pieces = sum(len(p["pieces"]) for p in doc["plans"].values())
    return ("OK: %d layers (%s), %d plans: %d pieces covered once, %d waypoints within the machine's "
            "limits, %d gantry breakpoints in %d multi-nozzle plans; %d local intervals recomputed "
            "over %d piece ends (%d plan pairs) within the material's %s and strength, waits "
            "recomputed; %d events "
            "(%d climbs, %d anchors strong enough); totals agree" % (
                len(doc["layers"]), "feasible" if doc["feasible"] else "marked infeasible",
                len(infos), pieces, sum(i.waypoints for i in infos.values()),
                sum(i.breakpoints for i in multi), len(multi), stats["layers"], stats["ends"],
                stats["pairs"], "bounds" if doc["feasible"] else "minimum", len(doc["events"]),
                stats["climbs"], stats["anchors"])) + (
        "; site calendar (%s): %d working windows, %d days, %d planned joints, timestamps agree" % (
            doc["inputs"]["site"]["time_zone"], stats.get("windows", 0), stats.get("days", 0),
            stats.get("joints", 0)) if doc["inputs"].get("site") is not None else "") + (
        "; %.3f m3 of concrete in %d deliveries" % (stats["concrete_m3"], stats["deliveries"])
        if "concrete_m3" in stats else "") + (
        ", %d walls' concrete recomputed from their timed paths" % stats["walls_volume_from_paths"]
        if "walls_volume_from_paths" in stats else "")


# ---------------------------------------------------------------- self-test

def shift_from(d, i, delta):
    """Moves layer i, the purge before it and everything after it by delta s, as if the
    scheduler had started layer i that much later; of the intervals, only layer i's to the
    layer below change. For the self-test's corruptions that must stay consistent."""
    layer = d["layers"][i]
    purge = d["inputs"]["machine"]["purge_s"] if layer["purge_before"] else 0.0
    since = layer["start_s"] - purge - ROUND_T
    for e in d["events"]:
        if e["start_s"] >= since:
            e["start_s"] += delta
            e["end_s"] += delta
    for later in d["layers"][i:]:
        later["start_s"] += delta
        later["end_s"] += delta
    for key in ("interval_s", "local_interval_min_s", "local_interval_max_s"):
        if layer[key] is not None:
            layer[key] += delta
    d["totals"]["makespan_s"] += delta


def place_corruptions(doc, stats, add):
    """local_interval_min_at / _max_at moved to a piece end where the interval is not the
    extreme, and the minimum's place written from the maximum's (a bug that once
    survived the tests)."""
    layers, infos = doc["layers"], stats["infos"]
    moved = {}                  # "min"/"max" -> (layer index, the end it is moved to)
    from_max = None             # a layer whose minimum is not where its maximum is
    for i, layer in enumerate(layers):
        below = layer_below(layers, i)
        if below is None or layer["local_interval_min_at"] is None:
            continue
        _, ends, low, high = pair_intervals(infos[layer["plan"]], infos[below["plan"]])
        for (wall, piece), there in ends.items():
            for x, y, lo, hi in there:
                end = {"wall": wall, "piece": piece, "x_m": x, "y_m": y}
                if "min" not in moved and lo > low[0] + 1.0:
                    moved["min"] = (i, end)
                if "max" not in moved and hi < high[0] - 1.0:
                    moved["max"] = (i, end)
        at = layer["local_interval_max_at"]
        if from_max is None and at is not None:
            there = [e for e in ends.get((at["wall"], at["piece"]), ())
                     if abs(e[0] - at["x_m"]) <= ROUND_P and abs(e[1] - at["y_m"]) <= ROUND_P]
            if there and min(e[2] for e in there) > low[0] + 1.0:
                from_max = i
    for name, (i, end) in sorted(moved.items()):
        key = "local_interval_%s_at" % name
        add("%s moved to another piece end" % key, key + " names")(
            lambda d, i=i, key=key, end=end: d["layers"][i].update({key: dict(end)}))
    if from_max is not None:
        add("local_interval_min_at written from the maximum's piece end", "local_interval_min_at names")(
            lambda d: d["layers"][from_max].update(
                local_interval_min_at=dict(d["layers"][from_max]["local_interval_max_at"])))


def wait_corruptions(doc, stats, add):
    """A strength wait shortened (for each kind of layer that needs it: the layer below,
    an older layer of the floor, a layer of a floor below), the rest of the schedule
    moved with it; and a purge after a wait taken out, the rest moved with it."""
    layers = doc["layers"]
    purge_s = doc["inputs"]["machine"]["purge_s"]
    chosen = {}
    # The last layer of each kind: the fewer layers after it, the fewer follow-on problems.
    for i, (need, who) in sorted(stats["strength_waits"].items(), reverse=True):
        layer = layers[i]
        if abs(need - layer["wait_before_s"]) > T_DOC:
            continue            # another reason needs a longer wait
        others = max([r["required_s"] for r in layer["wait_reasons"]
                      if r["kind"] != "strength" or abs(r["required_s"] - need) > T_DOC], default=0.0)
        cut = 0.5 * (layer["wait_before_s"] - others)
        # A purge after the wait leaves its own time as a margin: cut more than that.
        if cut < 1.0 or (layer["purge_before"] and cut < purge_s + 1.0):
            continue
        if who is layer_below(layers, i):
            kind = ("the layer below", "of the layer below is")
        elif who["floor"] == layer["floor"]:
            kind = ("an older layer of its floor", "old at its start")
        else:
            kind = ("a layer of a floor below", "old at its start")
        chosen.setdefault(kind, (i, need, cut))
    for (what, expect), (i, need, cut) in sorted(chosen.items()):
        def shorter(d, i=i, need=need, cut=cut):
            layer = d["layers"][i]
            for r in layer["wait_reasons"]:
                if r["kind"] == "strength" and abs(r["required_s"] - need) <= T_DOC:
                    r["required_s"] -= cut
            layer["wait_before_s"] -= cut
            d["totals"]["waits_s"] -= cut
            shift_from(d, i, -cut)
        add("a strength wait for %s shortened" % what, expect)(shorter)
    purged = [i for i, l in enumerate(layers) if l["purge_before"]]
    if purged:
        # Preferably a purge that follows a wait, not one after a slab or a climb; the last.
        i = next((i for i in reversed(purged) if layers[i]["wait_before_s"] > 0), purged[-1])

        def no_purge(d):
            layer = d["layers"][i]
            d["events"] = [e for e in d["events"]
                           if not (e["kind"] == "purge" and abs(e["end_s"] - layer["start_s"]) <= ROUND_T)]
            layer["purge_before"] = False
            d["totals"]["purges_s"] -= purge_s
            d["totals"]["machine_s"] -= purge_s
            shift_from(d, i, -purge_s)
        add("the purge before a layer taken out", "and no purge")(no_purge)


def corruptions(doc):
    """(name, change(doc), text the problems must contain) for the self-test; each change
    is applied to a fresh copy. Some need a feature of the document (several nozzles,
    a climb, a strength wait, a purge, a layer whose intervals differ) and are left out
    without it."""
    layers, plans = doc["layers"], doc["plans"]
    stats = check(doc)[2]
    out = []

    def add(name, expect):
        def wrap(fn):
            out.append((name, fn, expect))
            return fn
        return wrap

    used = layers[len(layers) // 2]["plan"]
    nozzle = max(range(len(plans[used]["nozzles"])), key=lambda n: len(plans[used]["nozzles"][n]["waypoints"]))
    w = plans[used]["nozzles"][nozzle]["waypoints"]
    extruding = [k for k in range(len(w) - 1) if w[k]["extruding"] and w[k + 1]["t_s"] - w[k]["t_s"] > 1.0]
    moving = [k for k in range(len(w) - 1) if not w[k]["extruding"] and
              math.hypot(w[k + 1]["x_m"] - w[k]["x_m"], w[k + 1]["y_m"] - w[k]["y_m"]) > 0.1]
    k = extruding[len(extruding) // 2]

    def path(d):
        return d["plans"][used]["nozzles"][nozzle]["waypoints"]

    add("schema version 3", "NOT A SCHEDULE")(lambda d: d.update(schema_version=3))
    skins = [(pc["length_m"], k2, j) for k2, p in plans.items() for j, pc in enumerate(p["pieces"])
             if pc.get("bead") == "skin"]
    if skins:
        _, bk, bj = max(skins)

        def wider(d):
            piece = d["plans"][bk]["pieces"][bj]
            piece["width_m"] *= 2
        add("a skin bead twice as wide", "overlap")(wider)
        add("a skin bead narrower than the machine lays", "outside the machine's bead widths")(
            lambda d: d["plans"][bk]["pieces"][bj].update(width_m=0.5 * d["plans"][bk]["pieces"][bj]["width_m"]))
        add("a bead of no known kind", "bead kind")(
            lambda d: d["plans"][bk]["pieces"][bj].update(bead="brick"))
    add("a layer without end_s", "no `end_s`")(lambda d: d["layers"][3].pop("end_s"))
    add("two layers swapped", "out of building order")(
        lambda d: d["layers"].__setitem__(slice(3, 5), [d["layers"][4], d["layers"][3]]))
    add("a layer's plan missing", "not in plans")(lambda d: d["layers"][2].update(plan="nowhere"))
    add("a layer's nozzle count", "nozzle paths")(lambda d: d["layers"][2].update(nozzles=d["layers"][2]["nozzles"] + 1))
    add("a span left undeposited", "never deposited")(lambda d: path(d)[k].update(extruding=False))
    add("a span on an unknown wall", "not a piece of the plan")(lambda d: path(d)[k].update(wall=987654))

    @add("a span deposited twice", "deposited twice")
    def twice(d):
        p = path(d)
        a, b = p[k], p[k + 1]
        end = max(n["waypoints"][-1]["t_s"] for n in d["plans"][used]["nozzles"])
        p.append(dict(p[-1], t_s=end + 1e5, x_m=a["x_m"], y_m=a["y_m"], heading_rad=a["heading_rad"],
                      extruding=True, wall=a["wall"], piece=a["piece"]))
        p.append(dict(b, t_s=end + 1e5 + b["t_s"] - a["t_s"], extruding=False))

    add("depositing too fast", "not the deposition speed")(
        lambda d: [q.update(t_s=q["t_s"] - 0.5 * (w[k + 1]["t_s"] - w[k]["t_s"])) for q in path(d)[k + 1:]])
    if moving:
        j = moving[len(moving) // 2]
        add("an air move too fast", "faster than the")(
            lambda d: [q.update(t_s=q["t_s"] - 0.9 * (w[j + 1]["t_s"] - w[j]["t_s"])) for q in path(d)[j + 1:]])
    add("time running backwards", "time runs backwards")(lambda d: path(d)[k + 1].update(t_s=w[k]["t_s"] - 1.0))
    add("past the stopper", "past the stopper")(lambda d: path(d)[-1].update(heading_rad=w[-1]["heading_rad"] + 40.0))
    turns = [j for j in range(len(w) - 1) if abs(w[j + 1]["heading_rad"] - w[j]["heading_rad"]) > 0.05]
    if turns:
        # The largest turn, done in half the time the rotation speed allows.
        t = max(turns, key=lambda j: abs(w[j + 1]["heading_rad"] - w[j]["heading_rad"]))
        quick = 0.5 * abs(w[t + 1]["heading_rad"] - w[t]["heading_rad"]) / \
            doc["inputs"]["machine"]["rotation_speed_rad_s"]
        add("turning too fast", "over the rotation speed")(
            lambda d: [q.update(t_s=q["t_s"] - (w[t + 1]["t_s"] - w[t]["t_s"] - quick)) for q in path(d)[t + 1:]])
    add("a plan's layer time", "layer_time_s")(lambda d: d["plans"][used].update(layer_time_s=d["plans"][used]["layer_time_s"] + 5.0))
    multi = [key for key, p in plans.items() if len(p["nozzles"]) > 1]
    if multi:
        @add("two gantries too close", "under the gantry width")
        def close(d):
            p = d["plans"][multi[0]]
            axis = d["inputs"]["machine"]["rail_axis"] + "_m"
            left, right = p["nozzles"][0]["waypoints"], p["nozzles"][1]["waypoints"]
            w = right[len(right) // 2]
            # Onto the left gantry's rail position at that moment.
            t = min(max(w["t_s"], left[0]["t_s"]), left[-1]["t_s"])
            for a, b in zip(left, left[1:]):
                if a["t_s"] <= t <= b["t_s"]:
                    f = (t - a["t_s"]) / (b["t_s"] - a["t_s"]) if b["t_s"] > a["t_s"] else 1.0
                    w[axis] = a[axis] + f * (b[axis] - a[axis])
                    break
    with_below = [i for i, l in enumerate(layers) if l["local_interval_min_s"] is not None]
    i = with_below[len(with_below) // 2]
    add("a layer ends late", "lasts")(lambda d: d["layers"][i].update(end_s=d["layers"][i]["end_s"] + 5.0))

    @add("a layer overlapping the previous one", "before the previous layer's end")
    def overlap(d):
        shift = d["layers"][i]["start_s"] - d["layers"][i - 1]["end_s"] + 10.0
        for l in d["layers"][i:]:
            l["start_s"] -= shift
            l["end_s"] -= shift
    add("a wait longer than its reasons", "its reasons need")(
        lambda d: d["layers"][i].update(wait_before_s=d["layers"][i]["wait_before_s"] + 60.0))
    add("an unknown wait reason", "wait reason 0")(
        lambda d: d["layers"][i]["wait_reasons"].insert(0, {"kind": "lunch", "required_s": 0.0, "from_s": 0.0, "binding_s": 0.0, "detail": "x"}))
    add("a wrong local_interval_min_s", "local_interval_min_s")(
        lambda d: d["layers"][i].update(local_interval_min_s=d["layers"][i]["local_interval_min_s"] + 1.0))
    add("a wrong local_interval_max_s", "local_interval_max_s")(
        lambda d: d["layers"][i].update(local_interval_max_s=d["layers"][i]["local_interval_max_s"] - 1.0))
    if layers[i].get("below_strength_mpa") is not None:
        add("a drawn strength of the layer below", "below_strength_mpa")(
            lambda d: d["layers"][i].update(below_strength_mpa=d["layers"][i]["below_strength_mpa"] * 1.01))
    climbs_drawn = [n for n, e in enumerate(doc["events"])
                    if e["kind"] == "climb" and e.get("youngest_anchor_strength")]
    if climbs_drawn:
        def anchor_point(d):
            points = d["events"][climbs_drawn[0]]["youngest_anchor_strength"]
            points[len(points) // 2][1] += 0.5
        add("a drawn anchor strength", "youngest_anchor_strength point")(anchor_point)
    # A wait's time blamed on another of its causes.
    two = [("events", n) for n, e in enumerate(doc["events"]) if len(e.get("wait_reasons", [])) > 1] + \
        [("layers", n) for n, l in enumerate(layers) if len(l["wait_reasons"]) > 1]
    if two:
        def blamed(d):
            reasons = d[two[0][0]][two[0][1]]["wait_reasons"]
            moved = min(60.0, max(r["binding_s"] for r in reasons))
            top = max(range(len(reasons)), key=lambda k: reasons[k]["binding_s"])
            reasons[top]["binding_s"] -= moved
            reasons[(top + 1) % len(reasons)]["binding_s"] += moved
        add("a wait's time blamed on another cause", "binding_s")(blamed)
    add("a minimum interval the schedule breaks", "under the minimum interval")(
        lambda d: d["inputs"]["material"].update(min_layer_interval_s=layers[i]["local_interval_min_s"] + 10.0))
    if doc["feasible"]:
        # In weather the bound holds in equivalent age (a cold night shortens it).
        largest = layers[i].get("equivalent_interval_max_s") or layers[i]["local_interval_max_s"]
        add("a maximum interval the schedule breaks", "over the maximum interval")(
            lambda d: d["inputs"]["material"].update(max_layer_interval_s=largest - 10.0))
        add("feasible, with an infeasibility", "with an infeasibility")(
            lambda d: d.update(infeasibility={"message": "x", "fix": {"text": "y"}}))
    add("infeasible without saying why", "infeasibility has no message")(
        lambda d: d.update(feasible=False, infeasibility={"message": "", "fix": {"text": ""}}))
    waited = [n for n, l in enumerate(layers) if any(r["kind"] == "min-interval" for r in l["wait_reasons"])]
    if waited:
        add("a min-interval reason left out", "no min-interval reason")(
            lambda d: d["layers"][waited[0]].update(wait_reasons=[
                r for r in d["layers"][waited[0]]["wait_reasons"] if r["kind"] != "min-interval"]))
    add("a wrong max_idle_s", "max_idle_s")(lambda d: d["layers"][i].update(max_idle_s=d["layers"][i]["max_idle_s"] + 1.0))
    add("an idle limit the plans break", "over the idle limit")(
        lambda d: d["inputs"]["machine"].update(nozzle_idle_limit_s=1.0))
    add("a wrong pipes_before_s", "pipes_before_s")(
        lambda d: d["layers"][i].update(pipes_before_s=d["layers"][i]["pipes_before_s"] + 50.0))
    add("a move longer than the gap", "account for")(
        lambda d: d["layers"][i].update(move_before_s=d["layers"][i]["move_before_s"] + 20.0))
    purged = [n for n, l in enumerate(layers) if l["purge_before"]]
    if purged:
        add("a purge not flagged", "purge_before")(lambda d: d["layers"][purged[0]].update(purge_before=False))
    if stats["overs"] > 1:
        add("later infeasible layers not warned", "not in warnings")(lambda d: d.update(warnings=[]))
    if doc["feasible"]:
        add("a weaker concrete", "to carry")(lambda d: d["inputs"]["material"].update(safety_factor=1e4))
    if not doc["feasible"] and stats["first_never"] is not None and \
            isinstance(doc["infeasibility"], dict):
        add("an infeasibility named after a load never carried", "that the infeasibility names")(
            lambda d: d["infeasibility"].update(floor=layers[-1]["floor"], layer=layers[-1]["layer"]))
    add("a slower concrete", "to carry")(
        lambda d: [p.update(age_s=p["age_s"] * 1e3) for p in d["inputs"]["material"]["strength_curve"]])
    first_plan = next(iter(plans))
    add("a waypoint off the rails", "outside the machine's y travel")(
        lambda d: d["plans"][first_plan]["nozzles"][0]["waypoints"][0].update(
            y_m=d["inputs"]["machine"]["y_range_m"][1] + 0.5))
    place_corruptions(doc, stats, add)
    wait_corruptions(doc, stats, add)
    add("a wrong makespan", "makespan_s")(lambda d: d["totals"].update(makespan_s=d["totals"]["makespan_s"] + 100.0))
    add("a wrong total deposition", "deposition_s")(lambda d: d["totals"].update(deposition_s=d["totals"]["deposition_s"] * 1.01))
    events = doc["events"]
    if len(events) >= 2:
        add("events out of order", "not sorted")(
            lambda d: d["events"].__setitem__(slice(0, 2), [d["events"][1], d["events"][0]]))

        @add("an event during a layer", "overlaps floor")
        def during(d):
            e = d["events"][0]
            l = d["layers"][-1]
            e.update(start_s=l["start_s"] + 1.0, end_s=l["start_s"] + 1.0 + e["end_s"] - e["start_s"])
    climbs = [n for n, e in enumerate(events) if e["kind"] == "climb"]
    if climbs:
        c = climbs[0]

        @add("a climb before its anchors are strong", "under the anchor strength")
        def early(d):
            e = d["events"][c]
            # Every anchor one hour old: far too young for any sensible anchor strength.
            cast = max(p["end_s"] for p in d["events"][:c] if p["kind"] == "pipe")
            shift = e["start_s"] - cast - 3600.0
            e["start_s"] -= shift
            e["end_s"] -= shift
        add("a climb's phases not its duration", "its phases")(
            lambda d: d["events"][c]["climb"].update(duration_s=d["events"][c]["climb"]["duration_s"] + 30.0))
        add("a climb's anchor age", "age_s")(
            lambda d: d["events"][c]["anchors"][0].update(age_s=d["events"][c]["anchors"][0]["age_s"] + 100.0))
        add("a climb's anchor-strength reason", "no anchor needs that")(
            lambda d: d["events"][c]["wait_reasons"].append(
                {"kind": "anchor-strength", "required_s": 1.0, "from_s": 0.0, "binding_s": 0.0, "detail": "x"}))
        add("a pipe without its anchor", "no `anchor`")(
            lambda d: next(e for e in d["events"] if e["kind"] == "pipe").pop("anchor"))
    site_corruptions(doc, add)
    lintel_slab_corruptions(doc, add)
    if "deliveries" in doc and doc["deliveries"]:
        add("a layer's concrete", "concrete_m3")(
            lambda d: d["layers"][0].update(concrete_m3=d["layers"][0]["concrete_m3"] * 1.01))
        add("a delivery late", "delivery")(
            lambda d: d["deliveries"][-1].update(due_s=d["deliveries"][-1]["due_s"] + 60.0))
        # A wall's extruding span laid as another wall of the layer: the layer's concrete
        # is unchanged, the two walls' are not.
        def relabel(d):
            for l in d["layers"]:
                plan = d["plans"][l["plan"]]
                walls = sorted({p["wall"] for p in plan["pieces"]})
                for n in plan["nozzles"]:
                    for a in n.get("waypoints", []):
                        if a["extruding"] and len(walls) > 1:
                            a["wall"] = walls[(walls.index(a["wall"]) + 1) % len(walls)]
                            return
        if any(len({p["wall"] for p in doc["plans"][l["plan"]]["pieces"]}) > 1 and
               any("waypoints" in n for n in doc["plans"][l["plan"]]["nozzles"])
               for l in doc["layers"]):
            add("an extruding span laid as another wall", "its paths lay")(relabel)
        add("a layer's peak flow", "peak_flow_m3_h")(
            lambda d: d["layers"][-1].update(peak_flow_m3_h=d["layers"][-1]["peak_flow_m3_h"] * 0.5))
    return out


def lintel_slab_corruptions(doc, add):
    """A lintel set after the first layer over it, or lasting less than the building says;
    a pour faster than its rate; the next floor started before its slab is strong."""
    events = doc["events"]
    lintels = [i for i, e in enumerate(events) if e["kind"] == "lintel"]
    if lintels:
        k = lintels[-1]     # the last before a layer: later, it overlaps that layer
        add("a lintel set an hour late", "(lintel)")(
            lambda d: d["events"][k].update(start_s=d["events"][k]["start_s"] + 3600.0,
                                             end_s=d["events"][k]["end_s"] + 3600.0))
        add("a lintel shortened", "the inputs say")(
            lambda d: d["events"][k].update(end_s=d["events"][k]["end_s"] - 60.0))
    modelled = [k for k, f in enumerate(doc["inputs"].get("provenance") or []) if f.get("quantities")]
    if modelled:
        f0 = modelled[0]
        add("a floor's printed volume a litre off its layers'", "quantities.printed_m3")(
            lambda d: d["inputs"]["provenance"][f0]["quantities"].update(
                printed_m3=d["inputs"]["provenance"][f0]["quantities"]["printed_m3"] + 0.001))
    pours = [i for i, e in enumerate(events) if e["kind"] == "pour" and not e["roof"]]
    if pours:
        p = pours[0]
        add("a pour at twice its rate", "m3/h that takes")(
            lambda d: d["events"][p].update(concrete_m3=2 * d["events"][p]["concrete_m3"]))
        add("a slab that must reach 1.2 fcm first", "before the slab reaches")(
            lambda d: d["inputs"]["slabs"].update(ready_mpa=1.2 * d["inputs"]["slabs"]["concrete"]["fcm_mpa"]))


def site_corruptions(doc, add):
    """On a site calendar: a timestamp an hour off, the shifts starting an hour later, a
    working day made a holiday, a planned joint unflagged or its treatment left out, a
    climb moved to the night, a day miscounted."""
    site = doc["inputs"].get("site")
    if site is None:
        return
    layers, events = doc["layers"], doc["events"]
    add("a layer's timestamp an hour off", "start_time")(
        lambda d: d["layers"][1].update(start_time=d["layers"][2]["start_time"]))
    # Every shift starting an hour after the hour the first layer starts in.
    later = "%02d:00" % min(int(layers[0]["start_time"][11:13]) + 1, 23)
    add("shifts starting later", "outside one working window")(
        lambda d: d["inputs"]["site"]["working_hours"].update(
            {k: [later + s[5:] if s[:5] < later < s[6:] else s for s in v]
             for k, v in site["working_hours"].items()}))
    last_day = doc["days"][-1]["date"]
    add("a working day made a holiday", "outside one working window")(
        lambda d: d["inputs"]["site"]["holidays"].append(last_day))
    add("a day miscounted", "days")(lambda d: d["days"][0].update(layers=d["days"][0]["layers"] + 1))
    joints = [i for i, l in enumerate(layers) if l["planned_joint"]]
    if joints:
        j = joints[0]
        add("a planned joint unflagged", "not a planned joint")(
            lambda d: d["layers"][j].update(planned_joint=False))
        add("a planned joint's treatment left out", "no joint event")(
            lambda d: d.update(events=[e for e in d["events"] if e["kind"] != "joint"]))
    if site.get("conditions") is not None:
        readings = site["conditions"]["readings"]
        times = [r[0] for r in readings]

        def in_force(t):
            return max(bisect.bisect_right(times, t) - 1, 0)
        mid = layers[len(layers) // 2]
        k = in_force(mid["start_s"])
        add("a frost while a layer prints", "placing range")(
            lambda d: d["inputs"]["site"]["conditions"]["readings"][k].__setitem__(1, -5.0))
        add("a warmer site", "equivalent_interval")(
            lambda d: [r.__setitem__(1, r[1] + 10.0) for r in d["inputs"]["site"]["conditions"]["readings"]])
        climbing = [e for e in events if e["kind"] == "climb"]
        if climbing:
            g = in_force(climbing[-1]["start_s"])
            add("a gale while the machine climbs", "climbing limit")(
                lambda d: d["inputs"]["site"]["conditions"]["readings"][g].__setitem__(2, 40.0))
    climbs = [i for i, e in enumerate(events) if e["kind"] == "climb"]
    if climbs:
        c = climbs[0]

        @add("a climb in the night", "outside one working window")
        def night(d):
            # To 02:xx local time the same day, whatever hour it started at.
            e = d["events"][c]
            back = (int(e["start_time"][11:13]) - 2) * 3600.0
            e["start_s"] -= back
            e["end_s"] -= back


class Caught(Exception):
    """The problem a corruption should cause was found: the rest of the check is skipped."""


class Watch(list):
    """Problems, raising Caught once one contains `expect`."""

    def __init__(self, expect):
        super().__init__()
        self.expect = expect

    def append(self, problem):
        super().append(problem)
        if self.expect in problem:
            raise Caught()


def self_test(text, doc):
    missed = []
    cases = corruptions(doc)
    for name, change, expect in cases:
        bad = json.loads(text)
        change(bad)
        problems = Watch(expect)
        try:
            check(bad, problems)
        except Caught:
            pass
        except NotASchedule as x:
            problems = ["NOT A SCHEDULE: %s" % x]
        if not any(expect in p for p in problems):
            missed.append(name)
            print("self-test: missed: %s (expected a problem with %r; got %d: %s)" % (
                name, expect, len(problems), "; ".join(problems[:3]) or "none"))
    print("self-test: %d of %d corruptions caught" % (len(cases) - len(missed), len(cases)))
    return not missed and len(cases) >= 10


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("schedule", help="a schedule JSON written by `ccbuild schedule -o`")
    parser.add_argument("--self-test", action="store_true",
                        help="also corrupt the document in many ways and check each is caught")
    args = parser.parse_args(argv)
    began = time.monotonic()
    try:
        with open(args.schedule) as f:
            text = f.read()
        doc = json.loads(text)
        problems, notes, stats = check(doc)
    except (OSError, ValueError, NotASchedule) as x:
        print("check_schedule: %s: not a schedule: %s" % (args.schedule, x), file=sys.stderr)
        return 2
    for n in notes[:5]:
        print("info (infeasible, as the document says): " + n)
    if len(notes) > 5:
        print("info: %d more of those" % (len(notes) - 5))
    if problems:
        for p in problems[:MAX_SHOWN]:
            print("problem: " + p)
        if len(problems) > MAX_SHOWN:
            print("... and %d more" % (len(problems) - MAX_SHOWN))
        print("%d problem(s) in %s" % (len(problems), args.schedule))
        return 1
    print("%s: %s (%.1f s)" % (args.schedule, summary(doc, stats), time.monotonic() - began))
    if args.self_test:
        return 0 if self_test(text, doc) else 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
