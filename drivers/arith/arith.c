/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Integer helpers (see arith.h for names and semantics).
 *
 * Only shifts, adds, compares and the two 8-bit operations the H8/300 does in one instruction are
 * used: an 8x8 -> 16-bit multiply of unsigned bytes (mulxu) and an unsigned byte divided by an
 * unsigned byte (divxu). gcc emits both inline; drivers/arith/check_arith.cmake rejects a build in
 * which any helper here calls one of gcc's helpers (that would recurse).
 *
 * The firmware links these from a library, one member per part, so that only the helpers the code
 * actually uses take space: the build compiles this file once per part with RCX_ARITH_PART set to
 * one of the ARITH_P_ numbers. Without RCX_ARITH_PART (host tests) every part is compiled.
 */
#include "arith.h"

#define ARITH_P_MUL16 1
#define ARITH_P_UDIVMOD16 2
#define ARITH_P_DIVU16 3
#define ARITH_P_MODU16 4
#define ARITH_P_DIVS16 5
#define ARITH_P_MODS16 6
#define ARITH_P_MUL32 7
#define ARITH_P_UDIVMOD32 8
#define ARITH_P_DIVU32 9
#define ARITH_P_MODU32 10
#define ARITH_P_DIVS32 11
#define ARITH_P_MODS32 12
#define ARITH_P_UDIV32_16 13

#ifdef RCX_ARITH_PART
#define ARITH_WANT(part) (RCX_ARITH_PART == ARITH_P_##part)
#else
#define ARITH_WANT(part) 1
#endif

#ifdef __H8300__
/*
 * gcc calls its 32-bit helpers with the first operand in r0:r1 and the second in r2:r3 (high word
 * first) and expects the result in r0:r1; r0-r3 are clobbered. A C function with two longs takes the
 * first in r0:r1 and finds the second on the stack above its return address. This glue pushes r2:r3
 * (low word first, so the high word ends up at the lower address, big-endian) and calls the C body.
 */
#define ARITH_GLUE32(helper, body)          \
    __asm__("\t.section .text\n"            \
            "\t.global " helper "\n"        \
            helper ":\n"                    \
            "\tmov.w\tr3,@-r7\n"            \
            "\tmov.w\tr2,@-r7\n"            \
            "\tjsr\t@" body "\n"            \
            "\tadds\t#2,r7\n"               \
            "\tadds\t#2,r7\n"               \
            "\trts\n")
#else
#define ARITH_GLUE32(helper, body) extern int rcx_arith_no_glue
#endif

#if ARITH_WANT(MUL16)
/* Three byte products: the high bytes' product lies entirely above bit 15. */
u16 rcx_mul16(u16 a, u16 b)
{
    u8 a0 = (u8)a, a1 = (u8)(a >> 8), b0 = (u8)b, b1 = (u8)(b >> 8);
    u8 cross = (u8)((u16)a0 * b1 + (u16)a1 * b0);

    return (u16)((u16)a0 * b0 + (u16)((u16)cross << 8));
}
#endif

#if ARITH_WANT(UDIVMOD16)
/*
 * Eight steps of long division. On entry *rem holds a partial remainder r < d and the top byte of lo
 * the next eight dividend bits. Each step moves the top bit of lo into r and a quotient bit into the
 * bottom of lo, so the low byte of lo comes out as the high byte of the result, above the eight
 * quotient bits. 2r + bit is compared with d as r + bit >= d - r, which cannot overflow.
 */
u16 rcx_udiv8(u16 lo, u16 d, u16 *rem)
{
    u16 r = *rem;
    u8 i = 8;

    do {
        u16 t = r, gap = (u16)(d - r);

        if (lo & 0x8000u)
            t++;
        lo = (u16)(lo << 1);
        if (t >= gap) {
            r = (u16)(t - gap);
            lo |= 1;
        } else {
            r = (u16)(r + t);
        }
    } while (--i);
    *rem = r;
    return lo;
}

/*
 * A divisor that fits in a byte divides the dividend's high byte in one divxu; a larger one leaves
 * at most eight quotient bits. Either way eight steps of rcx_udiv8 finish the job.
 */
u16 rcx_udivmod16(u16 n, u16 d, u16 *rem)
{
    u8 q_hi = 0;

    if (n < d || d == 0) {
        *rem = n;
        return 0;
    }
    if (n < 0x100u) { /* then d < 0x100 as well */
        *rem = (u8)((u8)n % (u8)d);
        return (u8)((u8)n / (u8)d);
    }
    if (d < 0x100u) {
        u8 hi = (u8)(n >> 8);

        q_hi = (u8)(hi / (u8)d);
        *rem = (u8)(hi % (u8)d);
    } else {
        *rem = (u16)(n >> 8); /* < 0x100 <= d */
    }
    return rcx_udiv8((u16)((u16)(n << 8) | q_hi), d, rem);
}
#endif

#if ARITH_WANT(UDIV32_16)
/* On the brick this is arith16.s's division core; here the reference. */
u16 rcx_udiv32_16(u16 lo, u16 d, u16 hi)
{
    u16 r = hi;

    lo = rcx_udiv8(lo, d, &r);
    return rcx_udiv8(lo, d, &r);
}
#endif

