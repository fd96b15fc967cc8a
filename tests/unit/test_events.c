/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The event engine against the spec's numbers: SetEvent defaults (p. 71), state change points with hysteresis
 * (reference-firmware.md), click and double-click timing (pp. 71, 102), the valid sensor/type combinations
 * (p. 101), mailbox, counter and timer events, DirectEvent (p. 63) and ClearAllEvents (p. 25). CalibrateEvent and
 * bad operands: tests/events/test_calibration.c.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <string.h>
#include <cmocka.h>
#include "../events/event_helpers.h"

/* ---- SetEvent defaults ------------------------------------------------------------------------------------- */

/* Spec p. 71, physical sensor modes (bits 5-7 of the sensor mode), a slope does not matter. */
static const struct { u8 mode; s16 lower, upper; } physical_defaults[] = {
    { 0x00, 0, 1023 },      /* RawMode */
    { 0x20, 0, 1 },         /* BooleanMode */
    { 0x40, 0, 32767 },     /* TransitionCntMode */
    { 0x60, 0, 32767 },     /* PeriodCounterMode */
    { 0x80, 0, 100 },       /* PctFullScaleMode */
    { 0xA0, -200, 700 },    /* CelsiusMode */
    { 0xC0, -40, 1580 },    /* FahrenheitMode */
    { 0xE0, 0, 32767 },     /* AngleStepsMode */
    { 0x85, 0, 100 },
    { 0xFF, 0, 32767 },
};

static void check_defaults(struct rcx *b, u8 ev, s16 lower, s16 upper)
{
    assert_int_equal(poll(b, 29, ev), lower);
    assert_int_equal(poll(b, 28, ev), upper);
    assert_int_equal(poll(b, 30, ev), 0);
    assert_int_equal(poll(b, 31, ev), 15);  /* 150 ms */
    assert_int_equal(poll(b, 27, ev), 0);   /* click counter cleared */
    assert_int_equal(poll(b, 25, ev), S_UNDEFINED);
}

static void dirty(struct rcx *b, u8 ev)
{
    set_source(b, 27, ev, 9);
    limits(b, ev, 4, 5, 3);
    set_source(b, 31, ev, 99);
}

static void defaults_per_physical_mode(void **state)
{
    unsigned i, n;
    (void)state;
    for (i = 0; i < sizeof physical_defaults / sizeof physical_defaults[0]; i++)
        for (n = 0; n < 3; n++) {
            struct rcx *b = brick();
            sensor_mode(b, (u8)n, physical_defaults[i].mode);
            dirty(b, 6);
            set_event(b, 6, (u8)n, NORMAL);
            check_defaults(b, 6, physical_defaults[i].lower, physical_defaults[i].upper);
            brick_free(b);
        }
}

static void defaults_per_virtual_sensor(void **state)
{
    static const struct { u8 sensor; s16 lower, upper; } rows[] = {
        { 3, 0, 32767 }, { 4, 0, 32767 }, { 5, 0, 32767 }, { 6, 0, 32767 },     /* timers */
        { 7, 0, 255 },                                                          /* IR message */
        { 8, -32768, 32767 }, { 9, -32768, 32767 }, { 10, -32768, 32767 },      /* counters */
    };
    unsigned i;
    (void)state;
    for (i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        struct rcx *b = brick();
        dirty(b, 15);
        set_event(b, 15, rows[i].sensor, LOW);
        check_defaults(b, 15, rows[i].lower, rows[i].upper);
        brick_free(b);
    }
}

/* ---- states and hysteresis ----------------------------------------------------------------------------------- */

/* reference-firmware.md: high when value > upper; back to normal at value <= upper - h; low when value < lower;
 * back to normal at value >= lower + h. Events 0, 1, 2 = enter low, normal, high on counter 0. */
