#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# `make bench`: rcxsim --world --fast with one robot - the Roverbot following the test pad's oval with the line
# follower of tests/world - in simulated seconds per wall-clock second (issue 22's goal: at least 2 000 x real time;
# without a world, rcxsim.sh's figure). The physics step is 1 ms, like the bricks'. The figure is per second of CPU
# time (the shell's `times` for the child), which other work on the machine does not change; the wall clock's is
# given beside it.
set -e
sim="$1/rcxsim"
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
nqc -TRCX2 -O"$work/lf.rcx" "$here/../world/linefollow.nqc"
printf '0 button run down\n50 button run up\n' >"$work/run"
seconds=600
times >"$work/before"
t0=$(date +%s.%N)
"$sim" --world testpad --fast --load "$work/lf.rcx" --script "$work/run" --duration $((seconds * 1000))
times >"$work/times"
cpu=$(tail -n 1 "$work/times")
t1=$(date +%s.%N)
echo "$t0 $t1 $seconds $cpu" | sed 's/\([0-9]*\)m\([0-9.]*\)s/\1 \2/g' | awk '{ w = $2 - $1; c = $4 * 60 + $5 + $6 * 60 + $7
    printf "rcxsim --world testpad --fast, one robot following the line: %d simulated s in %.2f s of CPU (%.2f s on the clock) = %.0f x real time (goal: 2 000)\n", $3, c, w, $3 / c }'
