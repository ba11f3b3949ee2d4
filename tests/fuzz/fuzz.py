#!/usr/bin/env python3
"""ccbuild's own fuzz harness: seeded, bounded, over every input surface.

Each case copies a good input of the project (a building and its plan and profiles, a plan,
an IFC model, a DXF drawing, a site programme and its weather, a machine or family
profile and its URDF, a schedule, a study, or just a command line) into a folder of its
own, mutates it as a hostile user would (hostile numbers and strings, lines deleted,
repeated a thousand times or swapped, truncation, stray bytes, JSON values replaced), runs
one ccbuild command on it under a time limit, and checks what every run must hold:

  - the exit code is 0, 1 or 2; never 3 (an internal error), a signal, or a hang;
  - exit 2 says "ccbuild: error:", and stderr stays short (echoed values are cut);
  - no input changed (bytes and modification time), no file made but the outputs the
    command was asked for, no temporary file left, no device replaced;
  - a command that fails writes none of its outputs (all or nothing);
  - a success reads back: an import's building validates (or is refused for what it holds,
    not because it does not parse), a fitted profile loads, a schedule is drawn, an export
    parses (CSV, XML, iCalendar), an sbatch script is valid shell.

The same --seed gives the same cases. Findings become regression tests (tests/cli/).

Usage: fuzz.py CCBUILD [--cases N] [--seed S] [--budget-s T] [--jobs J] [--surface NAME]
                       [--keep DIR] [--timeout-s T] [--quiet]
  CTest runs a short budget (Fuzz.*); the closing figures come from --cases 10000.
"""

import argparse
import csv
import hashlib
import io
import json
import os
import random
import re
import shutil
import stat
import subprocess
import sys
import tempfile
import threading
import time
import xml.etree.ElementTree as ElementTree
from concurrent.futures import ThreadPoolExecutor

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

HOSTILE_NUMBERS = [
    "0", "-0", "-1", "1e308", "-1e308", "1e-320", "4.9e-324", "nan", "NaN", ".nan", ".inf",
    "-.inf", "inf", "1e400", "99999999999999999999999", "2147483648", "-2147483649",
    "9223372036854775807", "9223372036854775808", "18446744073709551616", "0x10", "1_000",
    "1,5", "+1", "--1", "1e", ".", "", "\u0663", "1.0000000000000002", "0.1", "3", "100000",
]
HOSTILE_STRINGS = [
    "", " ", "\n", "a\nb", "x\r\ny", "\"", "'", "#", ": ", "- ", "{", "}", "[", "]", "&a",
    "*a", "!!binary", "\x00", "\x07", "\x1b[2J", "\u00e9\u20ac\U0001d11e", "\ufeff",
    "\u2028", "x" * 5000, "../../etc/passwd", "/dev/zero", "/dev/stdin", "%s%n", "$(id)",
    "`id`", "null", "~", "yes", "no", "true", "-", "--force", "\\", "\t",
]
RANDOM_BYTES = [b"\x00", b"\xff", b"\xc3", b"\xed\xa0\x80", b"\r", b"\x1a", b"\x7f"]

COMMANDS = ["validate", "import", "layers", "plan-layer", "sweep", "fit", "climb", "schedule",
            "report", "export", "diff", "study"]

# Messages of ccbuild's readers themselves: a success whose output fails with one of these
# on reading back did not write what it reads.
READER_FAILURES = re.compile(
    r"YAML|JSON|syntax|map keys|duplicate key|unknown key|expected a single value|"
    r"expected a map|expected a sequence|not UTF-8|cannot open file|control character")


