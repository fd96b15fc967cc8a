#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# `make bench`: byte codes per second of the firmware on the brick, counted in an H8/300 simulator running the
# image's own code (tests/drivers/h8bench.c; its timing model is in tests/drivers/h8sim.h), function by function and
# then the whole image in a simulated brick (tests/drivers/h8machine.h). Goal: 30 000 byte codes/s for one task
# running `x++` (firm0328: about 370).
# Usage: sh tests/bench/firmware.sh <host build dir> <firmware build dir>
host="${1:-build/host}"
fw="${2:-build/h8300}"
bench="$host/tests/drivers/h8bench"
nm=$(command -v h8300-hms-nm || command -v h8300-hitachi-coff-nm)
if [ ! -x "$bench" ] || [ -z "$nm" ] || [ ! -f "$fw/drivers/openrcx.srec" ]; then
    echo "firmware bench: needs the host build ($bench), the firmware ($fw) and h8300-hms-nm" >&2
    exit 1
fi
"$bench" "$fw/drivers/openrcx" "$nm"
rc=$?
[ $rc -eq 3 ] && echo "firmware bench: below the goal of 30 000 byte codes/s (not a failure of make bench)"
[ $rc -eq 3 ] && exit 0
exit $rc
