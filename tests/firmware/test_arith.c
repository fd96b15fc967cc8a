/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The firmware's integer helpers (drivers/arith/arith.c), compiled for the host under their rcx_ names,
 * against C's own operators: every pair of a list of edge values, then a few hundred thousand
 * pseudo-random pairs of mixed magnitudes per helper. Division by zero and the most negative value
 * divided by -1 must give the results arith.h promises (C leaves both undefined).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "arith.h"

#define RANDOM_PAIRS 300000L

static const u16 edges16[] = {
    0, 1, 2, 3, 5, 7, 8, 9, 10, 15, 16, 17, 31, 100, 126, 127, 128, 129, 254, 255, 256, 257, 511, 512,
    1000, 0x0FFF, 0x1000, 0x1234, 0x3FFF, 0x4000, 0x7FFE, 0x7FFF, 0x8000, 0x8001, 0x8002, 0xABCD,
    0xC000, 0xFEFF, 0xFF00, 0xFF01, 0xFFFD, 0xFFFE, 0xFFFF,
};

static const u32 edges32[] = {
    0, 1, 2, 3, 7, 10, 100, 127, 128, 255, 256, 1000, 0x7FFF, 0x8000, 0xFFFE, 0xFFFF, 0x10000,
    0x10001, 0x12345, 0x1FFFF, 0xFFFFFF, 0x1000000, 0x12345678, 0x7FFFFFFE, 0x7FFFFFFF, 0x80000000,
    0x80000001, 0x9ABCDEF0, 0xFFFF0000, 0xFFFF0001, 0xFFFFFFFE, 0xFFFFFFFF,
};

#define COUNT(a) (sizeof(a) / sizeof((a)[0]))

/* xorshift32: deterministic, so a failure repeats. */
static uint32_t rng_state;

static uint32_t rng(void)
{
    uint32_t x = rng_state;

    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    rng_state = x;
    return x;
}

/* Random values of every magnitude: small operands are the common case and take other paths. */
static u16 random16(void)
{
    uint32_t x = rng();

    return (u16)((x >> 8) >> (x & 15));
}

static u32 random32(void)
{
    uint32_t x = rng();

    return (u32)(rng() >> (x & 31));
}

/* The reference results, including the cases C leaves undefined. */
static void check16(u16 a, u16 b)
{
    s16 sa = (s16)a, sb = (s16)b;
    u16 q = b ? (u16)(a / b) : 0, r = b ? (u16)(a % b) : a;
    s16 sq = sb ? (s16)(int32_t)((int32_t)sa / sb) : 0;
    s16 sr = sb ? (s16)(int32_t)((int32_t)sa % sb) : sa;

    if (rcx_mul16(a, b) != (u16)((uint32_t)a * b) || rcx_divu16(a, b) != q || rcx_modu16(a, b) != r ||
        rcx_divs16(sa, sb) != sq || rcx_mods16(sa, sb) != sr) {
        print_error("16-bit a=0x%04X b=0x%04X: mul %04X/%04X divu %04X/%04X modu %04X/%04X "
                    "divs %d/%d mods %d/%d\n",
                    a, b, rcx_mul16(a, b), (u16)((uint32_t)a * b), rcx_divu16(a, b), q, rcx_modu16(a, b), r,
                    rcx_divs16(sa, sb), sq, rcx_mods16(sa, sb), sr);
        fail();
    }
}

static void check32(u32 a, u32 b)
{
    s32 sa = (s32)a, sb = (s32)b;
    u32 q = b ? a / b : 0, r = b ? a % b : a;
    s32 sq = sb ? (s32)(int64_t)((int64_t)sa / sb) : 0;
    s32 sr = sb ? (s32)(int64_t)((int64_t)sa % sb) : sa;
    u32 p = (u32)((uint64_t)a * b);

    if (rcx_mul32(a, b) != p || rcx_divu32(a, b) != q || rcx_modu32(a, b) != r || rcx_divs32(sa, sb) != sq ||
        rcx_mods32(sa, sb) != sr) {
        print_error("32-bit a=0x%08lX b=0x%08lX: mul %08lX/%08lX divu %08lX/%08lX modu %08lX/%08lX "
                    "divs %ld/%ld mods %ld/%ld\n",
                    (unsigned long)a, (unsigned long)b, (unsigned long)rcx_mul32(a, b), (unsigned long)p,
                    (unsigned long)rcx_divu32(a, b), (unsigned long)q, (unsigned long)rcx_modu32(a, b),
                    (unsigned long)r, (long)rcx_divs32(sa, sb), (long)sq, (long)rcx_mods32(sa, sb), (long)sr);
        fail();
    }
}

static void edge_pairs_16(void **state)
{
    size_t i, j;

    (void)state;
    for (i = 0; i < COUNT(edges16); i++)
        for (j = 0; j < COUNT(edges16); j++)
            check16(edges16[i], edges16[j]);
}

static void edge_pairs_32(void **state)
{
    size_t i, j;

    (void)state;
    for (i = 0; i < COUNT(edges32); i++)
        for (j = 0; j < COUNT(edges32); j++)
            check32(edges32[i], edges32[j]);
}

/* The cases the header promises explicitly. */
static void undefined_in_c(void **state)
{
    (void)state;
    assert_int_equal(rcx_divu16(1234, 0), 0);
    assert_int_equal(rcx_modu16(1234, 0), 1234);
    assert_int_equal(rcx_divs16(-1234, 0), 0);
    assert_int_equal(rcx_mods16(-1234, 0), -1234);
    assert_int_equal(rcx_divs16(-32767 - 1, -1), -32767 - 1);
    assert_int_equal(rcx_mods16(-32767 - 1, -1), 0);
    assert_true(rcx_divu32(0xFFFFFFFFu, 0) == 0);
    assert_true(rcx_modu32(0xFFFFFFFFu, 0) == 0xFFFFFFFFu);
    assert_true(rcx_divs32(-5, 0) == 0);
    assert_true(rcx_mods32(-5, 0) == -5);
    assert_true(rcx_divs32((s32)0x80000000u, -1) == (s32)0x80000000u);
    assert_true(rcx_mods32((s32)0x80000000u, -1) == 0);
}

static void random_pairs_16(void **state)
{
    long n;

    (void)state;
    rng_state = 0x2545F491u;
    for (n = 0; n < RANDOM_PAIRS; n++)
        check16(random16(), random16());
    /* Every dividend against a few divisors of each size class. */
    for (n = 0; n <= 0xFFFF; n++) {
        check16((u16)n, 7);
        check16((u16)n, 0x00FF);
        check16((u16)n, 0x0100);
        check16((u16)n, 0x8001);
        check16((u16)n, random16());
    }
}

static void random_pairs_32(void **state)
{
    long n;

    (void)state;
    rng_state = 0x9E3779B9u;
    for (n = 0; n < RANDOM_PAIRS; n++)
        check32(random32(), random32());
    for (n = 0; n < RANDOM_PAIRS / 4; n++) {
        u32 a = (u32)rng();

        check32(a, (u32)(rng() & 0xFFFF)); /* 16-bit divisors: the two-round path */
        check32(a, 100);
        check32(a, (u32)rng() | 0x10000u); /* wide divisors */
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(edge_pairs_16),   cmocka_unit_test(edge_pairs_32),   cmocka_unit_test(undefined_in_c),
        cmocka_unit_test(random_pairs_16), cmocka_unit_test(random_pairs_32),
    };

    return cmocka_run_group_tests(tests, NULL, NULL);
}
