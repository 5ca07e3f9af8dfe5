#!/usr/bin/env bash
# Run a command where the only network is loopback, and nothing it starts can outlive it.
#
# Usage: tools/real_hfo/loopback.sh CMD [ARG...]
#   e.g. HFO_DIR=/opt/hfo/HFO tools/real_hfo/loopback.sh python -m sb3_hfo.evaluate e6 --env HFO/RealKeeper-v0
#
# The real HFO is several programs (rcssserver, HFO's trainer, agent2d's players, the agent) talking UDP on a
# few ports; inside this runner they can reach 127.0.0.1 and nothing else, and no other program on the machine
# can reach them. CMD runs in
#   * a private network namespace whose only interface is `lo`, brought up here (`ip link set lo up`);
#   * a private PID namespace with its own /proc: when CMD ends, or this script is killed, the kernel ends every
#     process left inside, so no rcssserver is left behind.
# The environment and the working directory are kept. Without root, a user namespace maps the caller to root
# inside (`unshare --map-root-user`; the kernel must allow unprivileged user namespaces). Needs util-linux's
# `unshare` and iproute2's `ip`. The exit status is CMD's.
set -euo pipefail

if [ $# -eq 0 ] || [ "$1" = -h ] || [ "$1" = --help ]; then
  sed -n '2,/^set -euo/p' "$0" | sed -e '$d' -e 's/^# \{0,1\}//'
  if [ $# -eq 0 ]; then exit 2; else exit 0; fi
fi
for tool in unshare ip; do
  command -v "$tool" >/dev/null || { echo "loopback.sh: $tool not found (util-linux, iproute2)" >&2; exit 127; }
done

as_root=()
[ "$(id -u)" = 0 ] || as_root=(--user --map-root-user)
# bash stays PID 1 of the new namespace: it reaps orphans, and a PID 1 ignores the signals it has no handler for,
# so CMD must not be PID 1 (the `exit` after it keeps bash from exec-ing CMD). --kill-child takes the namespace
# down if unshare itself is killed.
exec unshare "${as_root[@]}" --net --pid --fork --mount-proc --kill-child -- \
  bash -c 'ip link set lo up || exit 125; "$@"; exit $?' loopback.sh "$@"
