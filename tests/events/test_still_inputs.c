/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Events on inputs fed by the sensor engine (sensor_sample(), one sample a millisecond as the brick gives them), issue
 * 21: an input that does not move costs its events nothing - it is at rest (sensors_at_rest(): a port may stop
 * feeding it) and its events are not evaluated - and every event type still fires exactly when its input moves, as
 * the spec says (pp. 70-74, 100-105): pressed, released, period, transition; low, normal, high; click and double click
 * with their timing; change rate; after SetSourceValue moves a threshold or the hysteresis; a calibration of a still
 * input; a value cleared.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <string.h>
#include <cmocka.h>
#include "event_helpers.h"

#define NOTHING 1023 /* raw of an input with nothing connected */

/* `n` milliseconds of input 0 at `raw` (the others with nothing connected), the clock running. */
static void feed(struct rcx *b, u16 raw, unsigned n)
{
    while (n--) {
        sensor_sample(b, 0, raw);
        sensor_sample(b, 1, NOTHING);
        sensor_sample(b, 2, NOTHING);
        vm_tick(b);
    }
}

/* Rotation sensor levels, phases 0-3 (rcx-hardware.md 3.3): phase n + 1 after n is a step up. */
static const u16 phase_raw[4] = { 1000, 860, 400, 640 };

/* One millisecond of input 1 at `raw` (input 0 as it was, input 2 with nothing connected). */
static void feed2(struct rcx *b, u16 raw)
{
    sensor_sample(b, 0, b->sensor[0].raw);
    sensor_sample(b, 1, raw);
    sensor_sample(b, 2, NOTHING);
    vm_tick(b);
}

static void sensor_type(struct rcx *b, u8 n, u8 type)
{
    u8 c[3] = { 0x32, n, type };
    cmd(b, c, 3);
}

/* Events ev..ev+n-1 are exactly those that fired since the last look. */
#define EVENTS(ev, n) ((u16)(((1u << (n)) - 1u) << (ev)))

/* A still input a few samples after it settled: at rest, nothing fired. */
static void still(struct rcx *b, u16 raw)
{
    feed(b, raw, 5);
    assert_int_equal(fired(b), 0);
    assert_true(sensors_at_rest(b));
}

/* 16 events on a touch sensor that is not touched: once classified, the input is at rest like one no event watches,
 * and its events are not looked at again (a state set by hand stays as it is) until the input moves. */
static void a_still_input_costs_its_events_nothing(void **state)
{
    static const u8 types[16] = { 0, 1, 2, 3, 7, 8, 9, 10, 11, 12, 8, 9, 10, 11, 0, 1 };
    struct rcx *b = brick();
    unsigned i;
    (void)state;
    sensor_type(b, 0, 1);                              /* touch: boolean mode, thresholds 0 and 1 */
    for (i = 0; i < 16; i++)
        set_event(b, (u8)i, 0, types[i]);
    feed(b, NOTHING, 1);
    assert_false(sensors_at_rest(b));                  /* the raw sample is not steady yet */
    for (i = 0; i < 16; i++)
        assert_int_equal(poll(b, 25, (u8)i), S_NORMAL);
    still(b, NOTHING);
    for (i = 0; i < 16; i++)
        b->event[i].state = S_HIGH;                    /* what an evaluation would put right */
    feed(b, NOTHING, 1000);
    for (i = 0; i < 16; i++)
        assert_int_equal(poll(b, 25, (u8)i), S_HIGH);
    assert_int_equal(fired(b), 0);
    assert_true(sensors_at_rest(b));
    feed(b, 100, 1);                                   /* pressed: evaluated again */
    assert_int_equal(poll(b, 25, 0), S_NORMAL);        /* value 1: not above 1 */
    brick_free(b);
}

/* Pressed, released, period and transition (absolute measurement, p. 101) fire at the edges of the boolean, and the
 * still input between them is at rest. */
static void touch_events_fire_at_the_edges(void **state)
{
    struct rcx *b = brick();
    (void)state;
    sensor_type(b, 0, 1);
    set_event(b, 0, 0, PRESSED);
    set_event(b, 1, 0, RELEASED);
    set_event(b, 2, 0, PERIOD);
    set_event(b, 3, 0, TRANSITION);
    still(b, NOTHING);
    feed(b, 180, 1);
    assert_int_equal(fired(b), 0x1 | 0x8);
    still(b, 180);
    feed(b, 900, 1);
    assert_int_equal(fired(b), 0x2 | 0x4 | 0x8);
    still(b, 900);
    brick_free(b);
}

