#!/usr/bin/env python3
"""Times `ccbuild plan-layer` of two builds on the same plan files, in turn (A B A B ...),
so a drift of the shared machine's speed hits both alike. For each plan: both airtimes
(metres with the distance objective, seconds with `--objective time`), how much less B's
is, and the median of each build's own "solve" time (the call's time, file reading left
out) with B/A of the pairs.

  bench/compare_builds.py --a OLD/ccbuild --b build/ccbuild --machine M.yaml PLAN ...
  bench/compare_builds.py --objective time --runs 1 --a ... --b ... PLAN ...
  bench/compare_builds.py --bounds CERTS --a ... --b ... PLAN ...

With --bounds, each plan's lower bound is read from CERTS/<plan name>.json, a certificate
of `plan-layer --bound-certificate`, and re-checked by tests/tools/check_bound.py (which
shares no code with ccbuild). Then also: the room A's tour leaves above it (the most any
tour can be shorter than A's) and how far B's is above it.

Plans: `bench_layer_search --write-plans DIR`; plans larger than the bundled machine's
reach need a machine with longer axes (bench/README.md)."""

import argparse
import json
import os
import re
import statistics
import subprocess
import sys


def plan_once(ccbuild, plan, machine, objective, extra):
    command = [ccbuild, "plan-layer", plan, "--objective", objective] + extra
    if machine:
        command += ["--machine", machine]
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"compare_builds: {' '.join(command)} failed ({done.returncode}):\n"
                 f"{done.stderr.strip()}")
    # "airtime  919.848 m, 2244.20 s (...)": metres, or with the time objective seconds.
    pattern = r"^\s*airtime\s+([0-9.]+) m" if objective == "distance" else \
        r"^\s*airtime\s+[0-9.]+ m, ([0-9.]+) s"
    airtime = re.search(pattern, done.stdout, re.M)
    solve = re.search(r"^\s*solve\s+([0-9.]+) s", done.stdout, re.M)
    if not airtime or not solve:
        sys.exit(f"compare_builds: no airtime or solve line in the output of {ccbuild}")
    return float(airtime.group(1)), float(solve.group(1))


CHECK_BOUND = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "tests",
                           "tools", "check_bound.py")


def proven_bound(certificate, plan):
    """The bound the certificate proves, m, as the independent checker computes it."""
    try:
        with open(certificate) as f:
            made_from = json.load(f).get("file", "")
    except (OSError, ValueError, AttributeError) as e:
        sys.exit(f"compare_builds: {certificate}: {e}")
    if os.path.basename(made_from) != os.path.basename(plan):
        sys.exit(f"compare_builds: {certificate} is the bound of {made_from}, not of {plan}")
    done = subprocess.run([sys.executable, CHECK_BOUND, certificate], capture_output=True,
                          text=True)
    found = re.search(r"at least ([0-9.]+) m", done.stdout)
    if done.returncode != 0 or not found:
        sys.exit(f"compare_builds: {certificate} proves nothing:\n"
                 f"{(done.stdout + done.stderr).strip()}")
    return float(found.group(1))


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--a", required=True, help="the baseline build's ccbuild")
    parser.add_argument("--b", required=True, help="the build compared with it")
    parser.add_argument("--machine", help="machine profile for both (--machine)")
    parser.add_argument("--runs", type=int, default=3, help="pairs per plan (default 3)")
    parser.add_argument("--objective", choices=("distance", "time"), default="distance",
                        help="plan-layer --objective; the airtimes compared are metres or "
                        "seconds (default distance)")
    parser.add_argument("--extra", default="--bound matching",
                        help="more plan-layer options for both (default: --bound matching, "
                        "so the time is the search's, not the connected bound's)")
    parser.add_argument("--bounds", metavar="DIR",
                        help="certificates of the plans' lower bounds, DIR/<plan name>.json "
                        "(distance objective only)")
    parser.add_argument("plans", nargs="+")
    args = parser.parse_args()
    if not 1 <= args.runs <= 50:
        sys.exit("compare_builds: --runs must be 1 to 50")
    if args.bounds and args.objective != "distance":
        sys.exit("compare_builds: --bounds bounds airtime distance: --objective distance only")
    bounds = {}
    if args.bounds:
        for plan in args.plans:
            stem = os.path.splitext(os.path.basename(plan))[0]
            bounds[plan] = proven_bound(os.path.join(args.bounds, stem + ".json"), plan)

    unit = "m" if args.objective == "distance" else "s"
    bound_columns = " bound m | A's room | B above bound |" if bounds else ""
    print(f"| plan | A airtime {unit} | B airtime {unit} | B less | A solve s | B solve s | "
          f"B/A (min-max) |{bound_columns}")
    print("|---|---:|---:|---:|---:|---:|---:|" + ("---:|---:|---:|" if bounds else ""))
    shorter_all, ratio_all, room_all, above_all = [], [], [], []
    for plan in args.plans:
        a_s, b_s, ratios = [], [], []
        a_m = b_m = None
        for _ in range(args.runs):
            a_m, a = plan_once(args.a, plan, args.machine, args.objective, args.extra.split())
            b_m, b = plan_once(args.b, plan, args.machine, args.objective, args.extra.split())
            a_s.append(a)
            b_s.append(b)
            ratios.append(b / a if a > 0 else float("nan"))
        shorter = (a_m - b_m) / a_m * 100.0
        shorter_all.append(shorter)
        ratio_all.append(statistics.median(ratios))
        row = (f"| {plan.rsplit('/', 1)[-1]} | {a_m:.3f} | {b_m:.3f} | {shorter:+.4f}% | "
               f"{statistics.median(a_s):.3f} | {statistics.median(b_s):.3f} | "
               f"{statistics.median(ratios):.2f} ({min(ratios):.2f}-{max(ratios):.2f}) |")
        if bounds:
            bound = bounds[plan]
            # The airtimes are printed to the millimetre: a tour at the bound may read below.
            def above(m):
                return max(m - bound, 0.0) if m >= bound - 5e-4 else m - bound
            room_all.append(above(a_m) / a_m * 100.0)
            above_all.append(above(b_m) / bound * 100.0 if bound > 0 else 0.0)
            row += f" {bound:.4f} | {room_all[-1]:.4f}% | {above_all[-1]:.4f}% |"
        print(row)
    print(f"\nB less airtime: mean {statistics.mean(shorter_all):+.4f}%, worst "
          f"{min(shorter_all):+.4f}%; B/A time: median {statistics.median(ratio_all):.2f}, "
          f"largest {max(ratio_all):.2f} (per plan, medians of {args.runs} pairs)")
    if bounds:
        print(f"A's room above the proven bounds: mean {statistics.mean(room_all):.4f}% (no "
              f"tour can be shorter than A's by more on average); B above them: mean "
              f"{statistics.mean(above_all):.4f}%")


if __name__ == "__main__":
    main()
