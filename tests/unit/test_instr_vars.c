/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Variable arithmetic SetVar..OrVar (0x14-0x94, spec pp. 75-83) from several sources, run as program code and as
 * direct commands. Edge values follow reference-firmware.md "Arithmetic" (observed on firm0328); variable ranges
 * follow spec p. 6 (source 0: "I: 0-31, D: 0-47") and p. 5 (locals only exist in a running program).
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
#define TIMER 1
#define CONST 2
#define RANDOM 4
#define PROGRAM 8
#define WATCH 14
#define COUNTER 21
#define TIMER10 26
#define FIRMWARE 35
#define INDIRECT 36
#define OPV(op, v, src, val) (op), (u8)(v), (src), LO(val), HI(val)
#define SETV(v, src, val) OPV(0x14, v, src, val)
#define SUMV(v, src, val) OPV(0x24, v, src, val)
#define WAIT(n) 0x43, CONST, LO(n), HI(n)

enum { SET = 0x14, SUM = 0x24, SUB = 0x34, DIV = 0x44, MUL = 0x54, SGN = 0x64, ABS = 0x74, AND = 0x84, OR = 0x94 };
static const u8 all_ops[9] = { SET, SUM, SUB, DIV, MUL, SGN, ABS, AND, OR };
/* Reply opcodes as printed on pp. 75-83 (toggle bit shown as zero, spec p. 11). */
static const u8 spec_reply[9] = { 0xE3, 0xD3, 0xC3, 0xB3, 0xA3, 0x93, 0x83, 0x73, 0x63 };

static void load(struct rcx *b, int is_task, u8 n, const u8 *code, unsigned len)
{
    assert_int_equal(brick_download(b, is_task, n, code, len), 0);
}

/* Run task 0 to completion. */
static void run_task0(struct rcx *b)
{
    brick_start(b, 0);
    assert_true(brick_run_until_idle(b, 2000, 10) >= 0);
}

/* One direct command; asserts it is answered by one byte, the complement of the opcode as sent
 * (host-tools.md §1: the reply opcode is the complement of the sent one; spec p. 11 prints it with bit 3 clear). */
static void direct_op(struct rcx *b, u8 op, u8 v, u8 src, u16 val)
{
    u8 cmd[5] = { OPV(op, v, src, val) }, reply[RCX_REPLY_MAX];
    unsigned i, n = brick_cmd(b, cmd, 5, reply);
    assert_int_equal(n, 1);
    assert_int_equal(reply[0], (u8)~op);
    for (i = 0; i < 9; i++)
        if (all_ops[i] == (op & ~RCX_TOGGLE))
            assert_int_equal(reply[0] & ~RCX_TOGGLE, spec_reply[i]);
}

/* ------------------------------------------------------------------------------------------------------------ */
/* Edge cases, one table, run both ways. */

struct arith_case { u8 op; s16 init; u8 src; s16 val; s16 expect; const char *why; };

