/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Swan's byte codes (issue 16): every opcode of swan-target.md 2 with its byte layout as the table there and
 * `nqc -TSwan -L` give it, every source of 3, and the OpenRCX rules of 4. Expected values are worked out from those
 * rules (C's 16-bit arithmetic), not taken from the machine.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <string.h>
#include <cmocka.h>
#include "brick.h"
#include "sources.h"

#define LO(x) ((u8)((unsigned)(x) & 0xFFu))
#define HI(x) ((u8)(((unsigned)(x) >> 8) & 0xFFu))
#define VAR 0
#define TIMER 1
#define CONST 2
#define GVAR 43
#define IGVAR 44
#define SRC(s, v) (s), LO(v), HI(v)           /* T v16 */
#define OP7(op, d, di, s, si) (op), SRC(d, di), SRC(s, si)
#define SETV(v, src, val) 0x14, (u8)(v), (src), LO(val), HI(val)
#define WAIT(n) 0x43, CONST, LO(n), HI(n)

/* Runs `code` as task 0 of slot 0 (a fresh brick) until it ends. */
static struct rcx *run(const u8 *code, unsigned len)
{
    struct rcx *b = brick_new();
    assert_int_equal(brick_download(b, 1, 0, code, len), 0);
    brick_start(b, 0);
    assert_true(brick_run_until_idle(b, 2000, 10) >= 0);
    return b;
}

/* ------------------------------------------------------------------------------------------------------------ */
/* The decoder: lengths of swan-target.md 2, on all eight bits. */

static const struct { u8 code, count, len; } spec_lengths[] = {
    { 0x2B, 1, 3 }, { 0x2C, 1, 4 }, { 0x2D, 1, 4 }, { 0x2F, 1, 7 }, { 0x48, 8, 3 }, { 0x58, 8, 4 }, { 0xC8, 8, 4 },
    { 0x08, 8, 7 }, { 0xF8, 8, 7 }, { 0x7B, 1, 7 }, { 0x7C, 1, 7 }, { 0x88, 1, 7 }, { 0x98, 1, 7 }, { 0x99, 1, 7 },
    { 0x7E, 1, 7 }, { 0x7F, 1, 7 }, { 0x9B, 1, 7 }, { 0x47, 1, 4 }, { 0xC7, 1, 2 }, { 0xA2, 1, 3 }, { 0xB3, 1, 4 },
    { 0xC3, 1, 6 }, { 0xC4, 1, 6 }, { 0xE3, 1, 4 }, { 0x01, 1, 2 },
};

static unsigned spec_len(u8 op)
{
    unsigned i;
    for (i = 0; i < sizeof spec_lengths / sizeof spec_lengths[0]; i++)
        if (op >= spec_lengths[i].code && op < spec_lengths[i].code + spec_lengths[i].count)
            return spec_lengths[i].len;
    return 0;
}

static void decoder_lengths_on_eight_bits(void **state)
{
    unsigned op, swan = 0;
    (void)state;
    for (op = 0; op < 256; op++) {
        unsigned want = spec_len((u8)op);
        if (want) {
            swan++;
            assert_non_null(rcx_swan_find((u8)op));
            if (rcx_prog_params((u8)op) + 1u != want)
                fail_msg("opcode %02X: length %u, swan-target.md says %u", op, rcx_prog_params((u8)op) + 1u, want);
        } else {
            /* any other byte keeps its RCX 2.0 meaning, toggle bit folded */
            assert_null(rcx_swan_find((u8)op));
            assert_int_equal(rcx_prog_params((u8)op), rcx_op_params((u8)(op & ~RCX_TOGGLE)));
        }
    }
    assert_int_equal(swan, 25 + 5 * 7); /* 20 single opcodes and five families of eight */
}

/* ------------------------------------------------------------------------------------------------------------ */
/* Assignments and the eight-fold arithmetic families. */

static void global_assignments(void **state)
{
    static const u8 code[] = {
        0x2B, 5, 0xFF,                     /* setgb gvar[5], 255: byte constants are unsigned */
        0x2C, 1, 0x01, 0x2C,               /* setgw gvar[1], 300: high byte first (swan-target.md 1) */
        0x2C, 2, 0xFF, 0xFE,               /* -2 */
        0x2D, 3, CONST, 7,                 /* setg gvar[3], 7 */
        0x2D, 200, GVAR, 1,                /* setg gvar[200], gvar[1] */
        0x2D, 4, TIMER, 9,                 /* timer 9 does not exist: 0 */
        0x2B, 255, 77,                     /* the last global */
    };
    struct rcx *b = run(code, sizeof code);
    (void)state;
    assert_int_equal(b->global[5], 255);
    assert_int_equal(b->global[1], 300);
    assert_int_equal(b->global[2], -2);
    assert_int_equal(b->global[3], 7);
    assert_int_equal(b->global[200], 300);
    assert_int_equal(b->global[4], 0);
    assert_int_equal(b->global[255], 77);
    brick_free(b);
}

/* x op v by the rules of swan-target.md 4, op = the family's low three bits: + - * / & | ~ % */
static s16 rule(unsigned op, s16 x, s16 v)
{
    long r;
    switch (op) {
    case 0: r = (long)x + v; break;
    case 1: r = (long)x - v; break;
    case 2: r = (long)x * v; break;
    case 3: r = v == 0 ? x : (x == -32768 && v == -1) ? -32768 : x / v; break;
    case 4: r = x & v; break;
    case 5: r = x | v; break;
    case 6: r = ~v; break;
    default: r = v == 0 ? x : v == -1 ? 0 : x % v; break;
    }
    return (s16)(u16)(unsigned long)r;
}

static const s16 xs[] = { 0, 1, 7, -7, 100, -100, 32767, -32768, 12345 };
static const s16 vs[] = { 0, 1, 2, 3, -1, -3, 255, 300, -32768, 32767 };

static void arithmetic_families(void **state)
{
    unsigned op, i, k, form;
    (void)state;
    for (form = 0; form < 4; form++)
        for (op = 0; op < 8; op++)
            for (i = 0; i < sizeof xs / sizeof xs[0]; i++)
                for (k = 0; k < sizeof vs / sizeof vs[0]; k++) {
                    s16 x = xs[i], v = vs[k];
                    u8 code[32];
                    unsigned n = 0;
                    struct rcx *b;
                    if (form == 0 && (v < 0 || v > 255))
                        continue;                  /* k8 is a byte */
                    code[n++] = 0x2C, code[n++] = 10, code[n++] = HI(x), code[n++] = LO(x);
                    code[n++] = 0x2C, code[n++] = 11, code[n++] = HI(v), code[n++] = LO(v);
                    if (form == 0) {                /* op g k8 */
                        code[n++] = (u8)(0x48 + op), code[n++] = 10, code[n++] = (u8)v;
                    } else if (form == 1) {         /* op g H L */
                        code[n++] = (u8)(0x58 + op), code[n++] = 10, code[n++] = HI(v), code[n++] = LO(v);
                    } else if (form == 2) {         /* op g T v8 */
                        code[n++] = (u8)(0xC8 + op), code[n++] = 10, code[n++] = GVAR, code[n++] = 11;
                    } else {                        /* op Td d16 Ts s16 */
                        const u8 seven[] = { OP7((u8)(0x08 + op), VAR, 10, GVAR, 11) };
                        memcpy(code + n, seven, sizeof seven);
                        n += sizeof seven;
                    }
                    b = run(code, n);
                    if (b->global[10] != rule(op, x, v))
                        fail_msg("form %u op %u: %d op %d = %d, rule says %d", form, op, x, v, b->global[10],
                                 rule(op, x, v));
                    brick_free(b);
                }
}

/* 0xF8-0xFF on any writable destination: Timer(0) += 3 is `f8 01 00 00 02 03 00` in nqc -L. */
static void arithmetic_on_any_source(void **state)
{
    static const u8 code[] = { 0xA1, 0, OP7(0xF8, TIMER, 0, CONST, 3), OP7(0xFA, TIMER, 0, CONST, 5),
                               OP7(0xF8, CONST, 0, CONST, 3),       /* a constant is read-only: nothing */
                               OP7(0xF8, 3, 0, CONST, 3),           /* motor status is read-only */
                               0x2D, 0, TIMER, 0 };
    struct rcx *b = run(code, sizeof code);
    (void)state;
    assert_int_equal(b->timer[0], 15);
    assert_int_equal(b->global[0], 15);
    brick_free(b);
}

/* 7-byte single operations: abs, sgn, xor, shifts, bits, negate, setsv. */
static void single_operations(void **state)
{
    static const struct { u8 op; s16 x, v, want; } cases[] = {
        { 0x7B, 5, -32768, 32767 }, { 0x7B, 5, -9, 9 }, { 0x7B, 5, 9, 9 },           /* abs */
        { 0x7C, 5, -9, -1 }, { 0x7C, 5, 0, 0 }, { 0x7C, -5, 40, 1 },                 /* sgn */
        { 0x88, 0x0F0F, 0x00FF, 0x0FF0 },                                             /* xor */
        { 0x98, 3, 2, 12 }, { 0x98, 1, 15, -32768 }, { 0x98, 1, 16, 0 }, { 0x98, 5, 300, 0 },
        { 0x98, -8, -1, -4 }, { 0x98, 12, -2, 3 },                                    /* shl; negative: right */
        { 0x99, -8, 1, -4 }, { 0x99, 16, 2, 4 }, { 0x99, -1, 20, -1 }, { 0x99, -32768, 15, -1 },
        { 0x99, 32767, 16, 0 }, { 0x99, -5, 16, -1 }, { 0x99, 3, -2, 12 }, { 0x99, 3, -32768, 0 }, /* shr */
        { 0x7E, 0, 3, 8 }, { 0x7E, 0, 15, -32768 }, { 0x7E, 1, 16, 1 }, { 0x7E, 1, -1, 1 }, /* bset */
        { 0x7F, -1, 0, -2 }, { 0x7F, -1, 15, 32767 }, { 0x7F, 7, 16, 7 },           /* bclr */
        { 0x9B, 5, 9, -9 }, { 0x9B, 5, -32768, -32768 },                              /* neg */
        { 0x2F, 5, -300, -300 },                                                      /* setsv */
    };
    unsigned i;
    (void)state;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const u8 code[] = { 0x2C, 10, HI(cases[i].x), LO(cases[i].x), 0x2C, 11, HI(cases[i].v), LO(cases[i].v),
                            OP7(cases[i].op, GVAR, 10, VAR, 11) };
        struct rcx *b = run(code, sizeof code);
        if (b->global[10] != cases[i].want)
            fail_msg("%02X: x %d, v %d gives %d, rule says %d", cases[i].op, cases[i].x, cases[i].v, b->global[10],
                     cases[i].want);
        brick_free(b);
    }
}

