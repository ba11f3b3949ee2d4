#!/usr/bin/env python3
"""Plants plausible one-line bugs, one at a time, and reports the ones the tests miss.

Clones the repository's HEAD into a scratch folder (your working tree is never touched),
builds it once, then for each mutant of tests/mutants/mutants.txt: applies it, rebuilds,
runs the CTest tests it names (stopping at the first failure), and restores the file.
A mutant is killed when a test fails (or the build breaks); it survives when they all
pass. Exit code 0 when at least 9 in 10 are killed.

Usage: scripts/mutation-check.py [--keep] [--reuse DIR] [--only N[-M][,...]] [--jobs 2]
                                 [--fast] [--check]
  --keep     leave the scratch clone (its path is printed)
  --reuse    run in the scratch folder a --keep run left (its clone's commit, built
             again where needed): a long run stopped part way goes on with --only N-M
  --only     run only these mutants (1-based, in file order; 5-9 is a range)
  --fast     rebuild only the programs the mutant's tests run (their executables, ccbuild,
             the simulator): a test that calls another would run it unmutated, so a
             survivor of a fast run is run again without --fast before it counts
  --check    only check that each mutant's text occurs exactly once in its file (CTest
             runs this, so that a mutant left behind by a moved line fails at once)
It takes about a minute per mutant on two cores, after a first build of four minutes.
"""

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def read_mutants(path):
    mutants, block, key = [], {}, None
    with open(path) as f:
        for line in f.read().splitlines() + [""]:
            if line.startswith("#"):
                continue
            if not line.strip():
                if block:
                    mutants.append(block)
                block, key = {}, None
                continue
            for name in ("file", "find", "replace", "tests", "why"):
                if line.startswith(name + ": "):
                    key = name
                    block[key] = line[len(name) + 2:]
                    break
            else:
                if key is None:
                    sys.exit("mutants.txt: a line outside any field: " + line)
                block[key] += "\n" + line  # a continued (multi-line) field
    for m in mutants:
        missing = [k for k in ("file", "find", "replace", "tests", "why") if k not in m]
        if missing:
            sys.exit("mutants.txt: a mutant lacks " + ", ".join(missing) + ": " + str(m))
    return mutants


def run(command, cwd, log):
    with open(log, "a") as out:
        out.write("\n$ " + " ".join(command) + "\n")
        out.flush()
        return subprocess.call(command, cwd=cwd, stdout=out, stderr=subprocess.STDOUT)


def known_targets(build):
    """The build's target names (the Makefile generator's help lists them)."""
    out = subprocess.run(["cmake", "--build", build, "--target", "help"],
                         capture_output=True, text=True).stdout
    return {line[4:].split()[0] for line in out.splitlines() if line.startswith("... ")}


def test_names(build, tests):
    """The names of the tests matching TESTS, in CTest's order."""
    listing = subprocess.run(["ctest", "-N", "--show-only=json-v1", "-R", tests], cwd=build,
                             capture_output=True, text=True)
    if listing.returncode:
        return []
    return [t["name"] for t in json.loads(listing.stdout).get("tests", [])]


def costs(build):
    """Each test's average time, s, from CTest's own record of earlier runs."""
    found = {}
    try:
        with open(os.path.join(build, "Testing", "Temporary", "CTestCostData.txt")) as f:
            for line in f:
                if line.startswith("---"):
                    break
                parts = line.split()
                if len(parts) == 3:
                    found[parts[0]] = float(parts[2])
    except (OSError, ValueError):
        pass
    return found


def test_rounds(build, tests, cheap_s=15.0, most=400):
    """The CTest regexes to run in turn: the tests that took under CHEAP_S before first,
    then the rest, so that a mutant a quick test kills stops before the long ones start
    (CTest itself starts the longest first). One round when the record is missing or the
    list is too long for a regex."""
    names, known = test_names(build, tests), costs(build)
    if not names or len(names) > most or any(n not in known for n in names):
        return [tests]
    exact = lambda group: "^(" + "|".join(re.escape(n) for n in group) + ")$"
    cheap = [n for n in names if known[n] < cheap_s]
    dear = [n for n in names if known[n] >= cheap_s]
    return [exact(g) for g in (cheap, dear) if g]


def linker_flags():
    """A faster linker for the clone where one is installed (lld, else gold): each mutant
    relinks several programs, 5 s each with the default linker, under 1 s with lld."""
    for linker in ("lld", "gold"):
        if shutil.which("ld." + linker):
            return ["-DCMAKE_EXE_LINKER_FLAGS=-fuse-ld=" + linker]
    return []


