/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Parameter sources 0-36 (spec pp. 6-10): reads through Poll 0x12 and SetVar 0x14, writes through
 * SetSourceValue 0x05 (p. 86), with firm0328's observed details from reference-firmware.md.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "brick.h"

#define SEND(b, r, ...) \
    brick_cmd((b), (const u8[]){ __VA_ARGS__ }, sizeof((const u8[]){ __VA_ARGS__ }), (r))

static void assert_unchanged(const struct rcx *b, struct rcx *s)
{
    assert_memory_equal(b, s, sizeof *b);
    brick_free_copy(s);
}

static s16 poll(struct rcx *b, u8 src, u8 idx)
{
    u8 r[RCX_REPLY_MAX];
    assert_int_equal(SEND(b, r, 0x12, src, idx), 3);
    return (s16)(u16)(r[1] | r[2] << 8);
}

/* Read any source with a 16-bit index: SetVar var[31] = S(src, idx), then poll var[31]. */
static s16 rd(struct rcx *b, u8 src, u16 idx)
{
    assert_int_equal(SEND(b, NULL, 0x14, 31, src, (u8)idx, (u8)(idx >> 8)), 1);
    return poll(b, 0, 31);
}

/* SetSourceValue dst[idx] = constant v. */
static void wr(struct rcx *b, u8 dst, u8 idx, s16 v)
{
    assert_int_equal(SEND(b, NULL, 0x05, dst, idx, 0x02, (u8)v, (u8)((u16)v >> 8)), 1);
}

static int running(const struct rcx *b, u8 n)
{
    return b->task[n].state != RCX_TASK_IDLE;
}

/* A brick where every source holds a distinctive non-zero value, so that a stray read or write shows. */
static struct rcx *filled(void)
{
    struct rcx *b = brick_new();
    u8 i;
    for (i = 0; i < 32; i++)
        wr(b, 0, i, (s16)(100 + i));
    for (i = 0; i < 4; i++)
        wr(b, 1, i, (s16)(1000 + i));
    for (i = 0; i < 3; i++) {
        SEND(b, NULL, 0x32, i, (u8)(i + 1));
        b->sensor[i].raw = (u16)(300 + i);   /* delivered by the sensor driver */
        b->sensor[i].value = (s16)(40 + i);
        b->sensor[i].boolean = 1;
    }
    for (i = 0; i < 16; i++) {
        wr(b, 27, i, (s16)(-10 - i));
        wr(b, 28, i, (s16)(500 + i));
        wr(b, 29, i, (s16)(-500 - i));
        wr(b, 30, i, (s16)(20 + i));
        wr(b, 31, i, (s16)(30 + i));
    }
    for (i = 0; i < 18; i++)
        wr(b, 33, i, (s16)(0x40 + i));
    wr(b, 14, 0, 754);
    wr(b, 15, 0, 0x5A);
    SEND(b, NULL, 0x21, 0x81);
    SEND(b, NULL, 0xA3, 0x02, 0x02, 0x04);
    return b;
}

static void variables(void **state)
{
    struct rcx *b = brick_new();
    struct rcx *s;
    u8 v;
    (void)state;
    for (v = 0; v < 32; v++)
        wr(b, 0, v, (s16)(v * 1000 - 16000));
    for (v = 0; v < 32; v++)
        assert_int_equal(poll(b, 0, v), v * 1000 - 16000);
    wr(b, 0, 7, -32768);
    assert_int_equal(rd(b, 0, 7), -32768);
    wr(b, 0, 7, 32767);
    assert_int_equal(rd(b, 0, 7), 32767);
    /* Direct commands have no locals (p. 5: only available to tasks in a running program). */
    s = brick_copy(b);
    for (v = 32; v < 48; v++)
        wr(b, 0, v, 5);
    assert_unchanged(b, s);
    brick_free(b);
}

