/* SPDX-License-Identifier: MPL-2.0 */
/*
 * memcpy, memmove, memset and memcmp for the freestanding firmware: the portable code calls them and gcc emits
 * calls to memcpy/memset for struct copies. Byte loops: small, and the brick copies little (downloads, compaction).
 * The brick links the same functions in assembler (string.s, half the size); this C is their reference: the host
 * tests compile it with RCX_LIBC_NAME renaming the functions (tests/unit/test_libc.c), and
 * tests/drivers/test_h8image.c holds the image's against the host's.
 */
#include <stddef.h>

#ifndef RCX_LIBC_NAME
#define RCX_LIBC_NAME(name) name
#endif

void *RCX_LIBC_NAME(memcpy)(void *dst, const void *src, size_t n)
{
    unsigned char *d = dst;
    const unsigned char *s = src;
    while (n--)
        *d++ = *s++;
    return dst;
}

void *RCX_LIBC_NAME(memmove)(void *dst, const void *src, size_t n)
{
    unsigned char *d = dst;
    const unsigned char *s = src;
    if (d < s) {
        while (n--)
            *d++ = *s++;
    } else if (d > s) {
        d += n;
        s += n;
        while (n--)
            *--d = *--s;
    }
    return dst;
}

void *RCX_LIBC_NAME(memset)(void *dst, int c, size_t n)
{
    unsigned char *d = dst;
    while (n--)
        *d++ = (unsigned char)c;
    return dst;
}

int RCX_LIBC_NAME(memcmp)(const void *a, const void *b, size_t n)
{
    const unsigned char *p = a, *q = b;
    for (; n; n--, p++, q++)
        if (*p != *q)
            return *p < *q ? -1 : 1;
    return 0;
}
