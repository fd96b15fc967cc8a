/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Bad byte code must never crash the machine or corrupt anything outside what a valid instruction may change.
 *   - unknown opcodes are skipped by the length in their low three bits, 6 and 7 meaning 0 and 1 (spec p. 5);
 *   - direct-only commands (availability "Direct") are not executed from program code;
 *   - a truncated last instruction, or a jump before 0 or past the end of its code object, stops the task;
 *   - out-of-range variable, source, timer, counter, task and subroutine numbers change nothing;
 *   - random programs never change any code (memory map 0x20, UploadRam 0x63, arena bytes).
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <string.h>
#include <cmocka.h>
#include "brick.h"

#define LO(x) ((u8)((unsigned)(x) & 0xFFu))
#define HI(x) ((u8)(((unsigned)(x) >> 8) & 0xFFu))
#define VAR 0
#define CONST 2
#define SETV(v, src, val) 0x14, (u8)(v), (src), LO(val), HI(val)
#define INC(v) 0x24, (u8)(v), CONST, 0x01, 0x00
#define MARK 31 /* global set by the instruction after the one under test */

/* The spec's opcodes (table of contents, pp. 2-3), toggle bit clear. */
static const u8 spec_ops[] = {
    0x10, 0x20, 0x30, 0x40, 0x50, 0x60, 0x70, 0x80, 0x90, 0xA0, 0xB0, 0xD0, 0xE0, 0x06, 0xF6, 0x21, 0x31,
    0x51, 0x61, 0x71, 0x81, 0x91, 0xA1, 0xB1, 0xC1, 0xD1, 0xE1, 0x17, 0x27, 0x37, 0x67, 0x77, 0x97, 0xA7,
    0xB7, 0xD7, 0xF7, 0x02, 0x12, 0x22, 0x32, 0x42, 0x52, 0x62, 0x72, 0x82, 0x92, 0xB2, 0xC2, 0xD2, 0xF2,
    0x03, 0x13, 0x23, 0x33, 0x43, 0x63, 0x73, 0x93, 0xA3, 0xF3, 0x04, 0x14, 0x24, 0x34, 0x44, 0x54, 0x64,
    0x74, 0x84, 0x94, 0xA4, 0xB4, 0x05, 0x15, 0x25, 0x35, 0x45, 0x65, 0x75, 0x85, 0x95, 0xA5, 0xB5, 0xE5,
};
/* Availability "Direct" only (spec pp. 13-15, 18, 30, 36, 50, 61, 68, 84, 87-92, 95). */
static const u8 direct_only[] = { 0x20, 0x30, 0x40, 0x70, 0x61, 0xC1, 0x12, 0xD2, 0x63, 0xA4,
                                  0x15, 0x25, 0x35, 0x45, 0x65, 0x75, 0xA5 };

static int known(u8 op)
{
    return memchr(spec_ops, op & ~RCX_TOGGLE, sizeof spec_ops) != NULL;
}

static unsigned nominal(u8 op)
{
    return (op & 7) >= 6 ? (op & 7) - 6u : (op & 7u); /* spec p. 5, footnote 1 */
}

static void load(struct rcx *b, int is_task, u8 n, const u8 *code, unsigned len)
{
    assert_int_equal(brick_download(b, is_task, n, code, len), 0);
}

static void memmap(struct rcx *b, u8 *out)
{
    u8 cmd = 0x20;
    assert_int_equal(brick_cmd(b, &cmd, 1, out), 189);
}

/* A brick whose task 1 spins with known locals and whose sub 0 and task 2 hold code that must never change. */
static const u8 spinner[] = { SETV(40, CONST, 1234), SETV(47, CONST, -5), 0x27, 0x81 };
static const u8 keep_sub[] = { SETV(0, CONST, 77), 0xF6 };
static const u8 keep_task[] = { 0x14, 0x01, 0x02, 0x05, 0x00, 0x27, 0x81 };

