#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# run.sh FUZZER CORPUS WORKDIR SECONDS: run one libFuzzer binary for SECONDS on a copy of the stored corpus
# (the source tree is never written) and print one summary line. Fails on any crash, leak or invariant violation;
# the failing input is left in WORKDIR as crash-*, to be added to the corpus and to a unit test. Paths may be
# relative to where it is started (make fuzz passes build/asan/...): the fuzzer runs inside WORKDIR. A fuzzer that
# did not run (missing, or no executions counted) is a failure, never "0 failures".
set -u
fuzzer="$1"; corpus="$2"; work="$3"; seconds="$4"
name=$(basename "$fuzzer")
case "$fuzzer" in /*) ;; *) fuzzer="$(pwd)/$fuzzer" ;; esac
rm -rf "$work" && mkdir -p "$work/corpus"
cp "$corpus"/* "$work/corpus/" 2>/dev/null || true
cd "$work" || exit 1
"$fuzzer" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=1024 -print_final_stats=1 corpus >log 2>&1
status=$?
runs=$(sed -n 's/^stat::number_of_executed_units: *//p' log | tail -1)
if [ -z "$runs" ] || [ "$runs" -eq 0 ]; then
    echo "$name: did not run (exit status $status)"
    tail -20 log
    exit 1
fi
cov=$(grep -o 'cov: [0-9]*' log | tail -1 | cut -d' ' -f2)
crashes=$(ls crash-* leak-* timeout-* 2>/dev/null | wc -l)
echo "$name: $runs executions in ${seconds} s, coverage ${cov:-0} edges, $crashes failures"
if [ $status -ne 0 ] || [ "$crashes" -ne 0 ]; then
    tail -40 log
    exit 1
fi
