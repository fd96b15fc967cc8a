#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# What a user of nqc sees of the brick's face and status (reference-firmware.md, "Observed" and "The brick's face"):
# outputs braked from the start and after nqc -run, bit 6 clear while an output runs, the status bytes of SetDatalog
# and DatalogNext, 0x8000 for polls of what does not exist, the watch with its leading zero and blinking point, and
# the IR mark lit for a moment around every exchange.
. "$E2E_DIR/lib.sh"
T="$WORK/tty"
start_sim --tty "$T" --speed 20

for m in 0 1 2; do expect "$(poll "$T" 3 $m)" 79 "output $m right after start (0x4F)"; done
nqc_on "$T" -raw 218f >/dev/null             # Off(OUT_ABC) ...
nqc_on "$T" -raw 2187 >/dev/null             # ... then On: on, not on and braked
expect "$(poll "$T" 3 0)" 143 "status after Off then On (0x8F)"
nqc_on "$T" -raw 13010203 >/dev/null         # A at power 3
expect "$(poll "$T" 3 0)" 139 "status forward at power 3 (0x8B)"
nqc_on "$T" -TRCX2 -d "$E2E_DIR/counter.nqc" -run >/dev/null || fail "download"
for m in 0 1 2; do expect "$(poll "$T" 3 $m)" 79 "output $m after nqc -run (0x4F)"; done

expect "$(raw "$T" 520a00)" "00" "SetDatalog 10"
expect "$(raw "$T" 620e00)" "00" "DatalogNext"
expect "$(raw "$T" 5200ff)" "01" "SetDatalog 65280: not enough memory"
expect "$(raw "$T" 12ff00)" "00 80" "poll of no such source"
expect "$(raw "$T" 1200ff)" "00 80" "poll of no such variable"
expect "$(raw "$T" 122000)" "00 80" "poll of a task's local variable"

# The watch (selected at power-on): both "00.00" and "0000" show, the point blinking.
[ -n "$(traced '"num":"00.00"')" ] && [ -n "$(traced '"num":"0000"')" ] || fail "watch not shown as 00.00, blinking"
nqc_on "$T" -watch 0930 || fail "-watch"
n=0
until [ -n "$(traced '"num":"09.30"')" ]; do
    n=$((n + 1))
    [ $n -lt 40 ] || fail "watch 09:30 not shown as 09.30"
    sleep 0.1
done

# The IR mark (segment 6.2: bit 2 of image byte 6) was lit and dark again between the exchanges above.
lit=0
dark=0
for img in $(grep -F '"lcd"' "$TRACE" | sed 's/.*"lcd":"\([0-9a-f]*\)".*/\1/'); do
    if [ $((0x$(echo "$img" | cut -c13-14) & 4)) -ne 0 ]; then lit=$((lit + 1)); else dark=$((dark + 1)); fi
done
[ $lit -gt 0 ] || fail "the IR mark was never lit"
[ $dark -gt 0 ] || fail "the IR mark was never dark"