/* Late samples (the brick fell behind and feeds the scans that waited, rcx_sensor.late in sensor[0]): their values
 * and rotation steps all count, but the events are told only of the newest sample, worked out in full for them even
 * when it repeats the one before. */
static void late_samples_count_and_tell_only_the_newest(void **state)
{
    static const u16 phase[4] = { 1023, 777, 368, 532 }; /* rotation phases 0-3, counted forwards */
    struct rcx *b = brick();
    unsigned i;
    (void)state;
    sensor_type(b, 0, 1);
    set_event(b, 0, 0, PRESSED);
    still(b, NOTHING);
    b->sensor[0].late = 1;
    feed(b, 180, 3);                                   /* pressed, in three late samples */
    assert_int_equal(fired(b), 0);
    assert_int_equal(b->sensor[0].value, 1);          /* the value moved with them */
    b->sensor[0].late = 0;
    feed(b, 180, 1);                                   /* the newest repeats them: the press is told now */
    assert_int_equal(fired(b), 0x1);
    still(b, 180);
    sensor_type(b, 1, 4);                              /* rotation on input 2: every late step counts */
    b->sensor[0].late = 1;
    for (i = 1; i <= 40; i++) {
        sensor_sample(b, 0, 180);
        sensor_sample(b, 1, phase[i & 3]);
        sensor_sample(b, 2, NOTHING);
        vm_tick(b);
    }
    b->sensor[0].late = 0;
    assert_int_equal(b->sensor[1].value < 0 ? -b->sensor[1].value : b->sensor[1].value, 40);
    brick_free(b);
}

/* Raw mode, thresholds 300 and 700: the ranges entered, a click (LOW -> HIGH -> LOW within the 150 ms duration), a
 * double click (a click starting within the duration after the last one ended) and a press too slow to be a click. */
static void range_and_click_events_fire_when_the_value_moves(void **state)
{
    struct rcx *b = brick();
    unsigned i;
    (void)state;
    for (i = 0; i < 5; i++) {
        set_event(b, (u8)i, 0, (u8)(LOW + i));         /* low, normal, high, click, double click */
        limits(b, (u8)i, 300, 700, 0);
    }
    still(b, 200);                                     /* LOW: the first classification fires nothing */
    assert_int_equal(poll(b, 25, 0), S_LOW);
    feed(b, 800, 1);
    assert_int_equal(fired(b), 0x4);                   /* high */
    still(b, 800);
    feed(b, 200, 1);                                   /* back low after some 60 ms: a click */
    assert_int_equal(fired(b), 0x1 | 0x8);
    assert_int_equal(poll(b, 27, 3), 1);
    still(b, 200);
    feed(b, 500, 1);
    assert_int_equal(fired(b), 0x2);                   /* normal */
    feed(b, 800, 1);
    assert_int_equal(fired(b), 0x4);
    feed(b, 200, 1);                                   /* the second click, within 150 ms of the first */
    assert_int_equal(fired(b), 0x1 | 0x8 | 0x10);
    still(b, 200);
    feed(b, 800, 200);                                 /* held high 200 ms: too slow for a click */
    assert_int_equal(fired(b), 0x4);
    feed(b, 200, 1);
    assert_int_equal(fired(b), 0x1);
    assert_int_equal(poll(b, 27, 3), 2);
    brick_free(b);
}

/* Dynamic measurement, slope 10 (p. 102): a fall faster than 10 in 3 ms makes the boolean 1, a rise 0; each change
 * is a change-rate event. A still input, whatever its level, changes nothing. */
static void change_rate_fires_when_the_slope_changes(void **state)
{
    struct rcx *b = brick();
    u16 raw;
    (void)state;
    sensor_mode(b, 0, 0x0A);                           /* raw, slope 10 */
    set_event(b, 0, 0, CHANGE_RATE);
    still(b, 500);
    for (raw = 500; raw > 300; raw = (u16)(raw - 20))  /* falling */
        feed(b, raw, 1);
    assert_int_equal(fired(b), 0x1);
    still(b, 300);
    assert_int_equal(poll(b, 13, 0), 1);
    for (raw = 300; raw < 600; raw = (u16)(raw + 20))  /* rising */
        feed(b, raw, 1);
    assert_int_equal(fired(b), 0x1);
    still(b, 600);
    brick_free(b);
}