def sha(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def snapshot(folder):
    """Every entry under folder: path -> (kind, sha256 or '', mtime_ns)."""
    out = {}
    for base, dirs, files in os.walk(folder):
        for name in dirs + files:
            p = os.path.join(base, name)
            st = os.lstat(p)
            if stat.S_ISREG(st.st_mode):
                out[p] = ("file", sha(p), st.st_mtime_ns)
            elif stat.S_ISDIR(st.st_mode):
                out[p] = ("dir", "", 0)
            else:
                out[p] = ("other", "", st.st_mtime_ns)
    return out


class Case:
    def __init__(self, surface, index, rng):
        self.surface = surface
        self.index = index
        self.rng = rng
        self.files = {}      # relative path -> bytes
        self.fifos = []      # relative paths of FIFOs to make
        self.folders = []    # relative folders to make
        self.argv = []
        self.outputs = []    # relative paths (files) the command may write
        self.output_folders = []  # relative folders whose contents it may write
        self.all_or_nothing = True
        self.readback = None  # (kind, detail)
        self.note = ""        # the mutation, in words

    def name(self):
        return "%s-%05d" % (self.surface, self.index)


# ---------------------------------------------------------------- mutations of text


def mutate_text(rng, data, times=None):
    """Mutates bytes as a hostile user would; returns (bytes, what was done)."""
    text = data.decode("utf-8", "surrogateescape")
    done = []
    for _ in range(times or rng.choice([1, 1, 1, 2, 3])):
        kind = rng.choice(["number", "number", "number", "string", "string", "delete", "repeat",
                           "swap", "duplicate", "truncate", "bytes", "indent", "nest"])
        lines = text.split("\n")
        if kind == "number":
            spots = [m for m in re.finditer(r"-?\d+(\.\d+)?([eE][-+]?\d+)?", text)]
            if not spots:
                continue
            m = rng.choice(spots)
            value = rng.choice(HOSTILE_NUMBERS)
            text = text[:m.start()] + value + text[m.end():]
            done.append("number %r -> %r" % (m.group(0), value))
        elif kind == "string":
            spots = [m for m in re.finditer(r"[A-Za-z_][A-Za-z_0-9.\-]*", text)]
            if not spots:
                continue
            m = rng.choice(spots)
            value = rng.choice(HOSTILE_STRINGS)
            text = text[:m.start()] + value + text[m.end():]
            done.append("word %r -> %r" % (m.group(0), value[:20]))
        elif kind == "delete" and len(lines) > 1:
            k = rng.randrange(len(lines))
            done.append("line %d deleted" % (k + 1))
            del lines[k]
            text = "\n".join(lines)
        elif kind == "repeat" and lines:
            k = rng.randrange(len(lines))
            n = rng.choice([2, 10, 1000, 5000])
            lines[k:k + 1] = [lines[k]] * n
            text = "\n".join(lines)
            done.append("line %d repeated %d times" % (k + 1, n))
        elif kind == "swap" and len(lines) > 2:
            a, b = rng.randrange(len(lines)), rng.randrange(len(lines))
            lines[a], lines[b] = lines[b], lines[a]
            text = "\n".join(lines)
            done.append("lines %d and %d swapped" % (a + 1, b + 1))
        elif kind == "duplicate" and len(lines) > 2:
            a = rng.randrange(len(lines))
            b = min(len(lines), a + rng.randrange(1, 20))
            lines[b:b] = lines[a:b]
            text = "\n".join(lines)
            done.append("lines %d-%d duplicated" % (a + 1, b))
        elif kind == "truncate" and text:
            k = rng.randrange(len(text))
            text = text[:k]
            done.append("truncated at %d" % k)
        elif kind == "bytes":
            k = rng.randrange(len(text) + 1)
            raw = rng.choice(RANDOM_BYTES).decode("utf-8", "surrogateescape")
            text = text[:k] + raw + text[k:]
            done.append("a stray byte at %d" % k)
        elif kind == "indent" and lines:
            k = rng.randrange(len(lines))
            lines[k] = rng.choice(["", " ", "    ", "\t"]) + lines[k]
            text = "\n".join(lines)
            done.append("line %d indented" % (k + 1))
        elif kind == "nest":
            depth = rng.choice([10, 100, 10000])
            k = rng.randrange(len(text) + 1)
            text = text[:k] + "[" * depth + text[k:]
            done.append("%d brackets at %d" % (depth, k))
    return text.encode("utf-8", "surrogateescape"), "; ".join(done) or "unchanged"


HOSTILE_JSON = [None, True, False, 0, -1, 1e308, -1e308, 9223372036854775807,
                18446744073709551616, 1.5, "", "x", "\n", "x" * 3000, [], {}, [1, 2], {"a": 1}]


def mutate_json(rng, data):
    """Replaces, deletes or adds a value at random places of a JSON document."""
    try:
        doc = json.loads(data)
    except ValueError:
        return mutate_text(rng, data)
    done = []
    for _ in range(rng.choice([1, 1, 2, 3])):
        # Collect (container, key) pairs.
        spots = []
        stack = [doc]
        while stack and len(spots) < 20000:
            node = stack.pop()
            if isinstance(node, dict):
                for k, v in node.items():
                    spots.append((node, k))
                    stack.append(v)
            elif isinstance(node, list):
                for i, v in enumerate(node):
                    spots.append((node, i))
                    stack.append(v)
        if not spots:
            break
        container, key = rng.choice(spots)
        action = rng.choice(["replace", "replace", "replace", "delete", "add"])
        if action == "replace":
            old = container[key]
            if isinstance(old, (int, float)) and not isinstance(old, bool) and rng.random() < 0.5:
                new = old * rng.choice([0, -1, 2, 1.0000001, 1e9]) + rng.choice([0, 1, -1, 1e-9])
            else:
                new = rng.choice(HOSTILE_JSON)
            container[key] = new
            done.append("%s replaced" % key)
        elif action == "delete":
            del container[key]
            done.append("%s deleted" % key)
        elif isinstance(container, dict):
            container["zz_unknown"] = 1
            done.append("a key added")
        else:
            container.append(container[key])
            done.append("an item repeated")
    text = json.dumps(doc, allow_nan=rng.random() < 0.1)
    return text.encode(), "; ".join(done)


def read(rel):
    with open(os.path.join(ROOT, rel), "rb") as f:
        return f.read()


# ---------------------------------------------------------------- the inputs, copied


def cottage_files():
    """The cottage building with its plan, machine (and URDF) and mix, side by side."""
    building = read("tests/data/buildings/cottage.yaml").decode()
    building = building.replace("../../../config/materials/standard-mix.yaml", "mix.yaml")
    building = building.replace("../../../config/machines/cc-gantry.yaml", "gantry.yaml")
    building = building.replace("plans/cottage.yaml", "plan.yaml")
    gantry = read("config/machines/cc-gantry.yaml").decode()
    return {
        "building.yaml": building.encode(),
        "plan.yaml": read("tests/data/plans/cottage.yaml"),
        "mix.yaml": read("config/materials/standard-mix.yaml"),
        "gantry.yaml": gantry.encode(),
        "cc_gantry.urdf": read("config/machines/cc_gantry.urdf"),
    }


def house_files():
    """The bundled house (two storeys, anchors for a climber) with its plans and mix."""
    building = read("config/buildings/house.yaml").decode()
    building = building.replace("../materials/standard-mix.yaml", "mix.yaml")
    building = building.replace("../machines/cc-gantry.yaml", "gantry.yaml")
    return {
        "building.yaml": building.encode(),
        "house/ground.yaml": read("config/buildings/house/ground.yaml"),
        "house/upper.json": read("config/buildings/house/upper.json"),
        "mix.yaml": read("config/materials/standard-mix.yaml"),
        "gantry.yaml": read("config/machines/cc-gantry.yaml"),
        "cc_gantry.urdf": read("config/machines/cc_gantry.urdf"),
    }


def site_files():
    site = read("config/sites/weekdays-berlin-2027-weather.yaml").decode()
    site = site.replace("../../tests/data/weather/berlin-spring-2027.csv", "weather.csv")
    # A week of weather keeps the case small.
    weather = "\n".join(read("tests/data/weather/berlin-spring-2027.csv").decode()
                        .split("\n")[:200]) + "\n"
    return {"site.yaml": site.encode(), "weather.csv": weather.encode()}


# ---------------------------------------------------------------- the surfaces


def surface_building(case):
    rng = case.rng
    case.files = cottage_files()
    target = rng.choice(["building.yaml", "building.yaml", "plan.yaml", "mix.yaml"])
    case.files[target], case.note = mutate_text(rng, case.files[target])
    case.note = target + ": " + case.note
    command = rng.choice(["validate", "validate", "layers"])
    case.argv = [command, "building.yaml"] + rng.choice([[], ["--json"], ["--units", "ft"]])


def surface_plan(case):
    rng = case.rng
    name = rng.choice(["cottage.yaml", "cottage.json", "cottage.txt", "one_room.txt",
                       "two_metre_room.yaml", "paper_example1.txt", "cottage_ft.yaml"])
    data, case.note = mutate_text(rng, read("tests/data/plans/" + name)) \
        if not name.endswith(".json") or rng.random() < 0.5 else \
        mutate_json(rng, read("tests/data/plans/" + name))
    ext = os.path.splitext(name)[1]
    case.files["plan" + ext] = data
    case.note = name + ": " + case.note
    if rng.random() < 0.5:
        case.argv = ["validate", "plan" + ext]
    else:
        case.argv = ["plan-layer", "plan" + ext, "--time-limit", "0.2", "--quiet",
                     "--svg", "out.svg"]
        case.outputs = ["out.svg"]


IFC_SEEDS = ["house_ifc4.ifc", "house_ifc2x3.ifc", "feet_ifc2x3.ifc", "layered_ifc4.ifc",
             "thick_ifc4.ifc", "public/wall-with-opening-and-window.ifc"]


def mutate_step(rng, data):
    """STEP-aware mutations on top of the text ones: entities repeated, references broken,
    sections doubled."""
    text = data.decode("utf-8", "surrogateescape")
    kind = rng.choice(["text", "text", "ref", "section", "string"])
    if kind == "ref":
        refs = list(re.finditer(r"#\d+", text))
        if refs:
            m = rng.choice(refs)
            new = rng.choice(["#0", "#999999999", "#" + "9" * 30, "$", "*", "#-1", "()"])
            return (text[:m.start()] + new + text[m.end():]).encode("utf-8", "surrogateescape"), \
                "reference %s -> %s" % (m.group(0), new)
    if kind == "section":
        k = text.find("ENDSEC;", text.find("DATA;"))
        if k >= 0:
            extra = rng.choice(["ENDSEC;\nDATA;\n#1=IFCCARTESIANPOINT((nan,0.,0.));\n",
                                "ENDSEC;\nDATA;\n", "\nENDSEC;\n", "END-ISO-10303-21;\n"])
            return (text[:k] + extra + text[k:]).encode("utf-8", "surrogateescape"), \
                "section text inserted"
    if kind == "string":
        strings = list(re.finditer(r"'[^']*'", text))
        if strings:
            m = rng.choice(strings)
            new = rng.choice(["'a\\X2\\000A\\X0\\b'", "''", "'\\X2\\D800\\X0\\'", "'''",
                              "'" + "x" * 3000 + "'", "'\n'", "'#'", "'\\S\\'"])
            return (text[:m.start()] + new + text[m.end():]).encode("utf-8", "surrogateescape"), \
                "string %s -> %s" % (m.group(0)[:20], new[:20])
    return mutate_text(rng, data)


def surface_ifc(case):
    rng = case.rng
    seed = rng.choice(IFC_SEEDS)
    case.files["model.ifc"], case.note = mutate_step(rng, read("tests/data/ifc/" + seed))
    case.note = seed + ": " + case.note
    case.folders = ["out"]
    case.argv = ["import", "model.ifc", "-o", "out/building.yaml"] + rng.choice(
        [[], [], ["--wall-types", "IfcWall"], ["--no-material-filter"]])
    case.output_folders = ["out"]
    case.readback = ("validate", "out/building.yaml")


DXF_SEEDS = ["faces_mm.dxf", "faces_m.dxf", "centrelines_m.dxf", "gaps_faces_mm.dxf",
             "gaps_m.dxf", "attributes_m.dxf", "unitless.dxf"]


def mutate_dxf(rng, data):
    """DXF-aware mutations: on (group code, value) pairs and whole entities, so that most
    cases get past the reader into the wall finding (duplicates, near-duplicates, floods of
    entities, hostile values)."""
    lines = data.decode("latin-1").replace("\r\n", "\n").split("\n")
    if len(lines) < 4 or rng.random() < 0.25:
        return mutate_text(rng, data)
    pairs = [(lines[k], lines[k + 1]) for k in range(0, len(lines) - 1, 2)]
    # Entities: runs of pairs from a code 0 to the next.
    starts = [k for k, (c, _) in enumerate(pairs) if c.strip() == "0"]
    entities = [(starts[i], starts[i + 1]) for i in range(len(starts) - 1)
                if pairs[starts[i]][1].strip() in ("LINE", "LWPOLYLINE", "POLYLINE", "INSERT",
                                                   "ARC", "CIRCLE", "VERTEX", "TEXT")]
    kind = rng.choice(["value", "value", "entity", "entity", "shift", "delete"])
    done = ""
    if kind == "value":
        numeric = [k for k, (c, v) in enumerate(pairs) if re.match(r"\s*-?[\d.]+\s*$", v)]
        if numeric:
            k = rng.choice(numeric)
            value = rng.choice(HOSTILE_NUMBERS + HOSTILE_STRINGS[:12])
            done = "value %r of code %s -> %r" % (pairs[k][1], pairs[k][0].strip(), value[:20])
            pairs[k] = (pairs[k][0], value)
    elif kind in ("entity", "shift") and entities:
        a, b = rng.choice(entities)
        block = pairs[a:b]
        n = rng.choice([1, 2, 100, 2000]) if kind == "entity" else rng.choice([1, 50])
        copies = []
        for i in range(n):
            copy = list(block)
            if kind == "shift":  # near-duplicates: each copy moved a little
                copy = [(c, "%.6f" % (float(v) + rng.uniform(-0.01, 0.01) * (i + 1)))
                        if c.strip() in ("10", "20", "11", "21") and
                        re.match(r"\s*-?[\d.]+\s*$", v) else (c, v) for c, v in copy]
            copies += copy
        pairs[b:b] = copies
        done = "an entity %s %d more times" % ("moved and repeated" if kind == "shift"
                                               else "repeated", n)
    elif kind == "delete" and pairs:
        k = rng.randrange(len(pairs))
        done = "pair %s/%s deleted" % (pairs[k][0].strip(), pairs[k][1][:20])
        del pairs[k]
    if not done:
        return mutate_text(rng, data)
    text = "\n".join(c + "\n" + v for c, v in pairs) + "\n"
    return text.encode("latin-1", "replace"), done


def surface_dxf(case):
    rng = case.rng
    seed = rng.choice(DXF_SEEDS)
    data = read("tests/data/drawings/" + seed)
    layers = sorted(set(re.findall(r"\n\s*8\r?\n([^\r\n]+)", data.decode("latin-1"))))
    case.files["drawing.dxf"], case.note = mutate_dxf(rng, data)
    case.note = seed + ": " + case.note
    walls = [l for l in layers if "WALL" in l.upper()] or layers or ["WALLS"]
    flags = ["--wall-layers", rng.choice(walls)]
    if "faces" in seed:
        flags += ["--wall-lines", "faces" if rng.random() < 0.9 else "centrelines"]
    elif rng.random() < 0.1:
        flags += ["--wall-lines", "faces"]
    if "gaps" in seed or rng.random() < 0.3:
        flags += ["--gap-openings"]
        if rng.random() < 0.3:
            flags += ["--max-gap", rng.choice(["2", "0", "-1", "1e9", "nan"])]
    doors = [l for l in layers if "DOOR" in l.upper()]
    windows = [l for l in layers if "WIND" in l.upper() or "GLAZ" in l.upper()]
    if doors:
        flags += ["--door-layers", rng.choice(doors)]
    if windows:
        flags += ["--window-layers", rng.choice(windows)]
    if seed == "unitless.dxf" or rng.random() < 0.1:
        flags += ["--unit", rng.choice(["mm", "m", "m", "ft", "furlong", ""])]
    case.folders = ["out"]
    case.argv = ["import", "drawing.dxf", "-o", "out/building.yaml"] + flags
    case.output_folders = ["out"]
    case.readback = ("validate", "out/building.yaml")


def surface_site(case):
    rng = case.rng
    case.files = cottage_files()
    case.files.update(site_files())
    if rng.random() < 0.6:
        case.files["site.yaml"], case.note = mutate_text(rng, case.files["site.yaml"])
        case.note = "site.yaml: " + case.note
    else:
        case.files["weather.csv"], case.note = mutate_text(rng, case.files["weather.csv"])
        case.note = "weather.csv: " + case.note
    case.argv = ["validate", "building.yaml", "--site", "site.yaml"]


def surface_machine(case):
    rng = case.rng
    case.files = cottage_files()
    target = rng.choice(["gantry.yaml", "gantry.yaml", "cc_gantry.urdf"])
    case.files[target], case.note = mutate_text(rng, case.files[target])
    case.note = target + ": " + case.note
    case.argv = rng.choice([["validate", "building.yaml"],
                            ["validate", "building.yaml", "--machine", "gantry.yaml"],
                            ["plan-layer", "building.yaml", "--time-limit", "0.2", "--quiet"]])


def surface_family(case):
    rng = case.rng
    case.files = house_files()
    family, case.note = mutate_text(rng, read("config/machines/cc-climber-family.yaml"))
    case.files["family.yaml"] = family
    case.note = "family.yaml: " + case.note
    case.argv = ["fit", "building.yaml", "--machine", "family.yaml", "-o", "fitted.yaml",
                 "--quiet"]
    case.outputs = ["fitted.yaml", "fitted.urdf"]
    case.readback = ("fitted", "fitted.yaml")


class ScheduleBase:
    """The cottage's schedule, made once, with its inputs beside it (the paths it records
    are relative to its folder)."""
    lock = threading.Lock()
    files = None

    @classmethod
    def get(cls, ccbuild):
        with cls.lock:
            if cls.files is None:
                folder = tempfile.mkdtemp(prefix="ccbuild_fuzz_base_")
                try:
                    files = cottage_files()
                    files.update(site_files())
                    for name, data in files.items():
                        with open(os.path.join(folder, name), "wb") as f:
                            f.write(data)
                    for out, extra in (("s.json", []), ("dated.json", ["--site", "site.yaml"])):
                        subprocess.run([ccbuild, "schedule", "building.yaml", "--quiet",
                                        "--no-compare", "-o", out] + extra, cwd=folder,
                                       check=True, stdout=subprocess.DEVNULL)
                        files[out] = open(os.path.join(folder, out), "rb").read()
                    cls.files = files
                finally:
                    shutil.rmtree(folder)
            return dict(cls.files)


def surface_schedule(case, ccbuild):
    rng = case.rng
    case.files = ScheduleBase.get(ccbuild)
    source = rng.choice(["s.json", "dated.json"])
    mutated = rng.random() < 0.9
    if mutated:
        data, case.note = mutate_json(rng, case.files[source]) if rng.random() < 0.8 else \
            mutate_text(rng, case.files[source])
        case.files["m.json"] = data
        case.note = source + ": " + case.note
    else:
        case.files["m.json"] = case.files[source]
    what = rng.choice(["report", "export", "export", "diff"])
    if what == "report":
        case.argv = ["report", "m.json", "-o", "r.html"]
        case.outputs = ["r.html"]
        case.readback = ("html", "r.html")
    elif what == "export":
        fmt = rng.choice(["csv", "ical", "mspdi", "days"])
        case.argv = ["export", "m.json", "--format", fmt, "-o", "e.out"]
        if source == "s.json" and fmt != "csv" or rng.random() < 0.2:
            case.argv += ["--start", rng.choice(["2027-03-01T07:00", "2200-12-31T23:00",
                                                 "9999-12-31T23:59", "2027-02-29T07:00",
                                                 "2027-03-+1T07:00", "1971-01-01 00:00"])]
        case.outputs = ["e.out"]
        case.readback = ("export-" + fmt, "e.out")
    else:
        case.argv = ["diff", source, "m.json"] + rng.choice(
            [[], ["--tolerance", "5s"], ["--tolerance", rng.choice(["-1s", "nan%", "1e400s"])]])


def study_text(rng):
    text = read("tests/data/studies/house-24.yaml").decode()
    text = text.replace("../../../config/buildings/house.yaml", "building.yaml")
    text = text.replace("../../../config/machines/cc-gantry.yaml", "gantry.yaml")
    text = text.replace("../../../config/materials/standard-mix.yaml", "mix.yaml")
    return text.encode()


def surface_study(case):
    rng = case.rng
    case.files = house_files()
    case.files["study.yaml"], case.note = mutate_text(rng, study_text(rng))
    case.note = "study.yaml: " + case.note
    # A Slurm script only (nothing submitted, no variant run): the study is read, planned
    # and written as it would be for a cluster.
    case.argv = ["study", "study.yaml", "-o", "results", "--slurm"] + rng.choice(
        [[], ["--partition", rng.choice(["short", "a\nb", "", "x" * 300, "$(id)"])],
         ["--time", rng.choice(["30", "2:00:00", "-1", "1\n#SBATCH --x"])]])
    case.output_folders = ["results"]
    case.all_or_nothing = False  # a study's folder is its journal: resumable, not atomic
    case.readback = ("sbatch", "results")


FLAG_VALUES = ["", "-1", "0", "nan", "1e400", "99999999999999999999", "x" * 2000, "a\nb",
               "1", "2", "0.5", "ft", "m", "x", "centre", "auto"]


def surface_flags(case):
    """A command with random flags and values on good inputs, outputs pointed at inputs,
    devices, folders, FIFOs and missing folders."""
    rng = case.rng
    case.files = cottage_files()
    case.fifos = ["fifo"]
    case.folders = ["sub"]
    command = rng.choice(["validate", "layers", "plan-layer", "sweep", "climb", "schedule",
                          "fit"])
    flags = {
        "validate": ["--json", "--units", "--place", "--floor-height", "--layer-height"],
        "layers": ["--floor", "--json", "--units"],
        "plan-layer": ["--floor", "--layer", "--metric", "--objective", "--algorithm",
                       "--start-vertex", "--first-wall", "--time-limit", "--seed", "--bound",
                       "--max-kicks", "--nozzles", "--gantry-width", "--rail-axis", "--method",
                       "--platform-width", "--svg", "--force", "--json"],
        "sweep": ["--nozzles", "--platform-width", "--gantry-width", "--rail-axis", "--csv"],
        "climb": ["--floor", "--seed", "--time-limit", "--svg", "--json"],
        "schedule": ["-o", "--report", "--seed", "--jobs", "--objective", "--export",
                     "--force", "--layer-time-limit"],
        "fit": ["-o", "--force", "--json"],
    }[command]
    argv = [command, "building.yaml"]
    outputs = []
    outputish = {"--svg", "--csv", "-o", "--report", "--export"}
    for flag in rng.sample(flags, rng.randrange(1, min(4, len(flags)) + 1)):
        if flag in ("--json", "--force"):
            argv.append(flag)
            continue
        if flag in outputish:
            value = rng.choice(["out.svg", "out.json", "out.csv", "out.html", "t.csv",
                                "building.yaml", "plan.yaml", "cc_gantry.urdf", "sub",
                                "fifo", "/dev/null", "/dev/full", "missing/x.json", "",
                                "sub/../plan.yaml", "gantry.yaml"])
            if value and not value.startswith("/dev/"):
                outputs.append(value)
        elif flag == "--time-limit" or flag == "--layer-time-limit":
            value = rng.choice(["0.2", "0", "-1", "nan", "1e9"])
        else:
            value = rng.choice(FLAG_VALUES)
        argv += [flag, value]
    if command in ("plan-layer", "climb") and "--time-limit" not in argv:
        argv += ["--time-limit", "0.2"]
    if command == "fit" and "-o" not in argv:
        argv += ["-o", "fitted.yaml"]
    if command == "fit":
        outputs += [os.path.splitext(o)[0] + ".urdf" for o in outputs]
        outputs.append("fitted.yaml")
        outputs.append("fitted.urdf")
    if command == "schedule":
        argv.append("--no-compare")
    case.argv = argv
    case.outputs = outputs
    case.note = " ".join(repr(a)[:30] for a in argv)


SURFACES = {
    "building": surface_building, "plan": surface_plan, "ifc": surface_ifc,
    "dxf": surface_dxf, "site": surface_site, "machine": surface_machine,
    "family": surface_family, "schedule": surface_schedule, "study": surface_study,
    "flags": surface_flags,
}
# How often each surface comes up (the slow ones less often).
WEIGHTS = {"building": 3, "plan": 2, "ifc": 2, "dxf": 3, "site": 2, "machine": 2,
           "family": 1, "schedule": 3, "study": 1, "flags": 2}


# ---------------------------------------------------------------- running and judging


def run(ccbuild, argv, cwd, timeout_s):
    started = time.monotonic()
    try:
        p = subprocess.run([ccbuild] + argv, cwd=cwd, stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, timeout=timeout_s, start_new_session=True)
        return p.returncode, p.stdout, p.stderr, time.monotonic() - started
    except subprocess.TimeoutExpired as e:
        return None, e.stdout or b"", e.stderr or b"", time.monotonic() - started


def reads_back(case, ccbuild, folder, timeout_s):
    """None when the output reads back, else why not."""
    kind, target = case.readback
    path = os.path.join(folder, target)
    if kind == "validate":
        code, out, err, _ = run(ccbuild, ["validate", target], folder, timeout_s)
        if code in (0, 1):
            return None
        if code == 2 and not READER_FAILURES.search(err.decode("utf-8", "replace")):
            return None  # refused for what it holds (a wall too thin, say), not unread
        return "validate of the import's building: exit %s: %s" % (
            code, err.decode("utf-8", "replace")[:300])
    if kind == "fitted":
        code, out, err, _ = run(ccbuild, ["validate", "building.yaml", "--machine", target],
                                folder, timeout_s)
        if code in (0, 1):
            return None
        return "the fitted profile does not load: exit %s: %s" % (
            code, err.decode("utf-8", "replace")[:300])
    if kind == "html":
        text = open(path, "rb").read()
        return None if text.rstrip().endswith(b"</html>") else "the report is not whole"
    if kind.startswith("export-"):
        fmt = kind[len("export-"):]
        text = open(path, "rb").read().decode("utf-8")
        try:
            if fmt == "csv":
                rows = list(csv.reader(io.StringIO(text)))
                if not rows or len({len(r) for r in rows}) != 1:
                    return "the CSV's rows differ in length"
            elif fmt == "mspdi":
                ElementTree.fromstring(text.encode())
            elif fmt == "ical":
                if not text.startswith("BEGIN:VCALENDAR") or "END:VCALENDAR" not in text:
                    return "not an iCalendar"
                for line in text.split("\r\n"):
                    if len(line.encode()) > 75:
                        return "an iCalendar line over 75 octets"
                for year in re.findall(r"(?:DTSTART|DTEND)[^:]*:(\d{4})", text):
                    if not 1971 <= int(year) <= 2200:
                        return "a date in year %s" % year
        except Exception as e:  # a parser's refusal is the finding
            return "the %s export does not parse: %s" % (fmt, e)
        return None
    if kind == "sbatch":
        scripts = []
        for base, _, files in os.walk(path):
            scripts += [os.path.join(base, f) for f in files if f.endswith(".sbatch")]
        for script in scripts:
            p = subprocess.run(["bash", "-n", script], stderr=subprocess.PIPE)
            if p.returncode != 0:
                return "the sbatch script is not valid shell: " + p.stderr.decode()[:200]
            for line in open(script, encoding="utf-8", errors="replace"):
                if line.startswith("#SBATCH") and not re.match(r"#SBATCH --[a-z-]+(=| |$)", line):
                    return "a stray #SBATCH line: " + line.strip()[:80]
        return None
    return None


def judge(case, ccbuild, folder, before, code, err, timeout_s):
    """The findings of one run, in words (empty: none)."""
    findings = []
    text = err.decode("utf-8", "replace")
    if code is None:
        return ["hang: no answer within %.0f s" % timeout_s]
    if code < 0:
        findings.append("killed by signal %d" % -code)
    elif code not in (0, 1, 2):
        findings.append("exit %d: %s" % (code, text[-400:]))
    if "internal error" in text:
        findings.append("internal error: " + text[-400:])
    if code == 2 and "ccbuild: error:" not in text:
        findings.append("exit 2 without 'ccbuild: error:'")
    if len(err) > 64 * 1024:
        findings.append("stderr of %d bytes" % len(err))
    after = snapshot(folder)
    allowed = {os.path.join(folder, o) for o in case.outputs}
    allowed_dirs = [os.path.join(folder, d) + os.sep for d in case.output_folders]

    def may_write(p):
        return p in allowed or any(p.startswith(d) for d in allowed_dirs)

    for p, was in before.items():
        now = after.get(p)
        if now is None:
            findings.append("removed: " + os.path.relpath(p, folder))
        elif now != was and not (may_write(p) and was[0] == "file"):
            if not (was[0] == "dir" and now[0] == "dir"):
                findings.append("changed: " + os.path.relpath(p, folder))
        elif now != was and "--force" not in case.argv and case.surface == "flags":
            findings.append("replaced without --force: " + os.path.relpath(p, folder))
    for p, now in after.items():
        if p in before:
            continue
        rel = os.path.relpath(p, folder)
        if ".tmp." in rel or ".old." in rel:
            findings.append("left behind: " + rel)
        elif not may_write(p) and now[0] != "dir":
            findings.append("a file not asked for: " + rel)
        elif code not in (0, 1) and case.all_or_nothing and now[0] == "file":
            findings.append("written by a run that failed: " + rel)
    for device in ("/dev/null", "/dev/full"):
        if not stat.S_ISCHR(os.stat(device).st_mode):
            findings.append(device + " is no longer a device")
    if not findings and code == 0 and case.readback:
        kind, target = case.readback
        if os.path.exists(os.path.join(folder, target)):
            why = reads_back(case, ccbuild, folder, timeout_s)
            if why:
                findings.append("success that does not read back: " + why)
    return findings


def run_case(case, ccbuild, work, timeout_s, keep):
    folder = os.path.join(work, case.name())
    os.makedirs(folder)
    for rel, data in case.files.items():
        path = os.path.join(folder, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "wb") as f:
            f.write(data)
    for rel in case.folders:
        os.makedirs(os.path.join(folder, rel), exist_ok=True)
    for rel in case.fifos:
        os.mkfifo(os.path.join(folder, rel))
    before = snapshot(folder)
    code, out, err, elapsed = run(ccbuild, case.argv, folder, timeout_s)
    findings = judge(case, ccbuild, folder, before, code, err, timeout_s)
    if findings and keep:
        target = os.path.join(keep, case.name())
        shutil.rmtree(target, ignore_errors=True)
        # The inputs as they were, the command, and what it said.
        os.makedirs(target)
        for rel, data in case.files.items():
            path = os.path.join(target, rel)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "wb") as f:
                f.write(data)
        with open(os.path.join(target, "CASE.txt"), "w") as f:
            f.write("ccbuild " + " ".join(repr(a) for a in case.argv) + "\n")
            f.write("mutation: " + case.note + "\n")
            f.write("findings:\n  " + "\n  ".join(findings) + "\n")
            f.write("stderr:\n" + err.decode("utf-8", "replace")[-3000:] + "\n")
    shutil.rmtree(folder, ignore_errors=True)
    return code, findings, elapsed