/* SetSourceValue uses bits 0-5 of both source bytes (p. 86). */
static void source_byte_bits_0_to_5(void **state)
{
    struct rcx *b = brick_new();
    (void)state;
    assert_int_equal(SEND(b, NULL, 0x05, 0x41, 0x02, 0x02, 0x2C, 0x01), 1); /* 0x41 -> timer */
    assert_int_equal(poll(b, 1, 2), 300);
    assert_int_equal(SEND(b, NULL, 0x05, 0xC0, 0x03, 0x82, 0x07, 0x00), 1); /* var[3] = constant 7 */
    assert_int_equal(poll(b, 0, 3), 7);
    brick_free(b);
}

static void timers(void **state)
{
    struct rcx *b = brick_new();
    (void)state;
    wr(b, 1, 3, 32767);
    wr(b, 1, 0, 0);
    assert_int_equal(poll(b, 1, 3), 32767);
    brick_run_ms(b, 100, 1);
    assert_int_equal(poll(b, 1, 0), 1);        /* 100 ms resolution */
    assert_int_equal(poll(b, 1, 3), 0);        /* 0x7FFF then 0 (p. 6) */
    brick_run_ms(b, 1000, 1);
    assert_int_equal(poll(b, 1, 0), 11);
    assert_int_equal(SEND(b, NULL, 0xA1, 0x00), 1); /* ClearTimer (p. 34) */
    assert_int_equal(poll(b, 1, 0), 0);
    assert_int_equal(poll(b, 1, 3), 10);
    brick_free(b);
}

/* Source 26 is derived from source 1: 10 x the 100 ms count + the 10 ms steps of the current tick (reference). */
static void fast_timers(void **state)
{
    struct rcx *b = brick_new();
    s16 v;
    (void)state;
    brick_run_ms(b, 350, 1);
    assert_int_equal(poll(b, 1, 0), 3);
    assert_int_equal(poll(b, 26, 0), 35);
    wr(b, 1, 1, 5);                            /* writing source 1 affects source 26 (p. 8) ... */
    v = poll(b, 26, 1);
    assert_in_range(v, 50, 60);                /* "up to 10 more" right after a set */
    wr(b, 26, 2, 250);                         /* ... and vice versa */
    assert_int_equal(poll(b, 1, 2), 25);
    wr(b, 1, 3, 0);
    brick_run_ms(b, 1000, 1);
    assert_in_range(poll(b, 26, 3), 100, 110);
    assert_int_equal(poll(b, 1, 3), 10);
    brick_free(b);
}

static void constant(void **state)
{
    struct rcx *b = brick_new();
    (void)state;
    assert_int_equal(poll(b, 2, 0), 0);
    assert_int_equal(poll(b, 2, 255), 255);
    assert_int_equal(rd(b, 2, 0x8000), -32768);
    assert_int_equal(rd(b, 2, 0x7FFF), 32767);
    assert_int_equal(rd(b, 2, 0xFFFF), -1);
    brick_free(b);
}

static void read_only_sources_ignore_writes(void **state)
{
    static const u8 ro[][2] = { { 2, 0 }, { 3, 0 }, { 3, 2 }, { 9, 0 }, { 12, 1 }, { 13, 2 }, { 17, 0 },
                                { 17, 1 }, { 23, 0 }, { 25, 3 }, { 34, 0 }, { 35, 0 } };
    unsigned i;
    (void)state;
    for (i = 0; i < sizeof ro / sizeof ro[0]; i++) {
        struct rcx *b = filled();
        struct rcx *s = brick_copy(b);
        wr(b, ro[i][0], ro[i][1], 5);
        wr(b, ro[i][0], ro[i][1], -1);
        assert_unchanged(b, s);
        brick_free(b);
    }
}

