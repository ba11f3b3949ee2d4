#!/usr/bin/env python3
"""Kill-and-resume bench: the dry-run's orchestrator SIGKILLed at random points and
restarted on the same journal and machine records, seed after seed, counting from the
simulated machines' own records the jobs that were lost or run twice (target: 0 and 0).

  nice -n 10 bench/kill_resume.py                           # 10 seeds, 3 kills each, apartment
  bench/kill_resume.py --ccbuild /work/bin-snapshot/ccbuild --seeds 3 --kills 5
  bench/kill_resume.py config/buildings/house.yaml --seeds 2
  bench/kill_resume.py --first-seed 7 --seeds 1 --kill-after 2.41,6.90,3.12   # one seed again

Run it from the repository's root (the schedule names its inputs relative to it). Needs
root for `unshare -n` (otherwise `unshare -rn`, which needs unprivileged user namespaces).

How it works:
- BUILDING is scheduled once (`ccbuild schedule BUILDING -o FILE`; a schedule JSON is
  used as it is), so no restart plans again.
- A reference dry-run, never killed, gives the run's duration D and the set of job ids
  (from its machines' records).
- For each seed: a fresh state folder and journal. The k-th of K kills falls at a random
  point (seeded) of the k-th of K equal parts of D, counted in running time summed over
  the runs so far; the dispatcher (`ccbuild dry-run`, only it) gets SIGKILL there. After
  each kill the machines (`ccbuild-sim`) must stop on their own within --grace seconds:
  any process left in the run's network namespace, or any naming the seed's state folder,
  is a finding (reported, then killed by its pid). The dry-run is then started again on
  the same --journal and --state-dir, until a run ends on its own.
- Then, from the machines' records (`<state-dir>/<machine>.state`, one line per job run,
  the job id first): "twice" counts the runs beyond the first of any job id; "lost" counts
  the reference's job ids no machine ran. The final run's summary ("N of M jobs
  executed") and the journal must agree with them.
- Every run is in a network namespace of its own (lo up, multicast on, 224.0.0.0/4 on
  lo), as tests/tools/dry_run_kill.sh does.

Output: one line per seed on stdout (kills made, the jobs in the records after each kill,
runs, jobs, twice, lost, wall time), then a total line. Progress on stderr. Exit 0 when
no job was lost or run twice over all seeds and nothing else went wrong (a leftover
process, a run that hung or ended non-zero on its own, a record line torn or a summary
or journal disagreeing); 1 otherwise; 2 for bad usage or a set-up that failed (schedule,
reference run).

Arguments after `--` go to every `ccbuild dry-run` (e.g. `-- --inject drop=0.05`); the
reference run gets them too, with the first seed. Faults that add recovery jobs (clog,
pin) make the job set depend on the seed: the id check is then only as good as the
reference."""

import argparse
import os
import random
import re
import shutil
import signal
import sqlite3
import subprocess
import sys
import tempfile
import time

NETNS_SETUP = ("ip link set lo up && ip link set lo multicast on && "
               "ip route add 224.0.0.0/4 dev lo && exec \"$@\"")
SUMMARY = re.compile(r"^\S.*: (\d+) of (\d+) jobs executed on (\d+) machine", re.M)


def progress(message):
    print(f"kill_resume: {message}", file=sys.stderr, flush=True)


def netns_prefix():
    return ["unshare", "-n"] if os.geteuid() == 0 else ["unshare", "-rn"]


def net_namespace(pid):
    try:
        return os.readlink(f"/proc/{pid}/ns/net")
    except OSError:
        return None


