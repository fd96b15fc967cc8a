#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# The ROM's download protocol packet by packet, from a script into the room (no host tool): every status code of
# 45 (0 OK, 3 block checksum / out of order, 4 firmware checksum, 6 not active), the unlock refused and accepted,
# and the firmware then answering. The brick's replies are the "ir" lines of the trace.
. "$E2E_DIR/lib.sh"
S="$WORK/script"
knock="44 6f 20 79 6f 75 20 62 79 74 65 2c 20 77 68 65 6e 20 49 20 6b 6e 6f 63 6b 3f" # Do you byte, when I knock?
# Block data: the knock string (26 bytes, sum 0x08e0: block checksum e0, image checksum 08e0).
{
    echo "100 ir $(frame 45 01 00 01 00 aa aa)"                  # no download active: 6
    echo "400 ir $(frame 75 00 80 00 00 00)"                     # begin, checksum 0000: 0
    echo "700 ir $(frame 4d 01 00 01 00 aa ab)"                  # block checksum wrong: 3
    echo "1000 ir $(frame 45 02 00 01 00 aa aa)"                 # block 2 before 1: 3
    echo "1300 ir $(frame 4d 01 00 1a 00 $knock e0)"             # block 1: 0
    echo "2300 ir $(frame 45 00 00 00 00 00)"                    # last block, image sum 08e0 != 0000: 4
    echo "2600 ir $(frame a5 4c 45 47 4f ae)"                    # unlock refused: no reply
    echo "2900 ir $(frame 7d 00 80 e0 08 00)"                    # begin again with the right checksum: 0
    echo "3200 ir $(frame 45 01 00 1a 00 $knock e0)"             # 0
    echo "4200 ir $(frame 4d 00 00 00 00 00)"                    # last: 0
    echo "4500 ir $(frame a5 4c 45 47 4f ae)"                    # unlocked: "Just a bit off the block!"
    echo "5000 ir $(frame 15 01 03 05 07 0b)"                    # the firmware answers: firmware 3.2.8
    echo "5500 quit"
} >"$S"
"$RCXSIM" --rom --fast --script "$S" --trace "$TRACE" --duration 10000 || fail "rcxsim failed"
replies=$(grep -F '"ir"' "$TRACE" | sed 's/.*"ir":"\([0-9a-f]*\)".*/\1/' | tr '\n' ' ')
just=$(printf 'Just a bit off the block!' | od -An -tx1 | tr -d ' \n')
payload() { # the reply payload of a framed packet, complements dropped
    echo "$1" | sed 's/^55ff00//' | sed 's/\(..\)../\1/g' | sed 's/..$//'
}
got=""
for r in $replies; do got="$got $(payload "$r")"; done
expect "$got" " ba06 8a00 b203 ba03 b200 ba04 8200 ba00 b200 5a$just ea0003000100030208" "ROM replies"
[ -n "$(traced '"rom":"unlock refused","checksum":false,"knock":true')" ] || fail "no refusal for the checksum"
[ -n "$(traced '"rom":"firmware started","bytes":26')" ] || fail "firmware not started"
