#!/usr/bin/env python3
"""Reads an LCM log (lcm-logger's format) of a dry-run and measures, from the simulated
machines' own status messages alone (not the dispatcher's watchdog), how close
neighbouring gantries came on the rails. Each machine's rail position is interpolated
between its statuses, and gaps are taken at every status time where both tracks reach.

  check_gaps.py LOG --width 1.5 [--axis x] [--expect-collision] [--expect-paused]

Exit 0 when the smallest gap is at least the width (or, with --expect-collision, when
it is under it); with --expect-paused, every machine's last status must say PAUSED.
"""
import argparse
import bisect
import re
import struct
import sys

SYNC = 0xEDA1DA01
PAUSED = 2


def events(path):
    with open(path, "rb") as f:
        data = f.read()
    at = 0
    while at + 28 <= len(data):
        sync, _num, _stamp, clen, dlen = struct.unpack_from(">IqqII", data, at)
        if sync != SYNC:
            raise SystemExit("%s: no sync word at byte %d" % (path, at))
        at += 28
        channel = data[at:at + clen].decode()
        at += clen
        yield channel, data[at:at + dlen]
        at += dlen


def status(payload):
    """ccbuild_status_t: fingerprint, utime, machine_id, seq, state, current_job_id,
    jobs_done, sim_time_s, x_m, y_m, z_m, heading, pump_on (big-endian, LCM's encoding)."""
    at = 8 + 8
    (n,) = struct.unpack_from(">i", payload, at)
    at += 4
    machine = payload[at:at + n - 1].decode()
    at += n
    seq, state, job, done, t, x, y, z, h = struct.unpack_from(">qbqqddddd", payload, at)
    return machine, state, t, x, y


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("log")
    ap.add_argument("--width", type=float, required=True)
    ap.add_argument("--axis", default="x")
    ap.add_argument("--expect-collision", action="store_true")
    ap.add_argument("--expect-paused", action="store_true")
    a = ap.parse_args()
    tracks, last_state = {}, {}
    for channel, payload in events(a.log):
        if not channel.startswith("CCBUILD_STATUS_"):
            continue
        machine, state, t, x, y = status(payload)
        track = tracks.setdefault(machine, [])
        if not track or t >= track[-1][0]:
            track.append((t, x if a.axis == "x" else y))
        last_state[machine] = state
    names = sorted(tracks, key=lambda m: int(re.sub(r"\D", "", m) or 0))
    if len(names) < 2:
        raise SystemExit("fewer than two machines reported a status")

    def at(track, t):
        times = [p[0] for p in track]
        k = bisect.bisect_left(times, t)
        if k < len(track) and times[k] == t:
            return track[k][1]
        if k == 0 or k == len(track):
            return None
        (t0, r0), (t1, r1) = track[k - 1], track[k]
        return r0 + (r1 - r0) * (t - t0) / (t1 - t0)

    smallest = None
    for left, right in zip(names, names[1:]):
        for t in sorted({p[0] for p in tracks[left]} | {p[0] for p in tracks[right]}):
            a_m, b_m = at(tracks[left], t), at(tracks[right], t)
            if a_m is None or b_m is None:
                continue
            gap = b_m - a_m
            if smallest is None or gap < smallest[0]:
                smallest = (gap, t, left, a_m, right, b_m)
    if smallest is None:
        raise SystemExit("no moment where two neighbours both reported")
    gap, t, left, a_m, right, b_m = smallest
    print("check_gaps: smallest gap %.3f m at %.1f s of machine time (%s at %.3f m, %s at %.3f m); "
          "gantry width %.3f m" % (gap, t, left, a_m, right, b_m, a.width))
    ok = gap < a.width if a.expect_collision else gap >= a.width
    if a.expect_paused:
        unpaused = [m for m in names if last_state.get(m) != PAUSED]
        if unpaused:
            print("check_gaps: not paused at the end: %s" % ", ".join(unpaused))
            ok = False
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