#if ARITH_WANT(DIVU16)
u16 rcx_divu16(u16 a, u16 b)
{
    u16 r;

    return rcx_udivmod16(a, b, &r);
}
#endif

#if ARITH_WANT(MODU16)
u16 rcx_modu16(u16 a, u16 b)
{
    u16 r;

    rcx_udivmod16(a, b, &r);
    return r;
}
#endif

#if ARITH_WANT(DIVS16) || ARITH_WANT(MODS16)
static inline u16 abs_16(s16 v)
{
    return v < 0 ? (u16)(0u - (u16)v) : (u16)v;
}
#endif

#if ARITH_WANT(DIVS16)
s16 rcx_divs16(s16 a, s16 b)
{
    u16 r, q = rcx_udivmod16(abs_16(a), abs_16(b), &r);

    if ((a ^ b) < 0)
        q = (u16)(0u - q);
    return (s16)q;
}
#endif

#if ARITH_WANT(MODS16)
s16 rcx_mods16(s16 a, s16 b)
{
    u16 r;

    rcx_udivmod16(abs_16(a), abs_16(b), &r);
    if (a < 0)
        r = (u16)(0u - r);
    return (s16)r;
}
#endif

#if ARITH_WANT(MUL32)
/* 16x16 -> 32 bits from four byte products. */
static __attribute__((noinline)) u32 mul_16_32(u16 a, u16 b)
{
    u8 a0 = (u8)a, a1 = (u8)(a >> 8), b0 = (u8)b, b1 = (u8)(b >> 8);
    u32 mid = (u32)(u16)((u16)a0 * b1) + (u16)((u16)a1 * b0);

    return ((u32)(u16)((u16)a1 * b1) << 16) + (u16)((u16)a0 * b0) + (mid << 8);
}

/* The high halves' product lies entirely above bit 31; the cross products only count mod 2^16. */
u32 rcx_mul32(u32 a, u32 b)
{
    u16 a0 = (u16)a, b0 = (u16)b;
    u16 cross = (u16)(mul_16_32((u16)(a >> 16), b0) + mul_16_32(a0, (u16)(b >> 16)));

    return mul_16_32(a0, b0) + ((u32)cross << 16);
}
ARITH_GLUE32("___mulsi3", "_rcx_mul32");
#endif

#if ARITH_WANT(UDIVMOD32)
/* A divisor above 16 bits leaves fewer than 16 quotient bits: shift it up under the dividend, then
 * subtract it back down bit by bit. n >= d. */
static __attribute__((noinline)) u16 udivmod32_wide(u32 n, u32 d, u32 *rem)
{
    u16 q = 0, bit = 1;

    while (d <= (n >> 1)) { /* d << 1 <= n, without overflowing d */
        d <<= 1;
        bit = (u16)(bit << 1);
    }
    do {
        if (n >= d) {
            n -= d;
            q |= bit;
        }
        d >>= 1;
        bit >>= 1;
    } while (bit);
    *rem = n;
    return q;
}

/* A divisor up to 16 bits: the dividend's high half goes through rcx_udivmod16, its low half through
 * two rounds of rcx_udiv8. */
u32 rcx_udivmod32(u32 n, u32 d, u32 *rem)
{
    u16 r, q_hi, q_lo;

    if (n < d || d == 0) {
        *rem = n;
        return 0;
    }
    if (d > 0xFFFFu)
        return udivmod32_wide(n, d, rem);
    q_hi = rcx_udivmod16((u16)(n >> 16), (u16)d, &r);
    q_lo = rcx_udiv8((u16)n, (u16)d, &r);
    q_lo = rcx_udiv8(q_lo, (u16)d, &r);
    *rem = r;
    return ((u32)q_hi << 16) | q_lo;
}
#endif

#if ARITH_WANT(DIVU32)
u32 rcx_divu32(u32 a, u32 b)
{
    u32 r;

    return rcx_udivmod32(a, b, &r);
}
ARITH_GLUE32("___udivsi3", "_rcx_divu32");
#endif

#if ARITH_WANT(MODU32)
u32 rcx_modu32(u32 a, u32 b)
{
    u32 r;

    rcx_udivmod32(a, b, &r);
    return r;
}
ARITH_GLUE32("___umodsi3", "_rcx_modu32");
#endif

#if ARITH_WANT(DIVS32) || ARITH_WANT(MODS32)
static inline u32 abs_32(s32 v)
{
    return v < 0 ? 0u - (u32)v : (u32)v;
}
#endif

#if ARITH_WANT(DIVS32)
s32 rcx_divs32(s32 a, s32 b)
{
    u32 r, q = rcx_udivmod32(abs_32(a), abs_32(b), &r);

    if ((a ^ b) < 0)
        q = 0u - q;
    return (s32)q;
}
ARITH_GLUE32("___divsi3", "_rcx_divs32");
#endif

#if ARITH_WANT(MODS32)
s32 rcx_mods32(s32 a, s32 b)
{
    u32 r;

    rcx_udivmod32(abs_32(a), abs_32(b), &r);
    if (a < 0)
        r = 0u - r;
    return (s32)r;
}
ARITH_GLUE32("___modsi3", "_rcx_mods32");
#endif
