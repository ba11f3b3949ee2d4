#!/usr/bin/env python3
"""Regenerates the example buildings in config/buildings/ (deterministic).

Each floor is drawn as axis-parallel wall lines (room outlines and partitions); lines are
merged, split at every junction into walls between vertices, and given doors (interior
walls) and windows (exterior walls). The house is in metres, the apartment block in feet,
and the plans use all three encodings (YAML, JSON, table text) on purpose.

    python3 scripts/make_examples.py          # rewrites config/buildings/
"""
import json
import os
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "config", "buildings")


def union(intervals):
    out = []
    for a, b in sorted(intervals):
        if out and a <= out[-1][1]:
            out[-1][1] = max(out[-1][1], b)
        else:
            out.append([a, b])
    return out


class Floor:
    def __init__(self, width, depth):
        self.w, self.d = width, depth
        self.h = {}  # y -> [x0, x1] intervals
        self.v = {}  # x -> [y0, y1] intervals
        self.rect(0, 0, width, depth)

    def hline(self, y, x0, x1):
        self.h.setdefault(y, []).append((min(x0, x1), max(x0, x1)))

    def vline(self, x, y0, y1):
        self.v.setdefault(x, []).append((min(y0, y1), max(y0, y1)))

    def rect(self, x0, y0, x1, y1):
        self.hline(y0, x0, x1)
        self.hline(y1, x0, x1)
        self.vline(x0, y0, y1)
        self.vline(x1, y0, y1)

    def walls(self):
        """Splits every merged line at every junction; returns vertices and walls."""
        h = {y: union(iv) for y, iv in self.h.items()}
        v = {x: union(iv) for x, iv in self.v.items()}
        pieces = []
        for y, ivs in sorted(h.items()):
            for a, b in ivs:
                cuts = {a, b}
                for x, vivs in v.items():
                    if a <= x <= b and any(c <= y <= d for c, d in vivs):
                        cuts.add(x)
                cuts = sorted(cuts)
                pieces += [((p, y), (q, y)) for p, q in zip(cuts, cuts[1:])]
        for x, ivs in sorted(v.items()):
            for a, b in ivs:
                cuts = {a, b}
                for y, hivs in h.items():
                    if a <= y <= b and any(c <= x <= d for c, d in hivs):
                        cuts.add(y)
                cuts = sorted(cuts)
                pieces += [((x, p), (x, q)) for p, q in zip(cuts, cuts[1:])]
        vid = {}
        for a, b in pieces:
            for p in (a, b):
                vid.setdefault(p, len(vid) + 1)
        walls = [(i + 1, vid[a], vid[b], a, b) for i, (a, b) in enumerate(pieces)]
        return vid, walls

    def exterior(self, a, b):
        return (a[0] == b[0] and a[0] in (0, self.w)) or (a[1] == b[1] and a[1] in (0, self.d))


def openings_for(floor, walls, units, entrance_walls=(), storey=0, solid=()):
    """Doors in interior walls, windows in exterior walls (ground floor entrances too)."""
    if units == "m":
        door_w, door_h, win_w, sill, head, min_door, min_win = 0.9, 2.1, 1.2, 0.9, 2.1, 1.6, 2.2
    else:
        door_w, door_h, win_w, sill, head, min_door, min_win = 3.0, 7.0, 4.0, 3.0, 7.0, 5.0, 7.0
    out = []
    for wid, _, _, a, b in walls:
        length = abs(b[0] - a[0]) + abs(b[1] - a[1])
        if (a, b) in solid:
            continue
        if wid in entrance_walls and length >= min_door:
            out.append({"id": "E%d" % wid, "kind": "door", "wall": wid,
                        "offset": round((length - door_w) / 2, 3), "width": door_w, "head": door_h})
        elif floor.exterior(a, b):
            if length >= min_win:
                out.append({"id": "W%d" % wid, "kind": "window", "wall": wid,
                            "offset": round((length - win_w) / 2, 3), "width": win_w,
                            "sill": sill, "head": head})
        elif length >= min_door and (wid + storey) % 3 != 0:
            # Doors sit near one end of the wall, as in real rooms.
            off = round(min(length - door_w, length * 0.15), 3)
            out.append({"id": "D%d" % wid, "kind": "door", "wall": wid, "offset": off,
                        "width": door_w, "head": door_h})
    return out


