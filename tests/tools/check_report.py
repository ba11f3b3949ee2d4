#!/usr/bin/env python3
"""Opens a ccbuild report (HTML) in headless Chromium and checks that it rendered.

Reads only the report and what Chromium makes of it: the DOM after the page's scripts
ran (--dump-dom) and a screenshot. Checks that every section rendered (the page marks
each with data-rendered="yes", or "failed" with the error), that the DOM holds the
Gantt's bars, the interval chart, the heat map's pieces, one card per plan, the strength
charts and a WebGL canvas that drew something (its colours read back on a grid), that no
error reached the console (the page collects them in #console-errors), that an
infeasible schedule's report says so before anything else, and that the screenshot is
not blank. Chromium missing is a failure, not a skip: scripts/install-deps.sh installs it.

Usage: check_report.py REPORT.html [--infeasible] [--min-plans N]
Exit 0 when every check passes, 1 otherwise.
"""
import argparse
import json
import os
import re
import shutil
import signal
import struct
import subprocess
import sys
import tempfile
import zlib

SECTIONS = ["summary", "gantt", "days", "intervals", "heatmap", "strength", "toolpaths", "playback"]


def chromium():
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    sys.exit("check_report: Chromium is not installed (Debian: apt-get install chromium; "
             "scripts/install-deps.sh installs it)")


CHROMIUM_TIMEOUT_S = 90  # a run takes 5 s here, 13 s with both cores busy
CHROMIUM_ATTEMPTS = 3


def run_chromium(browser, url, extra, out_dir):
    """Chromium's CompletedProcess for the page. Headless Chromium now and then hangs
    before it writes anything (seen once in hundreds of runs, the same page taking 5 s
    the next time), so a run that outlives CHROMIUM_TIMEOUT_S is killed with its
    children and tried again with a fresh profile, up to CHROMIUM_ATTEMPTS times."""
    for attempt in range(1, CHROMIUM_ATTEMPTS + 1):
        profile = os.path.join(out_dir, "profile-%d" % attempt)
        # The background-networking flags keep Chromium from reaching for the network,
        # which the test machines refuse.
        cmd = [browser, "--headless", "--no-sandbox", "--disable-gpu", "--use-angle=swiftshader",
               "--disable-background-networking", "--disable-component-update", "--disable-sync",
               "--disable-quic", "--no-first-run",
               "--enable-unsafe-swiftshader", "--hide-scrollbars", "--window-size=1400,2400",
               "--virtual-time-budget=20000", "--user-data-dir=" + profile] + extra + [url]
        proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, cwd=out_dir,
                                env=dict(os.environ, HOME=out_dir), start_new_session=True)
        try:
            out, err = proc.communicate(timeout=CHROMIUM_TIMEOUT_S)
            return subprocess.CompletedProcess(cmd, proc.returncode, out, err)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.communicate()
            print("check_report: chromium %s did not finish in %d s (attempt %d of %d)%s" % (
                " ".join(extra), CHROMIUM_TIMEOUT_S, attempt, CHROMIUM_ATTEMPTS,
                "; trying again" if attempt < CHROMIUM_ATTEMPTS else ""), file=sys.stderr)
    sys.exit("check_report: chromium hung %d times on %s" % (CHROMIUM_ATTEMPTS, url))


def png_not_blank(path):
    """(ok, why): the screenshot decodes and its filtered rows are not all zero (a blank
    image's rows filter to zeros; a drawn page's do not)."""
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        return False, "not a PNG"
    pos, idat, width, height = 8, b"", 0, 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        pos += 12 + n
        if kind == b"IHDR":
            width, height = struct.unpack(">II", body[:8])
        elif kind == b"IDAT":
            idat += body
    raw = zlib.decompress(idat)
    nonzero = len(raw) - raw.count(0)
    share = nonzero / max(1, len(raw))
    if width < 100 or height < 100:
        return False, "%dx%d" % (width, height)
    if share < 0.002:  # a blank page: 0.0002; the house report: 0.018
        return False, "%.4f of its bytes differ from their neighbours: blank" % share
    return True, "%dx%d, %.1f%% of bytes vary" % (width, height, 100 * share)


