#!/usr/bin/env python3
"""`ccbuild climb` and `ccbuild schedule` place the same stages (platform heights, the layers
each prints, every pipe) for BUILDING on MACHINE: compares their JSON outputs.

Usage: stages_agree.py CCBUILD BUILDING MACHINE"""

import json
import os
import subprocess
import sys
import tempfile


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    ccbuild, building, machine = sys.argv[1:]
    with tempfile.TemporaryDirectory() as tmp:
        climb = subprocess.run([ccbuild, "climb", building, "--machine", machine, "--json"],
                               capture_output=True, text=True, timeout=600)
        if climb.returncode not in (0, 1):
            sys.exit("climb: exit %d\n%s" % (climb.returncode, climb.stderr))
        out = os.path.join(tmp, "schedule.json")
        schedule = subprocess.run([ccbuild, "schedule", building, "--machine", machine, "--quiet",
                                   "--no-compare", "-o", out], capture_output=True, text=True, timeout=600)
        if schedule.returncode not in (0, 1):
            sys.exit("schedule: exit %d\n%s" % (schedule.returncode, schedule.stderr))
        a = json.loads(climb.stdout)["stages"]
        b = json.load(open(out))["stages"]
        if not a:
            sys.exit("no stages: not a climbing machine?")
        if a != b:
            for k, (x, y) in enumerate(zip(a, b)):
                if x != y:
                    sys.exit("stage %d differs:\nclimb    %s\nschedule %s" % (k, x, y))
            sys.exit("climb has %d stages, schedule %d" % (len(a), len(b)))
        print("%s on %s: climb and schedule place the same %d stages" % (building, machine, len(a)))


if __name__ == "__main__":
    main()
