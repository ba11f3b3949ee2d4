#!/usr/bin/env python3
"""Checks a command's text output for mixed units, without ccbuild's code: every column
of a table, and every figure that recurs under the same words, speaks one unit.

- A table is a header line (three or more cells apart by two or more spaces, none a
  number) and the lines under it with as many cells: each column's figures share a unit.
- Elsewhere a figure is known by the words around it (the three before it, numbers as #,
  and the one after): "after a wait of # s" and "after a wait of # h" on two climbs' lines
  are the same figure in two units. Dates, clock times and "day N" are not figures, nor is
  a whole number before "in" ("1309 in one pass": inches are written with decimals).
Units: s, min, h, d (times), mm, m, ft, in (lengths).
With --lengths ft (a building in feet) every length is in ft or in and every volume in yd³;
with --lengths m, in m or mm and m³. Speeds (m/s, the weather's wind) are not lengths.
Usage: check_units.py [--lengths m|ft] [OUTPUT.txt]   (stdin without a file)
Exit 1 naming every figure or column found in two units, or a length in the other system."""

import argparse
import collections
import re
import sys

UNIT = r"(?:s|min|h|d|mm|m|ft|in)"
FIGURE = re.compile(r"(?<![\w.])(-?\+?\d+(?:\.\d+)?)\s?(" + UNIT + r")(?![\w³²/])")


def figures(text):
    """The figures with a unit in `text`, as matches (group 1 the number, 2 the unit)."""
    return [m for m in FIGURE.finditer(text) if not (m.group(2) == "in" and "." not in m.group(1))]
NOT_FIGURES = [
    (re.compile(r"\b\d{4}-\d{2}-\d{2}\b"), "DATE"),
    (re.compile(r"\b\d{1,2}:\d{2}(?::\d{2})?\b"), "TIME"),
    (re.compile(r"\bday \d+\b"), "DAY"),
]


def plain(line):
    for pattern, word in NOT_FIGURES:
        line = pattern.sub(word, line)
    return line


def cells(line):
    return [c for c in re.split(r"\s{2,}", line.strip()) if c]


def is_header(parts):
    return len(parts) >= 3 and all(not re.search(r"\d", p) for p in parts)


SYSTEMS = {"m": {"m", "mm", "m³"}, "ft": {"ft", "in", "yd³"}}
LENGTH_OR_VOLUME = re.compile(r"(?<![\w.])(\d+(?:\.\d+)?)\s?(mm|m|ft|in|m³|yd³)(?![\w²/])")


def other_system(lines, system):
    """Lines with a length or volume figure outside `system` (m or ft)."""
    wrong = collections.defaultdict(list)
    for n, line in enumerate(lines):
        for m in LENGTH_OR_VOLUME.finditer(line):
            if m.group(2) == "in" and "." not in m.group(1):
                continue  # "1309 in one pass"
            if m.group(2) not in SYSTEMS[system]:
                wrong[m.group(2)].append(n + 1)
    return ["lengths in %s, the output's unit: %s" % (system, "; ".join(
        "%s (line %s)" % (u, ", ".join(map(str, ls[:3]))) for u, ls in sorted(wrong.items())))] if wrong else []


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("output", nargs="?")
    ap.add_argument("--lengths", choices=sorted(SYSTEMS))
    a = ap.parse_args()
    text = open(a.output, encoding="utf-8").read() if a.output else sys.stdin.read()
    lines = [plain(l.rstrip("\n")) for l in text.splitlines()]
    units = collections.defaultdict(lambda: collections.defaultdict(list))  # figure -> unit -> lines
    in_table = set()
    k = 0
    while k < len(lines):
        head = cells(lines[k])
        if not is_header(head):
            k += 1
            continue
        j = k + 1
        while j < len(lines) and len(cells(lines[j])) == len(head) and not is_header(cells(lines[j])):
            for c, cell in enumerate(cells(lines[j])):
                for m in figures(cell):
                    unit = m.group(2)
                    units["column '%s' of the table at line %d" % (head[c], k + 1)][unit].append(j + 1)
            in_table.add(j)
            j += 1
        k = j
    for n, line in enumerate(lines):
        if n in in_table:
            continue
        for m in figures(line):
            before = re.sub(r"\d+(?:\.\d+)?", "#", line[:m.start()]).split()[-3:]
            after = line[m.end():].split()[:1]
            key = "'%s <figure> %s'" % (" ".join(before), " ".join(after))
            units[key][m.group(2)].append(n + 1)
    problems = ["%s in %d units: %s" % (key, len(by), "; ".join(
        "%s (line %s)" % (u, ", ".join(map(str, ls[:3]))) for u, ls in sorted(by.items())))
        for key, by in units.items() if len(by) > 1]
    if a.lengths:
        problems += other_system(lines, a.lengths)
    print("\n".join(problems) or "OK: %d figures and columns, each in one unit" % len(units))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
