#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# The virtual RCX without a host tool: an nqc image preloaded with --load, started by an IR packet from the script
# (71 00, StartTask 0), a sensor value changed by the script, as fast as possible, and the trace of what followed.
. "$E2E_DIR/lib.sh"
"$NQC" -TRCX2 -O"$WORK/sensor.rcx" "$E2E_DIR/sensor.nqc" || fail "nqc"
S="$WORK/script"
{
    echo "# start task 0, then darken input 1 at 2 s"
    echo "500 ir $(frame 71 00)"
    echo "2000 sensor 1 raw 300"
    echo "2000 battery 7500"
    echo "3000 quit"
} >"$S"
start=$(date +%s)
timeout 60 "$RCXSIM" --fast --load "$WORK/sensor.rcx:2" --script "$S" --trace "$TRACE" || fail "rcxsim failed"
[ $(($(date +%s) - start)) -lt 30 ] || fail "--fast was slow"
t_tone=$(grep -F '"sound":880' "$TRACE" | sed 's/.*"from":\([0-9]*\).*/\1/')
[ -n "$t_tone" ] || fail "no 880 Hz tone"
[ "$t_tone" -ge 2000 ] && [ "$t_tone" -lt 2100 ] || fail "tone at $t_tone ms, expected right after 2000"
[ -n "$(traced '"motor":"B","dir":"fwd"')" ] || fail "motor B not on"
[ -n "$(traced '"ir":"55ff008e718e71"')" ] || fail "StartTask not acknowledged"
[ -n "$(traced '"prog":"2"')" ] || fail "slot 2 not shown"
expect "$(tail -n 1 "$TRACE")" '{"t":3000,"end":"quit"}' "last trace line"
