/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Control-flow byte codes (spec pp. 26, 31-33, 39-41, 47, 56-58, 62, 67, 73, 93-94), with encodings as nqc emits
 * them (host-tools.md §4). Every distance counts from the first byte of its own field (spec p. 11):
 *   27/72/F2/F3: sign and magnitude, bit 7 of the first distance byte = backwards, 16-bit = low 7 bits + byte 2 << 7;
 *   85/37: unsigned 8-bit forward; 92: unsigned 16-bit forward; 95: signed 16-bit.
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
#define SETV(v, src, val) 0x14, (u8)(v), (src), LO(val), HI(val)
#define SUMV(v, src, val) 0x24, (u8)(v), (src), LO(val), HI(val)
#define INC(v) SUMV(v, CONST, 1)
#define WAIT(n) 0x43, CONST, LO(n), HI(n)

/* Jumps written as (position of the instruction, target), distances computed per spec p. 11. */
#define MAG(field, to) ((to) >= (field) ? (to) - (field) : (field) - (to))
#define D8(field, to) ((u8)(MAG(field, to) | ((to) < (field) ? 0x80 : 0)))
#define D16(field, to) ((u8)((MAG(field, to) & 0x7F) | ((to) < (field) ? 0x80 : 0))), ((u8)(MAG(field, to) >> 7))
#define JMP(at, to) 0x27, D8((at) + 1, to)
#define JMPL(at, to) 0x72, D16((at) + 1, to)
#define DECVJN(at, v, to) 0xF2, (u8)(v), D8((at) + 2, to)
#define DECVJNL(at, v, to) 0xF3, (u8)(v), D16((at) + 2, to)
#define CHK(at, rel, s1, v1, s2, v2, to) \
    0x85, (u8)((rel) << 6 | (s1)), (s2), LO(v1), HI(v1), (u8)(v2), (u8)((to) - ((at) + 6))
#define CHKL(at, rel, s1, v1, s2, v2, to) \
    0x95, (u8)((rel) << 6 | (s1)), (s2), LO(v1), HI(v1), (u8)(v2), LO((to) - ((at) + 6)), HI((to) - ((at) + 6))
#define LOOPS(src, v) 0x82, (src), (u8)(v)
#define LOOPC(at, to) 0x37, (u8)((to) - ((at) + 1))
#define LOOPCL(at, to) 0x92, LO((to) - ((at) + 1)), HI((to) - ((at) + 1))
#define PUT(code, at, ...) do { const u8 put_[] = { __VA_ARGS__ }; memcpy((code) + (at), put_, sizeof put_); } while (0)

static void load(struct rcx *b, int is_task, u8 n, const u8 *code, unsigned len)
{
    assert_int_equal(brick_download(b, is_task, n, code, len), 0);
}

static void select_slot(struct rcx *b, u8 slot)
{
    u8 cmd[2] = { 0x91, slot };
    assert_int_equal(brick_cmd(b, cmd, 2, NULL), 1);
}

/* A fresh brick with `code` as task 0, run to completion. */
static struct rcx *run_code(const u8 *code, unsigned len)
{
    struct rcx *b = brick_new();
    load(b, 1, 0, code, len);
    brick_start(b, 0);
    assert_true(brick_run_until_idle(b, 5000, 10) >= 0);
    return b;
}

/* n bytes of filler that would visibly change var[0] if executed: SumVar var0 += 1, padded with ping (0x10). */
static void filler(u8 *code, unsigned at, unsigned n)
{
    while (n >= 5) {
        PUT(code, at, INC(0));
        at += 5;
        n -= 5;
    }
    while (n--)
        code[at++] = 0x10;
}

/* ------------------------------------------------------------------------------------------------------------ */