static void undefined_sources(void **state)
{
    static const u8 holes[] = { 5, 6, 7, 16, 18, 19, 20, 22, 24, 32 };
    struct rcx *b = filled();
    struct rcx *s;
    unsigned i, src;
    (void)state;
    s = brick_copy(b);
    /* Poll answers 0x8000 for what does not exist (reference-firmware.md, "The brick's face"); a program or a
     * SetVar reads 0 (below). */
    for (i = 0; i < sizeof holes; i++) {
        assert_int_equal((u16)poll(b, holes[i], 0), 0x8000);
        assert_int_equal((u16)poll(b, holes[i], 1), 0x8000);
        wr(b, holes[i], 0, 1234);
        wr(b, holes[i], 1, -1);
    }
    /* 37-42 are firm0332's datalog read-back and 43/44 Swan's globals (issue 16, swan-target.md 3): they exist. */
    for (src = 45; src < 64; src++) {
        assert_int_equal((u16)poll(b, (u8)src, 0), 0x8000);
        wr(b, (u8)src, 0, 1234);
    }
    for (src = 64; src < 256; src++)
        assert_int_equal((u16)poll(b, (u8)src, 0), 0x8000);
    assert_unchanged(b, s);
    for (i = 0; i < sizeof holes; i++)
        assert_int_equal(rd(b, holes[i], 0), 0);
    brick_free(b);
}

/* Out-of-range indices (ranges of pp. 6-10): read 0 (Poll: 0x8000), writes ignored, neighbours untouched. */
static void out_of_range_indices(void **state)
{
    static const u8 bad[][2] = { { 0, 48 }, { 0, 255 }, { 1, 4 }, { 3, 3 }, { 8, 1 }, { 9, 3 }, { 10, 3 },
                                 { 11, 3 }, { 12, 3 }, { 13, 3 }, { 14, 1 }, { 15, 1 }, { 17, 3 }, { 21, 3 },
                                 { 23, 10 }, { 25, 16 }, { 26, 4 }, { 27, 16 }, { 28, 16 }, { 29, 16 },
                                 { 30, 16 }, { 31, 16 }, { 33, 18 }, { 34, 1 }, { 35, 1 }, { 36, 48 } };
    static const u8 wide[] = { 0, 1, 9, 10, 21, 26, 28, 33 };
    struct rcx *b = filled();
    struct rcx *s;
    unsigned i;
    (void)state;
    s = brick_copy(b);
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        /* 23/10 is the asking task's own events: the host has none, and reads 0 */
        if ((u16)poll(b, bad[i][0], bad[i][1]) != (bad[i][0] == 23 ? 0 : 0x8000))
            fail_msg("source %u index %u does not poll as 0x8000", bad[i][0], bad[i][1]);
        wr(b, bad[i][0], bad[i][1], 7);
        if (bad[i][1] < 255)
            wr(b, bad[i][0], (u8)(bad[i][1] + 1), 7);
    }
    assert_unchanged(b, s);
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) /* through SetVar (var[31]), as a program reads them */
        if (rd(b, bad[i][0], bad[i][1]) != 0)
            fail_msg("source %u index %u does not read 0", bad[i][0], bad[i][1]);
    /* 16-bit indices whose low byte is a valid index are still out of range. */
    for (i = 0; i < sizeof wide; i++)
        if (rd(b, wide[i], 0x0100) != 0)
            fail_msg("source %u index 0x100 does not read 0", wide[i]);
    brick_free(b);
}

static u8 motor(struct rcx *b, u8 i)
{
    u8 v = (u8)poll(b, 3, i);
    v &= (u8)~0x30;        /* remote overlay marker: not asserted for source 3 */
    if (v & 0x80)
        v &= (u8)~0x40;    /* "when bit 7 is set, bit 6 is ignored" (p. 6) */
    return v;
}

