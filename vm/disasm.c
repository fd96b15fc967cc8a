/* SPDX-License-Identifier: MPL-2.0 */
/* Disassembler for host tools and tests. Reads only the operand layouts of rcx_opcodes.def. */
#include <string.h>
#include "rcx_opcodes.h"
#include "disasm.h"

static const char *const source_names[] = {
    "var", "Timer", "", "MotorStatus", "Random", "PwrSigned", "?6", "BrakePwr", "Program", "Input", "SensorType",
    "SensorMode", "SensorRaw", "SensorBool", "Watch", "Message", "Power128", "GlobalMotor", "EventType", "Event",
    "EventCnt", "Counter", "MSTimer", "TaskEvents", "System", "EventState", "FastTimer", "ClickCounter",
    "UpperLimit", "LowerLimit", "Hysteresis", "Duration", "Power8", "uart", "Battery", "FirmwareVersion", "*var",
    "LogTypeInd", "LogTypeDir", "LogValInd", "LogValDir", "LogByteInd", "LogByteDir", "gvar", "*gvar",
};

static int put_source(char *p, size_t n, unsigned src, int value)
{
    if (src == 2)
        return snprintf(p, n, "%d", value);
    if (src == 0 || src == 33 || src == 43)
        return snprintf(p, n, "%s[%d]", source_names[src], value);
    if (src == 44)
        return snprintf(p, n, "*gvar[%d]", value);
    if (src < sizeof source_names / sizeof source_names[0])
        return snprintf(p, n, "%s(%d)", source_names[src], value);
    return snprintf(p, n, "src%u(%d)", src, value);
}

static int put_jump(char *p, size_t n, long target)
{
    return snprintf(p, n, "%ld", target);
}

static const char *const motor_verbs[2][4] = { { "Float", "Off", "On", "?" }, { "Rev", "Flip", "Fwd", "?" } };

static int put_motors(char *p, size_t n, u8 m)
{
    char list[4];
    int k = 0;
    if (m & 1) list[k++] = 'A';
    if (m & 2) list[k++] = 'B';
    if (m & 4) list[k++] = 'C';
    list[k] = 0;
    return snprintf(p, n, "%s", k ? list : "-");
}

static const char *const relations[4] = { "<=", ">=", "!=", "==" }; /* the negated relation: when the jump is taken */

unsigned rcx_disasm_one(const u8 *code, unsigned size, unsigned pc, char *buf, size_t bufsize)
{
    u8 op = (u8)(code[pc] & ~RCX_TOGGLE);
    const struct rcx_opname *name = rcx_opname_find(op);
    const struct rcx_swanname *swan = rcx_swanname_find(code[pc]); /* all eight bits, as the interpreter */
    unsigned len = 1u + rcx_prog_params(code[pc]);
    const char *layout, *layouts;
    char mnemonic[16];
    const u8 *a = code + pc + 1;
    unsigned field = pc + 1;
    char *p = buf;
    size_t left = bufsize;
    int w;

    if (!swan && op == RCX_OP_CONTINUE_DL && pc + 5 <= size)
        len = 6u + RCX_LE16(code + pc + 3);
    if (pc + len > size) {
        snprintf(buf, bufsize, "(truncated)");
        return 0;
    }
    if (swan) {
        snprintf(mnemonic, sizeof mnemonic, swan->lasm, rcx_swan_ops[code[pc] & 7]);
        layouts = swan->layout;
    } else if (name) {
        snprintf(mnemonic, sizeof mnemonic, "%s", name->lasm[0] ? name->lasm : name->name);
        layouts = name->layout;
    } else {
        snprintf(buf, bufsize, "?%02x", op);
        return len;
    }
    w = snprintf(p, left, "%-8s ", mnemonic);
    p += w, left -= (size_t)w;
    for (layout = layouts; *layout && left > 1; layout++) {
        if (layout != layouts) {
            w = snprintf(p, left, ", ");
            p += w, left -= (size_t)w;
        }
        switch (*layout) {
        case 'b': case 'x': w = snprintf(p, left, "%u", a[0]); a += 1; break;
        case 'v': w = snprintf(p, left, "var[%u]", a[0]); a += 1; break;
        case 'g': w = snprintf(p, left, "gvar[%u]", a[0]); a += 1; break;
        case 'H': w = snprintf(p, left, "%d", (s16)(u16)(a[0] << 8 | a[1])); a += 2; break;
        case 'w': w = snprintf(p, left, "%u", RCX_LE16(a)); a += 2; break;
        case 's': w = put_source(p, left, a[0], a[1]); a += 2; break;
        case 'S': w = put_source(p, left, a[0], (s16)RCX_LE16(a + 1)); a += 3; break;
        case 'd': w = put_source(p, left, a[0] & 0x3F, a[1]); a += 2; break;
        case 'm': w = put_motors(p, left, a[0]); a += 1; break;
        case 'M': case 'D':
            w = put_motors(p, left, a[0]);
            w += snprintf(p + w, left - (size_t)w, ", %s", motor_verbs[*layout == 'D'][a[0] >> 6]);
            a += 1;
            break;
        case 'j': {
            long d = a[0] & 0x7F;
            w = put_jump(p, left, (long)(field + (unsigned)(a - code - pc - 1)) + ((a[0] & 0x80) ? -d : d));
            a += 1;
            break;
        }
        case 'J': {
            long d = (long)(a[0] & 0x7F) | ((long)a[1] << 7);
            w = put_jump(p, left, (long)(field + (unsigned)(a - code - pc - 1)) + ((a[0] & 0x80) ? -d : d));
            a += 2;
            break;
        }
        case 'f': w = put_jump(p, left, (long)(field + (unsigned)(a - code - pc - 1)) + a[0]); a += 1; break;
        case 'F': w = put_jump(p, left, (long)(field + (unsigned)(a - code - pc - 1)) + RCX_LE16(a)); a += 2; break;
        case 'L':
            w = put_jump(p, left, (long)(field + (unsigned)(a - code - pc - 1)) + (s16)RCX_LE16(a));
            a += 2;
            break;
        case 'c':
            w = put_source(p, left, a[0] & 0x3F, (s16)RCX_LE16(a + 2));
            w += snprintf(p + w, left - (size_t)w, " %s ", relations[a[0] >> 6]);
            w += put_source(p + w, left - (size_t)w, a[1] & 0x3F, a[4]);
            a += 5;
            break;
        case 'k': w = snprintf(p, left, "<%u bytes>", RCX_LE16(a - 2)); break;
        default: w = 0; break;
        }
        if (w < 0 || (size_t)w >= left)
            break;
        p += w, left -= (size_t)w;
    }
    while (p > buf && p[-1] == ' ')
        *--p = 0;
    return len;
}

void rcx_disasm_listing(FILE *out, const u8 *code, unsigned size)
{
    unsigned pc = 0, i, len;
    char text[96];

    while (pc < size) {
        len = rcx_disasm_one(code, size, pc, text, sizeof text);
        fprintf(out, "%03u %-42s ", pc, text);
        for (i = 0; i < (len ? len : size - pc); i++)
            fprintf(out, "%02x ", code[pc + i]);
        fprintf(out, "\n");
        if (!len)
            break;
        pc += len;
    }
}
