#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# The ROM's checks (rcx-hardware.md §2.1-2.2): an image without the knock string inside 8000-CBFF is downloaded but
# not started; the brick stays in the ROM and reports no firmware.
. "$E2E_DIR/lib.sh"
[ -f "$FIRMWARE" ] || fail "no firmware image $FIRMWARE (make firmware)"
T="$WORK/tty"

# The same image with "knock" spelled "knack": S1 records rewritten with their checksums.
awk 'function hex(s) { return index("0123456789ABCDEF", toupper(substr(s, 1, 1))) * 16 - 17 + index("0123456789ABCDEF", toupper(substr(s, 2, 1))) }
     /^S1/ { line = $0; n = hex(substr(line, 3, 2)); body = substr(line, 3, 2 * n)
             gsub(/6B6E6F636B3F/, "6B6E61636B3F", body)
             sum = 0; for (i = 1; i <= length(body); i += 2) sum += hex(substr(body, i, 2))
             printf "S1%s%02X\n", body, 255 - sum % 256; next }
     { print }' "$FIRMWARE" >"$WORK/bad.srec"
grep -q 6B6E61636B3F "$WORK/bad.srec" || fail "could not find the knock string in the image's records"
start_sim --rom --tty "$T" --speed 50

if out=$(nqc_on "$T" -firmware "$WORK/bad.srec" 2>&1); then fail "nqc -firmware succeeded: $out"; fi
[ -n "$(traced '"rom":"unlock refused","checksum":true,"knock":false')" ] || fail "unlock not refused for the knock"
[ -z "$(traced '"firmware started"')" ] || fail "a firmware without the knock string started"
expect "$(raw "$T" 15010305070b)" "00 03 00 01 00 00 00 00" "still no firmware"