static void motor_status(void **state)
{
    struct rcx *b = brick_new();
    u8 i;
    (void)state;
    for (i = 0; i < 3; i++)
        assert_int_equal(motor(b, i), 0x4F);   /* power-on: forward, brake, max power (reference-firmware.md) */
    SEND(b, NULL, 0x21, 0x81);                 /* A on */
    SEND(b, NULL, 0x21, 0x42);                 /* B off (brake) */
    assert_int_equal(motor(b, 0), 0x8F);
    assert_int_equal(motor(b, 1), 0x4F);
    assert_int_equal(motor(b, 2), 0x4F);
    SEND(b, NULL, 0x21, 0x02);                 /* B float */
    assert_int_equal(motor(b, 1), 0x0F);
    SEND(b, NULL, 0xE1, 0x01);                 /* A backwards (p. 38) */
    assert_int_equal(motor(b, 0), 0x87);
    SEND(b, NULL, 0xE1, 0x43);                 /* A and B reverse (flip) */
    assert_int_equal(motor(b, 0), 0x8F);
    assert_int_equal(motor(b, 1), 0x07);
    SEND(b, NULL, 0xE1, 0x86);                 /* B and C forwards */
    assert_int_equal(motor(b, 1), 0x0F);
    SEND(b, NULL, 0x13, 0x07, 0x02, 0x03);     /* SetPower all = 3 (p. 64) */
    assert_int_equal(motor(b, 0), 0x8B);
    assert_int_equal(motor(b, 2), 0x4B);
    SEND(b, NULL, 0x14, 0x00, 0x02, 0x05, 0x00);
    SEND(b, NULL, 0x13, 0x04, 0x00, 0x00);     /* C power = var[0] = 5 */
    assert_int_equal(motor(b, 2), 0x4D);
    assert_int_equal(motor(b, 0), 0x8B);
    brick_free(b);
}

/* firm0328 clears bit 6 of an output that is on (reference-firmware.md, "The brick's face"): the raw byte, not
 * only what p. 6 lets a reader ignore. */
static void motor_status_on_has_bit_6_clear(void **state)
{
    struct rcx *b = brick_new();
    (void)state;
    SEND(b, NULL, 0x21, 0x41);                 /* Off(OUT_A) */
    assert_int_equal((u8)poll(b, 3, 0), 0x4F);
    SEND(b, NULL, 0x21, 0x81);                 /* On(OUT_A) */
    assert_int_equal((u8)poll(b, 3, 0), 0x8F);
    SEND(b, NULL, 0x13, 0x01, 0x02, 0x03);     /* forward at power 3 */
    assert_int_equal((u8)poll(b, 3, 0), 0x8B);
    SEND(b, NULL, 0x21, 0x41);                 /* off again: brake */
    assert_int_equal((u8)poll(b, 3, 0), 0x4B);
    SEND(b, NULL, 0x21, 0x01);                 /* float, then on */
    SEND(b, NULL, 0x21, 0x81);
    assert_int_equal((u8)poll(b, 3, 0), 0x8B);
    brick_free(b);
}

/* firm0328 shows the effective output in source 3 (reference-firmware.md, "Observed"). */
static void motor_status_effective_output(void **state)
{
    struct rcx *b = brick_new();
    (void)state;
    SEND(b, NULL, 0x77, 0x01);                 /* A globally inverted */
    assert_int_equal(motor(b, 0), 0x47);       /* forward motor reads reverse */
    SEND(b, NULL, 0xE1, 0x01);
    assert_int_equal(motor(b, 0), 0x4F);       /* reverse motor reads forward */
    SEND(b, NULL, 0x77, 0x81);                 /* normal again */
    assert_int_equal(motor(b, 0), 0x47);
    SEND(b, NULL, 0xA3, 0x02, 0x02, 0x03);     /* B max power 3 */
    assert_int_equal(motor(b, 1), 0x4B);
    SEND(b, NULL, 0x13, 0x02, 0x02, 0x02);
    assert_int_equal(motor(b, 1), 0x4A);       /* below the cap: its own power */
    SEND(b, NULL, 0x21, 0x84);                 /* C on ... */
    SEND(b, NULL, 0x67, 0x04);                 /* ... but globally floated */
    assert_int_equal(motor(b, 2), 0x4F);       /* reads off/brake */
    SEND(b, NULL, 0x67, 0x44);                 /* globally off */
    assert_int_equal(motor(b, 2), 0x4F);
    SEND(b, NULL, 0x67, 0x84);                 /* connected again */
    assert_int_equal(motor(b, 2), 0x8F);
    brick_free(b);
}

