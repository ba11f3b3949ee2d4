#!/usr/bin/env bash
# A study on a one-node Slurm cluster started here, from Debian's packages (munge,
# slurmctld, slurmd), with a generated slurm.conf (ports of its own on localhost, state in
# a temporary folder); the same study run locally. One array task is cancelled while it
# runs: `collect` must list its variant with the task's state and log, `collect
# --resubmit --wait` must run it alone, and then the results must be the same bytes as the
# local run's. Another task's variant is killed with SIGKILL while it schedules (a crash,
# as the kernel's out-of-memory killer would end it): `collect` must list it as failed with
# the signal and its log, and resubmit it alone with the cancelled one. Exit 77 (skipped) where the Slurm packages are missing or not root.
# Usage: slurm_study_check.sh CCBUILD STUDY
set -euo pipefail
ccbuild=$(realpath "$1") study=$(realpath "$2")
for tool in munged slurmctld slurmd sbatch squeue scancel scontrol; do
  if ! command -v "$tool" >/dev/null; then
    echo "SKIP: $tool is not installed (scripts/install-deps.sh installs munge, slurmctld, slurmd, slurm-client)"
    exit 77
  fi
done
if [ "$(id -u)" -ne 0 ]; then
  echo "SKIP: a one-node Slurm cluster needs root here (slurmd runs the jobs as their user)"
  exit 77
fi
work=$(mktemp -d /tmp/ccbuild-slurm.XXXXXX)
export SLURM_CONF=$work/slurm.conf
stop() {
  scontrol shutdown >/dev/null 2>&1 || true
  sleep 1
  munged -s --socket="$work/munge/munge.sock" >/dev/null 2>&1 || true
  pkill -f "slurmd -f $work/slurm.conf" >/dev/null 2>&1 || true
  pkill -f "slurmctld -f $work/slurm.conf" >/dev/null 2>&1 || true
  rm -rf "$work"
}
trap stop EXIT
mkdir -p "$work"/{munge,state,spool,log}
chmod 700 "$work/munge"
head -c 1024 /dev/urandom > "$work/munge/munge.key"
chmod 400 "$work/munge/munge.key"
munged -f --key-file="$work/munge/munge.key" --socket="$work/munge/munge.sock" \
  --pid-file="$work/munge/munged.pid" --log-file="$work/munge/munged.log" --seed-file="$work/munge/seed"
# Two free ports on localhost for the controller and the node.
read -r ctld_port node_port < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')
# The node as slurmd sees this machine (CPUs, memory), under a name of its own.
node=$(slurmd -C | head -1 | sed -e 's/^NodeName=[^ ]*/NodeName=ccnode NodeAddr=127.0.0.1/' -e 's/ UpTime=.*//')
cat > "$SLURM_CONF" <<CONF
ClusterName=ccbuildtest
SlurmctldHost=$(hostname)(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$node_port
AuthType=auth/munge
AuthInfo=socket=$work/munge/munge.sock
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
$node State=UNKNOWN
PartitionName=ccbuild Nodes=ccnode Default=YES MaxTime=INFINITE State=UP
CONF
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF" -N ccnode
for _ in $(seq 1 30); do
  sinfo -h -o %T 2>/dev/null | grep -q idle && break
  sleep 1
done
sinfo -h -o %T | grep -q idle || { echo "the test cluster's node did not come up"; cat "$work"/log/*.log; exit 1; }
echo "slurm_study_check: one-node cluster up (controller port $ctld_port, node port $node_port)"

# The study here, two at once.
"$ccbuild" study "$study" -o "$work/local" --jobs 2 >"$work/local.txt" 2>&1 || { cat "$work/local.txt"; exit 1; }
# The same study as an array of one variant per task, two at a time; task 10 cancelled
# before it runs.
"$ccbuild" study "$study" -o "$work/slurm" --slurm --array-max 2 --submit --partition ccbuild \
  --time 30 | tee "$work/submit.txt"
job=$(sed -n 's/^submitted job \([0-9]*\).*/\1/p' "$work/submit.txt")
[ -n "$job" ] || { echo "no job id printed"; exit 1; }
grep -q -- "--array=0-11%2" "$work/slurm/slurm/study.sbatch"
# Variant v0006 (task 5) crashes: its `ccbuild schedule` killed while it runs.
crashed=no
# Only its `schedule` (its output followed by --force): the variant's `report` names the
# same file, and killing that instead leaves a feasible variant. Only this test's (its
# folder): another study test running beside it has a v0006 and a v0011 too (a local
# study's variant held stopped here hung Study.ALocalStudyKilledPartWayResumes).
for _ in $(seq 1 3000); do
  if pkill -KILL -f -- "$work/slurm/variants/v0006/schedule[.]json --force"; then crashed=yes; break; fi
  sleep 0.05
done
[ "$crashed" = yes ] || { echo "variant v0006 never ran"; exit 1; }
# Cancelled while it runs (Slurm keeps no record of a task cancelled before it starts).
# Its `schedule` is held stopped first: a variant takes about a second, and a task seen
# RUNNING by squeue had finished before scancel reached it in a CI run.
held=no
for _ in $(seq 1 3000); do
  if pkill -STOP -f -- "$work/slurm/variants/v0011/schedule[.]json --force"; then held=yes; break; fi
  sleep 0.05
done
[ "$held" = yes ] || { echo "variant v0011 never ran"; exit 1; }
[ "$(squeue -h -j "${job}_10" -o %T 2>/dev/null)" = RUNNING ] ||
  { echo "task ${job}_10 is not running while its variant is held"; squeue; exit 1; }
# Slurm sends SIGCONT and SIGTERM to the task's processes, then SIGKILL after KillWait.
scancel "${job}_10"
rc=0
"$ccbuild" study collect "$work/slurm" --wait > "$work/collect1.txt" 2>&1 || rc=$?
cat "$work/collect1.txt"
[ "$rc" -eq 1 ] || { echo "collect with a cancelled task exited $rc, expected 1"; exit 1; }
grep -Eq "^  v0011 missing.*Slurm task ${job}_10 CANCELLED, log .*/slurm/${job}_10.out" "$work/collect1.txt" ||
  { echo "the cancelled task's variant is not listed with its state and log"; exit 1; }
grep -Eq "^  v0006 failed: killed by signal 9 \(Killed\); log .*/variants/v0006/log.txt; Slurm task ${job}_5 [A-Z]+, log .*/slurm/${job}_5.out" "$work/collect1.txt" ||
  { echo "the crashed variant is not listed as failed with its signal and logs"; exit 1; }
"$ccbuild" study collect "$work/slurm" --resubmit --wait > "$work/collect2.txt" 2>&1 || { cat "$work/collect2.txt"; exit 1; }
cat "$work/collect2.txt"
grep -Eq "^resubmitted 2 variant\(s\) as job" "$work/collect2.txt" || { echo "not resubmitted alone"; exit 1; }
grep -q -- "--array=5,10$" "$work/slurm/slurm/resubmit-1.sbatch"
[ -s "$work/slurm/slurm/${job}_0.out" ] || { echo "no log of array task ${job}_0"; ls "$work/slurm/slurm"; exit 1; }
for f in results.csv results.json results.html; do
  cmp "$work/local/$f" "$work/slurm/$f" || { echo "$f differs between the local run and Slurm"; exit 1; }
done
echo "slurm_study_check: 12 variants on Slurm (one crashed, one cancelled, both resubmitted alone) give the local run's bytes"