def processes_left(namespace, folder):
    """Processes (not zombies) in the network namespace, or whose command line names the
    folder: {pid: command line}."""
    found = {}
    me = os.getpid()
    for entry in os.listdir("/proc"):
        if not entry.isdigit() or int(entry) == me:
            continue
        pid = int(entry)
        try:
            with open(f"/proc/{pid}/stat") as f:
                if f.read().rsplit(")", 1)[1].split()[0] == "Z":
                    continue
            with open(f"/proc/{pid}/cmdline", "rb") as f:
                command = f.read().replace(b"\0", b" ").decode(errors="replace").strip()
        except OSError:
            continue
        if (namespace and net_namespace(pid) == namespace) or folder in command:
            found[pid] = command
    return found


def read_records(state_dir):
    """Job ids in the machines' records, in file order, and the lines that are not one
    job's record (torn or malformed)."""
    ids, bad = [], []
    if not os.path.isdir(state_dir):
        return ids, bad
    for name in sorted(os.listdir(state_dir)):
        if not name.endswith(".state"):
            continue
        with open(os.path.join(state_dir, name), "rb") as f:
            data = f.read()
        lines = data.split(b"\n")
        if lines and lines[-1] == b"":
            lines.pop()
        elif lines:
            bad.append(f"{name}: last line not ended: {lines[-1][:80]!r}")
        for number, line in enumerate(lines, 1):
            fields = line.split()
            if len(fields) != 7 or not fields[0].isdigit():
                bad.append(f"{name}:{number}: {line[:80]!r}")
                continue
            ids.append(int(fields[0]))
    return ids, bad


def journal_states(journal):
    """{job_id: state} of the journal's job_state table ({} when there is none yet)."""
    if not os.path.exists(journal):
        return {}
    try:
        db = sqlite3.connect(f"file:{journal}?mode=ro", uri=True)
        try:
            return dict(db.execute("SELECT job_id, state FROM job_state"))
        finally:
            db.close()
    except sqlite3.Error:
        return {}


def journal_not_done(journal):
    """Rows of the journal whose job is not done: [(job_id, state)]."""
    try:
        db = sqlite3.connect(f"file:{journal}?mode=ro", uri=True)
        try:
            return db.execute(
                "SELECT job_id, state FROM job_state WHERE state != 'done'").fetchall()
        finally:
            db.close()
    except sqlite3.Error as e:
        return [(-1, f"journal unreadable: {e}")]


class Runner:
    def __init__(self, args, schedule, root):
        self.args = args
        self.schedule = schedule
        self.root = root
        self.current = None  # the dry-run running now, killed on an interrupt

    def start(self, folder, seed, attempt):
        """Starts one dry-run in a network namespace of its own. Its pid becomes the
        orchestrator's (nice, unshare and sh all exec)."""
        tmp = os.path.join(folder, "tmp")
        os.makedirs(tmp, exist_ok=True)
        command = netns_prefix() + ["sh", "-c", NETNS_SETUP, "sh", self.args.ccbuild,
                                    "dry-run", self.schedule,
                                    "--state-dir", os.path.join(folder, "state"),
                                    "--journal", os.path.join(folder, "journal.sqlite"),
                                    "--seed", str(seed)]
        if self.args.speed is not None:
            command += ["--speed", repr(self.args.speed)]
        command += self.args.dry_run_args
        env = dict(os.environ, TMPDIR=tmp)
        out = open(os.path.join(folder, f"run{attempt}.out"), "wb")
        err = open(os.path.join(folder, f"run{attempt}.err"), "wb")
        try:
            self.current = subprocess.Popen(command, stdout=out, stderr=err, env=env,
                                            stdin=subprocess.DEVNULL)
        finally:
            out.close()
            err.close()
        return self.current

    def stop_current(self):
        if self.current and self.current.poll() is None:
            try:
                os.kill(self.current.pid, signal.SIGKILL)
                self.current.wait()
            except OSError:
                pass


def wait_machines_gone(namespace, folder, grace):
    """Waits up to grace seconds for every process of the killed run to end. Returns
    (seconds it took, {pid: command} still running)."""
    began = time.monotonic()
    while True:
        left = processes_left(namespace, folder)
        waited = time.monotonic() - began
        if not left or waited >= grace:
            return waited, left
        time.sleep(0.05)


