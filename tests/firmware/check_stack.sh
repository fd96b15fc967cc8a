#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# Worst-case stack use of the firmware, from its disassembly, against the room the link left for the stack.
#
# Each function's frame is followed instruction by instruction (pushes, pops, adds/subs and add.w of a loaded
# constant to r7, a call of a shared prologue ___rcx_save6* as the pushes it makes); a call adds the caller's
# depth at that point plus the return address to the callee's own worst case. A call through a register (a handler
# table) may reach any function whose address the program takes: one
# loaded as a constant by an instruction, or stored as a word among the constants after the code (main and the
# interrupt entries excepted: only the CPU calls those); it counts as the deepest of them. The deepest chain from main, plus the deepest interrupt (interrupts do not nest: the CPU masks
# them) and the 8 bytes the CPU and the ROM's trampoline push before a handler runs, must fit between the on-chip
# variables and 0xFF80. Recursion, or a register call with no candidate, would leave the answer unknown: refused.
#
# The code is 0x8000 up to _rcx_code_end and section .high at 0xF000 (_rcx_high_start-_rcx_high_end); the constants
# follow the first part, up to where .high is loaded (_rcx_high_load).
#
# Usage: check_stack.sh image <objdump> <nm> <image>
#        check_stack.sh scan <disassembly> <stack bytes> [<objdump -s dump of the constants>]
set -e
scan() {
    awk -v room="$2" -v listing="$1" '
        function hex(s,   i, v) { v = 0; s = toupper(s)
            for (i = 1; i <= length(s); i++) v = v * 16 + index("0123456789ABCDEF", substr(s, i, 1)) - 1
            return v }
        BEGIN {    # the shared prologues (drivers/h8300/tails.s): a call leaves r4-r6 or r4-r5 pushed, and locals
            while ((getline l < listing) > 0)
                if (l ~ /^[0-9a-f]+ <___rcx_save(6|6_f[24]|5_r[45])>:$/)
                    save[hex(substr(l, 1, index(l, " ") - 1))] = (l ~ /save5/ ? 4 : 6) \
                                                                 + (l ~ /_f/ ? substr(l, length(l) - 2, 1) : 0)
            close(listing) }
        FNR == 1 { file++ }
        file == 2 && /^ [0-9a-f]+ [0-9a-f]/ {    # constants: every aligned word may be a function pointer
            base = hex($1)
            for (g = 2; g <= 5 && $g ~ /^[0-9a-f]+$/; g++)
                for (k = 0; k + 4 <= length($g); k += 4)
                    if ((base + (g - 2) * 4 + k / 2) % 2 == 0) word[hex(substr($g, k + 1, 4))] = 1
            next }
        file == 2 { next }
        /^[0-9a-f]+ <_[^.>][^>]*>:$/ {
            f = substr($2, 3, length($2) - 4); start[f] = hex($1); addr_of[hex($1)] = f
            names[++nf] = f; off = 0; top[f] = 0; next }
        /^ +[0-9a-f]+:\t/ && nf {
            split($0, part, "\t"); op = part[3]; arg = part[4]
            if (op == "mov.w" && arg ~ /,@-r7$/) off += 2
            else if (op == "mov.w" && arg ~ /^@r7\+/) off -= 2
            else if (op == "subs" && arg ~ /,r7$/) off += substr(arg, 2, 1)
            else if (op == "adds" && arg ~ /,r7$/) off -= substr(arg, 2, 1)
            else if (op == "mov.w" && arg ~ /^#0x/) {
                split(arg, a, ","); imm[a[2]] = hex(substr(a[1], 4)); word[imm[a[2]]] = 1 }
            else if (op == "add.w" && arg ~ /,r7$/) { split(arg, a, ","); v = imm[a[1]]; if (v >= 32768) v -= 65536; off -= v }
            else if ((op == "jsr" || op == "bsr") && match(arg, /0x[0-9a-f]+/) \
                     && (hex(substr(arg, RSTART + 2, RLENGTH - 2)) in save))
                off += save[hex(substr(arg, RSTART + 2, RLENGTH - 2))]
            else if (op == "jsr" || op == "bsr" || op == "jmp") {
                if (match(arg, /0x[0-9a-f]+/)) {
                    ncall[f]++; callee[f, ncall[f]] = hex(substr(arg, RSTART + 2, RLENGTH - 2))
                    at[f, ncall[f]] = off + (op == "jmp" ? 0 : 2); isjmp[f, ncall[f]] = op == "jmp"
                } else if (op == "jsr" && arg ~ /^@r[0-7]$/) {
                    ncall[f]++; callee[f, ncall[f]] = -1; at[f, ncall[f]] = off + 2; isjmp[f, ncall[f]] = 0
                } else if (op == "jsr") { print "call through a vector in " f ": " $0; unknown = 1 }
            }
            if (off > top[f]) top[f] = off }
        # The deepest function a register call may reach.
        function indirect(   a, d, best) {
            if (ind_done) return ind_best
            if (ind_busy) { print "recursion through a register call"; unknown = 1; return 0 }
            ind_busy = 1; best = -1
            for (a in word) if ((a in addr_of) && addr_of[a] !~ /^(main|start|rcx_.*_irq|rcx_irq_ignore)$/) {
                d = depth(addr_of[a]); if (d > best) { best = d; ind_via = addr_of[a] } }
            ind_busy = 0; ind_done = 1; ind_best = best; return best }
        function depth(f,   i, d, t, best) {
            if (f in memo) return memo[f]
            if (busy[f]) { print "recursion through " f; unknown = 1; return 0 }
            busy[f] = 1; best = top[f]; via[f] = ""
            for (i = 1; i <= ncall[f]; i++) {
                if (callee[f, i] == -1) {
                    d = indirect()
                    if (d < 0) { print "call through a register in " f " and no function address is taken"; unknown = 1; continue }
                    d += at[f, i]; t = "(" ind_via ")"
                } else {
                    t = addr_of[callee[f, i]]
                    if (t == "" || (t == f && isjmp[f, i])) continue    # a jump inside the function or to a label
                    d = at[f, i] + depth(t)
                }
                if (d > best) { best = d; via[f] = t }
            }
            busy[f] = 0; memo[f] = best; return best }
        function chain(f,   t) {
            if (via[f] == "") return f
            if (via[f] ~ /^\(/) { t = substr(via[f], 2, length(via[f]) - 2); return f " > [table] " chain(t) }
            return f " > " chain(via[f]) }
        END {
            if (!("main" in start)) { print "no main: not a disassembly of the firmware"; exit 1 }
            m = depth("main") + 2    # crt0 calls main
            irq = 0
            for (i = 1; i <= nf; i++) if (names[i] ~ /^rcx_.*_irq$/ && depth(names[i]) > irq) { irq = depth(names[i]); deep = names[i] }
            total = m + irq + 8
            if (unknown) exit 1
            printf "stack: main %d bytes (%s), interrupts %d (%s) + 8 on entry: %d of %d bytes\n", m, chain("main"), irq, deep == "" ? "none" : chain(deep), total, room
            if (total > room) { print "stack overflow: the stack would run into the on-chip variables"; exit 1 } }' "$1" "${3:-/dev/null}"
}
case "$1" in
scan)
    scan "$2" "$3" "$4" ;;