static void global_motor_status(void **state)
{
    struct rcx *b = brick_new();
    u8 i;
    (void)state;
    /* On, normal, max power 7; bits 4-5 always set (reference-firmware.md); bit 6 is not in the layout (p. 8). */
    for (i = 0; i < 3; i++)
        assert_int_equal(poll(b, 17, i), 0xBF);
    SEND(b, NULL, 0x67, 0x41);                 /* A off */
    assert_int_equal(poll(b, 17, 0) & ~0x40, 0x3F);
    SEND(b, NULL, 0x67, 0x01);                 /* A float */
    assert_int_equal(poll(b, 17, 0) & ~0x40, 0x3F);
    SEND(b, NULL, 0x67, 0x81);                 /* A on */
    assert_int_equal(poll(b, 17, 0), 0xBF);
    SEND(b, NULL, 0x77, 0x02);                 /* B inverse (p. 43: "backwards" verb) */
    assert_int_equal(poll(b, 17, 1), 0xB7);
    SEND(b, NULL, 0x77, 0x42);                 /* B alternate: normal again */
    assert_int_equal(poll(b, 17, 1), 0xBF);
    SEND(b, NULL, 0xA3, 0x04, 0x02, 0x02);     /* C max power 2 */
    assert_int_equal(poll(b, 17, 2), 0xBA);    /* the reference's own example */
    SEND(b, NULL, 0x14, 0x00, 0x02, 0x00, 0x00);
    SEND(b, NULL, 0xA3, 0x04, 0x00, 0x00);     /* from a variable: 0 */
    assert_int_equal(poll(b, 17, 2), 0xB8);
    assert_int_equal(poll(b, 17, 0), 0xBF);
    brick_free(b);
}

static void random_source(void **state)
{
    struct rcx *b = brick_new();
    s16 a[20], v;
    int seen[4] = { 0 }, distinct = 0;
    unsigned i;
    (void)state;
    a[0] = -1;
    for (i = 0; i < 400; i++) {
        v = rd(b, 4, 3);
        assert_in_range(v, 0, 3);              /* "between 0 and the actual given range" (p. 6) */
        seen[v] = 1;
    }
    assert_true(seen[0] && seen[1] && seen[2] && seen[3]);
    for (i = 0; i < 50; i++) {
        v = rd(b, 4, 32767);
        assert_in_range(v, 0, 32767);
        distinct += v != a[0];
        a[0] = v;
    }
    assert_true(distinct > 40);
    assert_in_range(poll(b, 4, 10), 0, 10);
    /* Writing random 0 seeds the generator: the same seed gives the same sequence. */
    wr(b, 4, 0, 1234);
    for (i = 0; i < 20; i++)
        a[i] = rd(b, 4, 1000);
    wr(b, 4, 0, 1234);
    wr(b, 4, 5, 999);                          /* only index 0 is writable ("W: 0") */
    for (i = 0; i < 20; i++)
        assert_int_equal(rd(b, 4, 1000), a[i]);
    brick_free(b);
}

static void program_slot(void **state)
{
    static const u8 chain[] = { 0x05, 0x08, 0x00, 0x02, 0x01, 0x00, 0x27, 0x81 }; /* set S(8,0) = 1 */
    static const u8 count[] = { 0x24, 0x00, 0x02, 0x01, 0x00, 0x27, 0x86 };
    struct rcx *b = brick_new();
    (void)state;
    assert_int_equal(poll(b, 8, 0), 0);
    SEND(b, NULL, 0x91, 0x03);
    assert_int_equal(brick_download(b, 1, 0, count, sizeof count), 0);
    SEND(b, NULL, 0x91, 0x01);
    assert_int_equal(brick_download(b, 1, 0, count, sizeof count), 0);
    SEND(b, NULL, 0x91, 0x00);
    assert_int_equal(brick_download(b, 1, 0, chain, sizeof chain), 0);
    /* Written by a direct command: selects without starting (p. 6, p. 33). */
    wr(b, 8, 0, 3);
    assert_int_equal(poll(b, 8, 0), 3);
    assert_false(running(b, 0));
    wr(b, 8, 0, 5);                            /* values outside 0-4 are not accepted */
    wr(b, 8, 0, -1);
    assert_int_equal(poll(b, 8, 0), 3);
    /* Written by a program: the new slot's task 0 starts. */
    wr(b, 8, 0, 0);
    brick_start(b, 0);
    brick_run_ms(b, 10, 5);
    assert_int_equal(poll(b, 8, 0), 1);
    assert_true(running(b, 0));
    assert_true(poll(b, 0, 0) > 0);
    brick_free(b);
}

