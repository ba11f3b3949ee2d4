#!/usr/bin/env python3
"""Checks that each physical and site rule is stated once (issue 51, "one rule, one
place"), from the sources alone:

- its definition is found exactly where the table below says, and nowhere else;
- every program that must obey it calls that definition (the scheduler, the schedule's
  re-checks, the what-ifs, the dispatcher's re-plans, the simulated machine: each
  rule names its callers);
- no source outside the rule's home holds the rule's arithmetic written out again (a
  pattern per rule: the strength curve's exponential, a temperature held to the placing
  range, a wind to the climb's limit, an age on the site's clock, crew times hours).

Usage: check_rules_once.py [REPO] [--self-test]. Exit 0 when every rule holds, 1 with
each finding on a line of its own.
"""
import pathlib
import re
import sys

# The library folders (tests, benches and tools are not the product).
SOURCES = ["common", "floors", "rules", "site", "machine", "wire", "sim", "planner", "climb",
           "schedule", "report", "dispatch", "study", "app"]

RULES = [
    {
        "rule": "where a local interval is taken (piece and bead ends, each side its beads)",
        "define": r"^IntervalOffsets interval_offsets\(",
        "home": ["rules/src/intervals.cpp"],
        "count": 2,  # the scheduler's form (pieces known) and the deposits-only form
        # The scheduler's adapter from a layer's segments to pieces, which calls the rule.
        "wrappers": ["schedule/src/schedule_deposits.cpp"],
        "callers": ["schedule/src/schedule_deposits.cpp", "dispatch/src/dispatcher_replan.cpp",
                    "sim/src/sim_machine.cpp"],
        "call": r"\brules::interval_offsets\(",
    },
    {
        "rule": "the interval window (in equivalent age with weather)",
        "define": r"^StartWindow start_window\(",
        "home": ["rules/src/intervals.cpp"],
        "callers": ["schedule/src/schedule.cpp", "dispatch/src/dispatcher_replan.cpp"],
        "call": r"\brules::start_window\(",
    },
    {
        "rule": "a mix's strength with age (the tests govern)",
        "define": r"^double MaterialProfile::strength_at_mpa\(",
        "home": ["floors/src/material.cpp"],
        "callers": ["schedule/src/schedule.cpp", "schedule/src/schedule_rules.cpp",
                    "schedule/src/what_if.cpp", "schedule/src/anchor_strength.cpp"],
        "call": r"\.strength_at_mpa\(",
        # The EN 1992 development written out anywhere else.
        "copy": r"std::exp\(\s*\w*\.?s\b|sqrt\(\s*(kDays28_s|28)",
    },
    {
        "rule": "when concrete is old enough (maturity on the site's clock, else real age)",
        "define": r"^double age_reached_s\(",
        "home": ["site/src/conditions.cpp"],
        "callers": ["schedule/src/scheduler.hpp", "schedule/src/schedule.cpp",
                    "schedule/src/schedule_rules.cpp", "schedule/src/what_if.cpp"],
        "call": r"\bsite::age_reached_s\(",
        # An age counted on the clock by hand: maturity->after(...) outside the rule.
        "copy": r"(maturity\w*(->|\.)|aged\.)after\(",
        "copy_allowed": ["rules/src/intervals.cpp"],  # the window, stated on the clock
    },
    {
        "rule": "placing temperature",
        "define": r"^bool placeable_at\(",
        "home": ["rules/src/weather.cpp"],
        "callers": ["schedule/src/schedule.cpp", "schedule/src/schedule_rules.cpp"],
        "call": r"\brules::placeable_at\(",
        "copy": r"temperature_c\s*[<>]=?\s*\w*\.?placing_(min|max)_c",
    },
    {
        "rule": "wind for climbs",
        "define": r"^bool climbable_in\(",
        "home": ["rules/src/weather.cpp"],
        "callers": ["schedule/src/schedule.cpp"],
        "call": r"\brules::climbable_in\(",
        "copy": r"wind_m_s\s*[<>]=?\s*\w*limit",
    },
    {
        "rule": "how far a stated move may seem over a speed limit",
        "define": r"^bool faster_than\(",
        "home": ["rules/src/tolerances.cpp"],
        "callers": ["sim/src/sim_machine.cpp", "schedule/src/schedule_rules.cpp"],
        "call": r"\brules::faster_than\(",
    },
    {
        "rule": "the numbering of distinct layers (the plan keys' g<number>)",
        "define": r"^int GeometryNumbering::number\(",
        "home": ["floors/src/slice.cpp"],
        "copy_allowed": ["floors/include/ccbuild/floors/slice.hpp"],  # its own member
        "callers": ["schedule/src/schedule_prepare.cpp", "schedule/src/project.cpp",
                    "schedule/src/layer_summary.cpp"],
        "call": r"\bnumbering\.number\(",
        # Geometries numbered by a map of their own.
        "copy": r"map<\s*(floors::)?GeometryKey\s*,\s*(int|std::size_t)",
    },
    {
        "rule": "person-hours",
        "define": r"^inline double person_hours\(",
        "home": ["rules/include/ccbuild/rules/crew.hpp"],
        "callers": ["schedule/src/schedule_model.cpp", "report/src/export_days.cpp",
                    "report/src/schedule_text.cpp"],
        "call": r"\brules::person_hours\(",
        "copy": r"crew\w*\s*\*\s*\(?[^;]*/\s*3600",
    },
]


