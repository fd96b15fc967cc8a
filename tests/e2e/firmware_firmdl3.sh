#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# brickOS's firmdl3 (Debian package brickos) loads the image: 10, 65, then 75 / 45 blocks numbered 1..N (the last
# is N, not 0) / A5. --slow: its default fast mode first runs a helper program on the brick that reprograms the
# ROM's serial port, which a simulated ROM cannot execute.
. "$E2E_DIR/lib.sh"
[ -f "$FIRMWARE" ] || fail "no firmware image $FIRMWARE (make firmware)"
command -v "$FIRMDL3" >/dev/null || fail "firmdl3 not installed (apt-get install brickos)"
T="$WORK/tty"
start_sim --rom --tty "$T" --speed 50

out=$(timeout 90 "$FIRMDL3" --slow --tty="$T" "$FIRMWARE" 2>&1) || fail "firmdl3: $out"
[ -n "$(traced '"rom":"firmware started"')" ] || fail "firmware not started"
expect "$(raw "$T" 15010305070b)" "00 03 00 01 00 03 02 08" "versions from the new firmware"