static void sensors(void **state)
{
    static const u8 mode[5] = { 0x00, 0x20, 0xA0, 0x80, 0xE0 }; /* p. 52 defaults */
    struct rcx *b = brick_new();
    struct rcx *s;
    u8 t, i;
    (void)state;
    for (i = 0; i < 3; i++) {
        b->sensor[i].raw = (u16)(1021 + i);
        b->sensor[i].value = (s16)(-7 - i);
        b->sensor[i].boolean = i & 1;
    }
    for (i = 0; i < 3; i++) {
        assert_int_equal(poll(b, 12, i), 1021 + i);
        assert_int_equal(poll(b, 9, i), -7 - i);
        assert_int_equal(poll(b, 13, i), i & 1);
    }
    for (t = 0; t < 5; t++) {
        b->sensor[1].value = 99;
        wr(b, 10, 1, t);
        assert_int_equal(poll(b, 10, 1), t);
        assert_int_equal(poll(b, 11, 1), mode[t]);
        assert_int_equal(poll(b, 9, 1), 0);    /* "resets previous sensor state" (p. 52) */
        SEND(b, NULL, 0x32, 2, t);
        assert_int_equal(poll(b, 10, 2), t);
        assert_int_equal(poll(b, 11, 2), mode[t]);
    }
    s = brick_copy(b);
    wr(b, 10, 1, 5);                           /* not a sensor type */
    wr(b, 10, 1, -1);
    wr(b, 10, 1, 0x101);                       /* beyond a byte: not type 1 */
    wr(b, 11, 1, 0x180);                       /* nor mode 0x80 */
    SEND(b, NULL, 0x32, 1, 5);
    SEND(b, NULL, 0x32, 3, 1);                 /* no sensor 3 */
    assert_unchanged(b, s);
    b->sensor[0].value = 12;
    wr(b, 11, 0, 0x85);                        /* mode | slope (p. 7) */
    assert_int_equal(poll(b, 11, 0), 0x85);
    assert_int_equal(poll(b, 9, 0), 0);        /* "also resets the processed sensor value" (p. 53) */
    assert_int_equal(poll(b, 10, 0), 0);
    brick_free(b);
}

static void watch(void **state)
{
    struct rcx *b = brick_new();
    (void)state;
    wr(b, 14, 0, 1439);                        /* 23:59 (p. 7) */
    assert_int_equal(poll(b, 14, 0), 1439);
    wr(b, 14, 0, 1440);
    wr(b, 14, 0, -1);
    assert_int_equal(poll(b, 14, 0), 1439);
    brick_run_ms(b, 60000, 0);
    assert_int_equal(poll(b, 14, 0), 0);       /* cannot exceed 23:59 */
    SEND(b, NULL, 0x22, 13, 7);                /* SetWatch (p. 51) */
    assert_int_equal(poll(b, 14, 0), 13 * 60 + 7);
    wr(b, 14, 0, 0);
    assert_int_equal(poll(b, 14, 0), 0);
    brick_free(b);
}

