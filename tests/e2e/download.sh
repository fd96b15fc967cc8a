#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# nqc -d / -run / -pgm with the real nqc over the pseudo-terminal, for the target named in $1 (RCX2 or RCX, nqc's
# default), then the results read back with poll commands (nqc -raw 12 ...).
. "$E2E_DIR/lib.sh"
flags=""
[ "$1" = RCX2 ] && flags=-TRCX2
T="$WORK/tty"
start_sim --tty "$T" --speed 20

out=$(nqc_on "$T" $flags -d "$E2E_DIR/counter.nqc" 2>&1) || fail "download: $out"
case "$out" in *complete*) ;; *) fail "download said: $out" ;; esac
expect "$(poll "$T" 0 0)" 0 "nothing runs before -run"
nqc_on "$T" -run || fail "-run"
wait_poll "$T" 0 0 60 "total after the loop and the subroutine"
wait_poll "$T" 0 1 10 "loop count"
wait_poll "$T" 0 2 1000 "the second task"

# Another slot: -pgm 3 selects program 3 (source 8 = 2) before downloading, and runs it there.
nqc_on "$T" $flags -d -pgm 3 "$E2E_DIR/slot.nqc" -run >/dev/null || fail "-pgm 3 -d"
expect "$(poll "$T" 8 0)" 2 "selected slot"
wait_poll "$T" 0 5 77 "program 3 ran"
expect "$(poll "$T" 0 0)" 60 "program 1's variables are global"

# What nqc -d sent ended with the download sound: the trace has the brick's sound.
[ -n "$(traced '"sound":')" ] || fail "no sound in the trace"
