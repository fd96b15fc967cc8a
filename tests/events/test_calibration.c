/* SPDX-License-Identifier: MPL-2.0 */
/*
 * CalibrateEvent (spec pp. 74, 103-105) against the spec's formulas worked out by hand, and bad event operands
 * (event numbers above 15, unknown types, sensors above 10, counters above 2): ignored without side effects.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <string.h>
#include <cmocka.h>
#include "event_helpers.h"

/* ---- CalibrateEvent (pp. 74, 103-105) -------------------------------------------------------------------------- */

/*
 * k1 = 256, k2 = 2048. Temperature and reflection (and raw, whose page is lost: taken as reflection):
 *   H = AvgRaw*HFct/k2, UT = Avg + Avg*UTFct/k1 + H, LT = Avg - Avg*LTFct/k1 - H.
 * All other modes and the virtual sensors: UT = Avg + Avg*UTFct/k1, LT = Avg - Avg*LTFct/k1, H = 0.
 * Command bytes (p. 74): event, lower %, upper %, hysteresis %. Divisions truncate toward zero; results saturate.
 */
static const struct {
    u8 mode;            /* sensor mode, or 0xFF: counter 0 */
    s16 value;
    u16 raw;
    u8 lo, up, h;
    s16 lower, upper, hyst;
} calibrations[] = {
    { 0x80, 50, 700, 32, 64, 100, 10, 96, 34 },         /* H 34.18; 12.5; 6.25 */
    { 0xA0, 250, 500, 26, 51, 41, 215, 309, 10 },       /* H 10.01; 49.8; 25.4 */
    { 0xC0, 770, 480, 10, 20, 200, 694, 876, 46 },      /* H 46.9; 60.2; 30.1 */
    { 0x00, 600, 600, 64, 64, 128, 413, 787, 37 },      /* H 37.5; 150 */
    { 0x20, 1, 300, 200, 200, 255, 1, 1, 0 },           /* 0.78 */
    { 0x40, 40, 900, 128, 64, 99, 20, 50, 0 },
    { 0x60, 7, 900, 255, 255, 255, 1, 13, 0 },          /* 6.97 */
    { 0xE0, 1000, 1023, 128, 128, 128, 500, 1500, 0 },
    { 0xE0, -1000, 1023, 100, 100, 0, -610, -1390, 0 }, /* -390.6 */
    { 0xE0, 30000, 0, 0, 255, 0, 30000, 32767, 0 },     /* 59882 saturates */
    { 0x85, 50, 700, 32, 64, 100, 10, 96, 34 },         /* the slope does not matter */
    { 0xFF, 200, 0, 64, 128, 255, 150, 300, 0 },        /* virtual: H = 0 whatever the factor */
};

/* CalibrateEvent as nqc encodes it: event, upper factor, lower factor, hysteresis (see vm/ops.c). */
static void calibrate(struct rcx *b, u8 ev, u8 lo, u8 up, u8 h)
{
    u8 c[5] = { 0x04, ev, up, lo, h };
    cmd(b, c, 5);
}

static void calibration_formulas(void **state)
{
    unsigned i, k;
    (void)state;
    for (i = 0; i < sizeof calibrations / sizeof calibrations[0]; i++) {
        struct rcx *b = brick();
        u8 virt = calibrations[i].mode == 0xFF;
        if (virt) {
            set_event(b, 5, SRC_COUNTER0, NORMAL);
            counter(b, 0, calibrations[i].value);
        } else {
            sensor_mode(b, 0, calibrations[i].mode);
            set_event(b, 5, 0, NORMAL);
        }
        calibrate(b, 5, calibrations[i].lo, calibrations[i].up, calibrations[i].h);
        assert_int_equal(poll(b, 25, 5), S_CAL_START);
        if (virt) {
            ms(b, 10);                                  /* one measurement, at the next 10 ms poll */
        } else {
            for (k = 0; k < 8; k++) {                   /* eight measurements */
                input(b, 0, calibrations[i].value, 0, calibrations[i].raw);
                assert_int_equal(poll(b, 25, 5), k < 7 ? S_CAL_BUSY : S_UNDEFINED);
            }
        }
        assert_int_equal(poll(b, 29, 5), calibrations[i].lower);
        assert_int_equal(poll(b, 28, 5), calibrations[i].upper);
        assert_int_equal(poll(b, 30, 5), calibrations[i].hyst);
        brick_free(b);
    }
}

