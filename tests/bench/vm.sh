#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# `make bench`: interpreter throughput, and instructions per byte code under callgrind when valgrind is present.
set -e
bin="$1/tests/bench_vm"
"$bin"
if command -v valgrind >/dev/null 2>&1; then
    n=1000000
    count() { valgrind --tool=callgrind --callgrind-out-file=/dev/null "$bin" --count "$1" "$2" 2>&1 |
              sed -n 's/.*Collected : *\([0-9]*\).*/\1/p'; }
    for tasks in 1 10; do
        base=$(count 0 "$tasks")
        full=$(count $n "$tasks")
        echo "host interpreter, $tasks task(s), callgrind: $(( (full - base) / n )) host instructions per byte code"
    done
else
    echo "valgrind not installed: instruction counts skipped"
fi
