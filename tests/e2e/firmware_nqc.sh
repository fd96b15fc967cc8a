#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# nqc -firmware of the built image into a brick in the ROM's download mode (host-tools.md §2: 10, 15, 65, 75,
# 45 blocks of 200 bytes numbered 1.. and 0 last, A5 "LEGO®", then 15 answered by the new firmware), and then the
# firmware at work: a program downloaded and run.
. "$E2E_DIR/lib.sh"
[ -f "$FIRMWARE" ] || fail "no firmware image $FIRMWARE (make firmware)"
T="$WORK/tty"
start_sim --rom --tty "$T" --speed 50

expect "$(raw "$T" 15010305070b)" "00 03 00 01 00 00 00 00" "ROM versions before the download"
out=$(nqc_on "$T" -firmware "$FIRMWARE" 2>&1) || fail "nqc -firmware: $out"
case "$out" in *"Current Version: 00030001/00030208"*) ;; *) fail "nqc -firmware said: $out" ;; esac
[ -n "$(traced '"rom":"download complete"')" ] || fail "no complete download"
[ -n "$(traced '"rom":"firmware started"')" ] || fail "firmware not started"

nqc_on "$T" -TRCX2 -d "$E2E_DIR/counter.nqc" -run >/dev/null || fail "download after the firmware"
wait_poll "$T" 0 0 60 "program on the new firmware"