def anchors_for(floor, walls, units):
    """Eight anchor pipes on exterior walls, one on each side of every corner."""
    inset = 0.3 if units == "m" else 1.0
    corners = [(0, 0), (floor.w, 0), (floor.w, floor.d), (0, floor.d)]
    out = []
    for c in corners:
        for wid, _, _, a, b in walls:
            if floor.exterior(a, b) and c in (a, b):
                length = abs(b[0] - a[0]) + abs(b[1] - a[1])
                off = inset if a == c else length - inset
                out.append({"id": "A%d" % (len(out) + 1), "wall": wid, "offset": round(off, 3)})
    return out


def anchors_at(floor, walls, xs):
    """Anchor pipes on the two long exterior walls (y = 0 and y = depth) at the given x:
    where config/machines/cc-climber.yaml's units reach them (its units hang at x = 2 ft
    and 97 ft; on the smaller top floors the far pair must reach in to 94 ft)."""
    out = []
    for y in (0, floor.d):
        for x in xs:
            for wid, _, _, a, b in walls:
                if a[1] == b[1] == y and min(a[0], b[0]) < x < max(a[0], b[0]):
                    off = abs(x - a[0])
                    out.append({"id": "A%d" % (len(out) + 1), "wall": wid, "offset": round(off, 3)})
    return out


def yaml_plan(units, vid, walls, openings, name):
    lines = ["# %s (generated by scripts/make_examples.py)" % name, "units: %s" % units, "vertices:"]
    for (x, y), i in sorted(vid.items(), key=lambda kv: kv[1]):
        lines.append("  - {id: %d, x: %g, y: %g}" % (i, x, y))
    lines.append("walls:")
    for wid, s, e, _, _ in walls:
        lines.append("  - {id: %d, start: %d, end: %d}" % (wid, s, e))
    if openings:
        lines.append("openings:")
        for o in openings:
            lines.append("  - {" + ", ".join("%s: %s" % (k, v) for k, v in o.items()) + "}")
    return "\n".join(lines) + "\n"


def json_plan(units, vid, walls, openings):
    doc = {"units": units,
           "vertices": [{"id": i, "x": x, "y": y} for (x, y), i in sorted(vid.items(), key=lambda kv: kv[1])],
           "walls": [{"id": w, "start": s, "end": e} for w, s, e, _, _ in walls],
           "openings": openings}
    return json.dumps(doc, indent=1) + "\n"


def table_plan(vid, walls, openings, name):
    lines = ["# %s (generated by scripts/make_examples.py)" % name,
             "# table format: lengths in the building's units", "vertices"]
    for (x, y), i in sorted(vid.items(), key=lambda kv: kv[1]):
        lines.append("%d %g %g" % (i, x, y))
    lines.append("walls")
    for wid, s, e, _, _ in walls:
        lines.append("%d %d %d" % (wid, s, e))
    if openings:
        lines.append("openings")
        lines.append("# wall offset width sill head")
        for o in openings:
            lines.append("%d %g %g %g %g" % (o["wall"], o["offset"], o["width"], o.get("sill", 0), o["head"]))
    return "\n".join(lines) + "\n"


def house():
    ground = Floor(12, 9)
    ground.vline(5, 0, 9)
    ground.hline(5, 5, 12)
    ground.vline(8.5, 5, 9)
    ground.hline(3.5, 0, 5)
    ground.vline(2.5, 3.5, 9)
    ground.hline(7, 8.5, 12)
    ground.hline(6.5, 0, 2.5)
    ground.vline(9, 0, 5)
    ground.hline(2.5, 9, 12)
    ground.vline(3.5, 0, 3.5)
    ground.hline(1.5, 3.5, 5)      # closet under the stairs
    ground.vline(10.5, 7, 9)       # shower
    ground.hline(8, 2.5, 5)        # pantry
    ground.vline(7, 0, 2)          # kitchen island wall
    upper = Floor(12, 9)
    upper.vline(4, 0, 9)
    upper.vline(8, 0, 9)
    upper.hline(4.5, 0, 12)
    upper.hline(6.5, 4, 8)
    upper.vline(6, 4.5, 6.5)
    upper.hline(2, 8, 12)
    upper.vline(10, 4.5, 9)
    upper.hline(7, 0, 4)
    upper.vline(2, 7, 9)
    upper.hline(2.5, 0, 2)         # wardrobes
    upper.hline(2.5, 6, 8)
    upper.vline(6, 0, 1.5)
    upper.hline(6.5, 10, 12)
    return ground, upper