static void encodings_match_nqc_listings(void **state)
{
    /* Each pair: our macro, and the bytes `nqc -L` printed for the same instruction at the same offset. */
    static const u8 mine[] = {
        JMP(19, 11), JMP(78, 73), DECVJN(11, 0x2F, 21), JMPL(165, 11), JMPL(168, 326), DECVJNL(11, 0x2F, 168),
        CHK(21, 1, CONST, 1, VAR, 0, 33), CHK(90, 1, CONST, -1, VAR, 0, 102), CHKL(326, 1, CONST, 0, VAR, 1, 171),
        CHKL(339, 1, CONST, 4, VAR, 1, 334), LOOPC(9, 18), LOOPC(9, 164), LOOPCL(9, 315), JMPL(312, 9),
        DECVJNL(11, 0x2F, 318), JMPL(315, 11),
    };
    static const u8 nqc[] = {
        0x27, 0x89, 0x27, 0x86, 0xF2, 0x2F, 0x08, 0x72, 0x9B, 0x01, 0x72, 0x1D, 0x01, 0xF3, 0x2F, 0x1B, 0x01,
        0x85, 0x42, 0x00, 0x01, 0x00, 0x00, 0x06, 0x85, 0x42, 0x00, 0xFF, 0xFF, 0x00, 0x06,
        0x95, 0x42, 0x00, 0x00, 0x00, 0x01, 0x5F, 0xFF, 0x95, 0x42, 0x00, 0x04, 0x00, 0x01, 0xF5, 0xFF,
        0x37, 0x08, 0x37, 0x9A, 0x92, 0x31, 0x01, 0x72, 0xB0, 0x02, 0xF3, 0x2F, 0x31, 0x02, 0x72, 0xB1, 0x02,
    };
    (void)state;
    assert_int_equal(sizeof mine, sizeof nqc);
    assert_memory_equal(mine, nqc, sizeof nqc);
}

/* "jmp 0" is 27 81 and "jmpl 0" 72 81 00: infinite loops (spec pp. 11, 40, 56). */
static void jump_to_itself_loops_forever(void **state)
{
    static const u8 s[] = { INC(0), 0x27, 0x81 }, l[] = { INC(0), 0x72, 0x81, 0x00 };
    const u8 *codes[2] = { s, l };
    unsigned sizes[2] = { sizeof s, sizeof l }, i;
    (void)state;
    for (i = 0; i < 2; i++) {
        struct rcx *b = brick_new();
        load(b, 1, 0, codes[i], sizes[i]);
        brick_start(b, 0);
        assert_int_equal(vm_run(b, 1000), 1000);
        assert_int_equal(b->task[0].state, RCX_TASK_RUNNING);
        assert_int_equal(b->task[0].pc, 5);
        assert_int_equal(b->global[0], 1);
        brick_free(b);
    }
}

/* LJump over more than 127 bytes both ways (spec p. 56), and the longest forward SJump, 127. */
static void long_jumps(void **state)
{
    static u8 code[214], s[133];
    struct rcx *b;
    (void)state;
    PUT(code, 0, JMPL(0, 211));
    PUT(code, 3, INC(1));
    PUT(code, 8, JMPL(8, 214));
    filler(code, 11, 200);
    PUT(code, 211, JMPL(211, 3));
    b = run_code(code, sizeof code);
    assert_int_equal(b->global[0], 0);
    assert_int_equal(b->global[1], 1);
    brick_free(b);

    PUT(s, 0, JMP(0, 128)); /* distance 127 = 0x7F */
    assert_int_equal(s[1], 0x7F);
    filler(s, 2, 126);
    PUT(s, 128, INC(1));
    b = run_code(s, sizeof s);
    assert_int_equal(b->global[0], 0);
    assert_int_equal(b->global[1], 1);
    brick_free(b);
}