def make_case(surface, index, seed, ccbuild):
    # One generator per case, from the seed and the case's number alone (the same cases
    # whatever --jobs, and a case is replayed by its number).
    rng = random.Random("%d/%s/%d" % (seed, surface, index))
    case = Case(surface, index, rng)
    if surface == "schedule":
        surface_schedule(case, ccbuild)
    else:
        SURFACES[surface](case)
    return case


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("ccbuild")
    parser.add_argument("--cases", type=int, default=500)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--budget-s", type=float, default=0.0,
                        help="stop starting cases after this long (0: no budget)")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--surface", default="", help="only this surface")
    parser.add_argument("--keep", default="", help="copy each failing case here")
    parser.add_argument("--timeout-s", type=float, default=60.0)
    parser.add_argument("--quiet", action="store_true")
    args = parser.parse_args()
    ccbuild = os.path.abspath(args.ccbuild)
    if args.surface and args.surface not in SURFACES:
        sys.exit("fuzz: --surface is one of " + ", ".join(SURFACES))
    # The order of surfaces: a weighted round, the same for a seed.
    order = []
    for name, weight in WEIGHTS.items():
        if not args.surface or name == args.surface:
            order += [name] * weight
    plan = [(order[k % len(order)], k) for k in range(args.cases)]
    work = tempfile.mkdtemp(prefix="ccbuild_fuzz_")
    started = time.monotonic()
    tally = {}
    failures = []
    slowest = (0.0, "")
    lock = threading.Lock()
    done = [0]

    def one(item):
        surface, index = item
        if args.budget_s and time.monotonic() - started > args.budget_s:
            return
        case = make_case(surface, index, args.seed, ccbuild)
        code, findings, elapsed = run_case(case, ccbuild, work, args.timeout_s, args.keep)
        with lock:
            nonlocal slowest
            t = tally.setdefault(surface, {"cases": 0, "exit": {}})
            t["cases"] += 1
            key = "hang" if code is None else str(code)
            t["exit"][key] = t["exit"].get(key, 0) + 1
            if elapsed > slowest[0]:
                slowest = (elapsed, case.name())
            if findings:
                failures.append((case.name(), case.argv, case.note, findings))
            done[0] += 1
            if not args.quiet and done[0] % 100 == 0:
                print("fuzz: %d cases, %d findings, %.0f s" %
                      (done[0], len(failures), time.monotonic() - started), flush=True)

    try:
        with ThreadPoolExecutor(max_workers=args.jobs) as pool:
            list(pool.map(one, plan))
    finally:
        shutil.rmtree(work, ignore_errors=True)
    total = sum(t["cases"] for t in tally.values())
    print("fuzz: seed %d, %d cases in %.0f s (slowest %.1f s, %s)" %
          (args.seed, total, time.monotonic() - started, slowest[0], slowest[1]))
    print("  surface    cases  exit 0  exit 1  exit 2  other")
    for name in SURFACES:
        if name not in tally:
            continue
        e = tally[name]["exit"]
        other = sum(v for k, v in e.items() if k not in ("0", "1", "2"))
        print("  %-9s  %5d  %6d  %6d  %6d  %5d" % (name, tally[name]["cases"], e.get("0", 0),
                                                   e.get("1", 0), e.get("2", 0), other))
    print("  cases: mutated inputs run; exit 0, 1, 2: how they ended; other: exit 3, a "
          "signal or a hang")
    hangs = sum(t["exit"].get("hang", 0) for t in tally.values())
    internal = sum(1 for f in failures if any("internal error" in x or x.startswith("exit 3")
                                               for x in f[3]))
    files = sum(1 for f in failures if any(x.startswith(("changed", "removed", "a file not",
                                                         "left behind", "written by",
                                                         "replaced"))
                                           for x in f[3]))
    unread = sum(1 for f in failures if any("does not read back" in x for x in f[3]))
    print("findings: %d (internal errors %d, hangs %d, files changed or made %d, successes "
          "that do not read back %d)" % (len(failures), internal, hangs, files, unread))
    for name, argv, note, findings in sorted(failures)[:50]:
        print("  %s: ccbuild %s\n    mutation: %s\n    %s" %
              (name, " ".join(a if len(a) < 40 else a[:37] + "..." for a in argv), note[:200],
               "\n    ".join(x[:300] for x in findings)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