def lab(colour):
    """CIELAB (D65) of '#rrggbb'."""
    r, g, b = [int(colour[i:i + 2], 16) / 255 for i in (1, 3, 5)]
    r, g, b = [c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4 for c in (r, g, b)]
    x = (0.4124 * r + 0.3576 * g + 0.1805 * b) / 0.95047
    y = 0.2126 * r + 0.7152 * g + 0.0722 * b
    z = (0.0193 * r + 0.1192 * g + 0.9505 * b) / 1.08883
    f = lambda t: t ** (1 / 3) if t > 0.008856 else 7.787 * t + 16 / 116
    return 116 * f(y) - 16, 500 * (f(x) - f(y)), 200 * (f(y) - f(z))


MIN_COLOUR_DISTANCE = 20.0  # CIE76: about 2.3 is just noticeable; 20 reads as another colour


def alike(named):
    """The pairs of {name: '#rrggbb'} closer than MIN_COLOUR_DISTANCE."""
    names = sorted(named)
    out = []
    for i, a in enumerate(names):
        for b in names[i + 1:]:
            d = sum((p - q) ** 2 for p, q in zip(lab(named[a]), lab(named[b]))) ** 0.5
            if d < MIN_COLOUR_DISTANCE:
                out.append("%s %s and %s %s (distance %.1f)" % (a, named[a], b, named[b], d))
    return out


def attributes(tag_text):
    """The attributes of one start tag's text, as a dict."""
    return dict(re.findall(r'([\w:-]+)="([^"]*)"', tag_text))


def chart(dom, chart_id):
    """The <svg id=chart_id>'s attributes and inner text, or (None, None)."""
    m = re.search(r'<svg([^>]*\bid="%s"[^>]*)>(.*?)</svg>' % chart_id, dom, re.S)
    return (attributes(m.group(1)), m.group(2)) if m else (None, None)


def inverse(scale_text):
    """From a chart's data-*-scale ("d0 d1 r0 r1"): pixels to values, and what one pixel is
    worth in values."""
    d0, d1, r0, r1 = (float(v) for v in scale_text.split())
    per_px = (d1 - d0) / (r1 - r0) if r1 != r0 else 0.0
    return (lambda px: d0 + (px - r0) * per_px), abs(per_px)