/* SetSourceValue moves thresholds of events on a still input: the input leaves its rest, and its next sample, the
 * same as before, is evaluated against them. Hysteresis widens the range being left (reference-firmware.md). */
static void a_threshold_moved_is_seen_at_the_next_sample(void **state)
{
    struct rcx *b = brick();
    (void)state;
    set_event(b, 0, 0, HIGH);
    set_event(b, 1, 0, LOW);
    still(b, 500);                                     /* NORMAL in 0 ... 1023 */
    set_source(b, 28, 0, 400);
    set_source(b, 28, 1, 400);
    assert_false(sensors_at_rest(b));
    feed(b, 500, 1);
    assert_int_equal(fired(b), 0x1);
    still(b, 500);
    set_source(b, 30, 0, 200);                         /* HIGH holds while above 400 - 200 ... */
    set_source(b, 28, 0, 650);                         /* ... now 650 - 200: still HIGH */
    feed(b, 500, 1);
    assert_int_equal(fired(b), 0);
    assert_int_equal(poll(b, 25, 0), S_HIGH);
    set_source(b, 29, 1, 600);                         /* 500 below the lower threshold of event 1 */
    set_source(b, 28, 1, 900);
    feed(b, 500, 1);
    assert_int_equal(fired(b), 0x2);
    still(b, 500);
    brick_free(b);
}

/* CalibrateEvent on a still input takes its 8 samples, one a millisecond, then classifies it (pp. 74, 103-105; the
 * numbers as tests/events/test_calibration.c works them out for raw 600), and the input is at rest again. */
static void a_still_input_is_calibrated(void **state)
{
    static const u8 calibrate[5] = { 0x04, 0, 64, 64, 128 };
    struct rcx *b = brick();
    unsigned k;
    (void)state;
    set_event(b, 0, 0, NORMAL);
    still(b, 600);
    cmd(b, calibrate, 5);
    assert_int_equal(poll(b, 25, 0), S_CAL_START);
    for (k = 0; k < 8; k++) {
        assert_false(sensors_at_rest(b));
        feed(b, 600, 1);
        assert_int_equal(poll(b, 25, 0), k < 7 ? S_CAL_BUSY : S_UNDEFINED);
    }
    assert_int_equal(poll(b, 29, 0), 413);
    assert_int_equal(poll(b, 28, 0), 787);
    assert_int_equal(poll(b, 30, 0), 37);
    feed(b, 600, 1);
    assert_int_equal(poll(b, 25, 0), S_NORMAL);
    still(b, 600);
    b->event[0].state = S_HIGH;                        /* what an evaluation would put right */
    for (k = 0; k < 100; k++)
        feed(b, (u16)(500 + k % 7 * 20), 1);           /* moving inside 413 ... 787: windowed again, not looked at */
    assert_int_equal(poll(b, 25, 0), S_HIGH);
    brick_free(b);
}

/* ClearSensorValue on a still input in transition mode: the events see the value go back to 0. */
static void a_value_cleared_is_seen(void **state)
{
    static const u8 clear[2] = { 0xD1, 0 };
    struct rcx *b = brick();
    (void)state;
    sensor_type(b, 0, 1);
    sensor_mode(b, 0, 0x40);                           /* transitions counted */
    set_event(b, 0, 0, LOW);
    limits(b, 0, 1, 5, 0);
    still(b, NOTHING);                                 /* 0: LOW */
    feed(b, 100, 1);
    feed(b, NOTHING, 1);                               /* 2 transitions: NORMAL */
    still(b, NOTHING);
    assert_int_equal(poll(b, 25, 0), S_NORMAL);
    cmd(b, clear, 2);
    assert_false(sensors_at_rest(b));
    feed(b, NOTHING, 1);
    assert_int_equal(fired(b), 0x1);
    still(b, NOTHING);
    brick_free(b);
}

/* An input that moves without leaving the values that keep its events as they are (vm/events.c events_window) costs
 * them nothing either: a state set by hand stays while the value moves inside 300 ... 700, and is put right by the
 * first sample outside. */