static struct rcx *bystanders(void)
{
    struct rcx *b = brick_new();
    load(b, 0, 0, keep_sub, sizeof keep_sub);
    load(b, 1, 1, spinner, sizeof spinner);
    load(b, 1, 2, keep_task, sizeof keep_task);
    b->global[5] = 200; /* a variable pointing nowhere, for source 36 */
    for (unsigned ms = 0; ms < 1234; ms++)
        vm_tick(b); /* timers 12, 10 ms view 123, so that a stray write to any of them shows */
    brick_start(b, 1);
    vm_run(b, 10);
    assert_int_equal(rcx_local(b, 1, 40 - 32), 1234);
    return b;
}

/* Runs `code` as task 0 next to the bystanders, then checks that nothing but globals 0 and MARK changed:
 * all other globals, task 1's locals and state, every code byte and the memory map reply, timers, sensors,
 * events, outputs, message, program slot. Returns the brick for further checks. */
static struct rcx *run_isolated(const u8 *code, unsigned len, unsigned budget)
{
    static struct rcx before;
    u8 map0[189], map1[189];
    struct rcx *b = bystanders();
    load(b, 1, 0, code, len);
    memmap(b, map0);
    memcpy(&before, b, sizeof before);
    brick_start(b, 0);
    vm_run(b, (u16)budget);
    memmap(b, map1);
    assert_memory_equal(map0, map1, sizeof map0);
    assert_memory_equal(before.arena, b->arena, before.obj_start[RCX_OBJS]);
    assert_memory_equal(before.obj_start, b->obj_start, sizeof before.obj_start);
    for (unsigned i = 1; i < RCX_GLOBALS; i++)
        if (i != MARK && before.global[i] != b->global[i])
            fail_msg("global %u changed from %d to %d", i, before.global[i], b->global[i]);
    assert_memory_equal(&before.task[1], &b->task[1], sizeof before.task[1]);
    assert_memory_equal(before.timer, b->timer, sizeof before.timer);
    assert_memory_equal(before.sensor, b->sensor, sizeof before.sensor);
    assert_memory_equal(before.event, b->event, sizeof before.event);
    assert_memory_equal(&before.out, &b->out, sizeof before.out);
    assert_memory_equal(before.uart, b->uart, sizeof before.uart);
    assert_int_equal(before.message, b->message);
    assert_int_equal(before.watch, b->watch);
    assert_int_equal(before.prog, b->prog);
    assert_int_equal(before.log_size, b->log_size);
    assert_int_equal(b->dl.active, 0);
    assert_int_equal(b->boot_mode, 0);
    return b;
}

/* ------------------------------------------------------------------------------------------------------------ */

static void unknown_opcodes_skipped_by_length(void **state)
{
    static const u8 params[5] = { 0x14, 0x01, 0x02, 0x07, 0x00 }; /* SetVar var1 = 7 if misread as code */
    unsigned op;
    (void)state;
    for (op = 0; op < 256; op++) {
        u8 code[32];
        unsigned n = 0, k, p = nominal((u8)op);
        struct rcx *b;
        if (known((u8)op) || rcx_swan_find((u8)op))
            continue; /* Swan's opcodes are known since issue 16 (test_swan.c) */
        for (k = 0; k < 2; k++) {
            code[n++] = (u8)op;
            memcpy(code + n, params, p);
            n += p;
            memcpy(code + n, (const u8[]){ INC(MARK) }, 5);
            n += 5;
        }
        b = run_isolated(code, n, 100);
        if (b->global[MARK] != 2)
            fail_msg("unknown opcode %02X: continued %d times, expected 2", op, b->global[MARK]);
        assert_int_equal(b->task[0].state, RCX_TASK_IDLE);
        brick_free(b);
    }
}

/* Direct-only commands in program code: skipped by their length, without effect (no deletion, no download,
 * no boot mode). Operands chosen so that executing them would be visible. */