def run_seed(runner, seed, reference_ids, duration, args):
    """One seed: kills, restarts, counts. Returns a dict of what was measured."""
    folder = os.path.join(runner.root, f"seed-{seed}")
    os.makedirs(folder)
    rng = random.Random(seed)
    k = args.kills
    if args.kill_after is not None:
        delays = list(args.kill_after)
        targets = None
    else:
        # The k-th kill in the k-th of K equal parts of the run, in running time summed
        # over the runs so far (a restart resumes, so the run shortens).
        targets = [duration * (i + rng.random()) / k for i in range(k)]
        delays = None
    result = dict(seed=seed, kills=0, at_kill=[], delays=[], runs=0, total=None,
                  twice=0, lost=0, problems=[], stop_s=[], ahead=[], open=[])
    began = time.monotonic()
    ran_for = 0.0
    attempt = 0
    while True:
        attempt += 1
        index = attempt - 1
        if delays is not None:
            delay = delays[index] if index < len(delays) else None
        else:
            delay = (max(args.min_delay, targets[index] - ran_for)
                     if index < len(targets) else None)
        process = runner.start(folder, seed, attempt)
        started = time.monotonic()
        limit = delay if delay is not None else args.run_timeout
        namespace = None
        # The namespace is known once unshare has run; read it while the run lives.
        while process.poll() is None and time.monotonic() - started < limit:
            if namespace is None:
                ns = net_namespace(process.pid)
                if ns and ns != net_namespace(os.getpid()):
                    namespace = ns
            time.sleep(min(0.02, max(0.0, limit - (time.monotonic() - started))))
        if process.poll() is None:
            comm = ""
            try:
                with open(f"/proc/{process.pid}/comm") as f:
                    comm = f.read().strip()
            except OSError:
                pass
            # The machines running at the kill (the check below must see them go).
            machines = len([c for p, c in processes_left(namespace, folder).items()
                            if p != process.pid and "ccbuild-sim" in c])
            os.kill(process.pid, signal.SIGKILL)
            process.wait()
            elapsed = time.monotonic() - started
            ran_for += elapsed
            hung = delay is None
            if not hung and comm != os.path.basename(args.ccbuild)[:15]:  # comm: 15 chars
                result["problems"].append(
                    f"run {attempt}: killed at {elapsed:.2f} s before the dispatcher "
                    f"started (process '{comm}')")
            waited, left = wait_machines_gone(namespace, folder, args.grace)
            result["stop_s"].append(waited)
            if left:
                result["problems"].append(
                    f"run {attempt}: {len(left)} process(es) still running {args.grace:g} s "
                    f"after the kill: " + "; ".join(f"{p} {c[:120]}" for p, c in left.items()))
                for pid in left:
                    try:
                        os.kill(pid, signal.SIGKILL)
                    except OSError:
                        pass
                wait_machines_gone(namespace, folder, 5.0)
            ids, _ = read_records(os.path.join(folder, "state"))
            # What the kill cut through: jobs a machine had run that the journal did not
            # yet hold as done (the restart must not run them again), and jobs sent or
            # acknowledged that no machine had finished (the restart must not lose them).
            states = journal_states(os.path.join(folder, "journal.sqlite"))
            ahead = len([j for j in set(ids) if states.get(j) != "done"])
            open_jobs = len([j for j, st in states.items()
                             if st in ("sent", "acked") and j not in set(ids)])
            result["ahead"].append(ahead)
            result["open"].append(open_jobs)
            if hung:
                result["problems"].append(
                    f"run {attempt}: not ended after {args.run_timeout:g} s (hung?), "
                    f"{len(ids)} jobs in the records")
                progress(f"seed {seed}: run {attempt} hung, killed after {elapsed:.1f} s")
                break
            result["kills"] += 1
            result["delays"].append(elapsed)
            result["at_kill"].append(len(ids))
            progress(f"seed {seed}: run {attempt} killed at {elapsed:.2f} s, {len(ids)} jobs "
                     f"in the records ({ahead} not yet done in the journal, {open_jobs} "
                     f"sent and unfinished); {machines} machine(s) were running, all gone "
                     f"{waited:.2f} s later")
            continue
        elapsed = time.monotonic() - started
        ran_for += elapsed
        code = process.returncode
        waited, left = wait_machines_gone(namespace, folder, args.grace)
        if left:
            result["problems"].append(
                f"run {attempt} (ended {code}): {len(left)} process(es) left: "
                + "; ".join(f"{p} {c[:120]}" for p, c in left.items()))
            for pid in left:
                try:
                    os.kill(pid, signal.SIGKILL)
                except OSError:
                    pass
        progress(f"seed {seed}: run {attempt} ended on its own ({code}) after {elapsed:.2f} s")
        if code != 0:
            result["problems"].append(
                f"run {attempt}: exit {code} without a kill (see run{attempt}.out/.err)")
        with open(os.path.join(folder, f"run{attempt}.out"), errors="replace") as f:
            summary = SUMMARY.search(f.read())
        if summary:
            executed, total = int(summary.group(1)), int(summary.group(2))
            result["total"] = total
            if executed != total:
                result["problems"].append(f"summary: {executed} of {total} jobs executed")
            if total != len(reference_ids):
                result["problems"].append(
                    f"summary: {total} jobs, the reference run had {len(reference_ids)}")
        else:
            result["problems"].append(f"run {attempt}: no 'N of M jobs executed' line")
        break
    result["runs"] = attempt
    ids, bad = read_records(os.path.join(folder, "state"))
    result["problems"] += [f"record: {b}" for b in bad]
    counts = {}
    for job in ids:
        counts[job] = counts.get(job, 0) + 1
    result["twice"] = sum(c - 1 for c in counts.values())
    result["twice_ids"] = sorted(j for j, c in counts.items() if c > 1)
    lost = sorted(set(reference_ids) - set(counts))
    if result["total"] is not None and result["total"] > len(counts):
        # The summary's total counts too: more jobs than any machine ran is a loss even
        # where the reference has fewer ids.
        result["lost"] = max(len(lost), result["total"] - len(counts))
    else:
        result["lost"] = len(lost)
    result["lost_ids"] = lost
    extra = sorted(set(counts) - set(reference_ids))
    if extra:
        result["problems"].append(f"records: {len(extra)} job id(s) not in the reference "
                                  f"run: {extra[:10]}")
    if result["twice_ids"]:
        result["problems"].append(f"run twice: job ids {result['twice_ids'][:20]}")
    if lost:
        result["problems"].append(f"lost: job ids {lost[:20]}")
    not_done = journal_not_done(os.path.join(folder, "journal.sqlite"))
    if not_done:
        result["problems"].append(f"journal: {len(not_done)} job(s) not done: {not_done[:10]}")
    left = os.listdir(os.path.join(folder, "tmp"))
    if left:
        result["problems"].append(f"the runs left {left[:5]} in their temporary folder")
    result["wall_s"] = time.monotonic() - began
    if args.keep:
        shutil.copytree(folder, os.path.join(args.keep, f"seed-{seed}"), dirs_exist_ok=True)
    shutil.rmtree(folder, ignore_errors=True)
    return result


