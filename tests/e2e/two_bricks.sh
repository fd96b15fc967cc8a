#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# Two bricks in one room, each with its own tower: brick 0's program sends two IR messages (SendPBMessage), brick 1
# receives them (source 15; both go out as F7, as firm0328 sends them: a message is never taken for a repeat); each
# tower talks to its own brick only.
. "$E2E_DIR/lib.sh"
T0="$WORK/tty0"
T1="$WORK/tty1"
start_sim --bricks 2 --tty "$T0" --tty "$T1" --speed 20

nqc_on "$T1" -TRCX2 -d "$E2E_DIR/receiver.nqc" -run >/dev/null || fail "download to brick 1"
nqc_on "$T0" -TRCX2 -d "$E2E_DIR/sender.nqc" >/dev/null || fail "download to brick 0"
expect "$(poll "$T1" 0 1)" 0 "brick 1 did not execute brick 0's download"
nqc_on "$T0" -run || fail "-run brick 0"
# Polling brick 1 while brick 0 sends would collide in the room (each tower hears its own brick only, but the
# bricks hear each other): wait until both messages are out (0.2 s apart, 20 x real time).
sleep 1
wait_poll "$T1" 0 0 9 "first message, seen by brick 1's program"
wait_poll "$T1" 15 0 11 "second message"
expect "$(poll "$T0" 15 0)" 0 "brick 0 does not receive its own messages"
[ -n "$(traced '"brick":0,"ir":"55ff00f708')" ] || fail "brick 0 did not send F7"
[ -z "$(traced '"brick":0,"ir":"55ff00ff00')" ] || fail "brick 0 sent a message as FF"
