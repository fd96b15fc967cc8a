/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Steady inputs (vm/sensors.c, vm/events.c): once an input's last three samples are equal, a further equal sample
 * is not worked out again, and only the events watching the input are told. Nothing a program or a host can see
 * may differ from working every sample out in full: these are the cases where a shortcut could show - a reset of
 * the value, mode or type while the input holds still, thresholds moved under a steady value, an event set or
 * calibrated on a steady input, a rotation sensor resting between steps.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <string.h>
#include <cmocka.h>
#include "../events/event_helpers.h"

static void sample(struct rcx *b, u8 n, u16 raw, unsigned times)
{
    while (times--)
        sensor_sample(b, n, raw);
}

static void set_type(struct rcx *b, u8 n, u8 type)
{
    u8 c[3] = { 0x32, n, type };
    cmd(b, c, 3);
}

static void clear_value(struct rcx *b, u8 n)
{
    u8 c[2] = { 0xD1, n };
    cmd(b, c, 2);
}

/* The shortcut itself: quiet after three equal samples, not before, and no longer after a change or a reset. */
static void an_input_goes_quiet_after_three_equal_samples(void **state)
{
    struct rcx *b = brick();
    (void)state;
    sample(b, 1, 700, 2);
    assert_int_equal(b->sensor[1].quiet, SENSOR_MOVING);
    sample(b, 1, 700, 1);
    assert_int_equal(b->sensor[1].quiet, SENSOR_STEADY | 700);
    sample(b, 1, 700, 5);
    assert_int_equal(b->sensor[1].quiet, SENSOR_STEADY | 700);
    sample(b, 1, 701, 1);
    assert_int_equal(b->sensor[1].quiet, SENSOR_MOVING);
    sample(b, 1, 701, 2);
    assert_int_equal(b->sensor[1].quiet, SENSOR_STEADY | 701);
    clear_value(b, 1);
    assert_int_equal(b->sensor[1].quiet, SENSOR_MOVING);
    brick_free(b);
}

/* ClearSensorValue, SetSensorMode and SetSensorType while the input holds still: the value and the boolean are
 * worked out again at the next sample (spec p. 30), and the counts start from 0. */
static void resets_of_a_steady_input_take_effect(void **state)
{
    struct rcx *b = brick();
    (void)state;
    sample(b, 0, 500, 5);                       /* power-on: raw mode */
    clear_value(b, 0);
    assert_int_equal(poll(b, 9, 0), 0);
    sample(b, 0, 500, 1);
    assert_int_equal(poll(b, 9, 0), 500);
    sensor_mode(b, 0, 0x80);                    /* percent: (1023 - 500) * 25 / 156 = 83 */
    sample(b, 0, 500, 1);
    assert_int_equal(poll(b, 9, 0), 83);
    set_type(b, 2, 1);                          /* touch, pressed and held */
    sample(b, 2, 100, 5);
    assert_int_equal(poll(b, 13, 2), 1);
    set_type(b, 2, 1);                          /* a new type: the boolean is reset ... */
    assert_int_equal(poll(b, 13, 2), 0);
    sample(b, 2, 100, 1);                       /* ... and the same level reads pressed again */
    assert_int_equal(poll(b, 13, 2), 1);
    assert_int_equal(poll(b, 9, 2), 1);
    sensor_mode(b, 2, 0x40);                    /* transitions: none while it is held */
    sample(b, 2, 100, 5);
    assert_int_equal(poll(b, 9, 2), 0);
    sample(b, 2, 1000, 1);
    assert_int_equal(poll(b, 9, 2), 1);
    brick_free(b);
}

/* A rotation sensor at rest between steps keeps its phase: the next step counts. */
static void rotation_resting_between_steps(void **state)
{
    struct rcx *b = brick();
    (void)state;
    set_type(b, 0, 4);
    sample(b, 0, 1000, 10);                     /* phase 0 */
    sample(b, 0, 860, 10);                      /* phase 1: up */
    sample(b, 0, 420, 10);                      /* phase 2: up */
    sample(b, 0, 860, 10);                      /* phase 1: down */
    assert_int_equal(poll(b, 9, 0), 1);
    brick_free(b);
}

/* Events on a steady input are still looked at every sample: a threshold moved under the value by SetSourceValue
 * (which does not tell the engine) fires the event at the next sample. */
static void thresholds_moved_under_a_steady_input(void **state)
{
    struct rcx *b = brick();
    (void)state;
    set_type(b, 1, 3);                          /* light: percent, raw 700 is 51 % */
    sample(b, 1, 700, 5);
    set_event(b, 4, 1, HIGH);
    limits(b, 4, 10, 60, 0);
    sample(b, 1, 700, 3);
    assert_int_equal(poll(b, 25, 4), S_NORMAL);
    assert_int_equal(fired(b), 0);
    set_source(b, 28, 4, 50);                   /* upper threshold below the value */
    assert_int_equal(fired(b), 0);
    sample(b, 1, 700, 1);
    assert_int_equal(fired(b), 0x10);
    assert_int_equal(poll(b, 25, 4), S_HIGH);
    brick_free(b);
}

/* An event set on a steady input is classified at the next sample; one calibrated on it takes its eight samples
 * from the steady value; an event moved to another input no longer follows the first. */
static void events_set_and_calibrated_on_a_steady_input(void **state)
{
    static const u8 calibrate[5] = { 0x04, 2, 64, 64, 128 }; /* event 2: upper 64, lower 64, hysteresis 128 */
    struct rcx *b = brick();
    unsigned k;
    (void)state;
    sample(b, 0, 600, 5);                       /* raw mode, 600 */
    set_event(b, 2, 0, NORMAL);
    assert_int_equal(poll(b, 25, 2), S_UNDEFINED);
    sample(b, 0, 600, 1);
    assert_int_equal(poll(b, 25, 2), S_NORMAL); /* 0 <= 600 <= 1023 */
    cmd(b, calibrate, sizeof calibrate);
    for (k = 0; k < 8; k++) {
        sample(b, 0, 600, 1);
        assert_int_equal(poll(b, 25, 2), k < 7 ? S_CAL_BUSY : S_UNDEFINED);
    }
    /* Avg 600, H = 600 * 128 / 2048 = 37.5 -> 37, LT = 600 - 150 - 37, UT = 600 + 150 + 37. */
    assert_int_equal(poll(b, 29, 2), 413);
    assert_int_equal(poll(b, 28, 2), 787);
    assert_int_equal(poll(b, 30, 2), 37);
    set_event(b, 2, 1, LOW);                    /* now on input 2, never sampled: raw 0 */
    sample(b, 0, 100, 3);                       /* input 1 moves: not this event's business any more */
    assert_int_equal(poll(b, 25, 2), S_UNDEFINED);
    sample(b, 1, 0, 1);
    assert_int_equal(poll(b, 25, 2), S_NORMAL); /* raw mode, 0: inside 0-1023 */
    assert_int_equal(fired(b), 0);
    brick_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(an_input_goes_quiet_after_three_equal_samples),
        cmocka_unit_test(resets_of_a_steady_input_take_effect),
        cmocka_unit_test(rotation_resting_between_steps),
        cmocka_unit_test(thresholds_moved_under_a_steady_input),
        cmocka_unit_test(events_set_and_calibrated_on_a_steady_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
