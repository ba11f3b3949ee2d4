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
With --help-text HELP.txt (the command's --help) every table's columns are explained once:
a column's name (its unit left off) stands before a colon, alone or in a list ("planned
start, planned end: ..."), in the help or in a line of the output outside the tables,
unless it is one of the plain words a site planner reads without help (PLAIN). A header
followed by a row of another number of columns is a table this check cannot read (its
columns must stand two spaces apart) and is a problem too.
Usage: check_units.py [--lengths m|ft] [--help-text HELP.txt] [OUTPUT.txt]   (stdin without a file)
       check_units.py --self-test   (planted outputs, each caught)
Exit 1 naming every figure or column found in two units, a length in the other system,
a column left unexplained or a table that cannot be read."""

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


def row_cells(line, header_line, head):
    """The cells of a row under `header_line`, or None when it is not a row of that table:
    as many cells as the header, or fewer when the ones left off are the last (empty)."""
    parts = cells(line)
    if len(parts) == len(head):
        return parts
    if not parts or len(parts) > len(head):
        return None
    first_missing = header_line.index(head[len(parts)], header_line.index(head[len(parts) - 1]))
    return parts if len(line.rstrip()) <= first_missing else None


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


# Column names read without a legend: what a floor, a layer or a wall is needs no help.
PLAIN = {"floor", "layer", "layers", "name", "height", "walls", "nozzles", "start", "end"}
UNIT_SUFFIX = re.compile(r"\s+(?:" + UNIT + r"|m³|yd³)$")


def column_name(cell):
    """A header cell without its unit: "construction min" -> "construction"."""
    return UNIT_SUFFIX.sub("", cell.strip()).strip()


def explained(name, legend):
    """Whether `legend` says what `name` is: the name before a colon, alone or listed, at the
    start of a line or of a clause (after '(', ';' or ',')."""
    words = r"[\w ³/-]+"
    return re.search(r"(?:^|[(;,])\s*" + re.escape(name) + r"(?:,\s*(?:and\s+)?" + words + r")*:",
                     legend, re.MULTILINE) is not None


def unexplained(tables, lines, in_table, help_text):
    """The tables' columns that neither the help nor a line outside the tables explains."""
    legend = help_text + "\n" + "\n".join(l for n, l in enumerate(lines) if n not in in_table)
    missing = collections.defaultdict(list)
    for at, head in tables:
        for cell in head:
            name = column_name(cell)
            if name.lower() not in PLAIN and not explained(name, legend):
                missing[name].append(at + 1)
    return ["column '%s' (the table at line %s) is explained nowhere: say '%s: ...' in a "
            "legend line or in --help" % (name, ", ".join(map(str, at[:3])), name)
            for name, at in missing.items()]


def problems_in(text, lengths=None, help_text=None):
    """The problems check() finds in `text`, for the self-test."""
    import io
    import contextlib
    import tempfile
    with tempfile.TemporaryDirectory() as d:
        out, hlp = d + "/out.txt", d + "/help.txt"
        open(out, "w", encoding="utf-8").write(text)
        args = [out] + (["--lengths", lengths] if lengths else [])
        if help_text is not None:
            open(hlp, "w", encoding="utf-8").write(help_text)
            args += ["--help-text", hlp]
        printed = io.StringIO()
        with contextlib.redirect_stdout(printed):
            code = check(args)
        return code, printed.getvalue()


def self_test():
    """Planted outputs: each must give the problem named, the good ones none."""
    table = ("floor  layers  waited  why\n"
             "    0      30   8.8 s  min-interval x1\n"
             "    1      30  12.0 s\n"
             "  (waited: the waits summed; why: their reasons)\n")
    cases = [
        ("a good table, its last cell empty on one row", table, None, ""),
        ("a column in two units", table.replace("12.0 s", "1.2 h"), None, "column 'waited'"),
        ("a figure recurring in two units", "climb 1: after a wait of 3.0 s\n"
         "climb 2: after a wait of 2.0 h\n", None, "in 2 units"),
        ("a column explained nowhere", table.replace("why: their reasons", "the reasons"), "",
         "column 'why'"),
        ("a column explained in --help", table.replace("why: their reasons", "the reasons"),
         "Prints a table (why: the reasons)", ""),
        ("a colon in prose is no legend", table.replace("why: their reasons", "the reasons"),
         "Where it stands on the why: somewhere", "column 'why'"),
        ("a header one space apart", "nozzles rails  gantry m  vertices\n"
         "2        x          1.5        81\n", "", "columns must stand two spaces apart"),
        ("metres in a feet building", "walls 12.0 ft long, 3.0 m high\n", "ft",
         "lengths in ft"),
        ("feet in a feet building", "walls 12.0 ft long, 3.0 in thick, 1309 in one pass\n",
         "ft", ""),
    ]
    failed = 0
    for name, text, extra, wanted in cases:
        lengths = extra if extra in SYSTEMS else None
        help_text = None if extra in SYSTEMS or extra is None else extra
        code, printed = problems_in(text, lengths, help_text)
        ok = (code == 0) if not wanted else (code == 1 and wanted in printed)
        print("%s: %s%s" % ("ok" if ok else "WRONG", name, "" if ok else " -> " + printed.strip()))
        failed += not ok
    return 1 if failed else 0


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    return check(sys.argv[1:])


def check(argv):
    ap = argparse.ArgumentParser()
    ap.add_argument("output", nargs="?")
    ap.add_argument("--lengths", choices=sorted(SYSTEMS))
    ap.add_argument("--help-text", help="the command's --help, to check the tables' columns")
    a = ap.parse_args(argv)
    text = open(a.output, encoding="utf-8").read() if a.output else sys.stdin.read()
    lines = [plain(l.rstrip("\n")) for l in text.splitlines()]
    units = collections.defaultdict(lambda: collections.defaultdict(list))  # figure -> unit -> lines
    in_table = set()
    tables = []  # (header line, header cells)
    unreadable = []
    k = 0
    while k < len(lines):
        head = cells(lines[k])
        if not is_header(head):
            k += 1
            continue
        j = k + 1
        row = lambda n: row_cells(lines[n], lines[k], head) if n < len(lines) else None
        if j < len(lines) and re.search(r"\d", lines[j]) and row(j) is None \
                and len(cells(lines[j])) >= 3:
            unreadable.append("the table at line %d: its header has %d columns and its first row "
                              "%d (columns must stand two spaces apart)" % (k + 1, len(head),
                                                                            len(cells(lines[j]))))
        if row(j) is not None:
            tables.append((k, head))
            in_table.add(k)
        while row(j) is not None and not is_header(cells(lines[j])):
            for c, cell in enumerate(row(j)):
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
    problems += unreadable
    if a.help_text is not None:
        problems += unexplained(tables, lines, in_table, open(a.help_text, encoding="utf-8").read())
    print("\n".join(problems) or "OK: %d figures and columns, each in one unit" % len(units))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
