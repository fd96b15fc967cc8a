#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# `make size`: what the firmware image costs. Usage: sh drivers/size.sh <firmware build dir, e.g. build/h8300>
#   sections     text/data/bss as h8300-hms-size counts them (.onchip shows under data and the unpacker, section
#                .unpack, under text: neither is part of the image as it runs)
#   download     bytes downloaded (openrcx.srec), against the 16 384 budget: the head as it runs (entry, knock
#                string), the unpacker, and the rest of the image packed (drivers/pack/pack.h)
#   image        the image unpacked: 0x8000 up to the end of code and constants, then section .high, the code run at
#                0xF000 (copied there by crt0.s; the bytes it was unpacked to become the arena's)
#   free memory  the program-memory arena on an empty brick (memory map word 93 - word 92), from the link
#   on-chip      driver variables at 0xFDC0, the stack left above them, and the .eight bytes at the top
#   checksum     what the ROM verifies: 16-bit sum of the image bytes 0x8000-0xCBFF (BeginFirmwareDownload)
set -e
dir="${1:-build/h8300}/drivers"
image="$dir/openrcx"
srec="$dir/openrcx.srec"
[ -f "$image" ] && [ -f "$srec" ] || { echo "size.sh: no firmware in $dir (make firmware)" >&2; exit 1; }
prefix=h8300-hms-
command -v ${prefix}nm >/dev/null 2>&1 || prefix=h8300-hitachi-coff-

${prefix}size "$image"
awk '
    function hex(s,   i, v) { v = 0; s = toupper(s)
        for (i = 1; i <= length(s); i++) v = v * 16 + index("0123456789ABCDEF", substr(s, i, 1)) - 1
        return v }
    /^S1/ { n += hex(substr($0, 3, 2)) - 3 }
    END { printf "download:     %5d bytes of 16384 (%d left)\n", n, 16384 - n }' "$srec"
${prefix}nm "$image" | awk '
    function hex(s,   i, v) { v = 0; s = toupper(s)
        for (i = 1; i <= length(s); i++) v = v * 16 + index("0123456789ABCDEF", substr(s, i, 1)) - 1
        return v % 65536 }
    { sym[$3] = hex($1) }
    END {
        image = sym["_rcx_image_end"] - sym["_rcx_image_base"]
        head = sym["_rcx_head_end"] - sym["_rcx_image_base"]
        printf "  of which:   %5d as they run (entry, knock string), %d the unpacker, the rest packed\n", head, sym["_rcx_unpacker_size"]
        printf "image:        %5d bytes unpacked (0x8000-0x%04X)\n", image, sym["_rcx_image_end"] - 1
        printf "free memory:  %5d bytes for programs and datalog (at least 12400)\n", sym["_rcx_arena_size"]
        high = sym["_rcx_high_end"] - sym["_rcx_high_start"]
        printf "run at F000:  %5d bytes of code of 2944 (0xF000-0x%04X; %d left), unpacked at 0x%04X\n", high, sym["_rcx_high_end"] - 1, 2944 - high, sym["_rcx_high_load"]
        printf "RAM:          code+data 0x8000-0x%04X, bss 0x%04X up to 0x%04X of 0xF000\n", sym["_rcx_high_load"] - 1, sym["_rcx_bss_start"], sym["_rcx_bss_end"]
        onchip = sym["_rcx_onchip_end"] - sym["_rcx_onchip_start"]
        printf "on-chip RAM:  %5d bytes of driver variables, %d bytes of stack, %d for bytes at 8-bit addresses\n", onchip, sym["_rcx_stack_top"] - sym["_rcx_onchip_end"], sym["_rcx_onchip_top"] - sym["_rcx_stack_top"]
    }'
awk '
    function hex(s,   i, v) { v = 0; s = toupper(s)
        for (i = 1; i <= length(s); i++) v = v * 16 + index("0123456789ABCDEF", substr(s, i, 1)) - 1
        return v }
    /^S1/ { n = hex(substr($0, 3, 2)) - 3; addr = hex(substr($0, 5, 4))
            for (i = 0; i < n; i++) if (addr + i >= 32768 && addr + i < 52224) sum += hex(substr($0, 9 + 2 * i, 2)) }
    END { printf "ROM checksum: 0x%04X (16-bit sum of 0x8000-0xCBFF)\n", sum % 65536 }' "$srec"