static void state_change_points(void **state)
{
    static const struct { s16 value; u8 state; u16 fired; } steps[] = {
        { 30, S_NORMAL, 0 },        /* first classification: no change of range */
        { 50, S_NORMAL, 0 },
        { 51, S_HIGH, 0x4 },
        { 46, S_HIGH, 0 },
        { 45, S_NORMAL, 0x2 },
        { 20, S_NORMAL, 0 },
        { 19, S_LOW, 0x1 },
        { 24, S_LOW, 0 },
        { 25, S_NORMAL, 0x2 },
        { 51, S_HIGH, 0x4 },
        { 19, S_LOW, 0x1 },         /* straight from high to low */
        { 60, S_HIGH, 0x4 },        /* and back */
        { -32768, S_LOW, 0x1 },
    };
    struct rcx *b = brick();
    unsigned i, ev;
    (void)state;
    for (ev = 0; ev < 3; ev++) {
        set_event(b, (u8)ev, SRC_COUNTER0, (u8)(LOW + ev));
        limits(b, (u8)ev, 20, 50, 5);
    }
    for (i = 0; i < sizeof steps / sizeof steps[0]; i++) {
        counter(b, 0, steps[i].value);
        for (ev = 0; ev < 3; ev++)
            assert_int_equal(poll(b, 25, (u8)ev), steps[i].state);
        assert_int_equal(fired(b), steps[i].fired);
    }
    brick_free(b);
}

/* Thresholds are read at each evaluation: moving one past a steady value changes the state. */
static void thresholds_apply_to_a_steady_value(void **state)
{
    struct rcx *b = brick();
    (void)state;
    set_event(b, 4, SRC_COUNTER0 + 1, HIGH);
    limits(b, 4, 0, 40, 0);
    counter(b, 1, 30);
    assert_int_equal(fired(b), 0);
    set_source(b, 28, 4, 29);
    ms(b, 10);                                  /* the virtual sensors are looked at every 10 ms */
    assert_int_equal(fired(b), 0x10);
    assert_int_equal(poll(b, 25, 4), S_HIGH);
    brick_free(b);
}

/* ---- clicks ---------------------------------------------------------------------------------------------------- */

/* Counter 2 goes from low (0) to high (30) for `high_ms`, then back to low; events 0 (click), 1 (double click)
 * watch it with lower 10, upper 20. */
static u16 pulse(struct rcx *b, unsigned high_ms)
{
    u16 f;
    counter(b, 2, 30);
    f = fired(b);
    ms(b, high_ms);
    counter(b, 2, 0);
    return (u16)(f | fired(b));
}

static struct rcx *clicker(void)
{
    struct rcx *b = brick();
    set_event(b, 0, SRC_COUNTER0 + 2, CLICK);
    set_event(b, 1, SRC_COUNTER0 + 2, DOUBLE);
    limits(b, 0, 10, 20, 0);
    limits(b, 1, 10, 20, 0);
    counter(b, 2, 0);
    ms(b, 1000);
    assert_int_equal(fired(b), 0);
    return b;
}

/* Default duration 150 ms (p. 71), in 10 ms steps. */
static void click_within_the_duration(void **state)
{
    struct rcx *b = clicker();
    (void)state;
    assert_int_equal(pulse(b, 100), 0x1);
    assert_int_equal(poll(b, 27, 0), 1);
    ms(b, 500);
    assert_int_equal(pulse(b, 140), 0x1);
    assert_int_equal(poll(b, 27, 0), 2);
    ms(b, 500);
    assert_int_equal(pulse(b, 150), 0x1);   /* the duration itself still counts */
    ms(b, 500);
    assert_int_equal(pulse(b, 160), 0);
    ms(b, 500);
    assert_int_equal(pulse(b, 400), 0);
    assert_int_equal(poll(b, 27, 0), 3);
    assert_int_equal(poll(b, 27, 1), 3);    /* each event counts the clicks of its sensor */
    brick_free(b);
}

/* A click must reach HIGH: low -> normal -> low is not one. */
static void click_needs_the_high_range(void **state)
{
    struct rcx *b = clicker();
    (void)state;
    counter(b, 2, 15);
    ms(b, 20);
    counter(b, 2, 0);
    assert_int_equal(fired(b), 0);
    assert_int_equal(poll(b, 27, 0), 0);
    brick_free(b);
}