static void direct_only_opcodes_skipped(void **state)
{
    unsigned i;
    (void)state;
    for (i = 0; i < sizeof direct_only; i++) {
        u8 op = direct_only[i], code[16] = { op };
        unsigned p = nominal(op), n;
        struct rcx *b;
        switch (op) {
        case 0x61: code[1] = 1; break;                                     /* DeleteTask 1 */
        case 0xC1: code[1] = 0; break;                                     /* DeleteSub 0 */
        case 0x25: case 0x35: memcpy(code + 1, (const u8[]){ 0, 1, 0, 4, 0 }, 5); break; /* begin download */
        case 0x65: case 0x15: memcpy(code + 1, (const u8[]){ 1, 3, 5, 7, 11 }, 5); break; /* boot-mode key */
        case 0xA5: memcpy(code + 1, (const u8[]){ 0x4C, 0x45, 0x47, 0x4F, 0xAE }, 5); break;
        case 0x45: memcpy(code + 1, (const u8[]){ 1, 0, 0, 0, 0 }, 5); break;
        default: break;
        }
        n = 1 + p;
        memcpy(code + n, (const u8[]){ INC(MARK) }, 5);
        n += 5;
        b = run_isolated(code, n, 100);
        if (b->global[MARK] != 1)
            fail_msg("direct-only %02X in a program: marker %d, expected 1", op, b->global[MARK]);
        assert_int_equal(b->task[1].state, RCX_TASK_RUNNING); /* not stopped by 0x40/0x61/0x70/0xC1 */
        brick_free(b);
    }
}

/* Bit 3 of an opcode byte is the toggle bit; XXXX NNN is the byte code (spec p. 5), in programs too, except for
 * the bytes that are Swan's opcodes (issue 16: 0x2C, 0x2F, 0xFE are no longer SumVar, SJump, EndOfSub there). */
static void toggle_bit_in_program_code(void **state)
{
    static const u8 code[] = { 0x1C, MARK, CONST, 0x05, 0x00, 0x3C, MARK, CONST, 0xFE, 0xFF };
    /* control flow too: 7A = LJump +7 (over SetVar MARK = 99), 1F = Gosub 0, F6 ends the task outside a sub */
    static const u8 flow[] = { 0x7A, 0x07, 0x00, SETV(MARK, CONST, 99), 0x1F, 0x00, 0x3C, MARK, CONST, 0xFE, 0xFF,
                               0xF6, INC(MARK) };
    struct rcx *b = run_isolated(code, sizeof code, 100);
    (void)state;
    assert_int_equal(b->global[MARK], 7);
    brick_free(b);
    b = run_isolated(flow, sizeof flow, 100);
    assert_int_equal(b->global[MARK], 2);     /* jumped, called sub 0, returned, then stopped */
    assert_int_equal(b->global[0], 77);       /* set by sub 0 */
    assert_int_equal(b->task[0].state, RCX_TASK_IDLE);
    brick_free(b);
}

/* Every program instruction cut short by the end of its code: the task stops, nothing else happens. The next
 * object in memory (task 1) begins with bytes that would complete it. */
static void truncated_instruction_stops_task(void **state)
{
    unsigned i, k;
    (void)state;
    for (i = 0; i < 256; i++) {
        u8 op = (u8)i;
        unsigned p = op == 0x85 ? 6 : op == 0x95 ? 7 : nominal(op);
        if ((op & RCX_TOGGLE) || memchr(direct_only, op, sizeof direct_only))
            continue; /* every program instruction, and every unknown opcode */
        for (k = 0; k < p; k++) {
            u8 code[16] = { INC(MARK), op };
            struct rcx *b = run_isolated(code, 6 + k, 100);
            assert_int_equal(b->global[MARK], 1);
            assert_int_equal(b->task[0].state, RCX_TASK_IDLE);
            brick_free(b);
        }
    }
}

/* Jumps that leave the code object stop the task; a jump to exactly its end is the normal end (nqc compiles
 * `return` in a subroutine to a jump to the end, host-tools.md §4). */