static void a_value_moving_inside_the_thresholds_costs_nothing(void **state)
{
    struct rcx *b = brick();
    unsigned i;
    (void)state;
    for (i = 0; i < 4; i++) {
        set_event(b, (u8)i, 0, (u8)(LOW + i));         /* low, normal, high, click */
        limits(b, (u8)i, 300, 700, 0);
    }
    still(b, 500);
    assert_int_equal(poll(b, 25, 0), S_NORMAL);
    for (i = 0; i < 4; i++)
        b->event[i].state = S_HIGH;                    /* what an evaluation would put right */
    for (i = 0; i < 400; i++)
        feed(b, (u16)(300 + (i * 37) % 401), 1);       /* every value from 300 to 700, none twice in a row */
    for (i = 0; i < 4; i++)
        assert_int_equal(poll(b, 25, (u8)i), S_HIGH);
    assert_int_equal(fired(b), 0);
    feed(b, 299, 1);                                   /* below: looked at, from HIGH to LOW */
    for (i = 0; i < 4; i++)
        assert_int_equal(poll(b, 25, (u8)i), S_LOW);
    assert_int_equal(fired(b) & 0x1, 0x1);
    brick_free(b);
}

/* The same with the thresholds SetEvent gives an angle (0 and 32767): a rotation sensor counting up is not looked at
 * while it stays inside them. */
static void a_rotation_counting_inside_its_default_thresholds_costs_nothing(void **state)
{
    struct rcx *b = brick();
    unsigned i;
    (void)state;
    sensor_mode(b, 1, 0xE0);                           /* input 2: angle */
    set_event(b, 0, 1, NORMAL);
    for (i = 0; i < 2; i++)
        feed2(b, phase_raw[i]);                        /* 0, then 1 step */
    assert_int_equal(poll(b, 25, 0), S_NORMAL);
    b->event[0].state = S_HIGH;                        /* what an evaluation would put right */
    for (i = 2; i < 402; i++)
        feed2(b, phase_raw[i % 4]);
    assert_int_equal(poll(b, 9, 1), 401);
    assert_int_equal(poll(b, 25, 0), S_HIGH);
    brick_free(b);
}

/* A HIGH that holds up to the top of the range (upper 32767, its hysteresis taking it down to 0) and a LOW from the
 * bottom (lower -32768, up to -1): the input leaves them when the value crosses 0 or -1, though no value lies above
 * the one threshold or below the other. */
static void states_held_by_hysteresis_at_the_ends_of_the_range_end(void **state)
{
    struct rcx *b = brick();
    unsigned i;
    (void)state;
    set_event(b, 0, 0, HIGH);                          /* input 1, raw */
    limits(b, 0, 0, 100, 0);
    feed(b, 500, 2);
    limits(b, 0, 0, 32767, 32767);                     /* HIGH holds while the value is above 0 */
    for (i = 0; i < 20; i++)
        feed(b, (u16)(500 - i * 20), 1);
    assert_int_equal(poll(b, 25, 0), S_HIGH);
    feed(b, 0, 1);
    assert_int_equal(poll(b, 25, 0), S_NORMAL);
    sensor_mode(b, 1, 0xE0);                           /* input 2: angle, counted down to -8 */
    set_event(b, 1, 1, LOW);
    limits(b, 1, -5, 100, 0);
    for (i = 1; i <= 8; i++)
        feed2(b, phase_raw[(8 - i) % 4]);             /* phases 3, 2, 1, 0, ...: a step down each */
    assert_int_equal(poll(b, 9, 1), -8);
    assert_int_equal(poll(b, 25, 1), S_LOW);
    limits(b, 1, -32768, 100, 32767);                  /* LOW holds while the value is below -1 */
    for (i = 1; i <= 7; i++)                           /* back up to -1, a step each sample */
        feed2(b, phase_raw[i % 4]);
    assert_int_equal(poll(b, 9, 1), -1);
    assert_int_equal(poll(b, 25, 1), S_NORMAL);
    brick_free(b);
}

/* A small deterministic generator (xorshift), so that a failure can be replayed. */
static unsigned rnd_state = 0x2545F491u;
static unsigned rnd(unsigned n)
{
    rnd_state ^= rnd_state << 13;
    rnd_state ^= rnd_state >> 17;
    rnd_state ^= rnd_state << 5;
    return rnd_state % n;
}

/* The same as a property: two bricks get the same random inputs (still stretches, steps, noise, rotation levels),
 * sensor modes, 16 events and threshold changes; the second's events are also evaluated after every sample, as
 * before issue 21. Nothing may differ - what fired, and every event's state, thresholds and click counts - and the
 * first brick's inputs are at rest whenever they have been still a few samples. (No calibration: an evaluation more
 * would be a calibration sample more; a_still_input_is_calibrated holds it.) */
