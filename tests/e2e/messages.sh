#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# IR messages (nqc -msg: F7 n) and the LEGO remote's commands (nqc -remote: D2 lo hi, spec p. 61), checked by
# polling source 15 (message), 8 (program slot) and variables, and by the motors and sound in the trace.
. "$E2E_DIR/lib.sh"
T="$WORK/tty"
start_sim --tty "$T" --speed 20

nqc_on "$T" -msg 7 || fail "-msg"
expect "$(poll "$T" 15 0)" 7 "message after nqc -msg 7"

# Two messages in a row from the PC, nothing in between (each nqc run sends F7): both are taken, as on firm0328
# (reference-firmware.md), and a program waiting for the second one sees it.
nqc_on "$T" -TRCX2 -d -pgm 5 "$E2E_DIR/two_messages.nqc" -run >/dev/null || fail "download two_messages"
nqc_on "$T" -msg 42 || fail "-msg 42"
nqc_on "$T" -msg 200 || fail "-msg 200"
wait_poll "$T" 0 0 2 "the program waiting for message 200"
expect "$(poll "$T" 15 0)" 200 "message after nqc -msg 42, nqc -msg 200"
nqc_on "$T" -pgm 1 >/dev/null || fail "back to slot 1"

# PB message 2 (high byte 02). nqc sends no ping before -remote: the polls in between end the repeat.
nqc_on "$T" -remote 0200 1 || fail "-remote message"
expect "$(poll "$T" 15 0)" 2 "message after the remote's message 2"

# Program 3 (low byte 08): selects slot 3 and starts its task 0.
nqc_on "$T" -TRCX2 -d -pgm 3 "$E2E_DIR/slot.nqc" -pgm 1 >/dev/null || fail "download to slot 3"
expect "$(poll "$T" 8 0)" 0 "slot 1 selected again"
nqc_on "$T" -remote 0008 1 || fail "-remote program 3"
expect "$(poll "$T" 8 0)" 2 "slot after the remote's program 3"
wait_poll "$T" 0 5 77 "program 3 started by the remote"

# Motor A forwards is held (repeated packets are repeats), released by remote 0 after another command.
nqc_on "$T" -remote 0800 3 || fail "-remote motor A"
sleep 0.3
[ -n "$(traced '"motor":"A","dir":"fwd","level":7')" ] || fail "motor A not forward"
nqc_on "$T" -raw 10 >/dev/null
nqc_on "$T" -remote 0000 1 || fail "-remote 0"
sleep 0.3
[ "$(grep -F '"motor":"A"' "$TRACE" | tail -n 1 | grep -c '"dir":"brake"')" = 1 ] ||
    fail "motor A not braked on release (spec p. 98)"

# The sound button: system sound 1, beep-beep at 996 Hz, 160 ms per beep as firm0328 plays it.
nqc_on "$T" -raw 10 >/dev/null
nqc_on "$T" -remote 0080 1 || fail "-remote sound"
sleep 0.5
[ -n "$(traced '"sound":996,"ms":160')" ] || fail "no beep"

# Stop program & motors (low byte 40): a program counting for ever stops counting.
nqc_on "$T" -TRCX2 -d -pgm 4 "$E2E_DIR/forever.nqc" -run >/dev/null || fail "download forever"
sleep 0.2
a=$(poll "$T" 0 0)
nqc_on "$T" -remote 0040 1 || fail "-remote stop"
b=$(poll "$T" 0 0)
[ "$a" != "$b" ] || fail "the counter was not running ($a)"
c=$(poll "$T" 0 0)
sleep 0.3
expect "$(poll "$T" 0 0)" "$c" "counter stopped by the remote"