/* ------------------------------------------------------------------------------------------------------------ */
/* Variables: 256 globals, RCX 2.0's locals overlaid at 32 + 16 t (swan-target.md 4). */

static void sources_43_and_44(void **state)
{
    static const u8 code[] = { 0x2B, 250, 7, 0x2B, 7, 33,       /* gvar[250] = 7, gvar[7] = 33 */
                               0x2D, 1, IGVAR, 250,              /* gvar[1] = *gvar[250] = gvar[7] */
                               OP7(0x2F, IGVAR, 250, CONST, -5), /* *gvar[250] = -5: gvar[7] */
                               0x2C, 8, 0x01, 0x2C,              /* gvar[8] = 300 */
                               OP7(0x2F, IGVAR, 8, CONST, 9),    /* *gvar[8]: global 300 does not exist */
                               OP7(0x2F, GVAR, 256, CONST, 9),   /* nor does index 256 */
                               OP7(0x2F, GVAR, 2, GVAR, 300) };  /* reads 0 */
    struct rcx *b = run(code, sizeof code);
    u8 r[8];
    static const u8 poll43[] = { 0x12, GVAR, 250 }, poll0[] = { 0x12, VAR, 40 };
    (void)state;
    assert_int_equal(b->global[1], 33);
    assert_int_equal(b->global[7], -5);
    assert_int_equal(b->global[0], 0);
    assert_int_equal(b->global[2], 0);
    /* a host polls every global through 43; through 0, 32-47 answer 0x8000 as in firm0328 */
    assert_int_equal(brick_cmd(b, poll43, sizeof poll43, r), 3);
    assert_int_equal(r[1] | r[2] << 8, 7);
    b->global[40] = 11;
    assert_int_equal(brick_cmd(b, poll0, sizeof poll0, r), 3);
    assert_int_equal(r[1] | r[2] << 8, 0x8000);
    brick_free(b);
}