static void jumps_outside_code_stop_task(void **state)
{
    static const struct { u8 code[13]; u8 len; } out[] = {
        { { INC(MARK), 0x27, 0x87 }, 7 },                          /* SJump to -1 */
        { { INC(MARK), 0x27, 0x7F }, 7 },                          /* SJump to 133 */
        { { INC(MARK), 0x72, 0x87, 0x00 }, 8 },                    /* LJump to -1 */
        { { INC(MARK), 0x72, 0x00, 0x7F }, 8 },                    /* LJump forward 16256 */
        { { INC(MARK), 0x72, 0xFF, 0xFF }, 8 },                    /* LJump back 32767 */
        { { INC(MARK), 0xF2, 0x00, 0x88 }, 8 },                    /* var0 = -1 < 0: back 8 from 7 */
        { { INC(MARK), 0xF3, 0x00, 0x00, 0x40 }, 9 },              /* forward 8192 */
        { { 0x85, 0x02, 0x02, 0x00, 0x00, 0x01, 0x40, INC(MARK) }, 12 },       /* 0 > 1 fails: +64 */
        { { INC(MARK), 0x95, 0x02, 0x02, 0x00, 0x00, 0x01, 0x00, 0x80 }, 13 }, /* signed -32768 */
        { { INC(MARK), 0x82, 0x02, 0x00, 0x37, 0x40 }, 10 },                   /* loop 0: exit +64 */
        { { INC(MARK), 0x82, 0x02, 0x00, 0x92, 0xFF, 0xFF }, 11 },             /* loop 0: exit +65535 */
    };
    static const u8 caller[] = { 0x17, 0x00, INC(MARK) };
    static const u8 ret[] = { 0x85, 0x82, 0x00, 0x00, 0x00, 0x00, 0x03, 0x27, 0x06, 0x14, 0x01, 0x02, 0x01, 0x00 };
    static const u8 past[] = { 0x27, 0x07, 0x14, 0x01, 0x02, 0x01, 0x00 }; /* to 8, one past the end */
    unsigned i;
    struct rcx *b;
    (void)state;
    for (i = 0; i < sizeof out / sizeof out[0]; i++) {
        b = run_isolated(out[i].code, out[i].len, 200);
        if (b->global[MARK] != (i == 7 ? 0 : 1) || b->task[0].state != RCX_TASK_IDLE)
            fail_msg("case %u: marker %d, state %u", i, b->global[MARK], b->task[0].state);
        brick_free(b);
    }
    /* nqc's `sub s0() { if (x == 0) return; y = 1; }` called from `s0(); z++`: the return jump lands on the end */
    b = brick_new();
    load(b, 0, 0, ret, sizeof ret);
    load(b, 1, 0, caller, sizeof caller);
    brick_start(b, 0);
    assert_true(brick_run_until_idle(b, 100, 10) >= 0);
    assert_int_equal(b->global[MARK], 1);
    assert_int_equal(b->global[1], 0);
    brick_free(b);
    /* one past the end of a subroutine: stopped, not returned */
    b = brick_new();
    load(b, 0, 0, past, sizeof past);
    load(b, 1, 0, caller, sizeof caller);
    brick_start(b, 0);
    assert_true(brick_run_until_idle(b, 100, 10) >= 0);
    assert_int_equal(b->global[MARK], 0);
    brick_free(b);
}

