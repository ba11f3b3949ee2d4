#!/usr/bin/env python3
"""Checks the code's layout against the README's (issue 51, "the layout says who owns
what"), from the sources alone:

- every library folder (a CMakeLists.txt that adds a library or the ccbuild program) is a
  row of the README's layout table, and every row naming a library folder exists;
- a folder's arrows are the other folders whose public headers its sources include
  (`#include "ccbuild/<name>/..."`); the table's "uses" column lists exactly those
  arrows, no more, no fewer;
- the arrows go one way: a folder uses only folders above it in the table, and no circle
  runs through any number of folders.

Usage: check_layout.py [REPO] [--self-test]. Exit 0 when the layout holds, 1 otherwise
(each finding on its own line), 2 on a README without the table.
"""
import pathlib
import re
import sys

# A header prefix's folder where the two differ.
HEADER_FOLDER = {"import": "floors/import"}
SKIP_TOP = {"tests", "bench", "build", "config", "docs", "scripts", "studies", ".git", ".ci"}
INCLUDE = re.compile(r'^\s*#\s*include\s+"ccbuild/([a-z_]+)/', re.M)


def library_folders(repo):
    found = set()
    for cm in repo.rglob("CMakeLists.txt"):
        rel = cm.parent.relative_to(repo)
        if not rel.parts or rel.parts[0] in SKIP_TOP or rel.parts[0].startswith("build"):
            continue
        text = cm.read_text()
        if re.search(r"^\s*add_(library|executable)\(", text, re.M):
            found.add(rel.as_posix())
    return found


def arrows(repo, folders):
    """folder -> set of folders its sources include, from the files it owns (a nested
    library folder owns its own files)."""
    out = {f: set() for f in folders}
    for f in folders:
        root = repo / f
        for src in root.rglob("*"):
            if src.suffix not in (".cpp", ".hpp", ".h", ".cc"):
                continue
            owner = src.parent
            while owner.relative_to(repo).as_posix() not in folders:
                owner = owner.parent
            if owner != root:
                continue
            for name in INCLUDE.findall(src.read_text(errors="replace")):
                target = HEADER_FOLDER.get(name, name)
                if target != f:
                    out[f].add(target)
    return out


def readme_table(readme):
    """folder -> set of folders from the layout table's `uses` column, in the table's order."""
    rows = {}
    in_table = False
    for line in readme.read_text().splitlines():
        if line.startswith("| folder |") and "uses" in line:
            header = [c.strip() for c in line.strip().strip("|").split("|")]
            uses_col = header.index("uses")
            in_table = True
            continue
        if in_table:
            if not line.startswith("|"):
                break
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if set(cells[0]) <= set("-: "):
                continue
            folder = cells[0].strip("`").rstrip("/")
            uses = {u.strip("`").rstrip("/") for u in re.findall(r"`[^`]+`", cells[uses_col])}
            rows[folder] = uses
    return rows


def circles(graph):
    """Every folder on a circle, found by depth-first search."""
    found = []
    state = {}

    def visit(node, stack):
        state[node] = 1
        stack.append(node)
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == 1:
                found.append(stack[stack.index(nxt):] + [nxt])
            elif nxt not in state:
                visit(nxt, stack)
        stack.pop()
        state[node] = 2

    for node in sorted(graph):
        if node not in state:
            visit(node, [])
    return found


def check(folders, actual, table):
    problems = []
    for f in sorted(folders - set(table)):
        problems.append(f"{f}/ is a library folder the README's layout table does not list")
    for f in sorted(set(table) - folders):
        problems.append(f"the README's layout table lists {f}/, which is not a library folder")
    for f in sorted(folders & set(table)):
        for extra in sorted(table[f] - actual[f]):
            problems.append(f"README: {f}/ uses {extra}/, but no source of {f}/ includes it")
        for missing in sorted(actual[f] - table[f]):
            problems.append(f"{f}/ includes {missing}/, which the README's table does not say")
    order = list(table)
    for f in sorted(folders & set(table)):
        for used in sorted(actual[f] & set(table)):
            if order.index(used) > order.index(f):
                problems.append(f"{f}/ uses {used}/, which stands below it in the README's table")
    for circle in circles(actual):
        problems.append("a circle of includes: " + " -> ".join(c + "/" for c in circle))
    return problems


def self_test(folders, actual, table):
    """Each planted fault must be found: an arrow the README does not say, a row too many,
    a folder left out, an arrow the code does not have, the table's order upside down, and
    a circle."""
    cases = []
    a = {k: set(v) for k, v in actual.items()}
    a["common"].add("schedule")  # an arrow back down: a circle, and unsaid
    cases.append(("an include back down", folders, a, table))
    t = dict(table)
    t["orchestrator"] = set()
    cases.append(("a row for a folder that is gone", folders, actual, t))
    t = dict(table)
    t.pop("app")
    cases.append(("a folder left out of the table", folders, actual, t))
    t = {k: set(v) for k, v in table.items()}
    t["report"].add("dispatch")
    cases.append(("an arrow the code does not have", folders, actual, t))
    t = dict(reversed(list(table.items())))
    cases.append(("the table upside down", folders, actual, t))
    failed = 0
    for name, f, a2, t2 in cases:
        if not check(f, a2, t2):
            print(f"self-test: {name} was not caught")
            failed += 1
    a = {k: set(v) for k, v in actual.items()}
    a["common"].add("schedule")
    if not circles(a):
        print("self-test: the circle common -> schedule -> ... -> common was not found")
        failed += 1
    return failed


def main(argv):
    args = [a for a in argv if not a.startswith("--")]
    repo = pathlib.Path(args[0] if args else ".").resolve()
    folders = library_folders(repo)
    table = readme_table(repo / "README.md")
    if not table:
        print("README.md: no layout table (a `| folder | ... | uses |` header)")
        return 2
    actual = arrows(repo, folders)
    if "--self-test" in argv:
        failed = self_test(folders, actual, table)
        if failed:
            return 1
        print("check_layout self-test: 6 planted faults caught")
    problems = check(folders, actual, table)
    for p in problems:
        print(p)
    if problems:
        return 1
    edges = sum(len(v) for v in actual.values())
    print(f"layout: {len(folders)} library folders, {edges} arrows, one way, as the README says")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
