#!/usr/bin/env bash
# Installs, with apt, every Debian 12 package ccbuild needs to build, test and run.
# Idempotent: packages already present are left alone, and apt is not touched at all
# when nothing is missing. Must run as root (or via sudo) when something is missing.
set -euo pipefail

packages=(
  cmake g++ make pkg-config
  liblcm-dev liblcm-bin libglib2.0-dev
  libeigen3-dev libboost-dev   # Boost.Geometry (header-only): walls as beads
  libompl-dev libboost-serialization-dev libboost-filesystem-dev libboost-system-dev libode-dev
  liburdfdom-dev libfcl-dev liblemon-dev
  liburdfdom-tools             # check_urdf: the fitted climbing machines' URDFs are fed to it
  libyaml-cpp-dev nlohmann-json3-dev libcli11-dev
  libdxflib-dev libifcplusplus-dev
  libhowardhinnant-date-dev tzdata   # site calendars: time zones and daylight saving
  libsqlite3-dev libgtest-dev libgmock-dev libbenchmark-dev
  iproute2 util-linux
  python3
  libjs-three chromium   # the report inlines three.js; its test opens it in headless Chromium
  # The exports' outside readers: iCalendar (python3-icalendar for Debian's python3, and
  # ical2html on libical); MS Project XML through GNOME Planner's stylesheet (xsltproc).
  python3-icalendar ical2html xsltproc planner-data
  # Design studies on Slurm: the client commands (sbatch, squeue, scancel, sacct), and the
  # daemons the Slurm test starts as a one-node cluster of its own (never the system's).
  slurm-client slurmctld slurmd munge
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${#missing[@]} missing package(s): ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null; then SUDO="sudo"; else
    echo "install-deps: not root and no sudo; run as root: $0" >&2
    exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
# Installed daemons (munge, slurmctld, slurmd) are not started: ccbuild needs their
# binaries only. policy-rc.d says so to invoke-rc.d for the install's duration.
policy=/usr/sbin/policy-rc.d
made_policy=""
if [ ! -e "$policy" ]; then
  printf '#!/bin/sh\nexit 101\n' | $SUDO tee "$policy" >/dev/null
  $SUDO chmod 755 "$policy"
  made_policy=1
fi
status=0
$SUDO apt-get update -q && $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}" || status=$?
[ -n "$made_policy" ] && $SUDO rm -f "$policy"
exit $status
