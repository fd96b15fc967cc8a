/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The brick's user interface (src/ui.c) driven the way the drivers drive it: debounced button edges, one rt_tick
 * per millisecond, rt_run in the main loop, with the recording HAL behind it. Expected behaviour: spec p. 98 (motor
 * scheme), p. 35 (power-down timer), p. 17 (PBTurnOff), reference-firmware.md (turn-off ignored without a
 * power-down time), rcx-hardware.md §3.4 (battery thresholds).
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

static struct rcx_brick *k;
static struct rcx *b;
static struct fake_hal *h;

static int setup(void **state)
{
    (void)state;
    k = calloc(1, sizeof *k);
    h = calloc(1, sizeof *h);
    assert_non_null(k);
    assert_non_null(h);
    k->vm.port = h;
    rt_init(k, TEST_ARENA_ADDR);
    b = &k->vm;
    return 0;
}

static void ms(unsigned n);

/* The brick as a user meets it: the double beep it starts with (firm0328 plays it, issue 15) heard out. */
static int setup_started(void **state)
{
    setup(state);
    ms(500);
    return 0;
}

/* firm0328 plays system sound 1, two beeps of 996 Hz for 160 ms 60 ms apart, when it starts
 * (reference-firmware.md "The brick's face", issue 15). */
static void starting_plays_the_double_beep(void **state)
{
    unsigned t, on = 0, starts = 0, was = 0;
    (void)state;
    for (t = 0; t < 600; t++) {
        ms(1);
        if (h->sound_hz == 996)
            on++;
        else if (h->sound_hz)
            fail_msg("a %u Hz tone at %u ms", h->sound_hz, t);
        starts += h->sound_hz && !was;
        was = h->sound_hz;
    }
    assert_int_equal(starts, 2);
    assert_in_range(on, 2 * 159, 2 * 161);
}

static int teardown(void **state)
{
    (void)state;
    free(h);
    free(k);
    return 0;
}

static void ms(unsigned n)
{
    while (n--) {
        rt_tick(k);
        rt_run(k, 4);
    }
}

static void press(u8 button)
{
    rt_button(k, button, 1);
    ms(20);
    rt_button(k, button, 0);
    ms(20);
}

/* task 0 of the selected slot: a loop forever (SetVar 0 += 1, jump back) */
static void load_forever(void)
{
    static const u8 code[] = { 0x24, 0x00, 0x02, 0x01, 0x00, 0x27, 0x86 };
    assert_int_equal(brick_download(b, 1, 0, code, sizeof code), 0);
}

static u8 running(void)
{
    u8 n, any = 0;
    for (n = 0; n < RCX_TASKS; n++)
        any |= b->task[n].state != RCX_TASK_IDLE;
    return any;
}

static void run_starts_task_0_with_motors_forward_braked_full(void **state)
{
    (void)state;
    load_forever();
    b->out.motor[1] = 0x03; /* reverse, float, power 3: all of it must be rewritten */
    press(RT_BUTTON_RUN);
    assert_int_equal(b->task[0].state, RCX_TASK_RUNNING);
    assert_true(b->global[0] > 0);
    for (u8 i = 0; i < 3; i++)
        assert_int_equal(b->out.motor[i], RCX_MOTOR_FWD | RCX_MOTOR_BRAKE | 7);
}

static void run_again_stops_everything_and_brakes(void **state)
{
    (void)state;
    load_forever();
    press(RT_BUTTON_RUN);
    b->out.motor[0] |= RCX_MOTOR_ON;
    press(RT_BUTTON_RUN);
    assert_false(running());
    for (u8 i = 0; i < 3; i++)
        assert_int_equal(b->out.motor[i] & (RCX_MOTOR_ON | RCX_MOTOR_BRAKE), RCX_MOTOR_BRAKE);
}

static void prgm_cycles_five_programs_and_brakes(void **state)
{
    static const u8 order[] = { 1, 2, 3, 4, 0, 1 };
    (void)state;
    for (u8 i = 0; i < sizeof order; i++) {
        press(RT_BUTTON_PRGM);
        assert_int_equal(b->prog, order[i]);
        assert_int_equal(b->out.motor[2] & (RCX_MOTOR_ON | RCX_MOTOR_BRAKE), RCX_MOTOR_BRAKE);
    }
}

static void prgm_stops_a_running_program(void **state)
{
    (void)state;
    load_forever();
    press(RT_BUTTON_RUN);
    assert_true(running());
    press(RT_BUTTON_PRGM);
    assert_false(running());
    assert_int_equal(b->prog, 1);
}

static void view_cycles_inputs_and_outputs_then_returns(void **state)
{
    (void)state;
    for (u8 v = DISPLAY_INPUT_1; v <= DISPLAY_OUTPUT_C; v++) {
        press(RT_BUTTON_VIEW);
        assert_int_equal(b->display.view, v);
    }
    press(RT_BUTTON_VIEW);
    assert_int_equal(b->display.view, DISPLAY_WATCH);
}