static const struct arith_case edge[] = {
    { SET, 99, CONST, 1234, 1234, "p. 75" },
    { SET, 99, CONST, -7, -7, "p. 6: constants are -32768..32767" },
    { SUM, 10, CONST, -3, 7, "p. 76" },
    { SUM, 32767, CONST, 1, -32768, "16-bit wrap (reference-firmware.md)" },
    { SUB, 5, CONST, 8, -3, "p. 77" },
    { SUB, -32768, CONST, 1, 32767, "16-bit wrap" },
    { MUL, 300, CONST, 300, 24464, "300 x 300 = 24464 (reference-firmware.md)" },
    { MUL, -3, CONST, 7, -21, "p. 79" },
    { MUL, -32768, CONST, -1, -32768, "16-bit wrap" },
    { DIV, 100, CONST, 7, 14, "p. 78" },
    { DIV, -7, CONST, 2, -3, "truncates toward zero (reference-firmware.md)" },
    { DIV, 7, CONST, -2, -3, "truncates toward zero" },
    { DIV, -7, CONST, -2, 3, "truncates toward zero" },
    { DIV, 7, CONST, 0, 7, "p. 78: division by zero is ignored" },
    { DIV, -32768, CONST, -1, -32768, "reference-firmware.md" },
    { SGN, 99, CONST, -5, -1, "sign(-5) = -1 (p. 80)" },
    { SGN, 99, CONST, 0, 0, "p. 80" },
    { SGN, 99, CONST, 300, 1, "p. 80" },
    { SGN, 99, CONST, -32768, -1, "p. 80" },
    { ABS, 99, CONST, -5, 5, "p. 81" },
    { ABS, 99, CONST, 7, 7, "p. 81" },
    { ABS, 99, CONST, -32768, 32767, "abs(-32768) = 32767 (reference-firmware.md)" },
    { AND, 0x0F0F, CONST, 0x00FF, 0x000F, "p. 82" },
    { AND, -1, CONST, 0x1234, 0x1234, "p. 82" },
    { OR, 0x0F00, CONST, 0x00F0, 0x0FF0, "p. 83" },
    { OR, (s16)0x8000, CONST, 1, (s16)0x8001, "p. 83" },
};

static void edge_cases_as_program(void **state)
{
    unsigned i;
    (void)state;
    for (i = 0; i < sizeof edge / sizeof edge[0]; i++) {
        const struct arith_case *c = &edge[i];
        struct rcx *b = brick_new();
        u8 code[] = { SETV(5, CONST, c->init), OPV(c->op, 5, c->src, c->val) };
        load(b, 1, 0, code, sizeof code);
        run_task0(b);
        if (b->global[5] != c->expect)
            fail_msg("program %02X: %d op %d = %d, expected %d (%s)", c->op, c->init, c->val, b->global[5],
                     c->expect, c->why);
        brick_free(b);
    }
}

static void edge_cases_as_direct_commands(void **state)
{
    unsigned i;
    (void)state;
    for (i = 0; i < sizeof edge / sizeof edge[0]; i++) {
        const struct arith_case *c = &edge[i];
        struct rcx *b = brick_new();
        direct_op(b, SET, 5, CONST, (u16)c->init);
        /* every other case with the toggle bit set: it marks a new command, never changes its meaning (p. 5) */
        direct_op(b, (u8)(c->op | ((i & 1) ? RCX_TOGGLE : 0)), 5, c->src, (u16)c->val);
        if (b->global[5] != c->expect)
            fail_msg("direct %02X: %d op %d = %d, expected %d (%s)", c->op, c->init, c->val, b->global[5],
                     c->expect, c->why);
        brick_free(b);
    }
}

/* ------------------------------------------------------------------------------------------------------------ */
/* Every operation from sources that all yield 6 (then -6), variable initially 20. */

static const s16 with_6[9] = { 6, 26, 14, 3, 120, 1, 6, 20 & 6, 20 | 6 };
static const s16 with_minus_6[9] = { -6, 14, 26, -3, -120, -1, 6, 20 & -6, 20 | -6 };

/* Make source `src` yield `v` and return the index to read it with. */
static u16 prepare_source(struct rcx *b, u8 src, s16 v)
{
    u8 cmd[6];
    switch (src) {
    case VAR:
        direct_op(b, SET, 3, CONST, (u16)v);
        return 3;
    case COUNTER: /* counters are globals 0-2 (spec p. 8) */
        direct_op(b, SET, 2, CONST, (u16)v);
        return 2;
    case INDIRECT: /* var[1] = 4 points at var[4] (spec p. 10) */
        direct_op(b, SET, 1, CONST, 4);
        direct_op(b, SET, 4, CONST, (u16)v);
        return 1;
    case TIMER: /* SetSourceValue timer 2 = v (spec p. 86; nqc SetTimer encodes 05 01 n 02 lo hi) */
        cmd[0] = 0x05; cmd[1] = TIMER; cmd[2] = 2; cmd[3] = CONST; cmd[4] = LO(v); cmd[5] = HI(v);
        assert_int_equal(brick_cmd(b, cmd, 6, NULL), 1);
        return 2;
    default: /* CONST */
        return (u16)v;
    }
}