/* Task 3 of an RCX 2.0 program has its variable 40 at global 40 + 48; in a Swan program source 0 index 40 is global
 * 40 from every task, as NQC's API macros (BitSet, Wait...) address globals through source 0. */
static void overlay_and_source_0(void **state)
{
    static const u8 rcx2[] = { SETV(40, CONST, 1234), SETV(47, CONST, 5), SETV(100, CONST, 6) };
    static const u8 swan[] = { SETV(40, CONST, 1234), 0x2B, 47, 5, OP7(0x7E, VAR, 100, CONST, 2) };
    static const u8 start3[] = { 0x71, 3 };
    struct rcx *b = brick_new();
    (void)state;
    assert_int_equal(brick_download(b, 1, 3, rcx2, sizeof rcx2), 0);
    assert_int_equal(brick_download(b, 1, 0, start3, sizeof start3), 0);
    brick_start(b, 0);
    assert_true(brick_run_until_idle(b, 100, 10) >= 0);
    assert_int_equal(b->global[32 + 16 * 3 + 8], 1234);
    assert_int_equal(b->global[32 + 16 * 3 + 15], 5);
    assert_int_equal(b->global[40], 0);
    assert_int_equal(b->global[100], 6);            /* 48-255: the global, also in an RCX 2.0 program */
    brick_free(b);

    b = brick_new();
    assert_int_equal(brick_download(b, 1, 3, swan, sizeof swan), 0);
    assert_int_equal(brick_download(b, 1, 0, start3, sizeof start3), 0);
    brick_start(b, 0);
    assert_true(brick_run_until_idle(b, 100, 10) >= 0);
    assert_int_equal(b->global[40], 1234);
    assert_int_equal(b->global[47], 5);
    assert_int_equal(b->global[32 + 16 * 3 + 8], 0);
    assert_int_equal(b->global[100], 4);
    brick_free(b);
}