/* firm0328 with a program's own display (reference-firmware.md, "The brick's face"): program value -> watch ->
 * inputs 1-3 -> A -> B -> C -> watch; the program's value drops out after the first press. */
static void view_from_a_user_display_goes_to_the_watch(void **state)
{
    static const u8 order[] = { DISPLAY_WATCH, DISPLAY_INPUT_1, DISPLAY_INPUT_2, DISPLAY_INPUT_3, DISPLAY_OUTPUT_A,
                                DISPLAY_OUTPUT_B, DISPLAY_OUTPUT_C, DISPLAY_WATCH, DISPLAY_INPUT_1 };
    (void)state;
    display_user(b, 0, 2, 42);         /* what nqc's SetUserDisplay sends */
    for (u8 i = 0; i < sizeof order; i++) {
        press(RT_BUTTON_VIEW);
        assert_int_equal(b->display.view, order[i]);
    }
}

static void presses_click_releases_do_nothing(void **state)
{
    (void)state;
    ms(100);
    assert_int_equal(h->sound_hz, 0);
    rt_button(k, RT_BUTTON_VIEW, 1);
    ms(2);
    assert_int_not_equal(h->sound_hz, 0); /* the click is playing */
    ms(200);
    u16 calls = h->sound_calls;
    u8 view = b->display.view;
    rt_button(k, RT_BUTTON_VIEW, 0);
    rt_button(k, RT_BUTTON_PRGM, 0);
    rt_button(k, RT_BUTTON_RUN, 0);
    rt_button(k, 9, 1); /* no such button */
    ms(200);
    assert_int_equal(h->sound_calls, calls);
    assert_int_equal(b->display.view, view);
    assert_int_equal(b->prog, 0);
    assert_false(running());
}

/* Milliseconds until the next standby (the recording HAL's hal_power_off returns at once: switched on again). */
static unsigned until_power_off(unsigned max)
{
    unsigned t = 0, offs = h->power_offs;
    while (h->power_offs == offs && t < max) {
        ms(1);
        t++;
    }
    return t;
}

/*
 * On-Off: the key click (1984 Hz 20 ms, 40 ms silence) is heard before standby; on waking the double beep (996 Hz,
 * 160 ms, 60 ms gap, 160 ms) plays, the watch starts again from 00:00 and the outputs read brake
 * (reference-firmware.md, "The brick's face"). Programs, variables and memory are kept; the program is stopped.
 */
static void on_off_clicks_powers_down_and_keeps_memory(void **state)
{
    (void)state;
    load_forever();
    press(RT_BUTTON_RUN);
    b->global[5] = 1234;
    b->watch = 600;
    u16 size = mem_obj_size(b, rcx_obj_task(0, 0));
    b->out.motor[0] |= RCX_MOTOR_ON;
    u16 calls = h->sound_calls;
    rt_button(k, RT_BUTTON_ONOFF, 1);
    unsigned t = until_power_off(1000);
    assert_int_equal(h->power_offs, 1);
    assert_true(t >= 60 && t <= 62);   /* after the click and its silence, not before */
    assert_int_equal(h->sound_calls, calls + 2);
    assert_int_equal(h->sound_log[calls], 1984);
    assert_int_equal(h->sound_log[calls + 1], 0);
    assert_false(running());
    assert_int_equal(b->global[5], 1234);
    assert_int_equal(b->watch, 0);
    assert_int_equal(mem_obj_size(b, rcx_obj_task(0, 0)), size);
    for (u8 i = 0; i < 3; i++) { /* back on: forward, brake, full power */
        assert_int_equal(b->out.motor[i], RCX_MOTOR_FWD | RCX_MOTOR_BRAKE | 7);
        assert_int_equal(h->motor_mode[i], HAL_MOTOR_BRAKE);
    }
    rt_button(k, RT_BUTTON_ONOFF, 0);
    calls = h->sound_calls;
    ms(1000);
    assert_int_equal(h->power_offs, 1);
    assert_int_equal(h->sound_calls, calls + 4);
    assert_int_equal(h->sound_log[calls], 996);
    assert_int_equal(h->sound_log[calls + 1], 0);
    assert_int_equal(h->sound_log[calls + 2], 996);
    assert_int_equal(h->sound_log[calls + 3], 0);
    assert_true(b->watch_ms >= 999 && b->watch_ms <= 1001);
}