def flats_floor(width, bathrooms=True, lobbies=True, closets=True):
    """A floor of flats `width` ft long and 52 ft deep: a corridor between y 22 and 30,
    flats 16 ft wide on both sides, each split into bedroom and living room; optionally a
    bathroom (south), a lobby (north) and a closet off the bedroom."""
    f = Floor(width, 52)
    f.hline(22, 0, width)
    f.hline(30, 0, width)
    flats = width // 16
    for k in range(1, flats):
        f.vline(16 * k, 0, 22)
        f.vline(16 * k, 30, 52)
    for k in range(flats):
        x0 = 16 * k
        f.hline(12, x0, x0 + 10)           # bedroom / living split
        f.vline(x0 + 10, 0, 12)
        if bathrooms:
            f.hline(16, x0 + 10, x0 + 16)
            f.vline(x0 + 10, 16, 22)
        f.hline(40, x0 + 6, x0 + 16)       # north flats, mirrored
        f.vline(x0 + 6, 40, 52)
        if lobbies:
            f.hline(36, x0, x0 + 6)
            f.vline(x0 + 6, 30, 36)
        if closets:
            f.vline(x0 + 4, 12, 16)
            f.hline(16, x0, x0 + 4)
    return f


def apartment():
    """The apartment block's typical floor (128 ft) and its set-back top (96 ft)."""
    return flats_floor(128), flats_floor(96, closets=False)