static void check_all_ops_from(u8 src, s16 v, const s16 *expect, int as_program)
{
    unsigned i;
    for (i = 0; i < 9; i++) {
        struct rcx *b = brick_new();
        u16 index = prepare_source(b, src, v);
        if (as_program) {
            u8 code[] = { SETV(10, CONST, 20), OPV(all_ops[i], 10, src, index) };
            load(b, 1, 0, code, sizeof code);
            run_task0(b);
        } else {
            direct_op(b, SET, 10, CONST, 20);
            direct_op(b, all_ops[i], 10, src, index);
        }
        if (b->global[10] != expect[i])
            fail_msg("%s %02X: 20 op source %u (= %d) gave %d, expected %d", as_program ? "program" : "direct",
                     all_ops[i], src, v, b->global[10], expect[i]);
        brick_free(b);
    }
}

static void all_ops_from_constant(void **state)
{
    (void)state;
    check_all_ops_from(CONST, 6, with_6, 1);
    check_all_ops_from(CONST, 6, with_6, 0);
    check_all_ops_from(CONST, -6, with_minus_6, 1);
    check_all_ops_from(CONST, -6, with_minus_6, 0);
}

static void all_ops_from_variable(void **state)
{
    (void)state;
    check_all_ops_from(VAR, 6, with_6, 1);
    check_all_ops_from(VAR, 6, with_6, 0);
    check_all_ops_from(VAR, -6, with_minus_6, 1);
    check_all_ops_from(VAR, -6, with_minus_6, 0);
}

static void all_ops_from_timer_counter_indirect(void **state)
{
    (void)state;
    check_all_ops_from(TIMER, 6, with_6, 1);
    check_all_ops_from(TIMER, 6, with_6, 0);
    check_all_ops_from(COUNTER, 6, with_6, 1);
    check_all_ops_from(COUNTER, -6, with_minus_6, 0);
    check_all_ops_from(INDIRECT, 6, with_6, 1);
    check_all_ops_from(INDIRECT, -6, with_minus_6, 0);
}

static void setvar_from_clock_sources(void **state)
{
    struct rcx *b = brick_new();
    u8 setw[3] = { 0x22, 1, 2 }; /* SetWatch 1:02 (spec p. 51) */
    unsigned i;
    (void)state;
    for (i = 0; i < 1250; i++)
        vm_tick(b); /* 1.25 s: 100 ms timers read 12, the 10 ms view 125 (reference-firmware.md) */
    assert_int_equal(brick_cmd(b, setw, 3, NULL), 1);
    direct_op(b, SET, 0, TIMER, 1);
    direct_op(b, SET, 1, TIMER10, 1);
    direct_op(b, SET, 2, WATCH, 0);
    direct_op(b, SET, 3, PROGRAM, 0);
    direct_op(b, SET, 4, FIRMWARE, 0);
    assert_int_equal(b->global[0], 12);
    assert_int_equal(b->global[1], 125);
    assert_int_equal(b->global[2], 62);  /* hours*60 + minutes (spec p. 7) */
    assert_int_equal(b->global[3], 0);   /* program slot 0 after power-on */
    assert_int_equal(b->global[4], 328); /* version x 100 (spec p. 9; firm0328 = 3.28) */
    brick_free(b);
}

