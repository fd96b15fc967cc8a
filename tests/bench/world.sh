#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# `make bench`: rcxsim --world --fast with one robot - the Roverbot following the test pad's oval with the line
# follower of tests/world, and the bumper car in the arena - in simulated seconds per second (issue 22's goal: at
# least 2 000 x real time; without a world, rcxsim.sh's figure). The physics step is 1 ms, like the bricks'. The figure is per second of CPU time (the
# shell's `times` for its children, before and after), which other work on the machine changes less than the clock's,
# given beside it.
set -e
sim="$1/rcxsim"
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
nqc -TRCX2 -O"$work/lf.rcx" "$here/../world/linefollow.nqc"
printf '0 button run down\n50 button run up\n' >"$work/run"
nqc -TRCX2 -O"$work/bumper.rcx" "$here/../world/bumper.nqc"
seconds=1800 # half an hour: `times` counts in hundredths
# run SCENE PROGRAM WHAT: one figure
run() {
    times >"$work/before"
    t0=$(date +%s.%N)
    "$sim" --world "$1" --fast --load "$work/$2.rcx" --script "$work/run" --duration $((seconds * 1000))
    t1=$(date +%s.%N)
    times >"$work/after"
    # The second line of `times`: children's user and system time, as 0m0.28s 0m0.01s
    cpu="$(tail -n 1 "$work/before") $(tail -n 1 "$work/after")"
    echo "$t0 $t1 $seconds $cpu" | sed 's/\([0-9]*\)m\([0-9.]*\)s/\1 \2/g' | awk -v what="$3" '{
        w = $2 - $1; c = ($8 - $4) * 60 + $9 - $5 + ($10 - $6) * 60 + $11 - $7
        printf "rcxsim --world --fast, %s: %d simulated s in %.2f s of CPU", what, $3, c
        printf " (%.2f s on the clock) = %.0f x real time (goal: 2 000)\n", w, $3 / c }'
}
run testpad lf "testpad, one robot following the line"
run arena bumper "arena, a bumper car among walls and obstacles"