def tower_flats():
    """The ten-storey tower's upper floors: the apartment block's footprint with fewer
    partitions (open-plan flats: no closets, bathrooms or lobbies), so that one nozzle
    keeps its layers within the material's interval; its ground floor (the apartment
    block's typical floor) is denser and takes more nozzles."""
    return flats_floor(128, bathrooms=False, lobbies=False, closets=False)


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def main():
    counts = {}
    # --- Two-storey house, metres: ground plan YAML, upper plan JSON.
    ground, upper = house()
    gv, gw = ground.walls()
    uv, uw = upper.walls()
    entrance = [w for w, _, _, a, b in gw if a[1] == 0 and b[1] == 0 and min(a[0], b[0]) >= 5][:1]
    write(os.path.join(ROOT, "house", "ground.yaml"),
          yaml_plan("m", gv, gw, openings_for(ground, gw, "m", entrance), "house, ground floor"))
    write(os.path.join(ROOT, "house", "upper.json"), json_plan("m", uv, uw, openings_for(upper, uw, "m", storey=1)))
    counts["house"] = (len(gw), len(uw))
    house_yaml = f"""# Two-storey house, 12 m x 9 m, 3 m floors (generated by scripts/make_examples.py).
name: Two-storey house
units: m
layer_height: 0.1
# A soffit form under each head, set by a crew of two; the layers above print the lintel.
lintels: {{type: formwork, bearing: 0.15, place_min: 10, crew: 2}}
material: ../materials/standard-mix.yaml
machine: ../machines/cc-gantry.yaml
floors:
  - name: ground
    height: 3.0
    plan: house/ground.yaml
    anchors:
{chr(10).join('      - ' + json.dumps(a).replace('"', '') for a in anchors_for(ground, gw, 'm'))}
  - name: upper
    height: 3.0
    plan: house/upper.json
    anchors:
{chr(10).join('      - ' + json.dumps(a).replace('"', '') for a in anchors_for(upper, uw, 'm'))}
"""
    write(os.path.join(ROOT, "house.yaml"), house_yaml)

    # --- Five-storey apartment block, feet: typical plan YAML (floors 0-2), top plan in
    # the table format (floors 3-4, smaller footprint); ground-floor entrances in the
    # building file.
    typical, top = apartment()
    tv, tw = typical.walls()
    pv, pw = top.walls()
    corridor_ends = {((x, 22), (x, 30)) for x in (0, 128)}
    write(os.path.join(ROOT, "apartment", "typical.yaml"),
          yaml_plan("ft", tv, tw, openings_for(typical, tw, "ft", solid=corridor_ends),
                    "apartment block, typical floor"))
    write(os.path.join(ROOT, "apartment", "top.txt"),
          table_plan(pv, pw, openings_for(top, pw, "ft", storey=1), "apartment block, top floors (setback)"))
    counts["apartment"] = (len(tw), len(pw))
    # Entrances: the corridor ends (x = 0 and x = 128 between y 22 and 30) become doors.
    ends = [w for w, _, _, a, b in tw if a[0] == b[0] and a[0] in (0, 128) and min(a[1], b[1]) == 22]
    entrance_lines = "\n".join(
        "      - {id: ENT%d, kind: door, wall: %d, offset: 2.5, width: 3, head: 7}" % (i + 1, w)
        for i, w in enumerate(ends))
    def anchors(fl, ws, xs):
        return "\n".join("      - " + json.dumps(a).replace('"', '') for a in anchors_at(fl, ws, xs))

    def floor_entry(k, plan, fl, ws, xs):
        """A 10 ft storey of the block or the tower; the ground floor has the entrances."""
        extra = f"\n    openings:\n{entrance_lines}" if k == 0 else ""
        return f"""  - name: level {k}
    height: 10
    plan: {plan}{extra}
    anchors:                    # where the climbing units' pins go (cc-climber.yaml)
{anchors(fl, ws, xs)}"""
    floors = []
    for k in range(5):
        plan, fl, ws = ("apartment/typical.yaml", typical, tw) if k < 3 else ("apartment/top.txt", top, pw)
        xs = (2, 97) if k < 3 else (2, 94)  # the top floors are set back: the far pair reaches in
        floors.append(floor_entry(k, plan, fl, ws, xs))
    apartment_yaml = f"""# Five-storey apartment block, 128 ft x 52 ft with a 96 ft setback on the top two
# storeys; 10 ft floors (generated by scripts/make_examples.py). Its machine is the fixed
# gantry; its anchor points are where the climbing machine's units go:
#   ccbuild climb config/buildings/apartment.yaml --machine config/machines/cc-climber.yaml
name: Five-storey apartment block
units: ft
layer_height: 0.4
# A soffit form under each head, set by a crew of two; the layers above print the lintel.
lintels: {{type: formwork, bearing: 0.5, place_min: 6, crew: 2}}
material: ../materials/standard-mix.yaml
machine: ../machines/cc-gantry.yaml
floors:
{chr(10).join(floors)}
"""
    write(os.path.join(ROOT, "apartment.yaml"), apartment_yaml)

    # --- Ten-storey tower, feet, on the climbing machine: the apartment block's typical
    # floor at the bottom (too slow for one nozzle), open-plan flats on floors 1-6, the
    # set-back top plan on floors 7-9; anchors where cc-climber.yaml's units reach.
    flats = tower_flats()
    fv, fw = flats.walls()
    write(os.path.join(ROOT, "tower", "flats.yaml"),
          yaml_plan("ft", fv, fw, openings_for(flats, fw, "ft", solid=corridor_ends),
                    "tower, open-plan flats (floors 1-6)"))
    counts["tower flats"] = len(fw)
    tower_floors = []
    for k in range(10):
        if k == 0:
            plan, fl, ws, xs = "apartment/typical.yaml", typical, tw, (2, 97)
        elif k < 7:
            plan, fl, ws, xs = "tower/flats.yaml", flats, fw, (2, 97)
        else:
            plan, fl, ws, xs = "apartment/top.txt", top, pw, (2, 94)
        tower_floors.append(floor_entry(k, plan, fl, ws, xs))
    tower_yaml = f"""# Ten-storey tower, 128 ft x 52 ft, set back to 96 ft on the top three storeys; 10 ft
# floors (generated by scripts/make_examples.py). Built by the climbing machine: it
# climbs between floors once the anchors cast in the floor below are strong enough.
# The ground floor (the apartment block's typical plan) is too slow for one nozzle; the
# open-plan floors above and the top floors take one. Each floor's slab is formed and
# poured by a crew of four, and the next floor starts once it reaches 5 MPa; a roof on top.
name: Ten-storey tower
units: ft
layer_height: 0.4
slabs: {{thickness: 0.66, setup_h: 8, pour_m3_h: 30, ready_mpa: 5, concrete: {{fcm_mpa: 38, cement_class: N}}, crew: 4, roof: true}}
lintels: {{type: formwork, bearing: 0.5, place_min: 6, crew: 2}}
material: ../materials/standard-mix.yaml
machine: ../machines/cc-climber.yaml
floors:
{chr(10).join(tower_floors)}
"""
    write(os.path.join(ROOT, "tower.yaml"), tower_yaml)
    print("walls per floor:", counts, file=sys.stderr)


if __name__ == "__main__":
    main()
