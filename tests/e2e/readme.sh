#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# The README's commands, as a newcomer copies them: every nqc command line in it that compiles a program names the
# RCX 2.0 target, or Swan's in its own section (Debian's nqc compiles for the RCX 1.0 by default, where SetUserDisplay
# does not exist), and the virtual RCX's example, run as written against rcxsim, downloads and starts an RCX 2.0
# program.
. "$E2E_DIR/lib.sh"
README="$E2E_DIR/../../README.md"
# Command lines in backticks or code blocks that run nqc on a .nqc source.
grep -o -E '(`|^)nqc [^`]*\.nqc[^`]*' "$README" | tr -d '`' >"$WORK/compiles"
[ -s "$WORK/compiles" ] || fail "no nqc command compiling a program in the README"
while IFS= read -r line; do
    case " $line " in
    *" -TRCX2 "* | *" -TSwan "*) ;; # Swan's programs (issue 16) name their target too
    *) fail "README: '$line' compiles for nqc's default target, the RCX 1.0: add -TRCX2" ;;
    esac
done <"$WORK/compiles"

# The virtual RCX's example with its own tty and a program only an RCX 2.0 has.
example=$(grep -m 1 -E '^nqc -S/tmp/rcx .*prog\.nqc' "$WORK/compiles") ||
    fail "no 'nqc -S/tmp/rcx ... prog.nqc' example"
cat >"$WORK/prog.nqc" <<'NQC'
int shown;
task main()
{
    shown = 42;
    SetUserDisplay(shown, 0);
}
NQC
T="$WORK/tty"
start_sim --tty "$T" --speed 20
# shellcheck disable=SC2086 # the example's words, split as a shell would
set -- $(echo "$example" | sed "s#/tmp/rcx#$T#; s#prog\.nqc#$WORK/prog.nqc#")
shift # nqc
timeout 60 "$NQC" "$@" >"$WORK/nqc.out" 2>&1 || fail "the README's example failed: $(cat "$WORK/nqc.out")"
wait_poll "$T" 0 0 42 "the program the README's example downloaded and started"
