/* SPDX-License-Identifier: MPL-2.0 */
/* The firmware's own memcpy/memmove/memset/memcmp (drivers/libc/string.c), compared with the host C library. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <string.h>
#include <stdlib.h>
#include <cmocka.h>

#define RCX_LIBC_NAME(name) fw_##name
#include "../../drivers/libc/string.c"

static void fill(unsigned char *p, size_t n, unsigned seed)
{
    size_t i;
    for (i = 0; i < n; i++)
        p[i] = (unsigned char)(seed * 31u + i * 7u);
}

static void copy_and_set(void **state)
{
    unsigned char a[64], b[64], c[64];
    size_t n, off;
    (void)state;
    for (n = 0; n <= 40; n++) {
        fill(a, sizeof a, (unsigned)n);
        memset(b, 0xEE, sizeof b);
        memset(c, 0xEE, sizeof c);
        assert_ptr_equal(fw_memcpy(b + 3, a, n), b + 3);
        memcpy(c + 3, a, n);
        assert_memory_equal(b, c, sizeof b);
        assert_ptr_equal(fw_memset(b + 5, 0x1A5, n), b + 5); /* only the low byte of c is stored */
        memset(c + 5, 0xA5, n);
        assert_memory_equal(b, c, sizeof b);
    }
    for (n = 0; n <= 24; n++) {
        for (off = 0; off <= 8; off++) {
            /* Overlapping moves in both directions. */
            fill(a, sizeof a, (unsigned)(n + off));
            memcpy(c, a, sizeof a);
            fw_memmove(a + off, a + 8, n);
            memmove(c + off, c + 8, n);
            assert_memory_equal(a, c, sizeof a);
            fw_memmove(a + 8, a + off, n);
            memmove(c + 8, c + off, n);
            assert_memory_equal(a, c, sizeof a);
        }
    }
}

static int sign(int v)
{
    return (v > 0) - (v < 0);
}

static void compare(void **state)
{
    unsigned char a[16], b[16];
    unsigned i, j;
    (void)state;
    for (i = 0; i < 2000; i++) {
        for (j = 0; j < sizeof a; j++) {
            a[j] = (unsigned char)(rand() & 3 ? 0x41 : rand());
            b[j] = (unsigned char)(rand() & 3 ? 0x41 : rand());
        }
        j = (unsigned)rand() % (sizeof a + 1);
        assert_int_equal(sign(fw_memcmp(a, b, j)), sign(memcmp(a, b, j)));
        assert_int_equal(fw_memcmp(a, a, j), 0);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = { cmocka_unit_test(copy_and_set), cmocka_unit_test(compare) };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