/* Random (source 4): between 0 and the given range (spec p. 6). */
static void random_source_stays_in_range(void **state)
{
    struct rcx *b = brick_new();
    unsigned i, seen = 0;
    u8 code[] = { SETV(0, RANDOM, 10), SUMV(1, RANDOM, 10), OPV(SUB, 2, RANDOM, 10), OPV(MUL, 3, RANDOM, 10) };
    (void)state;
    load(b, 1, 0, code, sizeof code);
    for (i = 0; i < 300; i++) {
        b->global[1] = 100;
        b->global[2] = 100;
        b->global[3] = 100;
        run_task0(b);
        assert_in_range(b->global[0], 0, 10);
        assert_in_range(b->global[1], 100, 110);
        assert_in_range(b->global[2], 90, 100);
        assert_in_range(b->global[3], 0, 1000);
        assert_int_equal(b->global[3] % 100, 0);
        seen |= 1u << b->global[0];
        direct_op(b, SET, 4, RANDOM, 3); /* and as a direct command */
        assert_in_range(b->global[4], 0, 3);
    }
    /* a random number generator: many different values come out over 300 draws */
    assert_true(__builtin_popcount(seen) >= 6);
    brick_free(b);
}

/* Writing random 0 seeds the generator (spec p. 6): the same seed gives the same sequence. */
static void random_seed_repeats_sequence(void **state)
{
    static const u8 seed[6] = { 0x05, RANDOM, 0, CONST, 0x07, 0x00 }; /* nqc SetRandomSeed(7) */
    struct rcx *b = brick_new();
    s16 first[8];
    unsigned i;
    (void)state;
    assert_int_equal(brick_cmd(b, seed, 6, NULL), 1);
    for (i = 0; i < 8; i++) {
        direct_op(b, SET, 0, RANDOM, 32767);
        first[i] = b->global[0];
    }
    assert_int_equal(brick_cmd(b, seed, 6, NULL), 1);
    for (i = 0; i < 8; i++) {
        direct_op(b, SET, 0, RANDOM, 32767);
        assert_int_equal(b->global[0], first[i]);
    }
    brick_free(b);
}

/* ------------------------------------------------------------------------------------------------------------ */
/* Variable numbers. */

struct snapshot { s16 global[RCX_ALL_GLOBALS]; u8 arena[RCX_ARENA_SIZE]; };

static void take(const struct rcx *b, struct snapshot *s)
{
    memcpy(s->global, b->global, sizeof s->global);
    memcpy(s->arena, b->arena, sizeof s->arena);
}

/* Direct commands have no task, so no locals: variables 32-47 are not theirs (spec p. 6 "I: 0-31", p. 5). */
static void direct_writes_to_locals_are_ignored(void **state)
{
    static const u8 loop[] = { SETV(40, CONST, 5), 0x27, 0x81 }; /* local 40 = 5, then jmp 0 forever (p. 11) */
    struct rcx *b = brick_new();
    static struct snapshot before, after;
    unsigned i, v;
    (void)state;
    load(b, 1, 0, loop, sizeof loop);
    brick_start(b, 0);
    brick_run_ms(b, 5, 10);
    assert_int_equal(rcx_local(b, 0, 40 - 32), 5);
    take(b, &before);
    for (v = 32; v < 48; v++)
        for (i = 0; i < 9; i++)
            direct_op(b, all_ops[i], (u8)v, CONST, 77);
    take(b, &after);
    assert_memory_equal(&before, &after, sizeof before);
    brick_free(b);
}

/* Inside a task, 32-47 are that task's own locals (spec p. 5: 16 locals for each task). */
static void locals_are_per_task(void **state)
{
    static const u8 t0[] = { 0x71, 0x01,                  /* start task 1 */
                             SETV(40, CONST, 111), SUMV(40, CONST, 1), WAIT(2), SETV(0, VAR, 40) };
    static const u8 t1[] = { SETV(40, CONST, 222), OPV(MUL, 40, CONST, 2), WAIT(2), SETV(1, VAR, 40),
                             SETV(47, CONST, -9), SETV(3, VAR, 47) };
    struct rcx *b = brick_new();
    (void)state;
    load(b, 1, 0, t0, sizeof t0);
    load(b, 1, 1, t1, sizeof t1);
    run_task0(b);
    assert_int_equal(b->global[0], 112);
    assert_int_equal(b->global[1], 444);
    assert_int_equal(b->global[3], -9);
    assert_int_equal(rcx_local(b, 0, 40 - 32), 112);
    assert_int_equal(rcx_local(b, 1, 40 - 32), 444);
    assert_int_equal(rcx_local(b, 1, 47 - 32), -9);
    brick_free(b);
}

