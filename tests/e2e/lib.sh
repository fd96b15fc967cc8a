# SPDX-License-Identifier: MPL-2.0
# Sourced by every end-to-end test. CTest sets RCXSIM (the virtual RCX), NQC, E2E_DIR (this folder) and
# E2E_TMP (a scratch folder in the build tree). Every host-tool call is bounded by `timeout`, and the simulator is
# killed (by its own pid) however the test ends.
set -eu

WORK=$(mktemp -d "${E2E_TMP:-/tmp}/$(basename "$0" .sh).XXXXXX")
SIM_PID=""
TRACE="$WORK/trace.jsonl"

cleanup() {
    if [ -n "$SIM_PID" ]; then
        kill "$SIM_PID" 2>/dev/null || true
        wait "$SIM_PID" 2>/dev/null || true
    fi
    rm -rf "$WORK"
}
trap cleanup EXIT
trap 'exit 1' INT TERM

fail() {
    echo "FAIL: $*" >&2
    if [ -f "$TRACE" ]; then
        echo "--- last trace lines:" >&2
        tail -n 15 "$TRACE" >&2
    fi
    if [ -f "$WORK/sim.err" ]; then
        cat "$WORK/sim.err" >&2
    fi
    exit 1
}

# Start rcxsim in the background with the given options (plus the trace); waits for every --tty link to appear.
# Under `timeout`: should this script itself be killed (CTest's TIMEOUT), the simulator still ends.
start_sim() {
    timeout 300 "$RCXSIM" --trace "$TRACE" "$@" >"$WORK/sim.out" 2>"$WORK/sim.err" &
    SIM_PID=$!
    for a in "$@"; do
        case "$a" in
        "$WORK"/*)
            n=0
            while [ ! -e "$a" ]; do
                n=$((n + 1))
                [ $n -lt 200 ] || fail "rcxsim did not create $a"
                kill -0 "$SIM_PID" 2>/dev/null || fail "rcxsim exited early"
                sleep 0.05
            done
            ;;
        esac
    done
}

stop_sim() {
    kill "$SIM_PID" 2>/dev/null || true
    wait "$SIM_PID" 2>/dev/null || true
    SIM_PID=""
}

# nqc against a tower: nqc_on TTY args...
nqc_on() {
    tty="$1"
    shift
    timeout 60 "$NQC" -S"$tty" "$@"
}

# The data bytes of a direct command's reply as nqc -raw prints them, on one line: "2b 00".
raw() {
    nqc_on "$1" -raw "$2" | tr -s ' \n' '  ' | sed 's/ *$//'
}

# A 16-bit value polled from source $2 index $3, as a signed decimal number.
poll() {
    r=$(raw "$1" "$(printf '12%02x%02x' "$2" "$3")")
    lo=$(printf '%d' "0x${r%% *}")
    hi=$(printf '%d' "0x${r##* }")
    v=$((hi * 256 + lo))
    [ $v -lt 32768 ] || v=$((v - 65536))
    echo $v
}

expect() {
    [ "$1" = "$2" ] || fail "$3: got '$1', expected '$2'"
}

# Lines of the trace matching a fixed string.
traced() {
    grep -F -- "$1" "$TRACE" || true
}

# A standard IR packet (host-tools.md §1) as hex bytes for a script's `ir` line: frame 10 → 55 ff 00 10 ef 10 ef
frame() {
    out="55 ff 00"
    sum=0
    for b in "$@"; do
        v=$(printf '%d' "0x$b")
        out="$out $(printf '%02x %02x' $v $((v ^ 255)))"
        sum=$(((sum + v) & 255))
    done
    echo "$out $(printf '%02x %02x' $sum $((sum ^ 255)))"
}

# Poll until the value is as expected (programs run in simulated time; give them a few wall seconds).
wait_poll() {
    n=0
    while :; do
        v=$(poll "$1" "$2" "$3")
        [ "$v" = "$4" ] && return 0
        n=$((n + 1))
        [ $n -lt 20 ] || fail "$5: source $2 index $3 is $v, expected $4"
        sleep 0.2
    done
}