/* Two clicks with the second starting within the duration after the first ended. */
static void double_click(void **state)
{
    struct rcx *b = clicker();
    (void)state;
    assert_int_equal(pulse(b, 20), 0x1);
    ms(b, 20);
    assert_int_equal(pulse(b, 20), 0x3);
    ms(b, 20);
    assert_int_equal(pulse(b, 20), 0x1);    /* a third click starts a new pair */
    ms(b, 100);
    assert_int_equal(pulse(b, 50), 0x3);
    ms(b, 300);
    assert_int_equal(pulse(b, 50), 0x1);    /* too late for a double */
    ms(b, 150);
    assert_int_equal(pulse(b, 50), 0x3);    /* just in time */
    ms(b, 160);
    assert_int_equal(pulse(b, 50), 0x1);
    assert_int_equal(poll(b, 27, 0), 7);
    brick_free(b);
}

/* The duration is source 31 (10 ms units). */
static void click_duration_is_source_31(void **state)
{
    struct rcx *b = clicker();
    (void)state;
    set_source(b, 31, 0, 30);
    assert_int_equal(pulse(b, 250), 0x1);
    ms(b, 1000);
    assert_int_equal(pulse(b, 350), 0);
    set_source(b, 31, 0, 5);
    ms(b, 1000);
    assert_int_equal(pulse(b, 40), 0x1);
    ms(b, 1000);
    assert_int_equal(pulse(b, 80), 0);
    brick_free(b);
}

/* ---- valid combinations (p. 101) ----------------------------------------------------------------------------- */

enum kind { K_ABS, K_DYN, K_TIMER, K_MSG, K_COUNTER, KINDS };

/* The spec's table, '+' as 1: Input absolute, Input dynamic, Timer, PBMessage, Counter. */
static const struct { u8 type; u8 valid[KINDS]; } combinations[] = {
    { PRESSED,     { 1, 0, 0, 0, 0 } },
    { RELEASED,    { 1, 0, 0, 0, 0 } },
    { PERIOD,      { 1, 1, 0, 0, 0 } },
    { TRANSITION,  { 1, 1, 0, 0, 0 } },
    { CHANGE_RATE, { 0, 1, 0, 0, 0 } },
    { LOW,         { 1, 1, 1, 1, 1 } },
    { NORMAL,      { 1, 1, 1, 1, 1 } },
    { HIGH,        { 1, 1, 1, 1, 1 } },
    { CLICK,       { 1, 1, 1, 1, 1 } },
    { DOUBLE,      { 1, 1, 1, 1, 1 } },
    { MAILBOX,     { 0, 0, 0, 1, 0 } },
};

/* Drive one sensor of each kind through every kind of change: low, normal, high, low, high, low 20 ms apart (two
 * quick clicks), the inputs' booleans following the level, the message re-sent each time. */
static u16 stimulate(struct rcx *b, u8 kind)
{
    static const s16 levels[] = { 0, 15, 30, 0, 30, 0 };
    u16 all = 0;
    unsigned i;
    for (i = 0; i < sizeof levels / sizeof levels[0]; i++) {
        s16 v = levels[i];
        u8 msg[2] = { 0xF7, (u8)v };
        switch (kind) {
        case K_ABS:
        case K_DYN: input(b, 1, v, v > 20, 500); break;
        case K_TIMER: set_source(b, 1, 2, v); break;
        case K_MSG: cmd(b, msg, 2); break;
        default: counter(b, 1, v); break;
        }
        ms(b, 20);
        all |= fired(b);
    }
    return all;
}

static void only_valid_combinations_generate(void **state)
{
    static const u8 sensor[KINDS] = { 1, 1, SRC_TIMER0 + 2, SRC_MESSAGE, SRC_COUNTER0 + 1 };
    unsigned i, k;
    (void)state;
    for (i = 0; i < sizeof combinations / sizeof combinations[0]; i++)
        for (k = 0; k < KINDS; k++) {
            struct rcx *b = brick();
            u16 got;
            sensor_mode(b, 1, k == K_DYN ? 0x23 : 0x20);
            input(b, 1, 0, 0, 500);
            set_event(b, 9, sensor[k], combinations[i].type);
            limits(b, 9, 10, 20, 0);
            got = stimulate(b, (u8)k);
            if ((got == 0x200) != combinations[i].valid[k] || (got & ~0x200u))
                fail_msg("type %u on sensor kind %u: fired %#x", combinations[i].type, k, got);
            brick_free(b);
        }
}

