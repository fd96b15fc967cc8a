#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# rcxsim refuses what it cannot do, with a one-line message and exit status 2, instead of running half set up.
. "$E2E_DIR/lib.sh"
# Each refusal is one line, "rcxsim: " first, naming the option (or argument) it refuses: refused "what" NAME args...
refused() {
    what="$1"
    name="$2"
    shift 2
    status=0
    "$RCXSIM" --fast --duration 10 "$@" >"$WORK/out" 2>&1 || status=$?
    [ $status -eq 2 ] || fail "$what: exit status $status, expected 2"
    [ "$(wc -l <"$WORK/out")" -eq 1 ] || fail "$what: not one line: $(cat "$WORK/out")"
    grep -q '^rcxsim: ' "$WORK/out" || fail "$what: no rcxsim: prefix: $(cat "$WORK/out")"
    grep -q -F -- "$name" "$WORK/out" || fail "$what: does not name $name: $(cat "$WORK/out")"
}
refused "unknown option" --frobnicate --frobnicate
grep -q 'unknown option' "$WORK/out" || fail "unknown option: no reason: $(cat "$WORK/out")"
refused "unknown option before another" --bogus --bogus --fast
refused "stray argument" stray stray
grep -q 'unexpected argument' "$WORK/out" || fail "stray argument: no reason: $(cat "$WORK/out")"
refused "option without value" --speed --speed
grep -q 'needs' "$WORK/out" || fail "--speed: no reason: $(cat "$WORK/out")"
refused "zero speed" --speed --speed 0
refused "nine bricks" --bricks --bricks 9
refused "two ttys, one brick" --tty --tty "$WORK/a" --tty "$WORK/b"
refused "slot 9" "slot 9" --load "$WORK/prog.rcx:9"
refused "hub without address" --tcp-join --tcp-join
refused "hub port too large" --tcp --tcp 127.0.0.1:65536
refused "two TCP towers, one brick" --tcp-tower --tcp-tower 127.0.0.1:0 --tcp-tower 127.0.0.1:0
grep -q 'more than the 1 brick' "$WORK/out" || fail "two TCP towers: no reason: $(cat "$WORK/out")"
refused "TCP tower port too large" "--tcp-tower 127.0.0.1:65536" --tcp-tower 127.0.0.1:65536
grep -q 'PORT 0-65535' "$WORK/out" || fail "TCP tower port: no reason: $(cat "$WORK/out")"
refused "missing script" --script --script "$WORK/none.txt"
refused "trace nowhere" --trace --trace "$WORK/no/such/dir/trace.jsonl"
printf '100 sensor 4 raw 10\n' >"$WORK/s1"
refused "sensor 4" --script --script "$WORK/s1"
grep -q 's1:1:' "$WORK/out" || fail "no line number: $(cat "$WORK/out")"
printf '# fine\n100 button run down\n200 ir 55 ff zz\n' >"$WORK/s2"
refused "bad hex" --script --script "$WORK/s2"
grep -q 's2:3:' "$WORK/out" || fail "no line number: $(cat "$WORK/out")"
printf '100 @1 battery 7000\n' >"$WORK/s3"
refused "brick 1 of 1" --script --script "$WORK/s3"
refused "missing image" --load --load "$WORK/none.rcx"
head -c 300 /dev/urandom >"$WORK/junk.rcx"
refused "not an image" --load --load "$WORK/junk.rcx"
"$NQC" -TRCX2 -O"$WORK/slot.rcx" "$E2E_DIR/slot.nqc"
refused "image into the ROM" --load --rom --load "$WORK/slot.rcx"
# And what it accepts runs: the same image, a good script, every kind of line.
printf '0 @1 sensor 3 raw 0\n5 button view down\n6 button view up\n7 battery 7100\n8 ir 55 ff 00 10 ef 10 ef\n' >"$WORK/s4"
"$RCXSIM" --fast --bricks 2 --load "1@$WORK/slot.rcx:5" --script "$WORK/s4" --duration 100 --trace "$TRACE" ||
    fail "a good command line was refused"
[ -n "$(traced '"brick":1,"ir":"55ff00ef10ef10"')" ] || fail "brick 1 did not answer the script's ping"
[ -n "$(traced '"brick":0,"ir":"55ff00ef10ef10"')" ] || fail "brick 0 did not answer the script's ping"
expect "$(tail -n 1 "$TRACE")" '{"t":100,"end":"duration"}' "end of the trace"