/* Numbers out of range (spec pp. 6-10 and each command's page) change nothing; the program continues. */
static void out_of_range_numbers_change_nothing(void **state)
{
    static const u8 cases[][6] = {
        { SETV(48, CONST, 1) }, { SETV(200, CONST, 1) }, { 0x24, 0xFF, CONST, 1, 0 },
        { 0x05, 0x00, 48, CONST, 1, 0 },            /* variable 48 */
        { 0x05, 0x01, 4, CONST, 1, 0 },             /* timer 4 */
        { 0x05, 0x1A, 4, CONST, 1, 0 },             /* 10 ms timer 4 */
        { 0x05, 0x15, 3, CONST, 1, 0 },             /* counter 3 (counters are globals 0-2) */
        { 0x05, 0x0A, 3, CONST, 1, 0 },             /* sensor type 3 */
        { 0x05, 0x0B, 3, CONST, 0x20, 0 },          /* sensor mode 3 */
        { 0x05, 0x1B, 16, CONST, 1, 0 },            /* click counter 16 */
        { 0x05, 0x1C, 16, CONST, 1, 0 },            /* upper threshold 16 */
        { 0x05, 0x1F, 200, CONST, 50, 0 },          /* duration 200 */
        { 0x05, 0x21, 18, CONST, 1, 0 },            /* UART byte 18 */
        { 0x05, 0x24, 48, CONST, 1, 0 },            /* indirect through variable 48 */
        { 0x05, 0x24, 5, CONST, 1, 0 },             /* indirect: var5 = 200 points nowhere */
        { 0x05, 0x02, 0, CONST, 1, 0 },             /* constant: read-only */
        { 0x05, 0x03, 0, CONST, 1, 0 },             /* motor status: read-only */
        { 0x05, 0x09, 0, CONST, 1, 0 },             /* sensor value: read-only */
        { 0x05, 0x0C, 0, CONST, 1, 0 },             /* sensor raw: read-only */
        { 0x05, 0x11, 0, CONST, 1, 0 },             /* global motor status: read-only */
        { 0x05, 0x17, 0, CONST, 1, 0 },             /* task events: read-only */
        { 0x05, 0x19, 0, CONST, 1, 0 },             /* event state: read-only */
        { 0x05, 0x22, 0, CONST, 1, 0 },             /* battery: read-only */
        { 0x05, 0x23, 0, CONST, 1, 0 },             /* firmware version: read-only */
        { 0x05, 0x05, 0, CONST, 1, 0 }, { 0x05, 0x07, 0, CONST, 1, 0 }, { 0x05, 0x10, 0, CONST, 1, 0 },
        { 0x05, 0x14, 0, CONST, 1, 0 }, { 0x05, 0x20, 0, CONST, 1, 0 }, { 0x05, 0x25, 0, CONST, 1, 0 },
        { 0x05, 0x08, 0, CONST, 5, 0 },             /* program slot 5 (0-4; reference-firmware.md) */
        { 0x05, 0x08, 0, CONST, 0xFF, 0xFF },       /* program slot -1 */
        { 0x05, 0x3F, 0, CONST, 1, 0 }, { 0x05, 0xFF, 0xFF, 0x3F, 0xFF, 0xFF }, /* no such sources */
        { SETV(0, 0x3F, 0) }, { SETV(0, 0x01, 9) }, { SETV(0, VAR, 300) }, { SETV(0, 0x24, 5) }, /* reads */
        { 0xA1, 4 }, { 0xA1, 0xFF }, { 0xD1, 3 }, { 0x97, 3 }, { 0xA7, 3 }, { 0xB7, 3 }, { 0x97, 0xFF },
        { 0x93, 16, 0, 0 }, { 0x93, 0, 11, 0 }, { 0x32, 3, 1 }, { 0x42, 3, 0x20 }, { 0x32, 0, 9 },
        { 0x71, 10 }, { 0x71, 0xFF }, { 0x81, 10 }, { 0x17, 8 }, { 0x17, 0xFF }, { 0x91, 5 }, { 0x91, 0xFF },
        { 0x02, 48, 10 }, { 0x62, 0x00, 40 }, { 0x62, 0x3F, 0 },
    };
    unsigned i;
    (void)state;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        u8 op = cases[i][0], code[16];
        unsigned p = nominal(op);
        struct rcx *b;
        memcpy(code, (const u8[]){ SETV(5, CONST, 200) }, 5);
        memcpy(code + 5, cases[i], 1 + p);
        memcpy(code + 6 + p, (const u8[]){ INC(MARK) }, 5);
        b = run_isolated(code, 11 + p, 100);
        if (b->global[MARK] != 1)
            fail_msg("case %u (%02X %02X %02X): marker %d", i, op, cases[i][1], cases[i][2], b->global[MARK]);
        brick_free(b);
    }
}