static void message(void **state)
{
    struct rcx *b = brick_new();
    (void)state;
    assert_int_equal(poll(b, 15, 0), 0);
    wr(b, 15, 0, 0x1234);                      /* only the low 8 bits (p. 7) */
    assert_int_equal(poll(b, 15, 0), 0x34);
    wr(b, 15, 0, -1);
    assert_int_equal(poll(b, 15, 0), 0xFF);
    SEND(b, NULL, 0xF7, 0x81);
    assert_int_equal(poll(b, 15, 0), 0x81);
    SEND(b, NULL, 0x90);                       /* ClearPBMessage (p. 20) */
    assert_int_equal(poll(b, 15, 0), 0);
    brick_free(b);
}

static void counters(void **state)
{
    struct rcx *b = filled();
    u8 i;
    (void)state;
    for (i = 0; i < 3; i++)                    /* identical to globals 0-2 (p. 8) */
        assert_int_equal(poll(b, 21, i), 100 + i);
    wr(b, 21, 1, -7);
    assert_int_equal(poll(b, 0, 1), -7);
    wr(b, 0, 2, 9);
    assert_int_equal(poll(b, 21, 2), 9);
    SEND(b, NULL, 0x97, 0x02);                 /* IncCounter (p. 44) */
    assert_int_equal(poll(b, 0, 2), 10);
    SEND(b, NULL, 0xA7, 0x01);
    assert_int_equal(poll(b, 21, 1), -8);
    SEND(b, NULL, 0xB7, 0x00);
    assert_int_equal(poll(b, 0, 0), 0);
    SEND(b, NULL, 0x97, 0x03);                 /* no counter 3: var[3] untouched */
    assert_int_equal(poll(b, 0, 3), 103);
    brick_free(b);
}

static void event_sources(void **state)
{
    struct rcx *b = brick_new();
    u8 e;
    (void)state;
    for (e = 0; e < 16; e++) {
        wr(b, 27, e, (s16)(-100 * e));         /* clicks: -32768 - 32767 */
        wr(b, 28, e, (s16)(32767 - e));
        wr(b, 29, e, (s16)(-32768 + e));
        wr(b, 30, e, (s16)(e * 2));
        wr(b, 31, e, (s16)(5 + e));
    }
    for (e = 0; e < 16; e++) {
        assert_int_equal(poll(b, 27, e), -100 * e);
        assert_int_equal(poll(b, 28, e), 32767 - e);
        assert_int_equal(poll(b, 29, e), -32768 + e);
        assert_int_equal(poll(b, 30, e), e * 2);
        assert_int_equal(poll(b, 31, e), 5 + e);
    }
    /* Hysteresis "must be non-negative" (p. 9): 0 - 32767. */
    wr(b, 30, 4, -1);
    wr(b, 30, 4, -32768);
    assert_int_equal(poll(b, 30, 4), 8);
    wr(b, 30, 4, 32767);
    assert_int_equal(poll(b, 30, 4), 32767);
    wr(b, 30, 4, 0);
    assert_int_equal(poll(b, 30, 4), 0);
    /* Duration 5 - 32767 (p. 9). */
    wr(b, 31, 6, 4);
    wr(b, 31, 6, 0);
    wr(b, 31, 6, -5);
    assert_int_equal(poll(b, 31, 6), 11);
    wr(b, 31, 6, 32767);
    assert_int_equal(poll(b, 31, 6), 32767);
    wr(b, 31, 6, 5);
    assert_int_equal(poll(b, 31, 6), 5);
    /* Task events (23) and event state (25) are read-only: see read_only_sources_ignore_writes. */
    for (e = 0; e < 10; e++)
        assert_int_equal(poll(b, 23, e), 0);   /* no monitoring has ended yet */
    brick_free(b);
}

static void uart_buffer(void **state)
{
    struct rcx *b = brick_new();
    u8 i;
    (void)state;
    for (i = 0; i < 18; i++)
        wr(b, 33, i, (s16)(0x1A0 + i));        /* 8-bit values (p. 9) */
    for (i = 0; i < 18; i++)
        assert_int_equal(poll(b, 33, i), 0xA0 + i);
    wr(b, 33, 17, -1);
    assert_int_equal(poll(b, 33, 17), 0xFF);
    brick_free(b);
}

