#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# nqc -datalog and -datalog_full read the datalog a program wrote (host-tools.md §2: A4 uploads).
. "$E2E_DIR/lib.sh"
T="$WORK/tty"
start_sim --tty "$T" --speed 20
nqc_on "$T" -TRCX2 -d "$E2E_DIR/datalog.nqc" -run >/dev/null || fail "download"
wait_poll "$T" 0 0 300 "program ran"
sleep 0.3
log=$(nqc_on "$T" -datalog 2>/dev/null | tr '\n' ' ')
expect "$log" "300 -7 5 " "nqc -datalog"
full=$(nqc_on "$T" -datalog_full 2>/dev/null | tr '\n' '|')
case "$full" in
"Variable 0: 300|"*": -7|"*": 5|") ;;
*) fail "nqc -datalog_full: $full" ;;
esac