/* Locals are how parameters reach a subroutine (spec p. 5): the sub sees the calling task's locals. */
static void subroutine_sees_callers_locals(void **state)
{
    static const u8 sub0[] = { SETV(33, VAR, 32), OPV(MUL, 33, CONST, 2) }; /* local33 = local32 * 2 */
    static const u8 t0[] = { 0x71, 0x01, SETV(32, CONST, 3), 0x17, 0x00, WAIT(3), SETV(0, VAR, 33) };
    static const u8 t1[] = { SETV(32, CONST, 50), 0x17, 0x00, WAIT(3), SETV(1, VAR, 33) };
    struct rcx *b = brick_new();
    (void)state;
    load(b, 0, 0, sub0, sizeof sub0);
    load(b, 1, 0, t0, sizeof t0);
    load(b, 1, 1, t1, sizeof t1);
    run_task0(b);
    assert_int_equal(b->global[0], 6);
    assert_int_equal(b->global[1], 100);
    brick_free(b);
}

/* Variable numbers 48 and up exist nowhere (spec p. 6: 0-47): nothing may change. */
static void variables_48_and_up_touch_nothing(void **state)
{
    struct rcx *b = brick_new();
    static struct snapshot before, after;
    unsigned v, i;
    (void)state;
    for (v = 48; v < 256; v += 13)
        for (i = 0; i < 9; i++) {
            take(b, &before);
            direct_op(b, all_ops[i], (u8)v, CONST, 77);
            take(b, &after);
            assert_memory_equal(&before, &after, sizeof before);
        }
    brick_free(b);
}

/* Variables 48-255 of a program are the globals of those numbers, in an RCX 2.0 program too (swan-target.md 4,
 * issue 16; before it they were ignored). */
static void variables_48_to_255_are_globals_in_programs(void **state)
{
    static const u8 code[] = { SETV(48, CONST, 99), SUMV(49, CONST, 1), OPV(OR, 63, CONST, -1),
                               OPV(ABS, 128, CONST, -3), SETV(255, CONST, 7), SETV(0, CONST, 1) };
    struct rcx *b = brick_new();
    static struct snapshot before, after;
    (void)state;
    load(b, 1, 0, code, sizeof code);
    take(b, &before);
    run_task0(b);
    take(b, &after);
    assert_int_equal(b->global[0], 1); /* the last instruction still ran */
    assert_int_equal(b->global[48], 99);
    assert_int_equal(b->global[49], 1);
    assert_int_equal(b->global[63], -1);
    assert_int_equal(b->global[128], 3);
    assert_int_equal(b->global[255], 7);
    after.global[0] = after.global[48] = after.global[49] = after.global[63] = after.global[128] = after.global[255] = 0;
    assert_memory_equal(&before, &after, sizeof before);
    brick_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(edge_cases_as_program),
        cmocka_unit_test(edge_cases_as_direct_commands),
        cmocka_unit_test(all_ops_from_constant),
        cmocka_unit_test(all_ops_from_variable),
        cmocka_unit_test(all_ops_from_timer_counter_indirect),
        cmocka_unit_test(setvar_from_clock_sources),
        cmocka_unit_test(random_source_stays_in_range),
        cmocka_unit_test(random_seed_repeats_sequence),
        cmocka_unit_test(direct_writes_to_locals_are_ignored),
        cmocka_unit_test(locals_are_per_task),
        cmocka_unit_test(subroutine_sees_callers_locals),
        cmocka_unit_test(variables_48_and_up_touch_nothing),
        cmocka_unit_test(variables_48_to_255_are_globals_in_programs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