/* Boolean edges on an input in absolute mode, and no edge made up from the state before SetEvent. */
static void pressed_released_period_transition(void **state)
{
    struct rcx *b = brick();
    (void)state;
    input(b, 2, 1, 1, 100);
    set_event(b, 0, 2, PRESSED);
    set_event(b, 1, 2, RELEASED);
    set_event(b, 2, 2, PERIOD);
    set_event(b, 3, 2, TRANSITION);
    input(b, 2, 1, 1, 100);
    assert_int_equal(fired(b), 0);
    input(b, 2, 0, 0, 1000);
    assert_int_equal(fired(b), 0xE);
    input(b, 2, 0, 0, 1000);
    assert_int_equal(fired(b), 0);
    input(b, 2, 1, 1, 100);
    assert_int_equal(fired(b), 0x9);
    brick_free(b);
}

/* ---- mailbox, counters, timers ------------------------------------------------------------------------------- */

/* Every message received, set or cleared is a mailbox event, even with the same value (p. 103;
 * reference-firmware.md for ClearPBMessage). */
static void mailbox_on_every_message(void **state)
{
    static const u8 msg5[] = { 0xF7, 5 }, clear[] = { 0x90 };
    struct rcx *b = brick();
    (void)state;
    set_event(b, 12, SRC_MESSAGE, MAILBOX);
    set_event(b, 13, SRC_COUNTER0, MAILBOX);    /* not a valid combination */
    cmd(b, msg5, 2);
    assert_int_equal(fired(b), 0x1000);
    cmd(b, msg5, 2);
    assert_int_equal(fired(b), 0x1000);
    cmd(b, clear, 1);
    assert_int_equal(fired(b), 0x1000);
    set_source(b, 15, 0, 77);
    assert_int_equal(fired(b), 0x1000);
    b->message = 9;
    events_message_changed(b);                 /* what the IR link does on a received message */
    assert_int_equal(fired(b), 0x1000);
    ms(b, 10);
    assert_int_equal(fired(b), 0);
    cmd(b, (const u8[]){ 0x97, 0 }, 2);
    assert_int_equal(fired(b), 0);
    brick_free(b);
}

/* IncCounter, DecCounter and ClearCounter raise counter events at once; SetVar on variables 0-2 within 10 ms. */
static void counter_events(void **state)
{
    static const u8 inc0[] = { 0x97, 0 }, dec1[] = { 0xA7, 1 }, clr0[] = { 0xB7, 0 };
    static const u8 setvar2[] = { 0x14, 2, 2, 100, 0 };
    struct rcx *b = brick();
    (void)state;
    set_event(b, 0, SRC_COUNTER0, HIGH);
    set_event(b, 1, SRC_COUNTER0 + 1, LOW);
    set_event(b, 2, SRC_COUNTER0, NORMAL);
    set_event(b, 3, SRC_COUNTER0 + 2, HIGH);
    limits(b, 0, 0, 2, 0);
    limits(b, 1, 0, 2, 0);
    limits(b, 2, 0, 2, 0);
    limits(b, 3, 0, 50, 0);
    ms(b, 10);
    cmd(b, inc0, 2);
    cmd(b, inc0, 2);
    assert_int_equal(fired(b), 0);
    cmd(b, inc0, 2);
    assert_int_equal(b->global[0], 3);
    assert_int_equal(fired(b), 0x1);
    cmd(b, dec1, 2);
    assert_int_equal(fired(b), 0x2);
    cmd(b, clr0, 2);
    assert_int_equal(fired(b), 0x4);
    cmd(b, setvar2, 5);
    assert_int_equal(fired(b), 0);
    ms(b, 10);
    assert_int_equal(fired(b), 0x8);
    brick_free(b);
}