/* `repeat(2)` around 30 `x += i` statements, byte for byte as nqc -TRCX2 and nqc (RCX 1.0 target) emit it. */
static void nqc_long_repeat_loops(void **state)
{
    static u8 rcx2[168], rcx1a[164], rcx1b[315];
    static const u8 prologue[6] = { 0x13, 0x07, 0x02, 0x07, 0xE1, 0x87 }; /* host-tools.md §4 */
    unsigned i;
    struct rcx *b;
    (void)state;
    memcpy(rcx2, prologue, 6);
    PUT(rcx2, 6, 0x14, 0x2F, 0x02, 0x02, 0x00, 0xF3, 0x2F, 0x1B, 0x01);
    for (i = 0; i < 30; i++)
        PUT(rcx2, 15 + 5 * i, 0x24, 0x00, 0x02, (u8)(i + 1), 0x00);
    PUT(rcx2, 165, 0x72, 0x9B, 0x01);
    b = run_code(rcx2, sizeof rcx2);
    assert_int_equal(b->global[0], 2 * 465);
    brick_free(b);

    /* RCX 1.0: loops 2 / loopc with distance 0x9A = 154 forward (nqc's listing prints it as -92) */
    memcpy(rcx1a, prologue, 6);
    PUT(rcx1a, 6, 0x82, 0x02, 0x02, 0x37, 0x9A);
    for (i = 0; i < 30; i++)
        PUT(rcx1a, 11 + 5 * i, 0x24, 0x00, 0x02, (u8)(i + 1), 0x00);
    PUT(rcx1a, 161, 0x72, 0x99, 0x01);
    b = run_code(rcx1a, sizeof rcx1a);
    assert_int_equal(b->global[0], 2 * 465);
    brick_free(b);

    /* RCX 1.0 with 60 statements: loopcl 0x0131 */
    memcpy(rcx1b, prologue, 6);
    PUT(rcx1b, 6, 0x82, 0x02, 0x02, 0x92, 0x31, 0x01);
    for (i = 0; i < 60; i++)
        PUT(rcx1b, 12 + 5 * i, 0x24, 0x00, 0x02, (u8)(i + 1), 0x00);
    PUT(rcx1b, 312, 0x72, 0xB0, 0x02);
    b = run_code(rcx1b, sizeof rcx1b);
    assert_int_equal(b->global[0], 2 * 1830);
    brick_free(b);
}

/* "Decrements the variable and jumps if the variable is negative afterwards" (spec pp. 62, 73). */
static void decvar_loops_exactly_n_times(void **state)
{
    static const s16 counts[] = { 0, 1, 5, 200, -3 };
    unsigned i;
    (void)state;
    for (i = 0; i < sizeof counts / sizeof counts[0]; i++) {
        s16 n = counts[i];
        const u8 s[] = { SETV(46, CONST, n), DECVJN(5, 46, 15), INC(0), JMP(13, 5) };
        const u8 l[] = { SETV(46, CONST, n), DECVJNL(5, 46, 16), INC(0), JMP(14, 5) };
        struct rcx *b = run_code(s, sizeof s);
        assert_int_equal(b->global[0], n > 0 ? n : 0);
        brick_free(b);
        b = run_code(l, sizeof l);
        assert_int_equal(b->global[0], n > 0 ? n : 0);
        brick_free(b);
    }
}

static void decvar_jumps_backwards(void **state)
{
    static const s16 start[2] = { -5, 5 };
    unsigned i;
    (void)state;
    for (i = 0; i < 2; i++) {
        const u8 s[] = { SETV(3, CONST, start[i]), JMP(5, 14), /* 7: */ INC(1), JMP(12, 22),
                         /* 14: */ DECVJN(14, 3, 7), INC(2) };
        const u8 l[] = { SETV(3, CONST, start[i]), JMP(5, 14), INC(1), JMP(12, 23),
                         DECVJNL(14, 3, 7), INC(2) };
        int neg = start[i] - 1 < 0;
        struct rcx *b = run_code(s, sizeof s);
        assert_int_equal(b->global[1], neg);
        assert_int_equal(b->global[2], !neg);
        assert_int_equal(b->global[3], start[i] - 1);
        brick_free(b);
        b = run_code(l, sizeof l);
        assert_int_equal(b->global[1], neg);
        assert_int_equal(b->global[2], !neg);
        brick_free(b);
    }
}

/* SCheckDo / LCheckDo: 0 >, 1 <, 2 ==, 3 !=; "if the comparison fails execution jumps" (spec pp. 93-94). */
static const struct { u8 rel; s16 v1; u8 v2; int holds; } relations[] = {
    { 0, 5, 3, 1 }, { 0, 3, 5, 0 }, { 0, 4, 4, 0 }, { 0, -1, 0, 0 },
    { 1, 3, 5, 1 }, { 1, 5, 3, 0 }, { 1, 4, 4, 0 }, { 1, -1, 0, 1 },
    { 2, 4, 4, 1 }, { 2, 4, 5, 0 }, { 2, 300, 44, 0 },
    { 3, 4, 5, 1 }, { 3, 4, 4, 0 }, { 3, 127, 127, 0 },
};