/* The physical average is over 8 samples: values 10..17 (108/8 = 13.5 -> 13), raw 100..800 (450). */
static void calibration_averages_eight_samples(void **state)
{
    struct rcx *b = brick();
    unsigned k;
    (void)state;
    sensor_mode(b, 2, 0x80);
    set_event(b, 0, 2, HIGH);
    calibrate(b, 0, 0, 0, 255);
    for (k = 0; k < 8; k++)
        input(b, 2, (s16)(10 + k), 0, (u16)(100 * (k + 1)));
    assert_int_equal(poll(b, 30, 0), 56);               /* 450 * 255 / 2048 = 56.03 */
    assert_int_equal(poll(b, 28, 0), 69);
    assert_int_equal(poll(b, 29, 0), -43);
    input(b, 2, 13, 0, 450);                            /* then a silent first classification */
    assert_int_equal(poll(b, 25, 0), S_NORMAL);
    assert_int_equal(fired(b), 0);
    input(b, 2, 70, 0, 450);
    assert_int_equal(fired(b), 0x1);
    brick_free(b);
}

/* Nothing to measure for a cleared event. */
static void calibrating_a_cleared_event_does_nothing(void **state)
{
    struct rcx *b = brick();
    struct rcx_event before;
    (void)state;
    before = b->event[3];
    calibrate(b, 3, 10, 10, 10);
    ms(b, 1);
    input(b, 0, 100, 1, 100);
    assert_memory_equal(&b->event[3], &before, sizeof before);
    brick_free(b);
}

/* ---- bad operands -------------------------------------------------------------------------------------------- */

/* Out-of-range operands change nothing: not the events, not the tasks, not the variables. */
static void bad_operands_are_ignored(void **state)
{
    static const u8 rows[][5] = {
        { 4, 0x93, 16, 0, HIGH }, { 4, 0x93, 255, 0, HIGH },           /* event number */
        { 4, 0x93, 1, 11, HIGH }, { 4, 0x93, 1, 255, HIGH },           /* sensor number */
        { 4, 0x93, 1, 8, 4 }, { 4, 0x93, 1, 8, 5 }, { 4, 0x93, 1, 8, 6 }, { 4, 0x93, 1, 8, 13 },
        { 4, 0x93, 1, 8, 15 }, { 4, 0x93, 1, 8, 17 }, { 4, 0x93, 1, 8, 255 },  /* event type */
        { 2, 0x97, 3 }, { 2, 0xA7, 200 }, { 2, 0xB7, 3 },              /* counter number */
        { 4, 0x03, 2, 0, 0 },                                          /* DirectEvent with no bits */
    };
    static const u8 cal_rows[][5] = { { 0x04, 16, 1, 2, 3 }, { 0x04, 255, 1, 2, 3 } };
    static const u8 bad_cal[] = { 0x04, 200, 1, 1, 1 };
    static struct rcx_event events[RCX_EVENTS];
    static struct rcx_task tasks[RCX_TASKS];
    static s16 globals[RCX_GLOBALS];
    struct rcx *b = brick();
    unsigned i;
    (void)state;
    set_event(b, 1, SRC_COUNTER0, HIGH);
    limits(b, 1, -5, 5, 2);
    set_event(b, 2, 0, PRESSED);
    set_event(b, 15, SRC_COUNTER0 + 2, LOW);
    calibrate(b, 15, 1, 2, 3);
    counter(b, 0, 3);
    brick_enter_ev(b, &b->task[4], 0x8000, 0x44);
    for (i = 0; i < sizeof rows / sizeof rows[0] + sizeof cal_rows / sizeof cal_rows[0] + 6; i++) {
        memcpy(events, b->event, sizeof events);
        memcpy(tasks, b->task, sizeof tasks);
        memcpy(globals, b->global, sizeof globals);
        if (i < sizeof rows / sizeof rows[0]) {
            cmd(b, rows[i] + 1, rows[i][0]);
        } else if (i < sizeof rows / sizeof rows[0] + 2) {
            cmd(b, cal_rows[i - sizeof rows / sizeof rows[0]], 5);
        } else {
            switch (i - sizeof rows / sizeof rows[0] - 2) {  /* the engine's own guards */
            case 0: events_set(b, 16, 0, HIGH); break;
            case 1: events_set(b, 0, 11, HIGH); break;
            case 2: events_set(b, 0, 0, 13); break;
            case 3: events_calibrate(b, bad_cal); break;
            case 4: events_input(b, 3); events_input(b, 255); break;
            default: events_counter_changed(b, 3); events_counter_changed(b, 248); break;
            }
        }
        if (memcmp(b->event, events, sizeof events) || memcmp(b->task, tasks, sizeof tasks) ||
            memcmp(b->global, globals, sizeof globals))
            fail_msg("bad operand row %u changed the machine", i);
    }
    brick_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(calibration_formulas),
        cmocka_unit_test(calibration_averages_eight_samples),
        cmocka_unit_test(calibrating_a_cleared_event_does_nothing),
        cmocka_unit_test(bad_operands_are_ignored),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
