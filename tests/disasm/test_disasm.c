/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Cross-check of the instruction table against the real nqc: every instruction `nqc -L` lists must have the
 * same offset, length and mnemonic in our disassembler, and every jump the same target. Lengths decide where
 * the interpreter finds the next byte code, so this checks the decoder too.
 *
 * Usage: test_disasm NQC_EXECUTABLE (-TRCX2|-TRCX|-TSwan) FILE.nqc
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "rcx_opcodes.h"
#include "disasm.h"

#define MAX_LINES 1024
#define MAX_CODE 8192

struct line {
    unsigned offset, len;
    char mnemonic[16];
    long last_number;   /* last number among the operands (a jump's target) */
    int has_number;
};

static int failures;

static void fail(const char *chunk, unsigned offset, const char *what)
{
    printf("FAIL %s @%03u: %s\n", chunk, offset, what);
    failures++;
}

static int is_jump(const char *layout)
{
    return strpbrk(layout, "jJfFL") != NULL;
}

static void check_chunk(const char *chunk, const u8 *code, unsigned size, const struct line *lines, unsigned n)
{
    unsigned i, resync = 0;
    for (i = 0; i < n; i++) {
        const struct line *l = &lines[i];
        /* Swan's opcodes are read on all eight bits (0x2F is setsv, not SJump with its toggle bit) */
        const struct rcx_opname *name = rcx_swanname_find(code[l->offset]) ? NULL : rcx_opname_find(code[l->offset]);
        char text[128], mnem[16], msg[256];
        unsigned len;
        const char *p;

        /* nqc -L does not know Swan's pop `01 n` (its table has it commented out): it lists 01 as a one-byte "?" and
         * decodes n, and perhaps more, as instructions. Its lines are skipped until they meet one of our instruction
         * boundaries again. */
        if (resync) {
            while (resync < l->offset)
                resync += rcx_disasm_one(code, size, resync, text, sizeof text);
            if (resync > l->offset)
                continue;
            resync = 0;
        }
        len = rcx_disasm_one(code, size, l->offset, text, sizeof text);
        if (code[l->offset] == 0x01 && strcmp(l->mnemonic, "?") == 0 && len == 2) {
            resync = l->offset + len;
            continue;
        }

        if (len != l->len) {
            snprintf(msg, sizeof msg, "length %u, nqc says %u (%s)", len, l->len, text);
            fail(chunk, l->offset, msg);
            continue;
        }
        sscanf(text, "%15s", mnem);
        if (strcmp(mnem, l->mnemonic) != 0) {
            snprintf(msg, sizeof msg, "mnemonic %s, nqc says %s", mnem, l->mnemonic);
            fail(chunk, l->offset, msg);
        }
        if (name && is_jump(name->layout) && l->has_number) {
            long ours;
            p = strrchr(text, ' ');
            ours = p ? strtol(p + 1, NULL, 10) : -1;
            /* nqc's listing reads the unsigned 8-bit forward distance of 0x37 as signed: its target is 256 short. */
            if (ours != l->last_number &&
                !((code[l->offset] & ~RCX_TOGGLE) == RCX_OP_SCHECK_LOOP && ours == l->last_number + 256)) {
                snprintf(msg, sizeof msg, "jump target %ld, nqc says %ld (%s)", ours, l->last_number, text);
                fail(chunk, l->offset, msg);
            }
        }
    }
}

int main(int argc, char **argv)
{
    static struct line lines[MAX_LINES];
    static u8 code[MAX_CODE];
    char cmd[1024], buf[512], chunk[128] = "";
    unsigned nlines = 0, size = 0, chunks = 0, instructions = 0;
    FILE *f;

    if (argc != 4)
        return 2;
    snprintf(cmd, sizeof cmd, "'%s' %s -L '%s'", argv[1], argv[2], argv[3]);
    f = popen(cmd, "r");
    if (!f)
        return 2;
    while (fgets(buf, sizeof buf, f)) {
        char *hex;
        unsigned off;
        if (strncmp(buf, "*** Task", 8) == 0 || strncmp(buf, "*** Sub", 7) == 0 || strncmp(buf, "Total", 5) == 0) {
            if (nlines) {
                check_chunk(chunk, code, size, lines, nlines);
                chunks++;
                instructions += nlines;
            }
            nlines = size = 0;
            snprintf(chunk, sizeof chunk, "%.*s", (int)strcspn(buf + 4, ","), buf + 4);
            continue;
        }
        if (sscanf(buf, "%3u ", &off) != 1 || strlen(buf) < 8 || nlines == MAX_LINES)
            continue;
        /* Columns: offset, mnemonic, operands, then two spaces or more before the hex bytes. */
        hex = strstr(buf + 4, "  ");
        while (hex && strstr(hex + 1, "  "))
            hex = strstr(hex + 1, "  ");
        if (!hex)
            continue;
        {
            struct line *l = &lines[nlines++];
            char *ops = buf + 4, *end, *p;
            unsigned v;
            int used;
            l->offset = off;
            l->len = 0;
            sscanf(ops, "%15s", l->mnemonic);
            for (p = hex; sscanf(p, " %2x%n", &v, &used) == 1 && size < MAX_CODE; p += used) {
                code[size++] = (u8)v;
                l->len++;
            }
            /* Last number among the operands (text between the mnemonic and the hex column). */
            *hex = 0;
            l->has_number = 0;
            for (p = ops + strlen(l->mnemonic); *p; p++) {
                if ((*p == '-' && p[1] >= '0' && p[1] <= '9') || (*p >= '0' && *p <= '9')) {
                    l->last_number = strtol(p, &end, 10);
                    l->has_number = 1;
                    p = end - 1;
                }
            }
            if (off != size - l->len)
                fail(chunk, off, "nqc listing offset disagrees with its own bytes");
        }
    }
    if (pclose(f) != 0) {
        printf("nqc failed on %s\n", argv[3]);
        return 1;
    }
    printf("%s %s: %u chunks, %u instructions checked, %d failures\n", argv[2], argv[3], chunks, instructions,
           failures);
    return failures || instructions == 0 ? 1 : 0;
}