/* ------------------------------------------------------------------------------------------------------------ */

/* A subroutine chain 0 -> 1 -> ... -> 7: one return address, so sub 7 returns into sub 6, whose end stops the
 * task (spec pp. 26, 39); and a subroutine calling itself forever runs in bounded memory. */
static void deep_gosub_misuse(void **state)
{
    static const u8 task[] = { 0x17, 0x00, INC(MARK) };
    static const u8 self[] = { INC(0), 0x17, 0x00 };
    struct rcx *b = brick_new();
    unsigned k;
    (void)state;
    for (k = 0; k < RCX_SUBS; k++) {
        u8 sub[12] = { INC(k), 0x17, (u8)(k + 1), INC(k + 8) };
        load(b, 0, (u8)k, sub, k < 7 ? 12 : 5);
    }
    load(b, 1, 0, task, sizeof task);
    brick_start(b, 0);
    assert_true(brick_run_until_idle(b, 100, 10) >= 0);
    for (k = 0; k < 8; k++)
        assert_int_equal(b->global[k], 1);
    for (k = 8; k < 16; k++)
        assert_int_equal(b->global[k], k == 14);
    assert_int_equal(b->global[MARK], 0);
    brick_free(b);

    b = brick_new();
    load(b, 0, 0, self, sizeof self);
    load(b, 1, 0, task, sizeof task);
    brick_start(b, 0);
    assert_int_equal(vm_run(b, 10001), 10001);
    assert_int_equal(b->global[0], 5000);
    assert_int_equal(b->task[0].state, RCX_TASK_RUNNING);
    brick_free(b);
}

/* All 0xFF: by spec p. 5 that was InternMessage (0xF7, toggle bit set); since issue 16 it is Swan's modp on source
 * 0xFF, which does not exist: nothing happens, and the 100 or 101 bytes end in a truncated instruction. */
static void task_of_ff_bytes(void **state)
{
    static u8 ff[101];
    static struct rcx before;
    unsigned len;
    (void)state;
    memset(ff, 0xFF, sizeof ff);
    for (len = 100; len <= 101; len++) {
        struct rcx *b = bystanders();
        load(b, 1, 0, ff, len);
        memcpy(&before, b, sizeof before);
        brick_start(b, 0);
        vm_run(b, 1000);
        assert_int_equal(b->task[0].state, RCX_TASK_IDLE);
        assert_int_equal(b->message, 0);
        assert_memory_equal(before.global, b->global, sizeof before.global);
        assert_memory_equal(before.arena, b->arena, before.obj_start[RCX_OBJS]);
        assert_memory_equal(&before.task[1], &b->task[1], sizeof before.task[1]);
        brick_free(b);
    }
}

/* ------------------------------------------------------------------------------------------------------------ */

static u32 rng = 0x2545F491u;
static u32 next(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 17;
    rng ^= rng << 5;
    return rng;
}

/* Random code: mostly real opcodes with random operands (small numbers half the time), some random bytes. */
static unsigned random_code(u8 *code, unsigned max)
{
    unsigned len = 1 + next() % max, n = 0;
    while (n < len) {
        u8 op = (next() % 4) ? spec_ops[next() % sizeof spec_ops] : (u8)next();
        unsigned p = op == 0x85 ? 6 : op == 0x95 ? 7 : nominal(op), k;
        if (next() % 8 == 0)
            op |= RCX_TOGGLE;
        code[n++] = op;
        for (k = 0; k < p && n < len; k++)
            code[n++] = (u8)((next() % 2) ? next() % 16 : next());
    }
    return len;
}

