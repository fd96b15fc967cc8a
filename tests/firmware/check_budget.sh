#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# The image's budgets: at most 16 384 bytes downloaded (the S-records: the image's head, its unpacker and the rest
# packed), at least 12 400 bytes of program memory on an empty brick (the arena the link left, symbol
# _rcx_arena_size), entry at 0x8000. The unpacked image (up to _rcx_image_end) may be larger than the download. It
# ends with the bytes of section .high; they run at 0xF000-0xFB7F once crt0.s has copied them there, and .bss must
# start where they were unpacked (that RAM is the arena's): checked when the listing has .high's symbols.
#
# Usage: check_budget.sh image <nm> <image>              checks the image's symbols and <image>.srec
#        check_budget.sh scan <nm listing> <downloaded>  checks an `nm` listing, with the download's size in bytes
set -e
scan() {
    awk '
        function hex(s,   i, v) { v = 0; s = toupper(s)
            for (i = 1; i <= length(s); i++) v = v * 16 + index("0123456789ABCDEF", substr(s, i, 1)) - 1
            return v % 65536 }
        NF == 3 { sym[$3] = hex($1); seen[$3] = 1 }
        END {
            split("_start _rcx_image_end _rcx_arena_size", need, " ")
            for (i = 1; i <= 3; i++) if (!seen[need[i]]) { print "symbol " need[i] " missing"; exit 1 }
            image = sym["_rcx_image_end"] - 32768
            free = sym["_rcx_arena_size"]
            printf "download %d bytes (budget 16384), image %d bytes unpacked, program memory %d bytes (at least 12400)\n", download, image, free
            if (sym["_start"] != 32768) { print "entry is not 0x8000"; exit 1 }
            if (download !~ /^[0-9]+$/ || download == 0) { print "no download size"; exit 1 }
            if (download > 16384) { print "image over budget"; exit 1 }
            if (free < 12400) { print "too little program memory"; exit 1 }
            if (seen["_rcx_high_start"]) {
                high = sym["_rcx_high_end"] - sym["_rcx_high_start"]
                printf "code run at 0x%04X: %d bytes, loaded at 0x%04X\n", sym["_rcx_high_start"], high, sym["_rcx_high_load"]
                if (!seen["_rcx_high_load"] || !seen["_rcx_bss_start"] || sym["_rcx_high_start"] != 61440 ||
                    high < 0 || sym["_rcx_high_end"] > 64384 || sym["_rcx_high_load"] + high != sym["_rcx_image_end"] ||
                    sym["_rcx_bss_start"] != sym["_rcx_high_load"]) {
                    print "relocated code not laid out as crt0.s copies it"; exit 1 }
            }
        }' download="$2" "$1"
}
case "$1" in
scan)
    scan "$2" "$3" ;;
image)
    [ -f "$3" ] && [ -f "$3.srec" ] || { echo "no firmware image $3 or $3.srec (make firmware)"; exit 1; }
    tmp="${TMPDIR:-/tmp}/check_budget.$$"
    trap 'rm -f "$tmp"' EXIT
    "$2" "$3" > "$tmp"
    # The bytes downloaded: every S1 record's data (its count less 2 address bytes and the checksum).
    download=$(awk '
        function hex(s,   i, v) { v = 0; s = toupper(s)
            for (i = 1; i <= length(s); i++) v = v * 16 + index("0123456789ABCDEF", substr(s, i, 1)) - 1
            return v }
        /^S1/ { n += hex(substr($0, 3, 2)) - 3 }
        END { print n + 0 }' "$3.srec")
    scan "$tmp" "$download" ;;
*)
    echo "usage: $0 image <nm> <image> | scan <listing> <downloaded bytes>" >&2; exit 2 ;;
esac
