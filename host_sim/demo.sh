#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# `make run`: the virtual RCX on a pseudo-terminal with its panel in the browser, a sample program downloaded and
# started by the real nqc, and the trace (JSON lines: motors, sound, LCD, IR bytes) on the terminal. The brick
# keeps running for the panel until Ctrl-C. The trace goes to a file while nqc talks, and is shown from its start
# once nqc is done: on one terminal, it would cut into nqc's progress line.
# Usage: sh host_sim/demo.sh BUILD_DIR (the host build, with rcxsim in it); PANEL_PORT (default 8330) for the page
set -eu
build="${1:-build/host}"
here=$(cd "$(dirname "$0")" && pwd)
sim="$build/rcxsim"
[ -x "$sim" ] || { echo "demo: $sim not built (make host)" >&2; exit 1; }
command -v nqc >/dev/null || { echo "demo: nqc not installed (apt-get install nqc)" >&2; exit 1; }
work=$(mktemp -d)
pid=""
tailpid=""
cleanup() {
    [ -z "$pid" ] || { kill "$pid" 2>/dev/null || true; wait "$pid" 2>/dev/null || true; }
    [ -z "$tailpid" ] || { kill "$tailpid" 2>/dev/null || true; wait "$tailpid" 2>/dev/null || true; }
    rm -rf "$work"
}
trap cleanup EXIT
trap 'exit 1' INT TERM

port="${PANEL_PORT:-8330}"
echo "== rcxsim --tty $work/rcx --panel $port --trace $work/trace.jsonl (real time)"
"$sim" --tty "$work/rcx" --panel "$port" --trace "$work/trace.jsonl" &
pid=$!
n=0
while [ ! -e "$work/rcx" ]; do
    n=$((n + 1))
    kill -0 "$pid" 2>/dev/null || { echo "demo: rcxsim did not start (PANEL_PORT=N: another port)" >&2; exit 1; }
    [ $n -lt 100 ] || { echo "demo: rcxsim did not start" >&2; exit 1; }
    sleep 0.05
done
echo "== the panel: open http://127.0.0.1:$port/ in a browser"
echo "== nqc -S$work/rcx -TRCX2 -d demo.nqc -run"
nqc -S"$work/rcx" -TRCX2 -d "$here/demo.nqc" -run
echo "== nqc -S$work/rcx -raw 120000 (poll variable 0, laps, as it counts)"
nqc -S"$work/rcx" -raw 120000
sleep 4
echo "== nqc -S$work/rcx -raw 120000"
nqc -S"$work/rcx" -raw 120000
echo "== the trace from the start; the brick runs on for the panel at http://127.0.0.1:$port/ (press Run there to"
echo "   start the program again); Ctrl-C stops it"
tail -n +1 -f --pid="$pid" "$work/trace.jsonl" &
tailpid=$!
wait "$pid" || true
wait "$tailpid" 2>/dev/null || true
