/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The four memory functions the portable code uses. A hosted compiler has them in <string.h>; the firmware is
 * built freestanding (no C library at all), so it declares them here and drivers/ supplies them. gcc may emit
 * calls to memcpy/memset by itself for struct copies, which is why the standard names are kept.
 */
#ifndef RCX_STRING_H
#define RCX_STRING_H

#include <stddef.h>

#if __STDC_HOSTED__
#include <string.h>
#else
void *memcpy(void *dst, const void *src, size_t n);
void *memmove(void *dst, const void *src, size_t n);
void *memset(void *dst, int c, size_t n);
int memcmp(const void *a, const void *b, size_t n);
#endif

#endif