static void checkdo_all_relations(void **state)
{
    unsigned i;
    (void)state;
    for (i = 0; i < sizeof relations / sizeof relations[0]; i++) {
        u8 r = relations[i].rel, v2 = relations[i].v2;
        s16 v1 = relations[i].v1;
        const u8 s[] = { CHK(0, r, CONST, v1, CONST, v2, 12), INC(0), INC(1) };
        const u8 l[] = { CHKL(0, r, CONST, v1, CONST, v2, 13), INC(0), INC(1) };
        /* the same comparison from variables: value 1 in var[8], value 2 read from var[9] by an 8-bit index */
        const u8 sv[] = { SETV(8, CONST, v1), SETV(9, CONST, v2), CHK(10, r, VAR, 8, VAR, 9, 22), INC(0), INC(1) };
        const u8 lv[] = { SETV(8, CONST, v1), SETV(9, CONST, v2), CHKL(10, r, VAR, 8, VAR, 9, 23), INC(0), INC(1) };
        const u8 *codes[4] = { s, l, sv, lv };
        unsigned sizes[4] = { sizeof s, sizeof l, sizeof sv, sizeof lv }, k;
        for (k = 0; k < 4; k++) {
            struct rcx *b = run_code(codes[k], sizes[k]);
            if (b->global[0] != relations[i].holds || b->global[1] != 1)
                fail_msg("form %u: %d rel%u %u: fell through %d times, expected %d", k, v1, r, v2, b->global[0],
                         relations[i].holds);
            brick_free(b);
        }
    }
}

static void checkdo_distances(void **state)
{
    /* nqc's do { y++; } while (y < 5): 95 42 00 04 00 01 F5 FF jumps back 11 from its field */
    static const u8 dowhile[] = { 0x24, 0x01, 0x02, 0x01, 0x00, 0x95, 0x42, 0x00, 0x04, 0x00, 0x01, 0xF5, 0xFF };
    static u8 fwd8[266], fwd16[313];
    struct rcx *b = run_code(dowhile, sizeof dowhile);
    (void)state;
    assert_int_equal(b->global[1], 5);
    brick_free(b);

    /* 85: distance 255 is unsigned forward (0 > 1 fails, so it jumps) */
    PUT(fwd8, 0, CHK(0, 0, CONST, 0, CONST, 1, 261));
    assert_int_equal(fwd8[6], 0xFF);
    filler(fwd8, 7, 254);
    PUT(fwd8, 261, INC(1));
    b = run_code(fwd8, sizeof fwd8);
    assert_int_equal(b->global[0], 0);
    assert_int_equal(b->global[1], 1);
    brick_free(b);

    /* 95: forward 300 */
    PUT(fwd16, 0, CHKL(0, 0, CONST, 0, CONST, 1, 308));
    filler(fwd16, 8, 300);
    PUT(fwd16, 308, INC(1));
    b = run_code(fwd16, sizeof fwd16);
    assert_int_equal(b->global[0], 0);
    assert_int_equal(b->global[1], 1);
    brick_free(b);
}

/* ------------------------------------------------------------------------------------------------------------ */
/* Straight programs: task 0 (and subroutines 0, 1) run to completion, then globals 0-4 are checked. */

#define CODE(...) { __VA_ARGS__ }, sizeof((const u8[]){ __VA_ARGS__ })
#define NONE { 0 }, 0

struct prog_case {
    const char *what;
    u8 task[48];
    u8 tlen;
    u8 sub0[24];
    u8 s0len;
    u8 sub1[24];
    u8 s1len;
    s16 expect[5]; /* globals 0-4 afterwards */
};

static void run_cases(const struct prog_case *c, unsigned n)
{
    unsigned i, g;
    for (i = 0; i < n; i++, c++) {
        struct rcx *b = brick_new();
        if (c->s0len)
            load(b, 0, 0, c->sub0, c->s0len);
        if (c->s1len)
            load(b, 0, 1, c->sub1, c->s1len);
        load(b, 1, 0, c->task, c->tlen);
        brick_start(b, 0);
        if (brick_run_until_idle(b, 5000, 10) < 0)
            fail_msg("%s: still running", c->what);
        for (g = 0; g < 5; g++)
            if (b->global[g] != c->expect[g])
                fail_msg("%s: global %u = %d, expected %d", c->what, g, b->global[g], c->expect[g]);
        brick_free(b);
    }
}

