#!/usr/bin/env bash
# Runs a command in a network namespace of its own, with a loopback that carries LCM's
# multicast (udpm://, ttl=0), so that a dry-run never touches the shared network.
# As root a plain network namespace; otherwise a user namespace with one (needs
# unprivileged user namespaces).
# Usage: scripts/in-netns.sh COMMAND ARGS...
# Example: scripts/in-netns.sh build/ccbuild dry-run config/buildings/house.yaml
set -euo pipefail
if [ $# -eq 0 ]; then
  echo "usage: $0 COMMAND ARGS..." >&2
  exit 2
fi
if [ "$(id -u)" -eq 0 ]; then netns="unshare -n"; else netns="unshare -rn"; fi
exec $netns sh -c 'ip link set lo up && ip link set lo multicast on &&
  ip route add 224.0.0.0/4 dev lo && exec "$@"' sh "$@"