static void check_invariants(const struct rcx *b)
{
    unsigned n, running = 0;
    assert_true(b->prog < RCX_PROGRAMS);
    for (n = 0; n < RCX_TASKS; n++) {
        const struct rcx_task *t = &b->task[n];
        u8 obj;
        if (t->state == RCX_TASK_IDLE)
            continue;
        assert_true(t->state == RCX_TASK_RUNNING || t->state == RCX_TASK_WAITING);
        running |= (unsigned)(t->state == RCX_TASK_RUNNING) << n;
        assert_true(t->sub == RCX_NO_SUB || t->sub < RCX_SUBS);
        assert_true(t->loop_depth <= RCX_LOOP_LEVELS);
        obj = t->sub == RCX_NO_SUB ? rcx_obj_task(b->prog, n) : rcx_obj_sub(b->prog, t->sub);
        assert_true(t->pc <= mem_obj_size(b, obj));
    }
    assert_int_equal(b->runmask, running); /* the scheduler's set of running tasks */
}

static void random_programs_never_corrupt(void **state)
{
    static const u8 slot1_task[] = { SETV(3, CONST, 9), 0x43, CONST, 5, 0, 0x27, 0x81 };
    static const u8 slot1_sub[] = { 0x24, 0x04, CONST, 1, 0 };
    static struct rcx before;
    unsigned prog;
    (void)state;
    for (prog = 0; prog < 3000; prog++) {
        struct rcx *b = brick_new();
        u8 code[64], map0[189], map1[189], up[RCX_REPLY_MAX];
        u8 sel1[2] = { 0x91, 1 }, sel0[2] = { 0x91, 0 }, ur[4] = { 0x63, 0, 0, 0 };
        unsigned i, ms;
        u16 addr;
        brick_cmd(b, sel1, 2, NULL);
        load(b, 1, 0, slot1_task, sizeof slot1_task);
        load(b, 0, 0, slot1_sub, sizeof slot1_sub);
        brick_cmd(b, sel0, 2, NULL);
        for (i = 0; i < 3; i++)
            load(b, 0, (u8)i, code, random_code(code, sizeof code));
        for (i = 0; i < 4; i++)
            load(b, 1, (u8)i, code, random_code(code, sizeof code));
        memmap(b, map0);
        memcpy(&before, b, sizeof before);
        brick_start(b, 0);
        for (ms = 0; ms < 40; ms++) {
            vm_run(b, 25);
            vm_tick(b);
            check_invariants(b);
        }
        memmap(b, map1);
        assert_memory_equal(map0 + 1, map1 + 1, 90 * 2); /* words 0-89: where every sub and task lives */
        assert_memory_equal(before.arena, b->arena, before.obj_start[RCX_OBJS]);
        /* slot 1's code through UploadRam at the addresses of the memory map (task 1/0 = word 50, sub 1/0 = 8) */
        addr = (u16)(map1[1 + 100] << 8 | map1[1 + 101]);
        ur[1] = LO(addr); ur[2] = HI(addr); ur[3] = sizeof slot1_task;
        assert_int_equal(brick_cmd(b, ur, 4, up), 1 + sizeof slot1_task);
        assert_memory_equal(up + 1, slot1_task, sizeof slot1_task);
        addr = (u16)(map1[1 + 16] << 8 | map1[1 + 17]);
        ur[1] = LO(addr); ur[2] = HI(addr); ur[3] = sizeof slot1_sub;
        assert_int_equal(brick_cmd(b, ur, 4, up), 1 + sizeof slot1_sub);
        assert_memory_equal(up + 1, slot1_sub, sizeof slot1_sub);
        brick_free(b);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(unknown_opcodes_skipped_by_length),
        cmocka_unit_test(direct_only_opcodes_skipped),
        cmocka_unit_test(toggle_bit_in_program_code),
        cmocka_unit_test(truncated_instruction_stops_task),
        cmocka_unit_test(jumps_outside_code_stop_task),
        cmocka_unit_test(out_of_range_numbers_change_nothing),
        cmocka_unit_test(deep_gosub_misuse),
        cmocka_unit_test(task_of_ff_bytes),
        cmocka_unit_test(random_programs_never_corrupt),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