static const struct prog_case jumps[] = {
    { "SJump forward and back, SDecVarJumpLTZero exit (pp. 40, 62)",
      CODE(SETV(2, CONST, 2), JMP(5, 12), SETV(1, CONST, 1), /* 12: */ INC(0), DECVJN(17, 2, 22), JMP(20, 12)),
      NONE, NONE, { 3, 0, -1 } },
    { "SCheckDo: timer as source 1; a task local as 8-bit value 2 (pp. 93, 6)",
      CODE(SETV(40, CONST, 7), 0xA1, 0x00,              /* local 40 = 7, timer 0 = 0 */
           CHK(7, 2, TIMER, 0, CONST, 0, 19), INC(0),   /* timer 0 == 0 holds */
           CHK(19, 1, CONST, 6, VAR, 40, 31), INC(1),   /* 6 < local 40 holds */
           CHK(31, 0, CONST, 6, VAR, 40, 43), INC(2)),  /* 6 > local 40 fails */
      NONE, NONE, { 1, 1, 0 } },
};

static const struct prog_case loops[] = {
    { "repeat(3) as nqc's RCX 1.0 target emits it: loops 3 / loopc / body / jmp",
      CODE(0x13, 0x07, 0x02, 0x07, 0xE1, 0x87, 0x82, 0x02, 0x03, 0x37, 0x08, 0x24, 0x00, 0x02, 0x01, 0x00,
           0x27, 0x88),
      NONE, NONE, { 3 } },
    { "four nested levels 2 x 3 x 4 x 5 (p. 57)",
      CODE(LOOPS(CONST, 2), LOOPC(3, 33), LOOPS(CONST, 3), LOOPC(8, 31), LOOPS(CONST, 4), LOOPC(13, 29),
           LOOPS(CONST, 5), LOOPC(18, 27), /* 20: */ INC(0), JMP(25, 18), /* 27: */ JMP(27, 13), JMP(29, 8),
           JMP(31, 3), /* 33: */ INC(1)),
      NONE, NONE, { 120, 1 } },
    /* "There are only 4 loop levels and if they are all in use, the command is ignored" (p. 57): the checks then
     * run on level 4 (count 2: twice; 9 if the fifth had been pushed or had overwritten level 4), then level 3 */
    { "a fifth SetLoopCounter is ignored",
      CODE(LOOPS(CONST, 1), LOOPS(CONST, 1), LOOPS(CONST, 1), LOOPS(CONST, 2), LOOPS(CONST, 9),
           /* 15: */ LOOPC(15, 24), INC(0), JMP(22, 15),
           /* 24: */ LOOPC(24, 31), INC(1),             /* level 3: 1 -> 0, falls through */
           /* 31: */ LOOPC(31, 38), INC(2)),            /* level 3: 0 -> pops and jumps */
      NONE, NONE, { 2, 1, 0 } },
    /* "If there is no current or active loop level, the command is ignored" (pp. 41, 58) */
    { "SCheckLoopCounter without a level", CODE(LOOPC(0, 7), INC(1)), NONE, NONE, { 0, 1 } },
    { "LCheckLoopCounter without a level", CODE(LOOPCL(0, 8), INC(1)), NONE, NONE, { 0, 1 } },
    { "check after the only level was popped",
      CODE(LOOPS(CONST, 0), LOOPC(3, 5), LOOPC(5, 12), INC(1)), NONE, NONE, { 0, 1 } },
};