/* A program is a Swan one when any of its code has a Swan opcode or tests source 43/44 (SCheckDo/LCheckDo). */
static void swan_program_detection(void **state)
{
    static const u8 test_only[] = { 0x85, 0x03, GVAR, 0, 0, 1, 5, SETV(40, CONST, 9) }; /* chk 1 <= gvar[0] */
    static const u8 plain[] = { 0x85, 0x03, CONST, 0, 0, 1, 5, SETV(40, CONST, 9) };
    static const u8 start3[] = { 0x71, 3 };
    unsigned k;
    (void)state;
    for (k = 0; k < 2; k++) {
        struct rcx *b = brick_new();
        assert_int_equal(brick_download(b, 1, 3, k ? test_only : plain, sizeof plain), 0);
        assert_int_equal(brick_download(b, 1, 0, start3, sizeof start3), 0);
        assert_int_equal(b->swan[0], k);
        brick_start(b, 0);
        assert_true(brick_run_until_idle(b, 100, 10) >= 0);
        assert_int_equal(b->global[k ? 40 : 88], 9);
        brick_free(b);
    }
}

/* Task 0 of a new brick, downloaded in blocks of `size` bytes; the slot's kind. */
static u8 kind_in_blocks(const u8 *code, unsigned len, unsigned size)
{
    struct rcx *b = brick_new();
    u8 begin[6] = { 0x25, 0, 0, 0, (u8)len, 0 }, block[6 + 32], r[RCX_REPLY_MAX], kind;
    unsigned at, i, n;

    assert_int_equal(brick_cmd(b, begin, sizeof begin, r), 2);
    assert_int_equal(r[1], 0);
    for (at = 0; at < len; at += n) {
        n = len - at < size ? len - at : size;
        block[0] = 0x45;
        block[1] = (u8)(at + n < len ? 1 + at / size : 0); /* 1, 2, ..., the last 0 */
        block[2] = 0;
        block[3] = (u8)n;
        block[4] = 0;
        block[5 + n] = 0;
        for (i = 0; i < n; i++)
            block[5 + n] = (u8)(block[5 + n] + (block[5 + i] = code[at + i]));
        assert_int_equal(brick_cmd(b, block, 6 + n, r), 2);
        assert_int_equal(r[1], 0);
    }
    kind = b->swan[0];
    brick_free(b);
    return kind;
}

/* The kind is found as the blocks come (vm/swanblock.c, swan_block), walked instruction by instruction whatever the
 * blocks' sizes: a Swan opcode's byte inside an operand is none, SCheckDo's source is read when it comes in the next block.
 * (Plain code, then Swan's: no such program runs here.) */
static void swan_code_found_whatever_the_blocks(void **state)
{
    static const u8 plain[] = { SETV(1, CONST, 0x2B2B), 0x95, 0x03, CONST, 0, 0, 1, 5, 0x2B, /* LCheckDo: 7 bytes */
                                0x85, 0x03, CONST, 0, 0, 1, 5, SETV(40, CONST, 0x47C7), 0x01 };
    static const u8 test_only[] = { SETV(1, CONST, 0x2B2B), 0x85, 0x03, GVAR, 0, 0, 1, 5, SETV(40, CONST, 9) };
    static const u8 last_op[] = { SETV(1, CONST, 0x2B2B), SETV(2, CONST, 3), 0x2B, 1, 7 }; /* setgb 1, 7 */
    unsigned size;
    (void)state;
    for (size = 1; size <= 22; size++) {
        assert_int_equal(kind_in_blocks(plain, sizeof plain - 1, size), 0);
        assert_int_equal(kind_in_blocks(test_only, sizeof test_only, size), 1);
        assert_int_equal(kind_in_blocks(last_op, sizeof last_op, size), 1);
    }
    assert_int_equal(kind_in_blocks(plain, sizeof plain, 8), 1); /* a truncated last instruction: pop, Swan's */
}

/* ------------------------------------------------------------------------------------------------------------ */
/* Time: WaitMS (0x47) and the 1 ms timers (source 22). */

