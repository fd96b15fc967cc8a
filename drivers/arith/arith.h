/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Integer helpers for the operations the H8/300 has no instruction for.
 *
 * gcc turns every 16-bit `*`, `/`, `%` and every 32-bit `*`, `/`, `%` into a call of a helper
 * (__mulhi3, __divhi3, ..., __umodsi3). Debian's libgcc.a for h8300-hms cannot be linked, so the
 * firmware brings its own (the memory functions gcc also calls are in drivers/libc/string.s). The
 * 16-bit ones are assembler on the brick (arith16.s, under gcc's names), with the C of arith.c as
 * their reference on the host; the 32-bit ones are arith.c's C functions under rcx_ names, reached
 * through a few instructions of glue because gcc hands both 32-bit operands of its helpers over in
 * registers (r0:r1, r2:r3) while an ordinary C function receives its second long on the stack.
 * On the host the same file compiles under the rcx_ names below, and tests/firmware/test_arith.c
 * compares each function with C's own operators.
 *
 * Semantics: results wrap modulo 2^16 / 2^32 like the H8 registers; division truncates toward zero
 * and the remainder has the dividend's sign (C99). Two cases C leaves undefined are defined here:
 *   - division by zero: quotient 0, remainder = dividend (never hangs, never traps);
 *   - most negative value / -1: quotient = the most negative value again, remainder 0.
 */
#ifndef RCX_ARITH_H
#define RCX_ARITH_H

#include "rcx_types.h"

#ifdef __H8300__
#define rcx_mul16 __mulhi3
#define rcx_divu16 __udivhi3
#define rcx_modu16 __umodhi3
#define rcx_divs16 __divhi3
#define rcx_mods16 __modhi3
#endif

u16 rcx_mul16(u16 a, u16 b);  /* a * b, signed or unsigned alike */
u16 rcx_divu16(u16 a, u16 b); /* a / b */
u16 rcx_modu16(u16 a, u16 b); /* a % b */
s16 rcx_divs16(s16 a, s16 b); /* a / b */
s16 rcx_mods16(s16 a, s16 b); /* a % b */

u32 rcx_mul32(u32 a, u32 b);  /* a * b, signed or unsigned alike; called as __mulsi3 on the brick */
u32 rcx_divu32(u32 a, u32 b); /* __udivsi3 */
u32 rcx_modu32(u32 a, u32 b); /* __umodsi3 */
s32 rcx_divs32(s32 a, s32 b); /* __divsi3 */
s32 rcx_mods32(s32 a, s32 b); /* __modsi3 */

/* Shared cores: unsigned division giving quotient and remainder at once. rcx_udiv8 is one byte of
 * long division (see arith.c). */
u16 rcx_udivmod16(u16 n, u16 d, u16 *rem);
u32 rcx_udivmod32(u32 n, u32 d, u32 *rem);
u16 rcx_udiv8(u16 lo, u16 d, u16 *rem);
/* (hi * 65536 + lo) / d for hi < d, a quotient of 16 bits: on the brick the core of the 16-bit divisions
 * (arith16.s), cheap to call from C. */
u16 rcx_udiv32_16(u16 lo, u16 d, u16 hi);

/* n / d for a quotient that fits in 8 bits (n < 256 d): a single divxu on the brick, no helper call. */
static inline u8 rcx_divu8(u16 n, u8 d)
{
#ifdef __H8300__
    __asm__("divxu.b\t%X2,%T0" : "=r"(n) : "0"(n), "r"(d));
    return (u8)n;
#else
    return (u8)(n / d);
#endif
}

#endif