/* Gosub / EndOfSub (spec pp. 26, 39). */
static const struct prog_case subs[] = {
    { "Gosub returns to the instruction after the call; EndOfSub returns",
      CODE(0x17, 0x00, INC(1), 0x17, 0x00, INC(1)), CODE(SUMV(0, CONST, 5), 0xF6, INC(3)), NONE, { 10, 2, 0, 0 } },
    { "running off the end of a subroutine returns (nqc appends no F6, host-tools.md §4)",
      CODE(0x17, 0x00, INC(1), 0x17, 0x00, INC(1)), CODE(SUMV(0, CONST, 5)), NONE, { 10, 2 } },
    { "jumps inside a subroutine are relative to its own code",
      CODE(0x17, 0x00, INC(1), 0x17, 0x00, INC(1)),
      CODE(SETV(5, CONST, 3), DECVJN(5, 5, 15), INC(2), JMP(13, 5)), NONE, { 0, 2, 6 } },
    /* "If called outside of a subroutine (when the return address is cleared) ... stop the task" (p. 26) */
    { "EndOfSub in a task stops it", CODE(INC(0), 0xF6, INC(1)), NONE, NONE, { 1, 0 } },
    /* One return address: a Gosub inside a sub overwrites it, the inner sub returns into the outer one, whose
     * end then finds no return address and stops the task (pp. 26, 39) */
    { "nested Gosub: outer end stops the task",
      CODE(0x17, 0x00, INC(1)), CODE(INC(0), 0x17, 0x01, INC(3)), CODE(INC(2)), { 1, 0, 1, 1, 0 } },
    { "nested Gosub with explicit EndOfSub",
      CODE(0x17, 0x00, INC(1)), CODE(INC(0), 0x17, 0x01, INC(3), 0xF6, INC(4)), CODE(INC(2), 0xF6),
      { 1, 0, 1, 1, 0 } },
    { "Gosub to an empty subroutine does nothing and leaves no return address",
      CODE(0x17, 0x03, INC(1), 0xF6, INC(2)), NONE, NONE, { 0, 1, 0 } },
    { "Gosub number 8 and up: no such subroutine", CODE(0x17, 0x08, 0x17, 0xFF, INC(1)), NONE, NONE, { 0, 1 } },
};

static void straight_jumps(void **state) { (void)state; run_cases(jumps, sizeof jumps / sizeof jumps[0]); }
static void straight_loops(void **state) { (void)state; run_cases(loops, sizeof loops / sizeof loops[0]); }
static void straight_subs(void **state) { (void)state; run_cases(subs, sizeof subs / sizeof subs[0]); }

/* ------------------------------------------------------------------------------------------------------------ */
/* SetLoopCounter / CheckLoopCounter (spec pp. 41, 57, 58). */

static void loop_counts(void **state)
{
    /* count from var[5]: 1-255 loop that often; anything else becomes 0 and exits at once (p. 57) */
    static const struct { s16 count; s16 loops; } cases[] = {
        { 1, 1 }, { 2, 2 }, { 255, 255 }, { 0, 0 }, { 256, 0 }, { 257, 0 }, { 511, 0 }, { -1, 0 }, { 1000, 0 },
        { -32768, 0 },
    };
    static const u8 s[] = { LOOPS(VAR, 5), LOOPC(3, 12), INC(0), JMP(10, 3), INC(1) };
    static const u8 l[] = { LOOPS(VAR, 5), LOOPCL(3, 13), INC(0), JMP(11, 3), INC(1) };
    unsigned i, k;
    (void)state;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++)
        for (k = 0; k < 2; k++) {
            struct rcx *b = brick_new();
            b->global[5] = cases[i].count;
            load(b, 1, 0, k ? l : s, k ? sizeof l : sizeof s);
            brick_start(b, 0);
            assert_true(brick_run_until_idle(b, 5000, 10) >= 0);
            if (b->global[0] != cases[i].loops || b->global[1] != 1)
                fail_msg("%s count %d: %d loops, expected %d", k ? "92" : "37", cases[i].count, b->global[0],
                         cases[i].loops);
            brick_free(b);
        }
}

/* ------------------------------------------------------------------------------------------------------------ */
/* Tasks from a program (spec pp. 16, 31, 32, 47). */

static void starttask_restarts_from_top(void **state)
{
    static const u8 task[] = { INC(0), 0x71, 0x00, INC(1) };
    struct rcx *b = brick_new();
    (void)state;
    load(b, 1, 0, task, sizeof task);
    brick_start(b, 0);
    assert_int_equal(vm_run(b, 100), 100);
    assert_int_equal(b->global[0], 50);
    assert_int_equal(b->global[1], 0);
    brick_free(b);
}