static void wait_ms_and_ms_timers(void **state)
{
    static const u8 code[] = { 0x47, CONST, 25, 0, 0x2B, 1, 1, 0x47, CONST, 0xFF, 0xFF, 0x47, GVAR, 2, 0,
                               0x2B, 2, 2, 0x2D, 3, 22, 1 };
    struct rcx *b = brick_new();
    unsigned ms;
    (void)state;
    assert_int_equal(brick_download(b, 1, 0, code, sizeof code), 0);
    brick_start(b, 0);
    for (ms = 0; ms < 24; ms++) {
        brick_run_ms(b, 1, 50);
        assert_int_equal(b->global[1], 0);
    }
    brick_run_ms(b, 2, 50);                         /* 25 ms: on; -1 and 0 (gvar[2]) do not wait */
    assert_int_equal(b->global[1], 1);
    assert_int_equal(b->global[2], 2);
    assert_in_range(b->global[3], 25, 27);          /* MSTimer(1), from power-on */
    brick_free(b);
}

static void ms_timer_counts_wraps_and_is_written(void **state)
{
    static const u8 set[] = { OP7(0x2F, 22, 0, CONST, 32760), OP7(0x2F, 22, 1, CONST, -4), 0x2B, 9, 1 };
    static const u8 get[] = { 0x2D, 0, 22, 0, 0x2D, 1, 22, 2, 0x2D, 5, 22, 1, 0xC7, 0x01, 0x2D, 2, 22, 0,
                              0x2D, 3, 1, 0, 0x2D, 4, 22, 4 };
    struct rcx *b = brick_new();
    (void)state;
    assert_int_equal(brick_download(b, 1, 0, set, sizeof set), 0);
    assert_int_equal(brick_download(b, 1, 1, get, sizeof get), 0);
    brick_run_ms(b, 300, 50);
    brick_start(b, 0);
    brick_run_ms(b, 1, 50);
    assert_int_equal(b->global[9], 1);
    brick_run_ms(b, 10, 50);                        /* 32760 + 10 wraps past 32767 */
    sched_start_task(b, 1);
    vm_run(b, 7);
    assert_in_range(b->global[0], 2, 3);
    assert_in_range(b->global[1], 310, 312);        /* timer 2, untouched: since power-on */
    assert_int_equal(b->global[2], 0);              /* ClearAll(timers) clears both kinds */
    assert_int_equal(b->global[3], 0);
    assert_int_equal(b->global[4], 0);              /* timer 4 does not exist */
    assert_in_range(b->global[5], 310, 312);        /* the negative write was ignored: from power-on */
    brick_free(b);
}

/* ------------------------------------------------------------------------------------------------------------ */
/* ClearAll (0xC7 flags). */

static void clear_all(void **state)
{
    static const u8 code[] = { 0x2B, 200, 5, 0x2B, 40, 5, 0x93, 0, 1, 0,       /* event 0: timer 0 pressed */
                               0x52, 5, 0, 0xE3, CONST, 1, 0,                 /* datalog of 5, one push */
                               0xC7, 0x04 | 0x10 | 0x40 | 0x08, 0x01, 1 };    /* the stack is empty: pop 1 stops */
    struct rcx *b = run(code, sizeof code);
    unsigned i;
    (void)state;
    for (i = 0; i < 256; i++)
        assert_int_equal(b->global[i], 0);
    assert_int_equal(b->event[0].type, 16);        /* cleared */
    assert_int_equal(b->log_size, 0);
    assert_int_equal(b->task[0].state, RCX_TASK_IDLE);
    brick_free(b);
}

/* ------------------------------------------------------------------------------------------------------------ */
/* The task stack: push (E3 T v16) and pop (01 n); overflow and underflow stop the task. */

static void stack_push_pop(void **state)
{
    u8 code[64];
    unsigned n = 0, k;
    struct rcx *b;
    (void)state;
    for (k = 0; k < RCX_SWAN_STACK; k++)
        code[n++] = 0xE3, code[n++] = CONST, code[n++] = (u8)k, code[n++] = 0;
    code[n++] = 0x01, code[n++] = 3;
    code[n++] = 0x2B, code[n++] = 1, code[n++] = 1;            /* reached */
    code[n++] = 0x01, code[n++] = RCX_SWAN_STACK - 3;
    code[n++] = 0x2B, code[n++] = 2, code[n++] = 1;            /* reached: empty now */
    code[n++] = 0x01, code[n++] = 1;                           /* underflow */
    code[n++] = 0x2B, code[n++] = 3, code[n++] = 1;
    b = run(code, n);
    assert_int_equal(b->global[1], 1);
    assert_int_equal(b->global[2], 1);
    assert_int_equal(b->global[3], 0);
    brick_free(b);
    n = 0;
    for (k = 0; k <= RCX_SWAN_STACK; k++)                      /* one more than there is room for */
        code[n++] = 0xE3, code[n++] = CONST, code[n++] = (u8)k, code[n++] = 0;
    code[n++] = 0x2B, code[n++] = 1, code[n++] = 1;
    b = run(code, n);
    assert_int_equal(b->global[1], 0);
    assert_int_equal(b->task[0].state, RCX_TASK_IDLE);
    brick_free(b);
}

