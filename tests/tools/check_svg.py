#!/usr/bin/env python3
"""Checks a plan drawing (plan-layer --svg) against what an engineer needs to read it.

Independent of ccbuild's code: it parses the SVG as XML and checks that
  - it is well-formed and every drawn element lies inside the image (titles, labels and
    tick labels included, their width estimated from their length);
  - it has a title, a legend, a scale bar, and axis ticks with labels along both axes;
  - air moves are drawn over the walls, so one running along a wall stays visible;
  - the walls carry their ids (every wall of the plan's JSON, given as the second
    argument, is labelled), not move numbers;
  - a multi-nozzle drawing has its x/t chart, every curve inside the chart; or, when the
    JSON says there is no plan, the reasons instead of a chart.

Usage: check_svg.py DRAWING.svg PLAN.json     exit 0 when sound, 1 with the problems
"""

import json
import re
import sys
import xml.etree.ElementTree as ET

NS = "{http://www.w3.org/2000/svg}"
TOLERANCE = 1.0  # px


def number_list(text):
    return [float(v) for v in re.findall(r"-?\d+(?:\.\d+)?(?:e[-+]?\d+)?", text or "")]


def text_extent(node):
    """Left and right of a text element, estimated: 0.6 em per character."""
    x = float(node.get("x", 0))
    size = float(node.get("font-size", 12))
    width = 0.6 * size * len("".join(node.itertext()))
    anchor = node.get("text-anchor", "start")
    if anchor == "middle":
        return x - width / 2, x + width / 2
    if anchor == "end":
        return x - width, x
    return x, x + width


def check(svg_path, plan):
    problems = []
    try:
        root = ET.parse(svg_path).getroot()
    except ET.ParseError as error:
        return ["not well-formed XML: %s" % error]
    width, height = float(root.get("width")), float(root.get("height"))
    view = number_list(root.get("viewBox"))
    if view != [0.0, 0.0, width, height]:
        problems.append("viewBox %s does not match the size %g x %g" % (root.get("viewBox"), width, height))

    def inside(x, y, what):
        if x < -TOLERANCE or x > width + TOLERANCE or y < -TOLERANCE or y > height + TOLERANCE:
            problems.append("%s at (%.1f, %.1f) is outside the %g x %g image" % (what, x, y, width, height))

    for node in root.iter():
        tag = node.tag.replace(NS, "")
        if tag == "line":
            inside(float(node.get("x1")), float(node.get("y1")), "a line")
            inside(float(node.get("x2")), float(node.get("y2")), "a line")
        elif tag in ("polyline", "polygon"):
            values = number_list(node.get("points"))
            for x, y in zip(values[0::2], values[1::2]):
                inside(x, y, "a " + tag)
        elif tag == "rect" and node.get("width") != "100%":
            x, y = float(node.get("x", 0)), float(node.get("y", 0))
            inside(x, y, "a rectangle")
            inside(x + float(node.get("width")), y + float(node.get("height")), "a rectangle")
        elif tag == "circle":
            inside(float(node.get("cx")), float(node.get("cy")), "a circle")
        elif tag == "text":
            left, right = text_extent(node)
            y = float(node.get("y", 0))
            label = "text '%s'" % "".join(node.itertext())[:40]
            inside(left, y, label)
            inside(right, y, label)

    ids = {node.get("id") for node in root.iter() if node.get("id")}
    for wanted in ("title", "legend", "scale-bar", "axes"):
        if wanted not in ids:
            problems.append("no %s" % wanted)
    # Air moves are drawn over the walls, so a move along a wall stays visible.
    order = [n.get("id") for n in root.iter() if n.get("id") in ("walls", "air-moves")]
    if order == ["air-moves", "walls"]:
        problems.append("the air moves are drawn under the walls (hidden where they run along one)")
    ticks = [n for n in root.iter() if n.get("class") == "tick-label"]
    if len(ticks) < 4:
        problems.append("only %d tick labels; the axes need them" % len(ticks))
    legend = next((n for n in root.iter() if n.get("id") == "legend"), None)
    if legend is not None and len([n for n in legend.iter() if n.tag == NS + "text"]) < 2:
        problems.append("the legend explains fewer than two things")

    # Wall ids, not move numbers, label the walls.
    labels = {"".join(n.itertext()) for n in root.iter() if n.get("class") == "wall-id"}
    solved = plan.get("nozzles", 1) == 1 or plan.get("status") == "solved"
    if solved:
        for piece in plan["pieces"]:
            name = str(piece["wall"]) + (":%d" % piece["piece"] if piece["piece_count"] > 1 else "")
            # A multi-nozzle plan may cut a piece at a section border and number the parts.
            if name not in labels and not any(l.split(":")[0] == str(piece["wall"]) for l in labels):
                problems.append("wall %s is not labelled with its id" % name)
    if plan.get("nozzles", 1) > 1:
        chart = next((n for n in root.iter() if n.get("id") == "xt-chart"), None)
        if solved:
            if chart is None:
                problems.append("no x/t chart")
            else:
                frame = next(n for n in chart if n.tag == NS + "rect")
                x0, y0 = float(frame.get("x")), float(frame.get("y"))
                x1, y1 = x0 + float(frame.get("width")), y0 + float(frame.get("height"))
                for curve in chart.iter(NS + "polyline"):
                    values = number_list(curve.get("points"))
                    for x, y in zip(values[0::2], values[1::2]):
                        if x < x0 - TOLERANCE or x > x1 + TOLERANCE or y < y0 - TOLERANCE or y > y1 + TOLERANCE:
                            problems.append("an x/t curve leaves the chart at (%.1f, %.1f)" % (x, y))
                            break
        else:
            if chart is not None:
                problems.append("an x/t chart is drawn for a plan that does not exist")
            if "no-plan" not in ids:
                problems.append("no explanation of why there is no plan")
    return problems


def main(argv):
    if len(argv) != 3:
        print(__doc__)
        return 2
    with open(argv[2]) as f:
        plan = json.load(f)
    problems = check(argv[1], plan)
    for p in problems[:40]:
        print("problem: " + p)
    if problems:
        print("%d problem(s) in %s" % (len(problems), argv[1]))
        return 1
    print("OK: %s is inside its frame, with title, legend, scale bar, axes and wall ids" % argv[1])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
