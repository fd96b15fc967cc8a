/* SPDX-License-Identifier: MPL-2.0 */
/* Smoke test: an nqc-shaped x++ loop downloaded and run. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>
#include "brick.h"

static void counts_to_ten(void **state)
{
    /* setv var[0],0 ; setv var[46],10 ; L: decvjn var[46], END ; sumv var[0],1 ; jmp L ; END: */
    static const u8 code[] = { 0x14, 0x00, 0x02, 0x00, 0x00, 0x14, 0x2e, 0x02, 0x0a, 0x00,
                               0xf2, 0x2e, 0x08, 0x24, 0x00, 0x02, 0x01, 0x00, 0x27, 0x89 };
    struct rcx *b = brick_new();
    (void)state;
    assert_int_equal(brick_download(b, 1, 0, code, sizeof code), 0);
    brick_start(b, 0);
    assert_true(brick_run_until_idle(b, 100, 10) >= 0);
    assert_int_equal(b->global[0], 10);
    brick_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = { cmocka_unit_test(counts_to_ten) };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