static void still_inputs_change_nothing_an_evaluation_would(void **state)
{
    static const u8 modes[] = { 0x00, 0x20, 0x40, 0x60, 0x80, 0xE0, 0x05, 0x2A };
    static const u8 types[] = { PRESSED, RELEASED, PERIOD, TRANSITION, CHANGE_RATE, LOW, NORMAL, HIGH, CLICK, DOUBLE };
    static const u16 levels[] = { 1000, 860, 400, 640, 100, 500, 900, 300 };
    struct rcx *b[2] = { brick(), brick() };
    u16 raw[3] = { NOTHING, NOTHING, NOTHING };
    unsigned ms_, k, n, still_for = 0;
    (void)state;
    for (k = 0; k < 2; k++)
        for (n = 0; n < 3; n++)
            sensor_type(b[k], (u8)n, (u8)(n + 1));        /* touch, temperature, light */
    for (ms_ = 0; ms_ < 30000; ms_++) {
        if (rnd(500) == 0) {                            /* now and then a new mode, event or threshold */
            u8 what = (u8)rnd(3), i = (u8)rnd(16), m = modes[rnd(sizeof modes)], t = types[rnd(sizeof types)];
            static const s16 ends[] = { -32768, -32767, 32766, 32767 }; /* thresholds at the ends of the range */
            s16 v = rnd(8) ? (s16)((s16)rnd(1200) - 100) : ends[rnd(4)];
            for (k = 0; k < 2; k++) {
                if (what == 0)
                    sensor_mode(b[k], (u8)rnd_state % 3, m);
                else if (what == 1)
                    set_event(b[k], i, (u8)(i % 3), t);
                else
                    set_source(b[k], (u8)(28 + rnd_state % 3), i, (u8)(28 + rnd_state % 3) == 30 ? (s16)(v < 0 ? -(v / 8) : v / 8) : v);
            }
        }
        if (rnd(20) == 0)                               /* a still stretch ends */
            for (n = 0; n < 3; n++) {
                unsigned how = rnd(4);
                raw[n] = how == 0 ? levels[rnd(sizeof levels / sizeof levels[0])]
                       : how == 1 ? (u16)((raw[n] + 1u + rnd(3)) & 0x3FF) : raw[n];
                still_for = 0;
            }
        for (k = 0; k < 2; k++) {
            for (n = 0; n < 3; n++)
                sensor_sample(b[k], (u8)n, raw[n]);
            if (k == 1)
                for (n = 0; n < 3; n++)
                    events_input(b[k], n);
            vm_tick(b[k]);
        }
        assert_int_equal(fired(b[0]), fired(b[1]));
        for (n = 0; n < RCX_EVENTS; n++) { /* bit 0 of the flags, the boolean last seen, is read by types 0-7 only */
            struct rcx_event e0 = b[0]->event[n], e1 = b[1]->event[n];
            if (e0.type >= LOW) {
                e0.flags &= 0xFE;
                e1.flags &= 0xFE;
            }
            if (memcmp(&e0, &e1, sizeof e0))
                fail_msg("event %u differs after %u ms: state %u, %u; flags %x, %x", n, ms_, e0.state, e1.state,
                         e0.flags, e1.flags);
        }
        if (++still_for > SENSOR_DT_MS + 1)
            assert_true(sensors_at_rest(b[0]));
    }
    brick_free(b[0]);
    brick_free(b[1]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_still_input_costs_its_events_nothing),
        cmocka_unit_test(touch_events_fire_at_the_edges),
        cmocka_unit_test(late_samples_count_and_tell_only_the_newest),
        cmocka_unit_test(range_and_click_events_fire_when_the_value_moves),
        cmocka_unit_test(change_rate_fires_when_the_slope_changes),
        cmocka_unit_test(a_threshold_moved_is_seen_at_the_next_sample),
        cmocka_unit_test(a_still_input_is_calibrated),
        cmocka_unit_test(a_value_cleared_is_seen),
        cmocka_unit_test(a_value_moving_inside_the_thresholds_costs_nothing),
        cmocka_unit_test(a_rotation_counting_inside_its_default_thresholds_costs_nothing),
        cmocka_unit_test(states_held_by_hysteresis_at_the_ends_of_the_range_end),
        cmocka_unit_test(still_inputs_change_nothing_an_evaluation_would),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