/* ------------------------------------------------------------------------------------------------------------ */
/* Messages with a parameter. */

static void message_parameter(void **state)
{
    static const u8 code[] = { 0xA2, 3, 200, 0x2D, 1, 15, 0, 0x2D, 2, 15, 1,          /* msgsb 3, 200 */
                               0xB3, 4, LO(1000), HI(1000), 0x2D, 3, 15, 0, 0x2D, 4, 15, 1, /* msgsw 4, 1000 */
                               0x2C, 9, 0xFF, 0xF0, 0xC4, CONST, 7, GVAR, 9, 0,  /* msgsv 7, gvar[9] = -16 */
                               0x2D, 5, 15, 0, 0x2D, 6, 15, 1,
                               OP7(0x2F, 15, 1, CONST, 55), 0x2D, 7, 15, 1 };    /* source 15 index 1 written */
    static const u8 f7[] = { 0xF7, 9 }, b3[] = { 0xB3, 12, LO(-2), HI(-2) }, f7b[] = { 0xF7, 12 };
    static const u8 f7c[] = { 0xF7, 13 };
    struct rcx *b = run(code, sizeof code);
    (void)state;
    assert_int_equal(b->global[1], 3);
    assert_int_equal(b->global[2], 200);
    assert_int_equal(b->global[3], 4);
    assert_int_equal(b->global[4], 1000);
    assert_int_equal(b->global[5], 7);
    assert_int_equal(b->global[6], -16);
    assert_int_equal(b->global[7], 55);
    /* received: a plain message has parameter 0; one after a B3 of the same number gets that one's */
    assert_int_equal(brick_cmd(b, f7, sizeof f7, NULL), 0);
    assert_int_equal(b->message, 9);
    assert_int_equal(b->msg_param, 0);
    assert_int_equal(brick_cmd(b, b3, sizeof b3, NULL), 0);  /* no reply, and not yet the message */
    assert_int_equal(b->message, 9);
    assert_int_equal(brick_cmd(b, f7b, sizeof f7b, NULL), 0);
    assert_int_equal(b->message, 12);
    assert_int_equal(b->msg_param, -2);
    assert_int_equal(brick_cmd(b, b3, sizeof b3, NULL), 0);  /* for 12, but 13 comes: plain */
    assert_int_equal(brick_cmd(b, f7c, sizeof f7c, NULL), 0);
    assert_int_equal(b->msg_param, 0);
    brick_free(b);
}

/* 0xC3: sent as `B3 m lo hi`, then `F7 m` (vm/remote.h); the program's own message is not changed. */
static void send_message_with_parameter(void **state)
{
    static const u8 code[] = { 0x2C, 1, 0x12, 0x34, 0xC3, CONST, 77, GVAR, 1, 0 };
    struct rcx *b = run(code, sizeof code);
    (void)state;
    assert_int_equal(b->remote.tx_len, 4);
    assert_int_equal(b->remote.tx[0], 0xB3);
    assert_int_equal(b->remote.tx[1], 77);
    assert_int_equal(b->remote.tx[2], 0x34);
    assert_int_equal(b->remote.tx[3], 0x12);
    assert_int_equal(b->remote.tx_pack, 0x07);
    assert_int_equal(b->message, 0);
    b->remote.tx_len = 0;                          /* what the IR layer does when it takes the request */
    remote_sent(b);
    assert_int_equal(b->remote.tx_len, 2);
    assert_int_equal(b->remote.tx[0], 0xF7);
    assert_int_equal(b->remote.tx[1], 77);
    b->remote.tx_len = 0;
    remote_sent(b);
    assert_int_equal(b->remote.tx_len, 0);         /* once */
    brick_free(b);
}

/* ------------------------------------------------------------------------------------------------------------ */
/* Swan's sources (swan-target.md 3). */