def targets_for(build, tests, known):
    """The targets the tests matching TESTS run: the executables their commands and
    environments name inside the build folder, and the programs scripts call (ccbuild,
    the simulator, the bus intruder). None when a test names none of them: build all."""
    listing = subprocess.run(["ctest", "-N", "--show-only=json-v1", "-R", tests], cwd=build,
                             capture_output=True, text=True)
    if listing.returncode:
        return None
    words = []
    for test in json.loads(listing.stdout).get("tests", []):
        words += test.get("command", [])
        for prop in test.get("properties", []):
            if prop.get("name") == "ENVIRONMENT":
                words += [w.split("=", 1)[-1] for w in prop.get("value", [])]
    named = {os.path.basename(w) for w in words if w.startswith(build)} & known
    if not named:
        return None
    return sorted(named | ({"ccbuild", "ccbuild-sim", "bus_intruder"} & known))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--keep", action="store_true")
    parser.add_argument("--only", default="")
    parser.add_argument("--jobs", default="2")
    parser.add_argument("--check", action="store_true")
    parser.add_argument("--fast", action="store_true")
    parser.add_argument("--reuse", default="")
    args = parser.parse_args()

    mutants = read_mutants(os.path.join(ROOT, "tests", "mutants", "mutants.txt"))
    if args.check:
        stale = []
        for n, m in enumerate(mutants, 1):
            path = os.path.join(ROOT, m["file"])
            found = open(path).read().count(m["find"]) if os.path.isfile(path) else 0
            if found != 1:
                stale.append("mutant %d (%s): its text occurs %d times in %s, not once"
                             % (n, m["why"], found, m["file"]))
        print("\n".join(stale) or "all %d mutants apply" % len(mutants))
        return 1 if stale else 0
    chosen = []
    for part in filter(None, args.only.split(",")):
        first, _, last = part.partition("-")
        chosen += list(range(int(first), int(last or first) + 1))
    chosen = chosen or list(range(1, len(mutants) + 1))
    if args.reuse:  # a scratch folder kept by --keep: its clone as it is, built again
        scratch = os.path.abspath(args.reuse)
        if not os.path.isdir(os.path.join(scratch, "ccbuild", "build")):
            sys.exit("--reuse: %s holds no kept clone (ccbuild/build)" % scratch)
    else:
        scratch = tempfile.mkdtemp(prefix="ccbuild-mutants-")
    clone = os.path.join(scratch, "ccbuild")
    log = os.path.join(scratch, "log.txt")
    print("scratch clone: %s (log: %s)" % (clone, log), flush=True)
    if args.reuse:
        head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=clone,
                              capture_output=True, text=True).stdout.strip()
        print("reusing the clone at %s (mutants read from this checkout's list)" % head,
              flush=True)
    else:
        subprocess.check_call(["git", "clone", "--quiet", ROOT, clone])
        # The clone's CI layout: ../shared beside it, as on a fresh machine.
        shared = os.path.join(os.path.dirname(ROOT), "shared")
        if os.path.isdir(shared):
            os.symlink(shared, os.path.join(scratch, "shared"))
    build = os.path.join(clone, "build")
    started = time.time()
    if run(["cmake", "-S", clone, "-B", build, "-DCCBUILD_BUILD_BENCH=OFF"] + linker_flags(),
           clone, log) or \
            run(["cmake", "--build", build, "-j" + args.jobs], clone, log):
        sys.exit("the unmutated clone does not build; see " + log)
    print("built the unmutated clone in %.0f s" % (time.time() - started), flush=True)

    known = known_targets(build)
    killed, survivors = 0, []
    for n in chosen:
        m = mutants[n - 1]
        path = os.path.join(clone, m["file"])
        with open(path) as f:
            original = f.read()
        if original.count(m["find"]) != 1:
            sys.exit("mutant %d: the text to change occurs %d times in %s (must be once)"
                     % (n, original.count(m["find"]), m["file"]))
        with open(path, "w") as f:
            f.write(original.replace(m["find"], m["replace"]))
        began = time.time()
        try:
            targets = targets_for(build, m["tests"], known) if args.fast else None
            command = ["cmake", "--build", build, "-j" + args.jobs]
            if targets:
                command += ["--target"] + targets
            if run(command, clone, log):
                verdict = "killed (does not build)"
            else:
                verdict = "SURVIVED"
                for regex in test_rounds(build, m["tests"]):
                    if run(["ctest", "-j" + args.jobs, "--stop-on-failure", "--timeout", "300",
                            "-R", regex], build, log):
                        verdict = "killed"
                        break
        finally:
            with open(path, "w") as f:
                f.write(original)
            os.utime(path)  # make sure the next build sees the restored file
        if verdict.startswith("killed"):
            killed += 1
        else:
            survivors.append(n)
        print("%2d. %-9s %s (%s; %.0f s)" % (n, verdict, m["why"], m["file"], time.time() - began), flush=True)

    total = len(chosen)
    print("\n%d of %d mutants killed%s" % (killed, total,
                                          "; survivors: " + ", ".join(map(str, survivors)) if survivors else ""))
    if args.keep or args.reuse:
        print("kept: " + scratch)
    else:
        shutil.rmtree(scratch, ignore_errors=True)
    return 0 if killed * 10 >= total * 9 else 1


if __name__ == "__main__":
    sys.exit(main())
