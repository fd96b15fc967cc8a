#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# The fuzz driver (run.sh) as `make fuzz` uses it: from the top of a clone, with paths relative to it.
#   test_run_script.sh SOURCE_DIR [FUZZER]
# Without FUZZER: a fuzzer that cannot be started must fail the run, and its summary must not claim "0 failures".
# With FUZZER (an absolute path to a built libFuzzer binary): it is given by a relative path, as make does, and must
# really run (executions counted, exit 0).
set -u
src="$1"; fuzzer="${2:-}"
top=$(mktemp -d)
trap 'rm -rf "$top"' EXIT
mkdir -p "$top/build/fz" "$top/corpus"
cp "$src/tests/fuzz/run.sh" "$top/run.sh"
echo seed >"$top/corpus/seed"
cd "$top" || exit 1
if [ -z "$fuzzer" ]; then
    out=$(sh run.sh build/fz/fuzz_missing corpus build/work 1)
    status=$?
    echo "$out"
    [ $status -ne 0 ] || { echo "FAIL: a fuzzer that did not run passed"; exit 1; }
    case "$out" in *"0 failures"*) echo "FAIL: summary claims 0 failures about a run that did not happen"; exit 1 ;; esac
    echo "ok: a run that did not happen fails"
    exit 0
fi
cp "$fuzzer" build/fz/fuzz_x
out=$(sh run.sh build/fz/fuzz_x corpus build/work 2)
status=$?
echo "$out"
[ $status -eq 0 ] || { echo "FAIL: exit status $status"; exit 1; }
case "$out" in *": 0 executions"*|*"did not run"*) echo "FAIL: the fuzzer did not run"; exit 1 ;; esac
echo "ok: fuzzer given by a relative path ran"
