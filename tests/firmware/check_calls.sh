#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# The firmware drives the hardware itself: no jsr/jmp may reach the ROM (addresses below 0x8000), except the
# single hand-back `jmp @@0:8` through the reset vector (GoIntoBootMode, rcx-hardware.md 2.4), which must exist.
# Memory-indirect jumps and calls (@@aa:8) go through the ROM's vector table, so any other one is a ROM call.
#
# The code is 0x8000 up to _rcx_code_end and section .high, which runs at 0xF000 (_rcx_high_start-_rcx_high_end).
#
# Usage: check_calls.sh image <objdump> <nm> <image>   disassembles the code of the image (data left out)
#        check_calls.sh scan <disassembly file>        checks an `objdump -d` listing
set -e
scan() {
    awk '
        function hex(s,   i, v) { v = 0; s = toupper(s)
            for (i = 1; i <= length(s); i++) v = v * 16 + index("0123456789ABCDEF", substr(s, i, 1)) - 1
            return v }
        $0 ~ /\t(jsr|jmp)\t@@/ {
            if ($0 ~ /\tjmp\t@@0 \(0x0\)/) { handback++; next }
            print "ROM call through a vector: " $0; bad++; next }
        $0 ~ /\t(jsr|jmp)\t@0x[0-9a-f]+:(16|24)/ {
            match($0, /@0x[0-9a-f]+/); a = hex(substr($0, RSTART + 3, RLENGTH - 3)) % 65536
            if (a < 32768) { print "ROM call: " $0; bad++ }
            calls++ }
        END {
            if (calls + handback == 0) { print "no calls found: not a disassembly of the firmware"; exit 1 }
            if (handback != 1) { print "expected exactly one jmp @@0:8 (the hand-back to the ROM), found " handback + 0; exit 1 }
            if (bad) exit 1
            printf "%d direct calls and jumps, none into the ROM; one hand-back to the ROM reset\n", calls }' "$1"
}

case "$1" in
scan)
    scan "$2" ;;
image)
    objdump="$2" nm="$3" image="$4"
    [ -f "$image" ] || { echo "no firmware image $image (make firmware)"; exit 1; }
    eval "$("$nm" "$image" | awk '$3 == "_start" || $3 == "_rcx_knock" || $3 == "_rcx_code_end" ||
        $3 == "_rcx_high_start" || $3 == "_rcx_high_end" {
        sub(/^_/, "", $3); print $3 "=0x" substr($1, length($1) - 3) }')"
    # The knock string sits among the instructions: disassemble around it, so that it is not decoded as code.
    after=$(printf '0x%x' $(( (rcx_knock + 27 + 1) / 2 * 2 )))
    tmp="${TMPDIR:-/tmp}/check_calls.$$"
    trap 'rm -f "$tmp"' EXIT
    { "$objdump" -d --start-address="$start" --stop-address="$rcx_knock" "$image"
      "$objdump" -d --start-address="$after" --stop-address="$rcx_code_end" "$image"
      [ -z "$rcx_high_start" ] || [ "$rcx_high_start" = "$rcx_high_end" ] ||
          "$objdump" -d --start-address="$rcx_high_start" --stop-address="$rcx_high_end" "$image"; } > "$tmp"
    scan "$tmp" ;;
*)
    echo "usage: $0 image <objdump> <nm> <image> | scan <listing>" >&2; exit 2 ;;
esac
