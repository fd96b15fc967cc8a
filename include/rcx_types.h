/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Fixed-width integer types for every layer of OpenRCX.
 *
 * The H8/300 cross compiler (gcc 3.4.6) ships no <stdint.h>, and its `int` is 16 bits where the host's is 32.
 * The widths are therefore chosen from <limits.h>, which both compilers have, instead of naming a target.
 * VM arithmetic is done in these explicit types so host and brick wrap identically.
 */
#ifndef RCX_TYPES_H
#define RCX_TYPES_H

#include <limits.h>
#include <stddef.h>

typedef unsigned char u8;
typedef signed char s8;

#if UINT_MAX == 0xFFFFu
typedef unsigned int u16;
typedef signed int s16;
typedef unsigned long u32;
typedef signed long s32;
#else
typedef unsigned short u16;
typedef signed short s16;
typedef unsigned int u32;
typedef signed int s32;
#endif

/* Compile-time check usable by gcc 3.4 (no _Static_assert): a negative array size fails the build. */
#define RCX_STATIC_ASSERT(name, cond) typedef char rcx_static_assert_##name[(cond) ? 1 : -1]

RCX_STATIC_ASSERT(u8_is_8_bits, sizeof(u8) == 1);
RCX_STATIC_ASSERT(u16_is_16_bits, sizeof(u16) == 2);
RCX_STATIC_ASSERT(u32_is_32_bits, sizeof(u32) == 4);

/* Scratch variables the brick keeps in its on-chip RAM (section .onchip, linker/openrcx.ld), beside the stack: not
 * in the external RAM, which is the programs' memory. */
#ifdef __H8300__
#define RCX_SCRATCH __attribute__((section(".onchip")))
#else
#define RCX_SCRATCH
#endif

/* Code the brick runs at 0xF000, outside the program memory (section .hitext, linker/openrcx.ld; drivers/h8300/h8.h
 * says the same for the drivers): for rarely run code, as far as the room there goes. */
#ifdef __H8300__
#define RCX_HIGH_CODE __attribute__((section(".hitext")))
#else
#define RCX_HIGH_CODE
#endif

/* Little-endian 16-bit operand at p (byte codes and IR packets are little-endian; the H8 is big-endian). */
#define RCX_LE16(p) ((u16)((u16)(p)[0] | ((u16)(p)[1] << 8)))

#endif