static void start_and_stop_other_tasks(void **state)
{
    static const u8 t0[] = { 0x71, 0x01, WAIT(5), 0x71, 0x01, WAIT(5), 0x81, 0x01, 0x71, 0x05, INC(2) };
    static const u8 t1[] = { INC(1), 0x27, 0x81 };
    static const u8 self[] = { 0x81, 0x00, INC(0) };
    struct rcx *b = brick_new();
    (void)state;
    load(b, 1, 0, t0, sizeof t0);
    load(b, 1, 1, t1, sizeof t1);
    brick_start(b, 0);
    assert_true(brick_run_until_idle(b, 1000, 10) >= 0); /* also: task 1 was stopped */
    assert_int_equal(b->global[1], 2);                   /* restarted from the top once */
    assert_int_equal(b->global[2], 1);                   /* start of empty task 5 ignored (p. 31) */
    assert_int_equal(b->task[5].state, RCX_TASK_IDLE);
    brick_free(b);
    b = run_code(self, sizeof self);
    assert_int_equal(b->global[0], 0);
    brick_free(b);
}

static void stopalltasks_from_program(void **state)
{
    static const u8 t0[] = { 0x71, 0x01, 0x71, 0x02, WAIT(3), 0x50, INC(0) };
    static const u8 t1[] = { INC(1), JMP(5, 0) }, t2[] = { INC(2), JMP(5, 0) };
    struct rcx *b = brick_new();
    unsigned n;
    (void)state;
    load(b, 1, 0, t0, sizeof t0);
    load(b, 1, 1, t1, sizeof t1);
    load(b, 1, 2, t2, sizeof t2);
    brick_start(b, 0);
    assert_true(brick_run_until_idle(b, 1000, 10) >= 0);
    assert_true(b->global[1] > 0 && b->global[2] > 0);
    assert_int_equal(b->global[0], 0); /* the caller is one of "all tasks" */
    for (n = 0; n < RCX_TASKS; n++)
        assert_int_equal(b->task[n].state, RCX_TASK_IDLE);
    brick_free(b);
}

static void setpriority_stored_in_task(void **state)
{
    static const u8 t0[] = { 0x71, 0x01, 0xD7, 0x05, WAIT(100) }, t1[] = { 0xD7, 0xFF, WAIT(100) };
    struct rcx *b = brick_new();
    (void)state;
    load(b, 1, 0, t0, sizeof t0);
    load(b, 1, 1, t1, sizeof t1);
    brick_start(b, 0);
    brick_run_ms(b, 5, 10);
    assert_int_equal(b->task[0].priority, 5);
    assert_int_equal(b->task[1].priority, 255); /* all 256 levels can be used (p. 47) */
    brick_free(b);
}

/* Wait: 10 ms units on a 10 ms grid; x++; Wait(1) runs 100 times a second (reference-firmware.md). */
static void wait_runs_on_10ms_grid(void **state)
{
    static const u8 loop[] = { INC(0), WAIT(1), JMP(9, 0) };
    struct rcx *b = brick_new();
    s16 x1;
    (void)state;
    load(b, 1, 0, loop, sizeof loop);
    brick_start(b, 0);
    brick_run_ms(b, 1000, 10);
    x1 = b->global[0];
    assert_in_range(x1, 99, 101);
    brick_run_ms(b, 1000, 10);
    assert_int_equal(b->global[0] - x1, 100);
    brick_run_ms(b, 8000, 10);
    assert_int_equal(b->global[0] - x1, 900);
    brick_free(b);
}

static void wait_negative_ignored_and_from_variable(void **state)
{
    static const u8 neg[] = { 0x43, 0x02, 0xF6, 0xFF, INC(1) }; /* nqc's Wait(-10) */
    static const u8 var[] = { 0x43, VAR, 0x00, 0x00, INC(1) };  /* nqc's Wait(x) */
    struct rcx *b = brick_new();
    (void)state;
    load(b, 1, 0, neg, sizeof neg);
    brick_start(b, 0);
    vm_run(b, 10); /* no time passes */
    assert_int_equal(b->global[1], 1);
    brick_free(b);

    b = brick_new();
    b->global[0] = 50; /* 500 ms */
    load(b, 1, 0, var, sizeof var);
    brick_start(b, 0);
    brick_run_ms(b, 485, 10);
    assert_int_equal(b->global[1], 0);
    brick_run_ms(b, 25, 10);
    assert_int_equal(b->global[1], 1);
    brick_free(b);
}

/* ------------------------------------------------------------------------------------------------------------ */
/* SelectProgram and source 8 (spec pp. 6, 33). */