def reference_run(runner, seed):
    """An uninterrupted run: its duration (s) and the job ids its machines ran."""
    folder = os.path.join(runner.root, "reference")
    os.makedirs(folder)
    started = time.monotonic()
    process = runner.start(folder, seed, 1)
    try:
        code = process.wait(timeout=runner.args.run_timeout)
    except subprocess.TimeoutExpired:
        runner.stop_current()
        sys.exit(f"kill_resume: the reference run (never killed) did not end within "
                 f"{runner.args.run_timeout:g} s")
    duration = time.monotonic() - started
    ids, bad = read_records(os.path.join(folder, "state"))
    if code != 0 or bad or len(ids) != len(set(ids)):
        with open(os.path.join(folder, "run1.out"), errors="replace") as f:
            out = f.read()
        with open(os.path.join(folder, "run1.err"), errors="replace") as f:
            err = f.read()
        sys.exit(f"kill_resume: the reference run (never killed) failed: exit {code}, "
                 f"{len(ids)} records, {len(set(ids))} distinct, {len(bad)} malformed\n"
                 f"{out[-2000:]}{err[-2000:]}")
    waited, left = wait_machines_gone(None, folder, runner.args.grace)
    if left:
        progress(f"the reference run left processes: {left}")
    shutil.rmtree(folder, ignore_errors=True)
    return duration, ids


