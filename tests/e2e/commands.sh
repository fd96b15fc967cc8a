#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# The other nqc actions over the link: -watch, -sleep, -near/-far, -clear, -raw, and a program larger than the
# free memory (BeginOfTask status 1, host-tools.md §2 / reference-firmware.md "Downloads").
. "$E2E_DIR/lib.sh"
T="$WORK/tty"
start_sim --tty "$T" --speed 20

nqc_on "$T" -watch 1234 || fail "-watch"
expect "$(poll "$T" 14 0)" 754 "watch (source 14 = 12 x 60 + 34)"
nqc_on "$T" -sleep 5 || fail "-sleep"
nqc_on "$T" -far || fail "-far"
nqc_on "$T" -near || fail "-near"
[ -n "$(traced '"range":"far"')" ] || fail "no far range"
[ "$(traced '"range":"near"' | wc -l)" -ge 2 ] || fail "not back to near"

# Version query and a bad key (reference-firmware.md: a wrong key gets a bare acknowledgement).
expect "$(raw "$T" 15010305070b)" "00 03 00 01 00 03 02 08" "versions"
expect "$(raw "$T" 15010305070c)" "" "wrong key"

# -clear: five slots emptied and an empty datalog (52 00 00: entry 0 only, spec p. 54) - the memory map is the
# one of a brick that has only ever had SetDataLog 0.
nqc_on "$T" -raw 520000 >/dev/null
empty=$(raw "$T" 20)
nqc_on "$T" -TRCX2 -d "$E2E_DIR/datalog.nqc" -run >/dev/null || fail "download"
nqc_on "$T" -TRCX2 -d -pgm 2 "$E2E_DIR/counter.nqc" >/dev/null || fail "download 2"
wait_poll "$T" 0 0 300 "program ran"
[ "$(raw "$T" 20)" != "$empty" ] || fail "downloads did not change the memory map"
nqc_on "$T" -clear || fail "-clear"
expect "$(raw "$T" 20)" "$empty" "memory map after -clear"

# More code than free memory: refused, and the brick still answers.
i=0
{
    echo "int x; task main() {"
    while [ $i -lt 3500 ]; do echo "x += $i;"; i=$((i + 1)); done
    echo "}"
} >"$WORK/big.nqc"
if out=$(nqc_on "$T" -TRCX2 -d "$WORK/big.nqc" 2>&1); then fail "a too large program was accepted"; fi
case "$out" in *"Not enough free memory"*) ;; *) fail "nqc said: $out" ;; esac
expect "$(poll "$T" 2 5)" 5 "poll after the refused download"

# Garbage and commands no firmware knows are not answered, and do no harm.
nqc_on "$T" -raw 01 >/dev/null 2>&1 || true
nqc_on "$T" -raw 550055 >/dev/null 2>&1 || true
expect "$(poll "$T" 2 9)" 9 "poll after garbage"

# Line noise from the host side: random bytes through the tower, then the brick answers again.
head -c 2000 /dev/urandom >"$T"
sleep 1.5
expect "$(poll "$T" 2 11)" 11 "poll after random bytes"