/* The 100 ms timers: enter high when timer 1 passes 5, i.e. at 600 ms, not at 500 ms. */
static void timer_events(void **state)
{
    static const u8 clear1[] = { 0xA1, 1 };
    struct rcx *b = brick();
    (void)state;
    set_event(b, 7, SRC_TIMER0 + 1, HIGH);
    set_event(b, 8, SRC_TIMER0 + 1, LOW);
    limits(b, 7, 2, 5, 0);
    limits(b, 8, 2, 5, 0);
    cmd(b, clear1, 2);
    ms(b, 590);
    assert_int_equal(fired(b), 0);
    assert_int_equal(poll(b, 25, 7), S_NORMAL);
    ms(b, 12);
    assert_int_equal(fired(b), 0x80);
    cmd(b, clear1, 2);
    ms(b, 10);
    assert_int_equal(fired(b), 0x100);
    brick_free(b);
}

/* ---- DirectEvent, ClearAllEvents ---------------------------------------------------------------------------- */

/* p. 63: every task monitoring one of the bits is alerted with the bits it monitors; the operand is a source. */
static void direct_event(void **state)
{
    static const u8 ev6[] = { 0x03, 2, 0x06, 0x00 }, ev_var5[] = { 0x03, 0, 5, 0 };
    struct rcx *b = brick_new();
    (void)state;
    brick_enter_ev(b, &b->task[0], 0x0005, 0x40);
    brick_enter_ev(b, &b->task[1], 0x0100, 0x41);
    brick_enter_ev(b, &b->task[2], 0x0002, 0x42);
    cmd(b, ev6, sizeof ev6);
    assert_int_equal(b->task[0].ev.state, ACCESS_NONE);
    assert_int_equal(poll(b, 23, 0), 0x0004);
    assert_int_equal(b->task[0].pc, 0x40);
    assert_int_equal(b->task[1].ev.state, ACCESS_EV);
    assert_int_equal(poll(b, 23, 1), 0);
    assert_int_equal(poll(b, 23, 2), 0x0002);
    b->global[5] = 0x0300;
    cmd(b, ev_var5, sizeof ev_var5);
    assert_int_equal(poll(b, 23, 1), 0x0100);
    assert_int_equal(b->task[1].pc, 0x41);
    brick_free(b);
}

/* p. 25: all 16 events are cleared; tasks monitoring them are not alerted and keep monitoring. */
static void clear_all_events(void **state)
{
    static const u8 clear_all[] = { 0x06 }, ev1[] = { 0x03, 2, 0x01, 0x00 };
    struct rcx *b = brick();
    unsigned ev;
    (void)state;
    for (ev = 0; ev < 16; ev++) {
        set_event(b, (u8)ev, SRC_COUNTER0, HIGH);
        limits(b, (u8)ev, 0, 5, 1);
    }
    counter(b, 0, 1);
    set_event(b, 3, SRC_COUNTER0, CLEAR);       /* ClearEvent: that one only */
    counter(b, 0, 10);
    assert_int_equal(fired(b), 0xFFF7);
    cmd(b, clear_all, 1);
    assert_int_equal(b->task[0].ev.state, ACCESS_EV);
    for (ev = 0; ev < 16; ev++) {
        assert_int_equal(poll(b, 25, (u8)ev), S_UNDEFINED);
        assert_int_equal(b->event[ev].type, RCX_EVENT_NONE);
    }
    counter(b, 0, 0);
    counter(b, 0, 100);
    ms(b, 5);
    assert_int_equal(fired(b), 0);
    cmd(b, ev1, sizeof ev1);
    assert_int_equal(fired(b), 0x0001);
    brick_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(defaults_per_physical_mode),
        cmocka_unit_test(defaults_per_virtual_sensor),
        cmocka_unit_test(state_change_points),
        cmocka_unit_test(thresholds_apply_to_a_steady_value),
        cmocka_unit_test(click_within_the_duration),
        cmocka_unit_test(click_needs_the_high_range),
        cmocka_unit_test(double_click),
        cmocka_unit_test(click_duration_is_source_31),
        cmocka_unit_test(only_valid_combinations_generate),
        cmocka_unit_test(pressed_released_period_transition),
        cmocka_unit_test(mailbox_on_every_message),
        cmocka_unit_test(counter_events),
        cmocka_unit_test(timer_events),
        cmocka_unit_test(direct_event),
        cmocka_unit_test(clear_all_events),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