static struct rcx *two_slots(const u8 *select, unsigned len)
{
    static const u8 slot2[] = { INC(2) };
    static const u8 spin[] = { INC(1), 0x27, 0x81 };
    struct rcx *b = brick_new();
    u8 t0[32];
    select_slot(b, 2);
    load(b, 1, 0, slot2, sizeof slot2);
    select_slot(b, 0);
    PUT(t0, 0, 0x71, 0x01, WAIT(2));
    memcpy(t0 + 6, select, len);
    PUT(t0, 6 + len, INC(0));
    load(b, 1, 0, t0, 6 + len + 5);
    load(b, 1, 1, spin, sizeof spin);
    return b;
}

static void selectprogram_from_program_chains(void **state)
{
    static const u8 prgm[] = { 0x91, 0x02 };
    static const u8 src8[] = { 0x05, 0x08, 0x00, CONST, 0x02, 0x00 };
    const u8 *sel[2] = { prgm, src8 };
    unsigned len[2] = { sizeof prgm, sizeof src8 }, k;
    (void)state;
    for (k = 0; k < 2; k++) {
        struct rcx *b = two_slots(sel[k], len[k]);
        brick_start(b, 0);
        assert_true(brick_run_until_idle(b, 1000, 10) >= 0); /* task 1 stopped, new task 0 ran and ended */
        assert_int_equal(b->prog, 2);
        assert_int_equal(b->global[1], 1);
        assert_int_equal(b->global[0], 0); /* the selecting task was stopped */
        assert_int_equal(b->global[2], 1); /* task 0 of slot 2 started */
        brick_free(b);
    }
}

static void selectprogram_direct_starts_nothing(void **state)
{
    static const u8 prgm[] = { 0x91, 0x02 };
    static const u8 src8[] = { 0x05, 0x08, 0x00, CONST, 0x02, 0x00 };
    const u8 *sel[2] = { prgm, src8 };
    unsigned len[2] = { sizeof prgm, sizeof src8 }, k, n;
    (void)state;
    for (k = 0; k < 2; k++) {
        struct rcx *b = two_slots(prgm, sizeof prgm);
        brick_start(b, 1); /* task 1 of slot 0 spinning */
        brick_run_ms(b, 2, 10);
        assert_int_equal(brick_cmd(b, sel[k], len[k], NULL), 1);
        assert_int_equal(b->prog, 2);
        for (n = 0; n < RCX_TASKS; n++)
            assert_int_equal(b->task[n].state, RCX_TASK_IDLE); /* stopped, and nothing started */
        assert_int_equal(vm_run(b, 100), 0);
        assert_int_equal(b->global[2], 0);
        brick_free(b);
    }
}

static void selectprogram_to_empty_slot(void **state)
{
    static const u8 code[] = { 0x91, 0x03, INC(0) };
    struct rcx *b = run_code(code, sizeof code);
    (void)state;
    assert_int_equal(b->prog, 3);
    assert_int_equal(b->global[0], 0);
    brick_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(encodings_match_nqc_listings),
        cmocka_unit_test(jump_to_itself_loops_forever),
        cmocka_unit_test(long_jumps),
        cmocka_unit_test(nqc_long_repeat_loops),
        cmocka_unit_test(decvar_loops_exactly_n_times),
        cmocka_unit_test(decvar_jumps_backwards),
        cmocka_unit_test(checkdo_all_relations),
        cmocka_unit_test(checkdo_distances),
        cmocka_unit_test(loop_counts),
        cmocka_unit_test(straight_jumps),
        cmocka_unit_test(straight_loops),
        cmocka_unit_test(straight_subs),
        cmocka_unit_test(starttask_restarts_from_top),
        cmocka_unit_test(start_and_stop_other_tasks),
        cmocka_unit_test(stopalltasks_from_program),
        cmocka_unit_test(setpriority_stored_in_task),
        cmocka_unit_test(wait_runs_on_10ms_grid),
        cmocka_unit_test(wait_negative_ignored_and_from_variable),
        cmocka_unit_test(selectprogram_from_program_chains),
        cmocka_unit_test(selectprogram_direct_starts_nothing),
        cmocka_unit_test(selectprogram_to_empty_slot),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
