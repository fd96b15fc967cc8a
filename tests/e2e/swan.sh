#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# Swan programs (nqc -TSwan, issue 16) on the virtual RCX, downloaded by the real nqc over the tower and checked by
# polling their globals over IR (source 43, any of the 256). Two bricks in one room: brick 0 sends a message with a
# parameter (0xC3: on the wire B3 m lo hi, then F7 m, vm/remote.h) and a plain one; brick 1's program reads Message()
# and MessageParam(): 42 with -1234, then 7 with 0 (a plain message has parameter 0, swan-target.md 4). Then brick 0
# runs tests/programs/swan_globals.nqc (more than 200 globals, an array indexed past 32) and swan_math.nqc.
. "$E2E_DIR/lib.sh"
T0="$WORK/tty0"
T1="$WORK/tty1"
PROGRAMS="$E2E_DIR/../programs"
start_sim --bricks 2 --tty "$T0" --tty "$T1" --speed 20

# The variable number nqc gives a name: "*** Var 210 = got_msg" in its listing.
var() {
    n=$("$NQC" -TSwan -L "$1" | sed -n "s/^\*\*\* Var \([0-9]*\) = $2\$/\1/p" | head -n 1)
    [ -n "$n" ] || fail "no variable $2 in $1"
    echo "$n"
}
gpoll() { # tty file name [element]
    poll "$1" 43 $(($(var "$2" "$3") + ${4:-0}))
}
wait_g() { # tty file name value what
    wait_poll "$1" 43 "$(var "$2" "$3")" "$4" "$5"
}

RX="$E2E_DIR/swan_receiver.nqc"
nqc_on "$T1" -TSwan -d "$RX" -run >/dev/null || fail "download to brick 1"
nqc_on "$T0" -TSwan -d "$E2E_DIR/swan_sender.nqc" >/dev/null || fail "download to brick 0"
[ "$(var "$RX" got_msg)" -gt 200 ] || fail "the receiver's results are not above global 200"
nqc_on "$T0" -run || fail "-run brick 0"
sleep 1
wait_g "$T1" "$RX" done 1 "brick 1 received both messages"
expect "$(gpoll "$T1" "$RX" got_msg)" 42 "message"
expect "$(gpoll "$T1" "$RX" got_param)" -1234 "its parameter"
expect "$(gpoll "$T1" "$RX" got2)" 7 "the plain message"
expect "$(gpoll "$T1" "$RX" param2)" 0 "a plain message's parameter"
# the parameter went out as B3 42 -1234 (2e fb), then the message as F7 42 (0x2a)
[ -n "$(traced '"brick":0,"ir":"55ff00b34c2ad52ed1fb04')" ] || fail "brick 0 did not send B3 2a 2e fb"
[ -n "$(traced '"brick":0,"ir":"55ff00f7082ad5')" ] || fail "brick 0 did not send F7 2a"

G="$PROGRAMS/swan_globals.nqc"
nqc_on "$T0" -TSwan -d "$G" -run >/dev/null || fail "download swan_globals"
wait_g "$T0" "$G" last -5 "swan_globals ran to its end"
expect "$(gpoll "$T0" "$G" big 35)" 105 "big[35]"
expect "$(gpoll "$T0" "$G" big 199)" 597 "big[199]"
expect "$(gpoll "$T0" "$G" sum)" -5836 "the sum, wrapped at 16 bits"
expect "$(gpoll "$T0" "$G" flags)" 9 "BitSet through source 0"
expect "$(poll "$T0" 0 40)" -32768 "source 0 index 40 polled by a host answers 0x8000, as in firm0328"

M="$PROGRAMS/swan_math.nqc"
nqc_on "$T0" -TSwan -d "$M" -run >/dev/null || fail "download swan_math"
wait_g "$T0" "$M" r_orw 259 "swan_math ran to its end"
expect "$(gpoll "$T0" "$M" r_mod)" -1 "-7 % 3"
expect "$(gpoll "$T0" "$M" r_shr)" -4 "-7 >> 1"
expect "$(gpoll "$T0" "$M" r_xor)" -6 "-7 ^ 3"
expect "$(gpoll "$T0" "$M" r_mulw)" -27680 "1000 * 300"
expect "$(gpoll "$T0" "$M" r_divz)" -7 "-7 / 0"