image)
    objdump="$2" nm="$3" image="$4"
    [ -f "$image" ] || { echo "no firmware image $image (make firmware)"; exit 1; }
    eval "$("$nm" "$image" | awk '$3 == "_rcx_code_end" || $3 == "_rcx_high_load" || $3 == "_rcx_onchip_end" ||
        $3 == "_rcx_high_start" || $3 == "_rcx_high_end" ||
        $3 == "_rcx_stack_top" { sub(/^_/, "", $3); print $3 "=0x" substr($1, length($1) - 3) }')"
    tmp="${TMPDIR:-/tmp}/check_stack.$$"
    trap 'rm -f "$tmp" "$tmp.s"' EXIT
    [ -n "$rcx_high_load" ] || { echo "symbol _rcx_high_load missing from $image"; exit 1; }
    { "$objdump" -d --stop-address="$rcx_code_end" "$image"
      [ "$rcx_high_start" = "$rcx_high_end" ] ||
          "$objdump" -d --start-address="$rcx_high_start" --stop-address="$rcx_high_end" "$image"; } > "$tmp"
    "$objdump" -s --start-address="$rcx_code_end" --stop-address="$rcx_high_load" "$image" > "$tmp.s"
    scan "$tmp" $(( rcx_stack_top - rcx_onchip_end )) "$tmp.s" ;;
*)
    echo "usage: $0 image <objdump> <nm> <image> | scan <listing> <bytes> [<dump>]" >&2; exit 2 ;;
esac