def strip_comments(text):
    """The code without // comments (a rule may be named in words anywhere)."""
    return "\n".join(line.split("//", 1)[0] for line in text.splitlines())


def sources(repo):
    out = {}
    for top in SOURCES:
        for f in (repo / top).rglob("*"):
            if f.suffix in (".cpp", ".hpp") and f.is_file():
                out[f.relative_to(repo).as_posix()] = strip_comments(f.read_text(errors="replace"))
    return out


def definitions(pattern, text):
    """How many times `text` defines what `pattern` names: a match whose declaration
    reaches a `{` before a `;` (a declaration in a header is not a definition)."""
    count = 0
    for m in pattern.finditer(text):
        rest = text[m.end():]
        brace, semicolon = rest.find("{"), rest.find(";")
        if brace >= 0 and (semicolon < 0 or brace < semicolon):
            count += 1
    return count


def check(files):
    problems = []
    for r in RULES:
        define = re.compile(r["define"], re.M)
        call = re.compile(r["call"])
        found = {}
        for f, t in files.items():
            n = definitions(define, t)
            if n and not (f in r.get("wrappers", []) and call.search(t)):
                found[f] = n
        wanted = r.get("count", 1)
        homes = r["home"]
        if sorted(found) != sorted(homes) or sum(found.values()) != wanted:
            where = ", ".join(f"{f} ({n})" for f, n in sorted(found.items())) or "nowhere"
            problems.append(f"{r['rule']}: defined {sum(found.values())} times ({where}); "
                            f"expected {wanted} in {', '.join(homes)}")
        for caller in r["callers"]:
            if caller not in files:
                problems.append(f"{r['rule']}: {caller} is gone; the table names it a caller")
            elif not call.search(files[caller]):
                problems.append(f"{r['rule']}: {caller} does not call the rule")
        if "copy" in r:
            copy = re.compile(r["copy"])
            allowed = set(homes) | set(r.get("copy_allowed", []))
            for f, t in sorted(files.items()):
                if f in allowed:
                    continue
                for n, line in enumerate(t.splitlines(), 1):
                    if copy.search(line):
                        problems.append(f"{r['rule']}: written out again at {f}:{n}: "
                                        f"{line.strip()}")
    return problems


def self_test(files):
    """Each planted copy must be found: a second definition, a caller that reimplements
    the rule, and the arithmetic written out again."""
    failed = 0
    cases = []
    f = dict(files)
    f["dispatch/src/dispatcher_replan.cpp"] = f["dispatch/src/dispatcher_replan.cpp"].replace(
        "rules::start_window(", "own_window(")
    cases.append(("a re-plan that takes its own window", f))
    f = dict(files)
    f["schedule/src/what_if.cpp"] += "\nbool placeable_at(double t) { return t > 5; }\n"
    cases.append(("a second definition of the placing rule", f))
    f = dict(files)
    f["schedule/src/what_if.cpp"] += "\nconst bool cold = r.temperature_c < m.placing_min_c;\n"
    cases.append(("the placing range written out", f))
    f = dict(files)
    f["report/src/schedule_text.cpp"] += "\nconst double s_ = maturity_->after(t, a);\n"
    cases.append(("an age on the clock counted by hand", f))
    f = dict(files)
    f["report/src/export_days.cpp"] += "\nh += t.crew * (t.end_s - t.start_s) / 3600.0;\n"
    cases.append(("person-hours written out", f))
    f = dict(files)
    f["schedule/src/schedule.cpp"] += "\nx = std::exp(mix.s * (1 - std::sqrt(28 / d)));\n"
    cases.append(("the strength curve written out", f))
    for name, planted in cases:
        if not check(planted):
            print(f"self-test: {name} was not caught")
            failed += 1
    return failed


def main(argv):
    args = [a for a in argv if not a.startswith("--")]
    repo = pathlib.Path(args[0] if args else ".").resolve()
    files = sources(repo)
    if "--self-test" in argv:
        if self_test(files):
            return 1
        print("check_rules_once self-test: 6 planted copies caught")
    problems = check(files)
    for p in problems:
        print(p)
    if problems:
        return 1
    print(f"rules: {len(RULES)} rules, each defined once where the table says, called by "
          f"{sum(len(r['callers']) for r in RULES)} callers, written out nowhere else")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
