#!/bin/sh
# `make run`: the virtual RCX on a pseudo-terminal, a sample program downloaded and started by the real nqc, and
# the trace (JSON lines: motors, sound, LCD, IR bytes) on the terminal for a few seconds.
# Usage: sh host_sim/demo.sh BUILD_DIR (the host build, with rcxsim in it)
set -eu
build="${1:-build/host}"
here=$(cd "$(dirname "$0")" && pwd)
sim="$build/rcxsim"
[ -x "$sim" ] || { echo "demo: $sim not built (make host)" >&2; exit 1; }
command -v nqc >/dev/null || { echo "demo: nqc not installed (apt-get install nqc)" >&2; exit 1; }
work=$(mktemp -d)
pid=""
cleanup() {
    [ -z "$pid" ] || { kill "$pid" 2>/dev/null || true; wait "$pid" 2>/dev/null || true; }
    rm -rf "$work"
}
trap cleanup EXIT
trap 'exit 1' INT TERM

echo "== rcxsim --tty $work/rcx --trace - (real time)"
"$sim" --tty "$work/rcx" --trace - &
pid=$!
n=0
while [ ! -e "$work/rcx" ]; do
    n=$((n + 1))
    [ $n -lt 100 ] || { echo "demo: rcxsim did not start" >&2; exit 1; }
    sleep 0.05
done
echo "== nqc -S$work/rcx -TRCX2 -d demo.nqc -run"
nqc -S"$work/rcx" -TRCX2 -d "$here/demo.nqc" -run
echo "== nqc -S$work/rcx -raw 120000 (poll variable 0, laps, as it counts)"
nqc -S"$work/rcx" -raw 120000
sleep 4
echo "== nqc -S$work/rcx -raw 120000"
nqc -S"$work/rcx" -raw 120000
sleep 1
echo "== done"
