#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# firmdl3 without --slow against the virtual ROM: its fast mode runs a helper on the brick that switches the serial
# port to 4800 baud, which the virtual RCX cannot do. firmdl3 then fails, and rcxsim says why on its own output and
# what to use instead; that advice works, with no restart of rcxsim.
. "$E2E_DIR/lib.sh"
[ -f "$FIRMWARE" ] || fail "no firmware image $FIRMWARE (make firmware)"
command -v "$FIRMDL3" >/dev/null || fail "firmdl3 not installed (apt-get install brickos)"
T="$WORK/tty"
start_sim --rom --tty "$T" --speed 20

if out=$(timeout 90 "$FIRMDL3" --tty="$T" "$FIRMWARE" 2>&1); then fail "firmdl3 in fast mode succeeded: $out"; fi
grep -q "^rcxsim: --tty $T: .*4800 baud.*fast mode is not available.*firmdl3 --slow" "$WORK/sim.err" ||
    fail "rcxsim did not say that fast mode is not available: $(cat "$WORK/sim.err")"
[ "$(grep -c '4800 baud' "$WORK/sim.err")" = 1 ] || fail "said more than once: $(cat "$WORK/sim.err")"

out=$(timeout 90 "$FIRMDL3" --slow --tty="$T" "$FIRMWARE" 2>&1) || fail "firmdl3 --slow after the fast attempt: $out"
expect "$(raw "$T" 15010305070b)" "00 03 00 01 00 03 02 08" "versions from the new firmware"
