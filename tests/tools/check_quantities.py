#!/usr/bin/env python3
"""Checks the concrete quantities of `ccbuild schedule` against a hand computation, outside
ccbuild: the house's ground floor from its plan file alone (vertices, walls, openings), as a
site planner would take it off the drawings: per layer, every wall's centreline length less
the openings open in that layer (an opening is open where the layer's mid-height lies in
[sill, head)), times the bead width (the nozzle's, 0.15 m) and the layer height. The
schedule's floor total must match within 0.1 %, and its deliveries must be the material's
8 m³ batches of the building's total, the first due at the first layer's start.

Usage: check_quantities.py CCBUILD SOURCE_DIR
"""
import json
import math
import os
import re
import subprocess
import sys
import tempfile

NUMBER = r"(-?[0-9.]+)"


def fields(line):
    """The key: value pairs of a one-line YAML flow map."""
    return dict(re.findall(r"(\w+): ([^,}]+)", line))


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    ccbuild, source = sys.argv[1], sys.argv[2]
    plan = open(os.path.join(source, "config/buildings/house/ground.yaml")).read()
    vertices, walls, openings = {}, {}, []
    section = None
    for line in plan.splitlines():
        if re.match(r"^(vertices|walls|openings):", line):
            section = line.split(":")[0]
            continue
        if not line.strip().startswith("- {"):
            continue
        f = fields(line)
        if section == "vertices":
            vertices[f["id"].strip()] = (float(f["x"]), float(f["y"]))
        elif section == "walls":
            a, b = vertices[f["start"].strip()], vertices[f["end"].strip()]
            walls[f["id"].strip()] = math.dist(a, b)
        elif section == "openings":
            openings.append((f["wall"].strip(), float(f["width"]), float(f.get("sill", 0)),
                             float(f["head"])))
    if len(walls) < 10 or len(openings) < 10:
        sys.exit("could not read the house's ground plan (%d walls, %d openings)"
                 % (len(walls), len(openings)))
    width_m, layer_m, floor_m = 0.15, 0.1, 3.0
    layers = round(floor_m / layer_m)
    hand_m3 = 0.0
    for k in range(layers):
        mid = (k + 0.5) * layer_m
        length = sum(walls.values()) - sum(w for _, w, sill, head in openings if sill <= mid < head)
        hand_m3 += length * width_m * layer_m

    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "house.json")
        subprocess.run([ccbuild, "schedule", os.path.join(source, "config/buildings/house.yaml"),
                        "--quiet", "--no-compare", "-o", out], check=True, capture_output=True, timeout=600)
        doc = json.load(open(out))
    floor0 = sum(l["concrete_m3"] for l in doc["layers"] if l["floor"] == 0)
    error = abs(floor0 - hand_m3) / hand_m3
    if error > 1e-3:
        sys.exit("the ground floor holds %.4f m3 in the schedule, %.4f m3 by hand (%.3f %% apart)"
                 % (floor0, hand_m3, 100 * error))
    total = sum(l["concrete_m3"] for l in doc["layers"])
    if abs(doc["totals"]["concrete_m3"] - total) > 1e-5:
        sys.exit("totals.concrete_m3 %.6f, the layers hold %.6f" % (doc["totals"]["concrete_m3"], total))
    batch = doc["inputs"]["material"]["delivery_batch_m3"]
    trucks = doc["deliveries"]
    if len(trucks) != math.ceil(total / batch - 1e-9) or \
            abs(sum(t["m3"] for t in trucks) - total) > 1e-5 or \
            abs(trucks[0]["due_s"] - doc["layers"][0]["start_s"]) > 1e-6:
        sys.exit("%d deliveries of %s m3 for %.4f m3, the first due at %.3f s"
                 % (len(trucks), batch, total, trucks[0]["due_s"] if trucks else math.nan))
    print("the house's ground floor: %.4f m3 in the schedule, %.4f m3 by hand from its plan "
          "(%.4f %% apart); %.3f m3 in all, %d deliveries of %g m3"
          % (floor0, hand_m3, 100 * error, total, len(trucks), batch))


if __name__ == "__main__":
    main()