static void motor_power_sources(void **state)
{
    static const u8 code[] = { OP7(0x2F, 32, 0, CONST, 4),      /* MotorPower8(A) = 4 */
                               OP7(0x2F, 16, 1, CONST, 100),    /* MotorPower128(B) = 100: level 6 */
                               OP7(0x2F, 5, 2, CONST, -50),     /* MotorPowerSigned(C) = -50: 3, reverse */
                               OP7(0x2F, 7, 0, CONST, 90),      /* MotorBrakePower(A): kept only */
                               OP7(0x2F, 32, 1, CONST, 9),      /* beyond the 8 scale: the end of it */
                               OP7(0x2F, 16, 0, CONST, 30000),  /* beyond the 128 scale: 7 (not 30000 x 7 wrapped) */
                               0x2D, 7, 16, 0,
                               OP7(0x2F, 32, 0, CONST, 4),
                               0x2D, 1, 32, 0, 0x2D, 2, 16, 1, 0x2D, 3, 5, 2, 0x2D, 4, 7, 0, 0x2D, 5, 32, 1,
                               0x2D, 6, 5, 3 };                 /* output D does not exist */
    struct rcx *b = run(code, sizeof code);
    (void)state;
    assert_int_equal(b->global[1], 4);
    assert_int_equal(b->global[2], 100);
    assert_int_equal(b->global[3], -50);
    assert_int_equal(b->global[4], 90);
    assert_int_equal(b->global[5], 9);
    assert_int_equal(b->global[6], 0);
    assert_int_equal(b->global[7], 30000);                          /* read back as written */
    assert_int_equal(b->out.motor[0] & RCX_MOTOR_POWER, 4);
    assert_int_equal(b->out.motor[1] & RCX_MOTOR_POWER, 7);         /* MotorPower8(B) = 9 after 100 */
    assert_int_equal(b->out.motor[2] & RCX_MOTOR_POWER, 3);
    assert_int_equal(b->out.motor[2] & RCX_MOTOR_FWD, 0);
    brick_free(b);
}

static void event_sources(void **state)
{
    static const u8 code[] = { 0x93, 2, 4, 1,                    /* SetEvent 2: timer 1 (EST 4), released (1) */
                               0x2D, 1, 18, 2, 0x2D, 2, 19, 2, 0x2D, 3, 19, 5, 0x2D, 4, 18, 5,
                               OP7(0x2F, 20, 2, CONST, 6), 0x2D, 5, 20, 2, 0x2D, 6, 27, 2,
                               OP7(0x2F, 18, 2, CONST, 0),       /* SetEventType(2, pressed) */
                               OP7(0x2F, 19, 2, CONST, 8),       /* SetEventSrc(2, counter 0) */
                               OP7(0x2F, 18, 2, CONST, 0x101),   /* beyond a byte: no type 1 ... */
                               OP7(0x2F, 19, 2, CONST, 0x103),   /* ... nor source 3 */
                               0x2D, 7, 18, 2, 0x2D, 8, 19, 2 };
    struct rcx *b = run(code, sizeof code);
    (void)state;
    assert_int_equal(b->global[1], 1);
    assert_int_equal(b->global[2], 4);
    assert_int_equal(b->global[3], 16);            /* cleared: EST_SENSOR_UNUSED */
    assert_int_equal(b->global[4], 16);            /* and type 16, SetEvent's "none" */
    assert_int_equal(b->global[5], 6);
    assert_int_equal(b->global[6], 6);             /* EventCounts is the click counter */
    assert_int_equal(b->global[7], 0);
    assert_int_equal(b->global[8], 8);
    brick_free(b);
}

static void system_settings(void **state)
{
    static const u8 task3[] = { 0x2D, 1, 24, 3, 0x2D, 2, 24, 0,
                                OP7(0x2F, 24, 20, CONST, 7), 0x2D, 3, 24, 20,
                                OP7(0x2F, 24, 9, CONST, -1234), 0x2D, 4, 24, 9,   /* kept, no effect */
                                OP7(0x2F, 24, 0, CONST, 5), 0x2D, 5, 24, 0,       /* read only */
                                OP7(0x2F, 24, 13, CONST, 1), 0x2D, 6, 24, 13,
                                OP7(0x2F, 24, 38, CONST, 10), 0x2D, 7, 24, 38,
                                0x2D, 8, 24, 39 };                               /* no index 39 */
    static const u8 start3[] = { 0x71, 3 };
    struct rcx *b = brick_new();
    (void)state;
    assert_int_equal(brick_download(b, 1, 3, task3, sizeof task3), 0);
    assert_int_equal(brick_download(b, 1, 0, start3, sizeof start3), 0);
    b->battery_mv = 7654;
    brick_start(b, 0);
    assert_true(brick_run_until_idle(b, 100, 10) >= 0);
    assert_int_equal(b->global[1], 3);
    assert_int_equal(b->global[2], 7654);
    assert_int_equal(b->global[3], 7);
    assert_int_equal(b->power_down_min, 7);
    assert_int_equal(b->global[4], -1234);
    assert_int_equal(b->global[5], 7654);
    assert_int_equal(b->global[6], 1);
    assert_int_equal(b->tx_range, 1);
    assert_int_equal(b->global[7], 10);
    assert_int_equal(b->log_size, 11);             /* entries + the header */
    assert_int_equal(b->global[8], 0);
    brick_free(b);
}

