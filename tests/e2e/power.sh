#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# PBTurnOff (60) from the room puts the brick in standby (hal_power_off): nothing is answered until On-Off is
# pressed in the script; then the brick answers again with its program memory intact.
. "$E2E_DIR/lib.sh"
"$NQC" -TRCX2 -O"$WORK/slot.rcx" "$E2E_DIR/slot.nqc" || fail "nqc"
S="$WORK/script"
{
    echo "100 ir $(frame 60)"          # turn off: acknowledged (9f), then standby
    echo "1000 ir $(frame 10)"         # unanswered
    echo "2000 button onoff down"
    echo "2100 button onoff up"
    echo "3000 ir $(frame 18)"         # answered (e7)
    echo "3500 ir $(frame 71 00)"      # program memory kept: task 0 starts and sets variable 5
    echo "3800 ir $(frame 12 00 05)"   # poll it: 77 (ed 4d 00)
    echo "4000 quit"
} >"$S"
timeout 60 "$RCXSIM" --fast --load "$WORK/slot.rcx" --script "$S" --trace "$TRACE" || fail "rcxsim failed"
[ -n "$(traced '"ir":"55ff009f609f60"')" ] || fail "PBTurnOff not acknowledged"
[ -n "$(traced '"power":"standby"')" ] || fail "no standby"
[ -z "$(traced '"ir":"55ff00ef10ef10"')" ] || fail "answered in standby"
[ -n "$(traced '"ir":"55ff00e718e718"')" ] || fail "not answered after On-Off"
[ "$(traced '"power":"on"' | wc -l)" -eq 2 ] || fail "power on, off, on expected"
[ -n "$(traced '"ir":"55ff00ed124db200ff3ac5"')" ] || fail "variable 5 is not 77 after the restart"