def parse_args(argv):
    if "--" in argv:
        cut = argv.index("--")
        argv, passed = argv[:cut], argv[cut + 1:]
    else:
        passed = []
    parser = argparse.ArgumentParser(
        prog="bench/kill_resume.py", description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("building", nargs="?", default="config/buildings/apartment.yaml",
                        help="building file, or a schedule JSON (default: %(default)s)")
    parser.add_argument("--ccbuild", default="build/ccbuild",
                        help="the ccbuild binary; ccbuild-sim must be beside it "
                             "(default: %(default)s)")
    parser.add_argument("--seeds", type=int, default=10, help="how many seeds (default 10)")
    parser.add_argument("--first-seed", type=int, default=1,
                        help="seeds are FIRST-SEED, FIRST-SEED+1, ... (default 1)")
    parser.add_argument("--kills", type=int, default=3,
                        help="SIGKILLs per seed, spread over the run (default 3)")
    parser.add_argument("--kill-after", type=lambda s: [float(x) for x in s.split(",")],
                        help="instead of drawing them: kill run 1 after T1 s, run 2 after "
                             "T2 s, ... (seconds from each run's start, as the per-seed "
                             "line prints them), to reproduce a seed")
    parser.add_argument("--speed", type=float,
                        help="the dry-run's --speed (default: the dry-run's, 10,000x)")
    parser.add_argument("--grace", type=float, default=5.0,
                        help="seconds the machines have to stop after a kill (default 5)")
    parser.add_argument("--min-delay", type=float, default=0.3,
                        help="no kill sooner than this after a run's start (default 0.3 s)")
    parser.add_argument("--run-timeout", type=float, default=None,
                        help="a run not killed and not ended after this many seconds hung "
                             "(default: 10 x the reference run, at least 120 s)")
    parser.add_argument("--keep", metavar="DIR",
                        help="copy each seed's folder (records, journal, outputs) into DIR")
    parser.add_argument("--schedule-seed", type=int, default=1,
                        help="seed of `ccbuild schedule` (default 1)")
    args = parser.parse_args(argv)
    args.dry_run_args = passed
    if args.seeds < 1 or args.kills < 0 or args.grace < 0 or args.min_delay < 0:
        parser.error("--seeds must be at least 1; --kills, --grace, --min-delay not negative")
    if args.kill_after is not None:
        if any(t <= 0 for t in args.kill_after):
            parser.error("--kill-after: every time must be above 0")
        args.kills = len(args.kill_after)
    for name in ("ccbuild", "building"):
        if not os.path.exists(getattr(args, name)):
            parser.error(f"{getattr(args, name)}: no such file (run from the repository's "
                         f"root, or give --ccbuild)")
    args.ccbuild = os.path.abspath(args.ccbuild)
    if not os.path.exists(os.path.join(os.path.dirname(args.ccbuild), "ccbuild-sim")):
        parser.error(f"no ccbuild-sim beside {args.ccbuild}")
    if args.keep:
        os.makedirs(args.keep, exist_ok=True)
    return args


def main(argv):
    args = parse_args(argv)
    root = tempfile.mkdtemp(prefix="kill_resume.")
    runner = Runner(args, None, root)

    def interrupted(signum, _frame):
        raise KeyboardInterrupt(f"signal {signum}")

    signal.signal(signal.SIGTERM, interrupted)
    signal.signal(signal.SIGHUP, interrupted)
    try:
        return bench(args, runner, root)
    except KeyboardInterrupt:
        progress("interrupted")
        return 130
    finally:
        runner.stop_current()
        shutil.rmtree(root, ignore_errors=True)


def bench(args, runner, root):
    began = time.monotonic()
    if args.building.endswith(".json"):
        schedule = os.path.abspath(args.building)
        progress(f"dry-running the schedule {args.building}")
    else:
        schedule = os.path.join(root, "schedule.json")
        t = time.monotonic()
        done = subprocess.run([args.ccbuild, "schedule", args.building, "-o", schedule,
                               "--seed", str(args.schedule_seed), "--quiet"],
                              capture_output=True, text=True)
        if done.returncode != 0:
            sys.exit(f"kill_resume: ccbuild schedule {args.building} failed "
                     f"({done.returncode}):\n{done.stdout}{done.stderr}")
        progress(f"scheduled {args.building} once in {time.monotonic() - t:.1f} s")
    runner.schedule = schedule
    given_timeout = args.run_timeout
    if given_timeout is None:
        args.run_timeout = 600.0  # the reference run's guard: the dry-run's own --timeout
    duration, reference_ids = reference_run(runner, args.first_seed)
    if given_timeout is None:
        args.run_timeout = max(120.0, 10 * duration)
    progress(f"reference run (never killed): {duration:.2f} s, {len(reference_ids)} jobs")
    print(f"{args.building}: {len(reference_ids)} jobs; an uninterrupted dry-run takes "
          f"{duration:.1f} s; {args.seeds} seed(s), {args.kills} kill(s) each")
    print(f"{'seed':>5} {'kills':>5}  {'jobs in the records at each kill':<32} {'runs':>4} "
          f"{'jobs':>5} {'twice':>5} {'lost':>4} {'wall s':>7}  kill after (s, each run)")
    results = []
    for seed in range(args.first_seed, args.first_seed + args.seeds):
        r = run_seed(runner, seed, reference_ids, duration, args)
        results.append(r)
        at = "/".join(str(n) for n in r["at_kill"]) or "-"
        after = ",".join(f"{d:.2f}" for d in r["delays"]) or "-"
        total = r["total"] if r["total"] is not None else "?"
        print(f"{seed:>5} {r['kills']:>5}  {at:<32} {r['runs']:>4} {total:>5} "
              f"{r['twice']:>5} {r['lost']:>4} {r['wall_s']:>7.1f}  {after}", flush=True)
        for p in r["problems"]:
            print(f"      seed {seed}: {p}", flush=True)
    kills = sum(r["kills"] for r in results)
    twice = sum(r["twice"] for r in results)
    lost = sum(r["lost"] for r in results)
    problems = sum(len(r["problems"]) for r in results)
    stops = [s for r in results for s in r["stop_s"]]
    ahead = sum(sum(r["ahead"]) for r in results)
    open_jobs = sum(sum(r["open"]) for r in results)
    cut = sum(1 for r in results for a, o in zip(r["ahead"], r["open"]) if a or o)
    print(f"kills that cut through a job: {cut} of {kills} ({ahead} job(s) run but not yet "
          f"journalled done, {open_jobs} sent and unfinished, at the kills)")
    print(f"total: {len(results)} seeds, {kills} kills, {sum(r['runs'] for r in results)} "
          f"runs; run twice {twice}, lost {lost}; other problems {problems}; machines gone "
          f"after a kill within {max(stops) if stops else 0:.2f} s (worst); "
          f"{time.monotonic() - began:.0f} s in all")
    return 0 if twice == 0 and lost == 0 and problems == 0 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
