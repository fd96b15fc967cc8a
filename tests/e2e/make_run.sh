#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# `make run` (host_sim/demo.sh): nqc's progress line and the trace's JSON lines do not share a line of the terminal,
# and the trace is still shown. The demo runs until interrupted: it gets SIGINT, as from Ctrl-C, after 15 s.
. "$E2E_DIR/lib.sh"
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
status=0
PANEL_PORT=$port timeout -s INT 15 sh "$E2E_DIR/../../host_sim/demo.sh" "$(dirname "$RCXSIM")" >"$WORK/out" 2>&1 ||
    status=$?
[ $status -eq 124 ] || fail "the demo ended by itself (status $status): $(cat "$WORK/out")"
grep -q 'Downloading Program' "$WORK/out" || fail "no nqc progress line: $(cat "$WORK/out")"
grep 'Downloading Program' "$WORK/out" | grep -q -v '{' ||
    fail "the trace cut into nqc's progress line: $(grep 'Downloading' "$WORK/out")"
grep -q '^{"t":[0-9]*,"brick":0,"motor"' "$WORK/out" || fail "no trace lines shown: $(cat "$WORK/out")"
