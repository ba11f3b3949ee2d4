#!/usr/bin/env python3
"""Reads an LCM log (lcm-logger's format) of a dry-run and checks every joint between two
layers from what the simulated machines said they did, without ccbuild's code: the paths
they were sent (job and path-chunk messages) placed at the times their DONE messages say
each job started, up to where a job stopped on a fault. A piece end laid on another (the
same wall, within 2 cm) must be covered between the material's minimum and maximum
interval after it, the maximum waived for a deposit sent on a planned joint.

  check_joints.py LOG --min 30 --max 200 [--expect-planned]

Exit 0 when every joint holds (and, with --expect-planned, some deposit was laid on a
planned joint).
"""
import argparse
import struct
import sys

from check_gaps import events

MATCH_M = 0.02
SLACK_S = 1e-3


class Reader:
    """LCM's big-endian encoding, after the 8-byte fingerprint."""

    def __init__(self, payload):
        self.data, self.at = payload, 8

    def take(self, fmt):
        values = struct.unpack_from(">" + fmt, self.data, self.at)
        self.at += struct.calcsize(">" + fmt)
        return values if len(values) > 1 else values[0]

    def string(self):
        n = self.take("i")
        text = self.data[self.at:self.at + n - 1].decode()
        self.at += n
        return text


def job(payload):
    r = Reader(payload)
    r.take("q")  # utime
    machine = r.string()
    job_id, _seq, kind, floor, layer, _nozzle, _start, _duration = r.take("qqbiiidd")
    r.string()  # plan
    r.string()  # detail
    _chunks, _points, on_joint = r.take("iib")
    return machine, job_id, dict(kind=kind, floor=floor, layer=layer, on_joint=bool(on_joint))


def chunk(payload):
    r = Reader(payload)
    r.take("q")
    machine = r.string()
    job_id, _seq, index, _count, n = r.take("qqiii")
    t, x, y = (r.take("%dd" % n) if n else () for _ in range(3))
    r.take("%dd" % (2 * n)) if n else None  # z, heading
    extruding = r.take("%db" % n) if n else ()
    wall = r.take("%dq" % n) if n else ()
    piece = r.take("%di" % n) if n else ()
    as_tuple = lambda v: v if isinstance(v, tuple) else (v,)
    return machine, job_id, index, list(zip(*(as_tuple(v) for v in (t, x, y, extruding, wall, piece))))


def done(payload):
    r = Reader(payload)
    r.take("q")
    machine = r.string()
    job_id, _seq, ok, started, _finished, stopped_at = r.take("qqbddi")
    return machine, job_id, bool(ok), started, stopped_at


def piece_ends(points):
    """(waypoint, wall) at both ends of each extruding run of one wall piece."""
    ends, k = [], 0
    while k + 1 < len(points):
        if not points[k][3]:
            k += 1
            continue
        first = k
        while (k + 1 < len(points) and points[k][3] and points[k][4] == points[first][4]
               and points[k][5] == points[first][5]):
            k += 1
        ends += [(first, points[first][4]), (k, points[first][4])]
    return ends


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("log")
    ap.add_argument("--min", type=float, required=True)
    ap.add_argument("--max", type=float, required=True)
    ap.add_argument("--expect-planned", action="store_true")
    a = ap.parse_args()
    jobs, chunks, dones = {}, {}, {}
    for channel, payload in events(a.log):
        if channel.startswith("CCBUILD_JOB_"):
            machine, job_id, info = job(payload)
            jobs[(machine, job_id)] = info
        elif channel.startswith("CCBUILD_PATH_"):
            machine, job_id, index, points = chunk(payload)
            chunks.setdefault((machine, job_id), {})[index] = points
        elif channel.startswith("CCBUILD_DONE_"):
            machine, job_id, ok, started, stopped_at = done(payload)
            dones.setdefault((machine, job_id), (ok, started, stopped_at))
    laid = {}  # (floor, layer) -> [(wall, x, y, t)]
    deposits = sorted(((d[1], key) for key, d in dones.items()
                       if key in jobs and jobs[key]["kind"] == 1), key=lambda p: p[0])
    checked = planned = 0
    worst = None
    for started, key in deposits:
        ok, started, stopped_at = dones[key]
        info = jobs[key]
        points = [p for i in sorted(chunks.get(key, {})) for p in chunks[key][i]]
        mine = [(wall, points[k][1], points[k][2], started + points[k][0])
                for k, wall in piece_ends(points) if ok or k <= stopped_at]
        for wall, x, y, t in mine:
            for bw, bx, by, bt in laid.get((info["floor"], info["layer"] - 1), []):
                if bw != wall or abs(bx - x) > MATCH_M or abs(by - y) > MATCH_M:
                    continue
                interval = t - bt
                checked += 1
                planned += info["on_joint"]
                too_late = interval > a.max + SLACK_S and not info["on_joint"]
                if interval < a.min - SLACK_S or too_late:
                    print("check_joints: %s job %d, floor %d layer %d, wall %d at (%.3f, %.3f) m: "
                          "covered %.1f s after it was laid, outside %.0f-%.0f s%s" % (
                              key[0], key[1], info["floor"], info["layer"], wall, x, y,
                              interval, a.min, a.max,
                              " (on a planned joint)" if info["on_joint"] else ""))
                    return 1
                if not info["on_joint"] and (worst is None or interval > worst):
                    worst = interval
        laid.setdefault((info["floor"], info["layer"]), []).extend(mine)
    print("check_joints: %d joints from %d deposits, %d on planned joints; the others covered "
          "%.0f-%.0f s after they were laid (the longest %.1f s)" % (
              checked, len(deposits), planned, a.min, a.max, worst or 0.0))
    if checked == 0:
        print("check_joints: no joint found in the log")
        return 1
    if a.expect_planned and planned == 0:
        print("check_joints: no deposit was laid on a planned joint")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
