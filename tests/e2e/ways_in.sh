#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# rcxsim says on its standard error how each brick can be reached (issue 23 §4): one line for each --tty tower (the
# TCP ways in are checked in tests/net), and, with no way in at all, that nothing can reach the brick.
. "$E2E_DIR/lib.sh"
T0="$WORK/tty0"
T1="$WORK/tty1"
start_sim --fast --bricks 2 --tty "$T0" --tty "$T1"
n=0
until [ "$(grep -c 'IR tower' "$WORK/sim.err")" = 2 ]; do
    n=$((n + 1))
    [ $n -lt 100 ] || fail "no line for each tower: $(cat "$WORK/sim.err")"
    sleep 0.05
done
grep -qx "rcxsim: IR tower of brick 0 at $T0 (tty)" "$WORK/sim.err" || fail "brick 0's tower: $(cat "$WORK/sim.err")"
grep -qx "rcxsim: IR tower of brick 1 at $T1 (tty)" "$WORK/sim.err" || fail "brick 1's tower: $(cat "$WORK/sim.err")"
stop_sim

# Nothing at all: it runs (a program loaded with --load may still run for the trace), and says why nobody answers.
start_sim --fast
n=0
until grep -q 'nothing can reach the brick' "$WORK/sim.err"; do
    n=$((n + 1))
    [ $n -lt 100 ] || fail "rcxsim without a way in said nothing: $(cat "$WORK/sim.err")"
    sleep 0.05
done
[ "$(wc -l <"$WORK/sim.err")" = 1 ] || fail "more than one line: $(cat "$WORK/sim.err")"
grep -q -- '--tty.*--tcp.*--panel.*rcxsim --help' "$WORK/sim.err" || fail "no hint: $(cat "$WORK/sim.err")"
kill -0 "$SIM_PID" 2>/dev/null || fail "rcxsim without a way in exited"
stop_sim

# A run with an end (--duration) or with inputs (--script) is no mistake: nothing said.
printf '5 button run down\n' >"$WORK/s"
"$RCXSIM" --fast --duration 100 >"$WORK/out" 2>&1 || fail "a timed run failed: $(cat "$WORK/out")"
"$RCXSIM" --fast --script "$WORK/s" --duration 100 >>"$WORK/out" 2>&1 || fail "a scripted run failed"
[ ! -s "$WORK/out" ] || fail "a timed or scripted run printed: $(cat "$WORK/out")"
