#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# `make bench`: the virtual RCX in --fast mode - simulated seconds per wall-clock second for ten busy tasks
# (goal: at least 1 000 x real time on one core), at the brick's own speed and at a flat 100 byte codes per ms.
set -e
sim="$1/rcxsim"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
{
    i=1
    while [ $i -lt 10 ]; do echo "int c$i; task t$i() { while (true) c$i++; }"; i=$((i + 1)); done
    printf 'int c0; task main() {'
    i=1
    while [ $i -lt 10 ]; do printf ' start t%d;' $i; i=$((i + 1)); done
    echo ' while (true) c0++; }'
} >"$work/busy10.nqc"
nqc -TRCX2 -O"$work/busy10.rcx" "$work/busy10.nqc"
echo "0 ir 55 ff 00 71 8e 00 ff 71 8e" >"$work/start" # StartTask 0
seconds=600
for rate in brick 100; do
    t0=$(date +%s.%N)
    "$sim" --fast --rate $rate --load "$work/busy10.rcx" --script "$work/start" --duration $((seconds * 1000))
    t1=$(date +%s.%N)
    echo "$t0 $t1 $seconds $rate" | awk '{ w = $2 - $1; printf "rcxsim --fast, 10 busy tasks, --rate %s: %d simulated s in %.2f s = %.0f x real time\n", $4, $3, w, $3 / w }'
done