/* The beep's timing, and the click of an automatic switch-off. */
static void switching_off_by_itself_clicks_too(void **state)
{
    static const u16 beep[] = { 996, 0, 996, 0 };
    static const unsigned at[] = { 0, 160, 220, 380 };
    unsigned t, i = 0, start;
    (void)state;
    b->power_down_min = 1;
    b->idle_reset = 1;
    u16 calls = h->sound_calls;
    t = until_power_off(UI_MINUTE_MS + 100);
    assert_true(t >= UI_MINUTE_MS + 60 && t <= UI_MINUTE_MS + 62);
    assert_int_equal(h->sound_log[calls], 1984);
    calls = h->sound_calls;
    for (start = 0, t = 0; t < 500; t++) {
        ms(1);
        if (h->sound_calls > calls + i) {
            if (i == 0)
                start = t;
            assert_int_equal(h->sound_log[calls + i], beep[i]);
            assert_int_equal(t - start, at[i]);
            i++;
        }
    }
    assert_int_equal(i, 4);
}

static void power_down_time_counts_idle_minutes(void **state)
{
    (void)state;
    b->power_down_min = 2;
    b->idle_reset = 1;
    ms(UI_MINUTE_MS + 30000);
    rt_button(k, RT_BUTTON_VIEW, 1); /* activity: the count starts over */
    ms(UI_MINUTE_MS + 59000);
    assert_int_equal(h->power_offs, 0);
    ms(2000);
    assert_int_equal(h->power_offs, 1);
    ms(UI_MINUTE_MS + 59000); /* switched on again: a whole power-down time before the next */
    assert_int_equal(h->power_offs, 1);

    b->idle_reset = 1; /* what the IR layer does for every command */
    ms(UI_MINUTE_MS + 59990);
    b->idle_reset = 1;
    ms(UI_MINUTE_MS + 59990);
    assert_int_equal(h->power_offs, 1);
}

static void power_down_time_zero_never_sleeps(void **state)
{
    (void)state;
    b->power_down_min = 0;
    b->idle_reset = 1;
    ms(20 * UI_MINUTE_MS);
    assert_int_equal(h->power_offs, 0);
}

static void turn_off_waits_for_the_reply_and_needs_a_power_down_time(void **state)
{
    static const u8 off[] = { 0x60 };
    (void)state;
    assert_int_equal(brick_cmd(b, off, 1, NULL), 1);
    h->ir_busy = 1; /* the acknowledgement is still going out */
    ms(50);
    assert_int_equal(h->power_offs, 0);
    h->ir_busy = 0;
    ms(100);                           /* and the click */
    assert_int_equal(h->power_offs, 1);

    b->power_down_min = 0;
    brick_cmd(b, off, 1, NULL);
    ms(100);
    assert_int_equal(h->power_offs, 1);
}

static void battery_mark_has_hysteresis(void **state)
{
    static const struct { u16 mv; u8 mark; } steps[] = {
        { 9000, 0 }, { 6400, 0 }, { 6299, 1 }, { 6600, 1 }, { 6700, 1 }, { 6701, 0 }, { 6350, 0 }, { 5000, 1 },
    };
    (void)state;
    for (u8 i = 0; i < sizeof steps / sizeof steps[0]; i++) {
        rt_battery(k, steps[i].mv);
        ms(60);
        assert_int_equal(k->ui.battery_low, steps[i].mark);
        assert_int_equal(!!(b->display.marks[DISPLAY_MARK_BATTERY >> 3] & (1u << (DISPLAY_MARK_BATTERY & 7))),
                         steps[i].mark);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(starting_plays_the_double_beep, setup, teardown),
        cmocka_unit_test_setup_teardown(run_starts_task_0_with_motors_forward_braked_full, setup, teardown),
        cmocka_unit_test_setup_teardown(run_again_stops_everything_and_brakes, setup, teardown),
        cmocka_unit_test_setup_teardown(prgm_cycles_five_programs_and_brakes, setup, teardown),
        cmocka_unit_test_setup_teardown(prgm_stops_a_running_program, setup, teardown),
        cmocka_unit_test_setup_teardown(view_cycles_inputs_and_outputs_then_returns, setup, teardown),
        cmocka_unit_test_setup_teardown(presses_click_releases_do_nothing, setup_started, teardown),
        cmocka_unit_test_setup_teardown(view_from_a_user_display_goes_to_the_watch, setup, teardown),
        cmocka_unit_test_setup_teardown(on_off_clicks_powers_down_and_keeps_memory, setup_started, teardown),
        cmocka_unit_test_setup_teardown(switching_off_by_itself_clicks_too, setup_started, teardown),
        cmocka_unit_test_setup_teardown(power_down_time_counts_idle_minutes, setup, teardown),
        cmocka_unit_test_setup_teardown(power_down_time_zero_never_sleeps, setup, teardown),
        cmocka_unit_test_setup_teardown(turn_off_waits_for_the_reply_and_needs_a_power_down_time, setup, teardown),
        cmocka_unit_test_setup_teardown(battery_mark_has_hysteresis, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
