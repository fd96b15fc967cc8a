#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# The brick's face through its buttons, scripted (reference-firmware.md, "The brick's face"): View from a program's
# own display goes to the watch, then inputs and outputs (an output shows 0 when off, power + 1 when running); the
# figure walks in 260 ms steps; On-Off plays the key click before standby and the double beep on starting and on waking, and the
# watch starts again from 00:00 (05:30 before).
. "$E2E_DIR/lib.sh"
"$NQC" -TRCX2 -O"$WORK/forever.rcx" "$E2E_DIR/forever.nqc" || fail "nqc"
S="$WORK/script"
press() { echo "$1 button $2 down"; echo "$(($1 + 50)) button $2 up"; }
{
    echo "100 ir $(frame 13 01 02 03)"  # A at power 3 ...
    echo "200 ir $(frame 21 81)"        # ... and on
    echo "300 ir $(frame 22 05 1e)"     # watch 05:30
    echo "400 ir $(frame e5 00 00 02 2a 00)" # SetUserDisplay(42)
    press 1000 view                      # the watch
    press 2000 view                      # input 1
    press 2200 view                      # input 2
    press 2400 view                      # input 3
    press 2600 view                      # output A: running at power 3
    press 3000 view                      # output B: off
    press 3400 run                       # the program runs: the figure walks
    press 5000 run
    press 6000 onoff                     # click, then standby
    press 8000 onoff                     # double beep
    echo "8600 ir $(frame 12 0e 00)"    # the watch: 0 minutes (ed 00 00)
    echo "9000 quit"
} >"$S"
timeout 60 "$RCXSIM" --fast --load "$WORK/forever.rcx" --script "$S" --trace "$TRACE" || fail "rcxsim failed"

num_at() { # the number shown at time $1
    awk -v t="$1" -F'"t":' '/"num"/ { split($2, a, ","); if (a[1] + 0 <= t) n = $0 } END { print n }' "$TRACE" |
        sed 's/.*"num":"\([^"]*\)".*/\1/'
}
expect "$(num_at 900)" "42" "the program's own display"
case "$(num_at 1900)" in 05.30 | 0530) ;; *) fail "View from the user display: $(num_at 1900), expected the watch" ;; esac
expect "$(num_at 2900)" "4" "output A running at power 3"
expect "$(num_at 3300)" "0" "output B off"

# Walking: the figure's legs (bit 3 of image byte 0) change every 260 ms while the program runs.
times=$(grep -F '"lcd"' "$TRACE" | awk -F'"t":' '{ split($2, a, ","); t = a[1] + 0 }
    /"lcd":"[0-9a-f]*"/ { sub(/.*"lcd":"/, ""); b = substr($0, 1, 2) } t > 3500 && t < 5000 {
        legs = index("89abcdef", substr(b, 2, 1)) > 0; if (legs != last) print t; last = legs }')
prev=""
changes=0
for t in $times; do
    if [ -n "$prev" ]; then
        [ $((t - prev)) -eq 260 ] || fail "the figure changed after $((t - prev)) ms, not 260"
        changes=$((changes + 1))
    fi
    prev=$t
done
[ $changes -ge 4 ] || fail "the figure did not walk ($changes changes)"

# Off: the click (1984 Hz, 20 ms) before standby; on: two beeps of 996 Hz, 160 ms, 60 ms apart.
standby=$(grep -F '"power":"standby"' "$TRACE" | sed 's/.*"t":\([0-9]*\).*/\1/')
click=$(grep -F '"sound":1984,"ms":20' "$TRACE" | sed 's/.*"from":\([0-9]*\).*/\1/' | tail -n 1) # every press clicks
[ -n "$click" ] && [ -n "$standby" ] || fail "no click ($click) or no standby ($standby)"
[ "$click" -ge 6000 ] && [ $((standby - click)) -ge 60 ] || fail "click at $click, standby at $standby"
beeps=$(grep -F '"sound":996,"ms":160' "$TRACE" | sed 's/.*"from":\([0-9]*\).*/\1/' | tr '\n' ' ')
set -- $beeps
# The first two: the double beep the firmware starts with, as firm0328 (issue 15); the others: waking.
[ $# -eq 4 ] && [ "$1" -lt 100 ] && [ $(($2 - $1)) -eq 220 ] && [ "$3" -ge 8000 ] && [ $(($4 - $3)) -eq 220 ] ||
    fail "double beep on starting and on waking: $beeps"
[ -n "$(traced '"ir":"55ff00ed1200ff00ffed12"')" ] || fail "the watch did not start again from 00:00"
