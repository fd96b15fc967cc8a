#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# A brick running the firmware is sent back to the ROM by GoIntoBootMode (65 01 03 05 07 0B) at the start of
# nqc -firmware, takes the new image and starts it: the old programs are gone.
. "$E2E_DIR/lib.sh"
[ -f "$FIRMWARE" ] || fail "no firmware image $FIRMWARE (make firmware)"
T="$WORK/tty"
start_sim --tty "$T" --speed 50

nqc_on "$T" -TRCX2 -d "$E2E_DIR/slot.nqc" -run >/dev/null || fail "download"
wait_poll "$T" 0 5 77 "program ran"
out=$(nqc_on "$T" -firmware "$FIRMWARE" 2>&1) || fail "nqc -firmware: $out"
case "$out" in *"Current Version: 00030001/00030208"*) ;; *) fail "nqc -firmware said: $out" ;; esac
[ -n "$(traced '"rom":"boot mode"')" ] || fail "the firmware did not hand over to the ROM"
[ -n "$(traced '"rom":"firmware started"')" ] || fail "firmware not started again"
expect "$(poll "$T" 0 5)" 0 "variables after the new firmware"
nqc_on "$T" -run >/dev/null
sleep 0.2
expect "$(poll "$T" 0 5)" 0 "no program left to run"
