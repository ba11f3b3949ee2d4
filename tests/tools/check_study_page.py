#!/usr/bin/env python3
"""Opens a study's results.html in headless Chromium and checks it against results.json.

Reads only the results folder and what Chromium makes of the page (the DOM after loading,
a screenshot): one table row per variant of results.json, with its status; each Pareto
chart's front (its larger, linked dots) is the set of feasible variants no other feasible
variant beats in both makespan and that cost, recomputed here from results.json; every
link on the page opens a file in the folder (a variant's report or schedule, a failed
variant's log); the screenshot is not blank.

Usage: check_study_page.py RESULTS_FOLDER
Exit 0 when every check passes, 1 otherwise.
"""
import html
import json
import os
import re
import sys
import tempfile
import urllib.parse

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_report import chromium, png_not_blank, run_chromium  # noqa: E402

COSTS = ("nozzles_max", "concrete_m3", "crew_h")


def front_of(variants, cost):
    """The ids of the feasible variants that no other feasible one beats: at most its cost
    and its makespan, and under it in one of them."""
    points = [(v["measures"][cost], v["measures"]["makespan_s"], v["id"]) for v in variants
              if v["status"] == "feasible" and v["measures"].get(cost) is not None
              and v["measures"].get("makespan_s") is not None]
    return {p[2] for p in points
            if not any(q[0] <= p[0] and q[1] <= p[1] and (q[0] < p[0] or q[1] < p[1]) for q in points)}


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    folder = os.path.abspath(sys.argv[1])
    results = json.load(open(os.path.join(folder, "results.json")))
    variants = results["variants"]
    problems = []
    with tempfile.TemporaryDirectory() as out:
        shot = os.path.join(out, "shot.png")
        run = run_chromium(chromium(), "file://" + os.path.join(folder, "results.html"),
                           ["--dump-dom", "--screenshot=" + shot], out)
        dom = run.stdout.decode("utf-8", "replace")
        if run.returncode != 0 or "<body" not in dom:
            sys.exit("check_study_page: chromium failed (%d): %s" % (
                run.returncode, run.stderr.decode("utf-8", "replace")[-2000:]))
        if not os.path.exists(shot):
            problems.append("no screenshot")
        else:
            ok, why = png_not_blank(shot)
            if not ok:
                problems.append("the screenshot is blank: " + why)

    table = re.search(r'<table id="variants">(.*?)</table>', dom, re.S)
    rows = re.findall(r'<tr data-id="([^"]+)">(.*?)</tr>', table.group(1), re.S) if table else []
    if [r[0] for r in rows] != [v["id"] for v in variants]:
        problems.append("the variants table has %d rows, results.json %d variants (or another order)"
                        % (len(rows), len(variants)))
    for (vid, cells), v in zip(rows, variants):
        if v["status"] not in re.sub(r"<[^>]+>", "", cells):
            problems.append("%s: its row does not say %s" % (vid, v["status"]))

    charts = dict(re.findall(r'<svg class="front-chart" data-cost="([^"]+)"[^>]*>(.*?)</svg>', dom, re.S))
    fronts = 0
    for cost in COSTS:
        if not any(cost in v.get("measures", {}) for v in variants if v["status"] == "feasible"):
            continue
        if cost not in charts:
            problems.append("no chart of makespan against %s" % cost)
            continue
        drawn = set(re.findall(r'<circle class="front" data-id="([^"]+)"', charts[cost]))
        dots = set(re.findall(r'<circle class="(?:front|dot)" data-id="([^"]+)"', charts[cost]))
        want = front_of(variants, cost)
        if drawn != want:
            problems.append("the front against %s is drawn as %s, recomputed %s"
                            % (cost, sorted(drawn), sorted(want)))
        feasible = {v["id"] for v in variants if v["status"] == "feasible"}
        if dots != feasible:
            problems.append("the chart against %s draws %d dots for %d feasible variants"
                            % (cost, len(dots), len(feasible)))
        fronts += len(want)

    links = set(html.unescape(h) for h in re.findall(r'<a href="([^"#]+)"', dom))
    broken = [h for h in sorted(links)
              if not os.path.isfile(os.path.join(folder, urllib.parse.unquote(h)))]
    if broken:
        problems.append("%d link(s) lead nowhere: %s" % (len(broken), ", ".join(broken[:5])))

    if problems:
        for p in problems:
            print("problem: " + p)
        return 1
    print("OK: %s: %d variants in the table, %d dots on fronts as recomputed, %d links open files, "
          "screenshot drawn" % (folder, len(rows), fronts, len(links)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
