/*
 * The runtime's quiet stretches (src/runtime.h, rt_quiet_ms and rt_advance): the brick's main loop skips the
 * milliseconds the runtime says would only count time and hands them over together. Skipping must be invisible:
 * rt_advance(k, n) for the n that rt_quiet_ms gave leaves the brick byte for byte as n rt_tick calls would, with no
 * call of the hardware in between, and rt_run would have done nothing either. Checked along an idle brick's minutes,
 * and through the things that end a stretch (a sound, a reversing pause, a task, IR bytes, a button, power-down).
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "brick.h"
#include "fake_hal.h"
#include "runtime.h"

static struct rcx_brick *k, *copy;
static struct fake_hal *h, *hc;
static unsigned stretches;

static int setup(void **state)
{
    (void)state;
    k = calloc(1, sizeof *k);
    copy = calloc(1, sizeof *copy);
    h = calloc(1, sizeof *h);
    hc = calloc(1, sizeof *hc);
    assert_non_null(k);
    assert_non_null(copy);
    assert_non_null(h);
    assert_non_null(hc);
    k->vm.port = h;
    rt_init(k, TEST_ARENA_ADDR);
    stretches = 0;
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    free(hc);
    free(h);
    free(copy);
    free(k);
    return 0;
}

/* `ms` milliseconds as the brick's main loop spends them: a quiet stretch, when there is one, is checked against the
 * same milliseconds ticked one by one on a copy (with a hardware of its own, which must see no call). */
static void run(unsigned ms)
{
    while (ms) {
        u8 n = rt_quiet_ms(k);
        if (n > ms)
            n = (u8)ms;
        if (!n) {
            rt_tick(k);
            rt_run(k, 8);
            ms--;
            continue;
        }
        memcpy(copy, k, sizeof *k);
        memcpy(hc, h, sizeof *h);
        copy->vm.port = hc;
        for (u8 i = 0; i < n; i++)
            rt_tick(copy);
        assert_int_equal(rt_run(copy, 8), 0);
        copy->vm.port = h;
        rt_advance(k, n);
        assert_memory_equal(copy, k, sizeof *k);
        assert_memory_equal(hc, h, sizeof *h);
        stretches++;
        ms -= n;
    }
}

/* Idle: stretches of up to 8 ms between the 10 ms steps, through new minutes of the watch and of the idle count. */
static void idle_minutes_pass_in_stretches(void **state)
{
    (void)state;
    k->vm.power_down_min = 0;
    run(3 * UI_MINUTE_MS + 17);
    assert_true(stretches > 3 * UI_MINUTE_MS / 10 * 9 / 10); /* most of the time */
    assert_int_equal(k->vm.watch, 3);
}

/* What ends a stretch: each of them, at any millisecond of the 10 ms step. */
static void activity_ends_stretches(void **state)
{
    static const u8 tone[] = { 0x23, 0xB8, 0x01, 5 };      /* PlayTone 440 Hz, 50 ms */
    static const u8 motor_on[] = { 0x21, 0x81 };            /* A on */
    static const u8 forward[] = { 0xE1, 0x81 }, reverse[] = { 0xE1, 0x41 };
    static const u8 ping[] = { 0x55, 0xFF, 0x00, 0x10, 0xEF, 0x10, 0xEF };
    static const u8 wait_loop[] = { 0x43, 0x02, 0x03, 0x00, 0x27, 0x85 }; /* Wait 30 ms; jump back */
    (void)state;
    for (unsigned at = 0; at < 10; at++) {
        run(at + 20);
        brick_cmd(&k->vm, tone, sizeof tone, NULL);
        run(100);
        brick_cmd(&k->vm, forward, sizeof forward, NULL);
        brick_cmd(&k->vm, motor_on, sizeof motor_on, NULL);
        run(at + 3);
        brick_cmd(&k->vm, reverse, sizeof reverse, NULL); /* the reversing pause */
        run(100);
        for (unsigned i = 0; i < sizeof ping; i++)
            rt_ir_byte(k, ping[i], 0);
        run(300);
        rt_button(k, RT_BUTTON_VIEW, 1);
        run(at + 30);
        rt_button(k, RT_BUTTON_VIEW, 0);
        run(50);
    }
    assert_int_equal(brick_download(&k->vm, 1, 0, wait_loop, sizeof wait_loop), 0);
    brick_start(&k->vm, 0);
    run(500);
    assert_true(h->ir_len > 0); /* the pings were answered */
    assert_true(stretches > 0);
}

/* The power-down time: switching off after the idle minutes, at the same millisecond as ticked one by one. */
static void power_down_in_stretches(void **state)
{
    (void)state;
    k->vm.power_down_min = 1;
    k->vm.idle_reset = 1;
    run(UI_MINUTE_MS + 500);
    assert_int_equal(h->power_offs, 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(idle_minutes_pass_in_stretches, setup, teardown),
        cmocka_unit_test_setup_teardown(activity_ends_stretches, setup, teardown),
        cmocka_unit_test_setup_teardown(power_down_in_stretches, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