/* Datalog read-back, 37-42: entry 0 the header (0xFF, entries used), then the points; for RCX 2.0 programs too. */
static void datalog_read_back(void **state)
{
    static const u8 code[] = { 0x52, 4, 0, SETV(3, CONST, -300), 0x62, VAR, 3, SETV(5, CONST, 1),
                               SETV(10, 38, 0), SETV(11, 40, 0), SETV(12, 38, 1), SETV(13, 40, 1),
                               SETV(14, 37, 5), SETV(15, 39, 5), SETV(16, 42, 4), SETV(17, 41, 5),
                               SETV(18, 40, 2), SETV(19, 42, 6) };
    struct rcx *b = run(code, sizeof code);
    (void)state;
    assert_int_equal(b->swan[0], 0);               /* an RCX 2.0 program */
    assert_int_equal(b->global[10], 0xFF);
    assert_int_equal(b->global[11], 2);
    assert_int_equal(b->global[12], 3);            /* variable 3: kind 0, index 3 */
    assert_int_equal(b->global[13], -300);
    assert_int_equal(b->global[14], 3);            /* indirect: entry var[5] = 1 */
    assert_int_equal(b->global[15], -300);
    assert_int_equal(b->global[16], LO(-300));     /* byte 4: entry 1's value, low byte */
    assert_int_equal(b->global[17], 2);            /* byte var[5] = 1: the header's value, low byte */
    assert_int_equal(b->global[18], 0);            /* entry 2 is not used */
    assert_int_equal(b->global[19], 0);            /* nor byte 6 */
    brick_free(b);
}

/* For an RCX 2.0 program and a host, Swan's sources do not exist (firm0328's holes); 15 index 1 neither. */
static void swan_sources_only_for_swan_programs(void **state)
{
    static const u8 code[] = { SETV(1, 22, 0), SETV(2, 24, 0), SETV(3, 15, 1), SETV(4, 43, 7),
                               0x05, 32, 0, CONST, 4, 0 };
    static const u8 poll[] = { 0x12, 24, 0 };
    struct rcx *b = brick_new();
    u8 r[4];
    (void)state;
    b->global[7] = 77;
    b->battery_mv = 7000;
    brick_run_ms(b, 50, 1);
    assert_int_equal(brick_download(b, 1, 0, code, sizeof code), 0);
    brick_start(b, 0);
    assert_true(brick_run_until_idle(b, 100, 10) >= 0);
    assert_int_equal(b->global[1], 0);
    assert_int_equal(b->global[2], 0);
    assert_int_equal(b->global[3], 0);
    assert_int_equal(b->global[4], 77);            /* 43 exists for both */
    assert_int_equal(b->swan_power[2][0], 0);
    assert_int_equal(brick_cmd(b, poll, sizeof poll, r), 3);
    assert_int_equal(r[1] | r[2] << 8, 0x8000);
    brick_free(b);
}

/* ------------------------------------------------------------------------------------------------------------ */
/* Bad input: opcodes NQC never emits are skipped as RCX 2.0 skips unknown ones; nothing outside the machine. */

static void bad_swan_input(void **state)
{
    static const u8 code[] = { 0x8C, 1, 2, 3, 4, 5, 6,           /* ftol (never emitted): RCX 0x84 toggled = AndVar */
                               0x26,                              /* setl: an unknown RCX 2.0 byte, no operands */
                               OP7(0x98, GVAR, 1, CONST, 40), OP7(0x7E, GVAR, 1, GVAR, 300),
                               OP7(0x08, 63, 0, CONST, 1), OP7(0x2F, 0xFF, 0xFFFF, 0xFF, 0xFFFF),
                               0x2B, 2, 1 };
    struct rcx *b = run(code, sizeof code);
    (void)state;
    assert_int_equal(b->global[2], 1);
    brick_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(decoder_lengths_on_eight_bits),
        cmocka_unit_test(global_assignments),
        cmocka_unit_test(arithmetic_families),
        cmocka_unit_test(arithmetic_on_any_source),
        cmocka_unit_test(single_operations),
        cmocka_unit_test(sources_43_and_44),
        cmocka_unit_test(overlay_and_source_0),
        cmocka_unit_test(swan_program_detection),
        cmocka_unit_test(swan_code_found_whatever_the_blocks),
        cmocka_unit_test(wait_ms_and_ms_timers),
        cmocka_unit_test(ms_timer_counts_wraps_and_is_written),
        cmocka_unit_test(clear_all),
        cmocka_unit_test(stack_push_pop),
        cmocka_unit_test(message_parameter),
        cmocka_unit_test(send_message_with_parameter),
        cmocka_unit_test(motor_power_sources),
        cmocka_unit_test(event_sources),
        cmocka_unit_test(system_settings),
        cmocka_unit_test(datalog_read_back),
        cmocka_unit_test(swan_sources_only_for_swan_programs),
        cmocka_unit_test(bad_swan_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