def check_drawn_values(dom, schedule, problems, counts):
    """The anchor, buildability and interval charts draw the schedule's own numbers: each
    drawn point, turned back into values by the chart's scales, equals the JSON's within
    the drawing's precision (0.01 px)."""
    layers = schedule["layers"]
    px = 0.011  # the page writes anchor points to 0.01 px
    checked = 0
    climbs = [e for e in schedule["events"] if e.get("kind") == "climb"]
    attrs, body = chart(dom, "anchor-chart")
    if climbs and attrs is None:
        problems.append("no anchor chart for %d climbs" % len(climbs))
    elif climbs:
        tx, t_px = inverse(attrs["data-x-scale"])
        ty, y_px = inverse(attrs["data-y-scale"])
        for tag in re.findall(r'<polyline([^>]*class="anchor-curve"[^>]*)>', body):
            a = attributes(tag)
            climb = climbs[int(a["data-climb"])]
            want = climb.get("youngest_anchor_strength")
            if not want:
                problems.append("climb %s -> %s: the schedule keeps no anchor strength" % (
                    climb["from_stage"], climb["to_stage"]))
                continue
            drawn = [tuple(float(v) for v in p.split(",")) for p in a["points"].split()]
            if len(drawn) != len(want):
                problems.append("climb %s -> %s: %d points drawn, %d in the schedule" % (
                    climb["from_stage"], climb["to_stage"], len(drawn), len(want)))
                continue
            for (x, y), (t, mpa) in zip(drawn, want):
                checked += 1
                if abs(tx(x) - t) > px * t_px + 1e-6 or abs(ty(y) - mpa) > px * y_px + 1e-9:
                    problems.append("climb %s -> %s: drawn at %.3f s, %.4f MPa; the schedule "
                                    "says %.3f s, %.4f MPa" % (climb["from_stage"],
                                                               climb["to_stage"], tx(x), ty(y), t, mpa))
                    break
    attrs, body = chart(dom, "margin-chart")
    with_margin = [i for i, l in enumerate(layers) if l.get("below_strength_mpa") is not None]
    if attrs is None:
        problems.append("no buildability chart")
    else:
        tx, t_px = inverse(attrs["data-x-scale"])
        ty, y_px = inverse(attrs["data-y-scale"])
        clip = float(attrs["data-clip"])
        dots = [attributes(t) for t in re.findall(r'<circle([^>]*class="margin-dot"[^>]*)>', body)]
        if [int(d["data-i"]) for d in dots] != with_margin:
            problems.append("buildability: %d points drawn for the %d layers the schedule gives "
                            "a strength below" % (len(dots), len(with_margin)))
        for d in dots:
            l = layers[int(d["data-i"])]
            want = min(l["below_strength_mpa"] / l["below_required_mpa"], clip)
            checked += 1
            if abs(ty(float(d["cy"])) - want) > 1e-6 * max(1.0, want) or \
                    abs(tx(float(d["cx"])) - l["start_s"]) > 1e-6 * max(1.0, l["start_s"]):
                problems.append("buildability: floor %d layer %d drawn at %.6f x, the schedule "
                                "says %.6f (%.4f over %.4f MPa)" % (
                                    l["floor"], l["layer"], ty(float(d["cy"])), want,
                                    l["below_strength_mpa"], l["below_required_mpa"]))
                break
    attrs, body = chart(dom, "interval-chart")
    if attrs is None:
        problems.append("no interval chart")
    else:
        ty, _ = inverse(attrs["data-y-scale"])
        equivalent = attrs.get("data-equivalent") == "yes"
        if equivalent != bool((schedule["inputs"].get("site") or {}).get("conditions")):
            problems.append("the interval chart draws %s age, the schedule's window is in %s" % (
                "equivalent" if equivalent else "clock", "equivalent" if not equivalent else "clock"))
        key = "equivalent_interval_%s_s" if equivalent else "local_interval_%s_s"
        for tag in re.findall(r'<line([^>]*class="interval-bar"[^>]*)>', body):
            a = attributes(tag)
            l = layers[int(a["data-i"])]
            checked += 1
            for end, pixel in (("min", a["y1"]), ("max", a["y2"])):
                if abs(ty(float(pixel)) - l[key % end]) > 1e-6 * max(1.0, l[key % end]):
                    problems.append("intervals: floor %d layer %d's %s drawn at %.6f s, the "
                                    "schedule says %.6f s" % (l["floor"], l["layer"], end,
                                                              ty(float(pixel)), l[key % end]))
    counts["drawn values checked against the JSON"] = checked


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("report")
    ap.add_argument("--infeasible", action="store_true", help="the schedule is infeasible: the report must say so first")
    ap.add_argument("--min-plans", type=int, default=1)
    args = ap.parse_args()
    browser = chromium()
    report = os.path.abspath(args.report)
    if not os.path.isfile(report):
        sys.exit("check_report: %s: no such file" % args.report)
    problems = []
    with tempfile.TemporaryDirectory() as out:
        url = "file://" + report
        shot = os.path.join(out, "shot.png")
        # One run gives both: the DOM after the scripts ran and the screenshot.
        run = run_chromium(browser, url, ["--dump-dom", "--screenshot=" + shot], out)
        dom = run.stdout.decode("utf-8", "replace")
        if run.returncode != 0 or "<body" not in dom:
            sys.exit("check_report: chromium --dump-dom failed (%d): %s" % (
                run.returncode, run.stderr.decode("utf-8", "replace")[-2000:]))
        if not os.path.exists(shot):
            problems.append("no screenshot (chromium exit %d)" % run.returncode)
        else:
            ok, why = png_not_blank(shot)
            if not ok:
                problems.append("the screenshot is blank: " + why)
            else:
                print("screenshot: " + why)

    for sid in SECTIONS:
        m = re.search(r'<section id="%s"[^>]*data-rendered="(\w+)"' % sid, dom)
        if not m:
            problems.append("section %s: not rendered (no data-rendered)" % sid)
        elif m.group(1) != "yes":
            problems.append("section %s: %s" % (sid, m.group(1)))
    if 'data-ready="yes"' not in dom:
        problems.append("the page's script did not finish (no data-ready on body)")
    counts = {
        "Gantt bars": len(re.findall(r'class="gantt-bar', dom)),
        "interval bars": len(re.findall(r'class="interval-bar"', dom)),
        "heat-map pieces": len(re.findall(r'class="heat-piece"', dom)),
        "plan cards": len(re.findall(r'class="plan-card layer-plan"', dom)),
        "buildability points": len(re.findall(r'class="margin-dot"', dom)),
        "x/t charts": len(re.findall(r'class="xt-chart"', dom)),
    }
    for what, n in counts.items():
        if n == 0 and what not in ("anchor curves", "lintels on plans"):
            problems.append("no %s in the DOM" % what)
    if counts["plan cards"] < args.min_plans:
        problems.append("%d plan cards, expected at least %d" % (counts["plan cards"], args.min_plans))
    # A climbing machine's climbs: one anchor strength curve each, from the schedule's data.
    data = re.search(r'<script id="schedule-data" type="application/json">(.*?)</script>',
                     open(args.report, encoding="utf-8").read(), re.S)
    if data:
        schedule = json.loads(data.group(1).replace("<\\/", "</"))
        climbs = sum(1 for e in schedule.get("events", []) if e.get("kind") == "climb")
        curves = len(re.findall(r'class="anchor-curve"', dom))
        if curves != climbs:
            problems.append("%d anchor strength curves for %d climbs" % (curves, climbs))
        what_ifs = len(schedule.get("what_if_anchors", []))
        rows = re.search(r'<table id="anchor-what-if">(.*?)</table>', dom, re.S)
        shown = len(re.findall(r"<tr>", rows.group(1))) - 2 if rows else 0
        if what_ifs and shown != what_ifs:
            problems.append("%d anchor what-ifs in the data, %d in the table" % (what_ifs, shown))
        counts["anchor curves"] = curves
        check_drawn_values(dom, schedule, problems, counts)
        # Every lintel as a beam in the 3-D view, and on the plan of the layer over it.
        lintels = sum(1 for e in schedule.get("events", []) if e.get("kind") == "lintel")
        beams = re.search(r'data-lintels="(\d+)"', dom)
        if beams is None or int(beams.group(1)) != lintels:
            problems.append("%s lintel beams in the 3-D view for %d lintels" % (
                beams.group(1) if beams else "no", lintels))
        drawn = len(re.findall(r'class="lintel"', dom))
        if lintels and drawn == 0:
            problems.append("%d lintels, none drawn on the plans" % lintels)
        counts["lintels on plans"] = drawn
    # The plan drawings: one per plan the layers use (none for a plan no layer uses), each
    # as plan-layer --svg draws one: axes with tick labels, a scale bar, wall ids, the
    # nozzles' paths; zoomable. The heat map rings the piece its caption names, labels the
    # walls, and separates its pieces by colour.
    drawings = re.findall(r'<div class="plan-drawing">(.*?)</svg>', dom, re.S)
    if data:
        used = len({l["plan"] for l in schedule["layers"]})
        if len(drawings) != used:
            problems.append("%d plan drawings for the %d plans the layers use" % (len(drawings), used))
    for n, d in enumerate(drawings):
        for what, pattern in (("axes", r'id="axes"'), ("tick labels", r'class="tick-label"'),
                              ("a scale bar", r'id="scale-bar"'), ("wall ids", r'class="wall-id"'),
                              ("zoom", r'data-zoomable="yes"')):
            if not re.search(pattern, d):
                problems.append("plan drawing %d has no %s" % (n + 1, what))
    counts["plan drawings"] = len(drawings)
    heat = re.search(r'<svg[^>]*id="heatmap-svg".*?</svg>', dom, re.S)
    if heat:
        h = heat.group(0)
        if 'id="heatmap-worst"' not in h:
            problems.append("the heat map does not ring the piece its caption names")
        if 'class="wall-id"' not in h:
            problems.append("the heat map labels no wall")
        # Its own scale: the shortest and the longest interval of the layer in two colours
        # (a layer whose pieces are all covered alike is one colour, rightly; pieces over
        # the maximum are all one dark red).
        pieces = [(float(v), c) for c, v in re.findall(
            r'class="heat-piece"[^>]*stroke="([^"]+)"[^>]*data-interval-s="([0-9.]+)"'
            r' data-over="no"', h)]
        colours = {c for _, c in pieces}
        if pieces and max(pieces)[0] - min(pieces)[0] > 1.0 and max(pieces)[1] == min(pieces)[1]:
            problems.append("the heat map paints its shortest (%.1f s) and longest (%.1f s) "
                            "intervals alike" % (min(pieces)[0], max(pieces)[0]))
        counts["heat-map colours"] = len(colours)
    # The palette: no two legend entries alike, on this chart or anywhere in the report.
    palette = re.search(r'<div id="palette"[^>]*data-colors="([^"]*)"', dom)
    if not palette:
        problems.append("no #palette in the DOM")
    else:
        named = json.loads(palette.group(1).replace("&quot;", '"').replace("&amp;", "&"))
        problems += ["two palette colours look alike: " + p for p in alike(named)]
        counts["palette colours"] = len(named)
    legend = dict(re.findall(r'<span class="legend-entry" data-color="(#[0-9A-Fa-f]{6})"><i[^>]*></i>([^<]*)</span>', dom))
    legend = {text: colour for colour, text in legend.items()}
    problems += ["two legend entries look alike: " + p for p in alike(legend)]
    if len(legend) < 2:
        problems.append("the Gantt's legend has %d entries" % len(legend))
    # The day view: one day's hours with its bars, the site's working time shaded on a
    # site calendar, and the day's package as a table.
    day_view = re.search(r'<svg[^>]*id="day-view"[^>]*data-date="([^"]+)"', dom)
    if not day_view:
        problems.append("no day view")
    else:
        counts["day-view bars"] = len(re.findall(r'class="day-bar', dom))
        if counts["day-view bars"] == 0:
            problems.append("the day view of %s has no bars" % day_view.group(1))
        shaded = len(re.findall(r'class="day-working"', dom))
        if data and schedule["inputs"].get("site") and shaded == 0:
            problems.append("the day view of a site calendar shades no working hours")
        if not re.search(r'<table class="day-package" id="day-package">.*?<td>print</td>', dom, re.S):
            problems.append("the day's package has no print line")
        ticks = re.findall(r'<text class="day-tick"[^>]*>(\d\d:\d\d)</text>', dom)
        if not ticks or ticks[0] != "00:00":
            problems.append("the day view's hours %r do not start at 00:00" % ticks[:3])
    canvas = re.search(r'<canvas id="playback-canvas"([^>]*)>', dom)
    if not canvas:
        problems.append("no playback canvas")
    else:
        attrs = canvas.group(1)
        if 'data-webgl="yes"' not in attrs:
            problems.append("the playback canvas has no WebGL context")
        colours = re.search(r'data-colours="(\d+)"', attrs)
        if not colours or int(colours.group(1)) < 4:
            problems.append("the 3-D view drew %s colours: blank" % (colours.group(1) if colours else "no"))
    errors = re.search(r'<pre id="console-errors" data-count="(\d+)"[^>]*>(.*?)</pre>', dom, re.S)
    if not errors:
        problems.append("no #console-errors element")
    elif errors.group(1) != "0":
        problems.append("console errors: " + errors.group(2)[:1500])
    infeasible = dom.find('id="infeasible"')
    if args.infeasible:
        summary = dom.find('<section id="summary"')
        if infeasible < 0:
            problems.append("the report of an infeasible schedule does not say so")
        elif summary >= 0 and infeasible > summary:
            problems.append("the infeasibility is not the first thing the report says")
        elif "NOT FEASIBLE" not in dom[infeasible:infeasible + 2000]:
            problems.append("the infeasible banner lacks its message")
    elif infeasible >= 0:
        problems.append("a feasible schedule's report says it is infeasible")
    if problems:
        for p in problems:
            print("problem: " + p)
        return 1
    print("OK: %s rendered every section: %s; %s" % (
        args.report, ", ".join("%d %s" % (n, w) for w, n in counts.items()),
        re.search(r'data-triangles="(\d+)"', dom).group(1) + " triangles in the 3-D view, " +
        (re.search(r'data-frame-ms="([\d.]+)"', dom) or re.search("()", "")).group(1) + " ms a frame"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
