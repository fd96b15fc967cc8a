#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# `make test` runs the suite in both build folders and reports both, even when the first run fails, and fails if
# either failed (issue 23 §6). Its runs are the Makefile's `test-runs` target, run here on two scratch build folders
# whose CTest files hold one passing or one failing test: each order, and both passing.
# Usage: test_runs.sh SOURCE_DIR CTEST SCRATCH
set -eu
src="$1"
ctest_dir=$(dirname "$2")
work=$(mktemp -d "$3/runs.XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() {
    echo "FAIL: $*" >&2
    [ ! -f "$work/out" ] || { echo "--- make's output:" >&2; cat "$work/out" >&2; }
    exit 1
}

# folder NAME true|false: a build folder whose one test passes or fails
folder() {
    mkdir -p "$work/$1/$2"
    printf 'add_test(%s_%s %s)\n' "$2" "$3" "$(command -v "$3")" >"$work/$1/$2/CTestTestfile.cmake"
}

# runs CASE: make test-runs on that case's folders; prints make's status
runs() {
    status=0
    PATH="$ctest_dir:$PATH" env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -s -C "$src" test-runs \
        BUILD="$work/$1" HOST_DIR="$work/$1/host" ASAN_DIR="$work/$1/asan" JOBS=1 >"$work/out" 2>&1 || status=$?
    echo $status
}

folder first_fails host false
folder first_fails asan true
[ "$(runs first_fails)" != 0 ] || fail "the normal run failed, make test did not"
grep -q 'asan_true .*Passed' "$work/out" || fail "the second run did not run after the first failed"
grep -q "normal run ($work/first_fails/host): FAILED" "$work/out" || fail "the first run's failure not reported"
grep -q "ASan/UBSan run ($work/first_fails/asan): passed" "$work/out" || fail "the second run's result not reported"

folder second_fails host true
folder second_fails asan false
[ "$(runs second_fails)" != 0 ] || fail "the ASan/UBSan run failed, make test did not"
grep -q "normal run ($work/second_fails/host): passed" "$work/out" || fail "the first run's result not reported"
grep -q "ASan/UBSan run ($work/second_fails/asan): FAILED" "$work/out" || fail "the second run's failure not reported"

folder both_pass host true
folder both_pass asan true
[ "$(runs both_pass)" = 0 ] || fail "both runs passed, make test failed"
grep -q "normal run .*: passed" "$work/out" && grep -q "ASan/UBSan run .*: passed" "$work/out" ||
    fail "the results are not reported"
echo "OK"