static void battery_and_firmware(void **state)
{
    struct rcx *b = brick_new();
    (void)state;
    b->battery_mv = 8234;                      /* volts x 1000 (p. 9) */
    assert_int_equal(poll(b, 34, 0), 8234);
    assert_int_equal(poll(b, 35, 0), 328);     /* version x 100 (p. 9, reference-firmware.md) */
    assert_int_equal(rd(b, 35, 0), 328);
    brick_free(b);
}

static void indirect(void **state)
{
    static const s16 bad_ptr[] = { 48, -1, 1000, 32, 47, -32768 };
    struct rcx *b = filled();
    struct rcx *s;
    unsigned i;
    (void)state;
    wr(b, 0, 5, 10);
    wr(b, 0, 10, 77);
    assert_int_equal(poll(b, 36, 5), 77);      /* S(36,5) = var[var[5]] (p. 10) */
    wr(b, 36, 5, 99);
    assert_int_equal(poll(b, 0, 10), 99);
    assert_int_equal(poll(b, 0, 5), 10);
    /* Pointers that name no variable: read 0, write ignored. Locals (32, 47) do not exist for a direct
     * command (p. 5), so writing through them changes nothing either; what a poll of them answers is not
     * specified (0x8000 for a plain local poll), so it is not checked. */
    for (i = 0; i < sizeof bad_ptr / sizeof bad_ptr[0]; i++) {
        wr(b, 0, 5, bad_ptr[i]);
        s = brick_copy(b);
        if (bad_ptr[i] < 32 || bad_ptr[i] > 47)
            assert_int_equal(poll(b, 36, 5), 0);
        wr(b, 36, 5, 1);
        assert_unchanged(b, s);
    }
    brick_free(b);
}

static void indirect_locals_in_a_task(void **state)
{
    static const u8 code[] = {
        0x14, 0x21, 0x02, 0x07, 0x00,          /* setv var[33], 7 */
        0x14, 0x14, 0x02, 0x21, 0x00,          /* setv var[20], 33 */
        0x05, 0x24, 0x14, 0x02, 0x37, 0x00,    /* set S(36,20) = 55 -> var[33] */
        0x14, 0x00, 0x00, 0x21, 0x00,          /* setv var[0], var[33] */
        0x14, 0x01, 0x24, 0x14, 0x00,          /* setv var[1], S(36,20) */
    };
    struct rcx *b = brick_new();
    (void)state;
    assert_int_equal(brick_download(b, 1, 0, code, sizeof code), 0);
    brick_start(b, 0);
    assert_true(brick_run_until_idle(b, 100, 10) >= 0);
    assert_int_equal(poll(b, 0, 0), 55);
    assert_int_equal(poll(b, 0, 1), 55);
    brick_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(variables),
        cmocka_unit_test(source_byte_bits_0_to_5),
        cmocka_unit_test(timers),
        cmocka_unit_test(fast_timers),
        cmocka_unit_test(constant),
        cmocka_unit_test(read_only_sources_ignore_writes),
        cmocka_unit_test(undefined_sources),
        cmocka_unit_test(out_of_range_indices),
        cmocka_unit_test(motor_status),
        cmocka_unit_test(motor_status_on_has_bit_6_clear),
        cmocka_unit_test(motor_status_effective_output),
        cmocka_unit_test(global_motor_status),
        cmocka_unit_test(random_source),
        cmocka_unit_test(program_slot),
        cmocka_unit_test(sensors),
        cmocka_unit_test(watch),
        cmocka_unit_test(message),
        cmocka_unit_test(counters),
        cmocka_unit_test(event_sources),
        cmocka_unit_test(uart_buffer),
        cmocka_unit_test(battery_and_firmware),
        cmocka_unit_test(indirect),
        cmocka_unit_test(indirect_locals_in_a_task),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
