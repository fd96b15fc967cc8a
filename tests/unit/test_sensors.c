/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Sensor engine: types and default modes (spec p. 52), modes and slope (p. 53, p. 102), the conversions of
 * rcx-hardware.md §3.3 and reference-firmware.md "Sensors". Every expected number below is worked out from those
 * formulas and tables by hand, never taken from a run. Values are read back as a host would, with Poll (0x12).
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <string.h>
#include <cmocka.h>
#include "brick.h"
#include "fake_hal.h"

static s16 poll(struct rcx *b, u8 src, u8 index)
{
    u8 cmd[3] = { 0x12, src, index }, reply[RCX_REPLY_MAX];
    assert_int_equal(brick_cmd(b, cmd, 3, reply), 3);
    return (s16)(reply[1] | reply[2] << 8);
}

#define VALUE(b, n) poll(b, 9, n)
#define BOOL(b, n) poll(b, 13, n)

static void set_type(struct rcx *b, u8 n, u8 type)
{
    u8 cmd[3] = { 0x32, n, type };
    brick_cmd(b, cmd, 3, NULL);
}

static void set_mode(struct rcx *b, u8 n, u8 mode)
{
    u8 cmd[3] = { 0x42, n, mode };
    brick_cmd(b, cmd, 3, NULL);
}

static void clear_value(struct rcx *b, u8 n)
{
    u8 cmd[2] = { 0xD1, n };
    brick_cmd(b, cmd, 2, NULL);
}

static void type_sets_default_mode_and_power(void **state)
{
    /* Spec p. 52: NoSensor raw, Switch boolean, Temperature Celsius, Reflection percent, Angle angle steps.
     * Light (3) and rotation (4) are the active sensors that need power (rcx-hardware.md §3.3). */
    static const struct { u8 type, mode, power; } rows[] = {
        { 0, 0x00, 0 }, { 1, 0x20, 0 }, { 2, 0xA0, 0 }, { 3, 0x80, 1 }, { 4, 0xE0, 1 },
    };
    unsigned i, n;
    (void)state;
    for (n = 0; n < 3; n++) {
        struct rcx *b = brick_new();
        for (i = 0; i < sizeof rows / sizeof rows[0]; i++) {
            set_type(b, (u8)n, rows[i].type);
            assert_int_equal(poll(b, 10, (u8)n), rows[i].type);
            assert_int_equal(poll(b, 11, (u8)n), rows[i].mode);
            assert_int_equal(fake_hal_of(b)->sensor_power[n], rows[i].power);
        }
        set_type(b, (u8)n, 3);
        set_type(b, (u8)n, 1); /* back to a passive sensor: power off again */
        assert_int_equal(fake_hal_of(b)->sensor_power[n], 0);
        brick_free(b);
    }
}

static void boolean_hysteresis_460_562(void **state)
{
    /* raw < 460 -> 1, raw > 562 -> 0, in between unchanged (reference-firmware.md). */
    static const struct { u16 raw; s16 expect; } seq[] = {
        { 1023, 0 }, { 500, 0 }, { 460, 0 }, { 459, 1 }, { 460, 1 }, { 562, 1 }, { 511, 1 },
        { 563, 0 }, { 562, 0 }, { 460, 0 }, { 0, 1 }, { 1023, 0 },
    };
    struct rcx *b = brick_new();
    unsigned i;
    (void)state;
    set_type(b, 0, 1); /* touch: boolean mode */
    for (i = 0; i < sizeof seq / sizeof seq[0]; i++) {
        sensor_sample(b, 0, seq[i].raw);
        if (BOOL(b, 0) != seq[i].expect || VALUE(b, 0) != seq[i].expect)
            fail_msg("raw %u: boolean %d value %d, expected %d", seq[i].raw, BOOL(b, 0), VALUE(b, 0), seq[i].expect);
        assert_int_equal(poll(b, 12, 0), seq[i].raw);
    }
    brick_free(b);
}

static void raw_mode_value_is_the_sample(void **state)
{
    static const u16 raws[] = { 0, 1, 459, 512, 1022, 1023 };
    struct rcx *b = brick_new();
    unsigned i;
    (void)state;
    for (i = 0; i < sizeof raws / sizeof raws[0]; i++) {
        sensor_sample(b, 2, raws[i]); /* power-on: type none, raw mode */
        assert_int_equal(VALUE(b, 2), raws[i]);
    }
    sensor_sample(b, 2, 0xFC00 | 77); /* only 10 bits come from the A/D */
    assert_int_equal(poll(b, 12, 2), 77);
    brick_free(b);
}

static void percent_formula(void **state)
{
    /* (1023 - raw) * 25 / 156, integer; below 391 firm0328 gives 100. At 391 and 392 the formula gives 101: we show
     * 100 there (judgement documented in vm/sensors.c), so the scale never leaves 0-100. */
    static const struct { u16 raw; s16 pct; } rows[] = {
        { 0, 100 }, { 200, 100 }, { 390, 100 }, { 391, 100 }, { 392, 100 }, { 393, 100 }, { 394, 100 },
        { 400, 99 }, { 500, 83 }, { 700, 51 }, { 800, 35 }, { 1000, 3 }, { 1017, 0 }, { 1023, 0 },
    };
    struct rcx *b = brick_new();
    unsigned i;
    (void)state;
    set_type(b, 1, 3); /* light: percent */
    for (i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        sensor_sample(b, 1, rows[i].raw);
        if (VALUE(b, 1) != rows[i].pct)
            fail_msg("raw %u: %d %%, expected %d", rows[i].raw, VALUE(b, 1), rows[i].pct);
    }
    brick_free(b);
}

static void temperature_table(void **state)
{
    /* trunc((raw * k + d) / 100) tenths of a degree Celsius on the pieces of rcx-hardware.md §3.3, 7FFF outside
     * 290-927; Fahrenheit tenths = C * 18 / 10 + 320. Each C value below is the formula worked by hand, e.g.
     * raw 801: 801 * -134 + 106600 = -734 -> -7. */
    static const struct { u16 raw; s16 c, f; } rows[] = {
        { 0, 0x7FFF, 0x7FFF }, { 289, 0x7FFF, 0x7FFF },
        { 290, 695, 1571 }, { 339, 567, 1340 },   /* k -261, d 145200 */
        { 340, 570, 1346 }, { 389, 475, 1175 },   /* k -194, d 123000 */
        { 390, 473, 1171 }, { 477, 348, 946 },    /* k -144, d 103500 */
        { 478, 348, 946 }, { 519, 297, 854 },     /* k -123, d 93600 */
        { 520, 295, 851 }, { 600, 210, 698 }, { 789, 7, 332 }, /* k -107, d 85200 */
        { 790, 7, 332 }, { 795, 0, 320 }, { 800, -6, 310 }, { 801, -7, 308 }, { 885, -119, 106 }, /* k -134 */
        { 886, -124, 97 }, { 927, -196, -32 },   /* k -175, d 142600 */
        { 928, 0x7FFF, 0x7FFF }, { 1023, 0x7FFF, 0x7FFF },
    };
    struct rcx *b = brick_new();
    unsigned i;
    (void)state;
    set_type(b, 0, 2);                 /* temperature: Celsius */
    set_type(b, 1, 2);
    set_mode(b, 1, 0xC0);              /* Fahrenheit */
    for (i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        sensor_sample(b, 0, rows[i].raw);
        sensor_sample(b, 1, rows[i].raw);
        if (VALUE(b, 0) != rows[i].c || VALUE(b, 1) != rows[i].f)
            fail_msg("raw %u: %d C %d F tenths, expected %d %d", rows[i].raw, VALUE(b, 0), VALUE(b, 1), rows[i].c,
                     rows[i].f);
    }
    brick_free(b);
}

/* Rotation levels, one raw value inside each band of rcx-hardware.md §3.3: phase 0 960-1023, 1 768-959,
 * 2 320-511, 3 512-767. Counting up is 0-1-2-3-0. */
static const u16 phase_raw[4] = { 1000, 860, 420, 640 };

static void turn(struct rcx *b, u8 n, unsigned *phase, int steps)
{
    while (steps) {
        *phase = (*phase + (steps > 0 ? 1 : 3)) & 3;
        sensor_sample(b, n, phase_raw[*phase]);
        steps += steps > 0 ? -1 : 1;
    }
}

static void rotation_counts_both_ways_at_1000_ticks_per_second(void **state)
{
    struct rcx *b = brick_new();
    unsigned phase = 0, ms;
    (void)state;
    sensor_sample(b, 2, phase_raw[0]);
    set_type(b, 2, 4); /* rotation: angle */
    assert_int_equal(VALUE(b, 2), 0);
    /* One new phase every sample: 1 000 steps per second, three times what firm0328 could count. */
    for (ms = 0; ms < 1000; ms++) {
        turn(b, 2, &phase, 1);
        vm_tick(b);
    }
    assert_int_equal(VALUE(b, 2), 1000);
    for (ms = 0; ms < 1600; ms++) {
        turn(b, 2, &phase, -1);
        vm_tick(b);
    }
    assert_int_equal(VALUE(b, 2), -600);
    turn(b, 2, &phase, 16 * 3); /* three turns */
    assert_int_equal(VALUE(b, 2), -552);
    brick_free(b);
}

static void rotation_ignores_invalid_levels_and_jumps(void **state)
{
    struct rcx *b = brick_new();
    (void)state;
    set_type(b, 0, 4);
    sensor_sample(b, 0, phase_raw[0]);
    sensor_sample(b, 0, phase_raw[1]);   /* +1 */
    sensor_sample(b, 0, 100);            /* below 320: no level at all */
    sensor_sample(b, 0, 319);
    sensor_sample(b, 0, phase_raw[2]);   /* +1 from phase 1 */
    assert_int_equal(VALUE(b, 0), 2);
    sensor_sample(b, 0, phase_raw[0]);   /* 2 -> 0: a jump of two, direction unknown */
    assert_int_equal(VALUE(b, 0), 2);
    sensor_sample(b, 0, phase_raw[3]);   /* 0 -> 3: down */
    sensor_sample(b, 0, phase_raw[3]);   /* same phase: nothing */
    assert_int_equal(VALUE(b, 0), 1);
    /* Band edges: 959 is phase 1, 960 phase 0, 767 phase 3, 768 phase 1, 511 phase 2, 512 phase 3. */
    sensor_sample(b, 0, 960);            /* 3 -> 0: up */
    sensor_sample(b, 0, 959);            /* 0 -> 1: up */
    sensor_sample(b, 0, 511);            /* 1 -> 2: up */
    sensor_sample(b, 0, 512);            /* 2 -> 3: up */
    sensor_sample(b, 0, 768);            /* 3 -> 1: jump */
    sensor_sample(b, 0, 767);            /* 1 -> 3: jump */
    sensor_sample(b, 0, 320);            /* 3 -> 2: down */
    assert_int_equal(VALUE(b, 0), 4);
    brick_free(b);
}

static void clear_and_mode_reset_the_value(void **state)
{
    struct rcx *b = brick_new();
    unsigned phase = 0;
    (void)state;
    sensor_sample(b, 1, phase_raw[0]);
    set_type(b, 1, 4);
    turn(b, 1, &phase, 10);
    assert_int_equal(VALUE(b, 1), 10);
    clear_value(b, 1);                   /* spec p. 30 */
    assert_int_equal(VALUE(b, 1), 0);
    turn(b, 1, &phase, 3);
    assert_int_equal(VALUE(b, 1), 3);
    set_mode(b, 1, 0xE0);                /* spec p. 53: SetSensorMode resets the processed value */
    assert_int_equal(VALUE(b, 1), 0);
    turn(b, 1, &phase, -2);
    assert_int_equal(VALUE(b, 1), -2);
    set_type(b, 1, 4);                   /* spec p. 52: SetSensorType resets the sensor */
    assert_int_equal(VALUE(b, 1), 0);
    turn(b, 1, &phase, 1);
    assert_int_equal(VALUE(b, 1), 1);
    brick_free(b);
}

static void converted_values_come_back_after_a_reset(void **state)
{
    /* Spec p. 30: after ClearSensorValue "the current sensor value is computed again as part of the normal sensor
     * processing", even when the raw value has not moved. */
    struct rcx *b = brick_new();
    (void)state;
    set_type(b, 0, 3);                   /* percent */
    sensor_sample(b, 0, 500);
    sensor_sample(b, 0, 500);
    assert_int_equal(VALUE(b, 0), 83);
    clear_value(b, 0);
    assert_int_equal(VALUE(b, 0), 0);
    sensor_sample(b, 0, 500);
    assert_int_equal(VALUE(b, 0), 83);
    set_mode(b, 0, 0xA0);                /* Celsius, same raw: (500 * -123 + 93600) / 100 = 321 */
    sensor_sample(b, 0, 500);
    assert_int_equal(VALUE(b, 0), 321);
    set_mode(b, 0, 0xC0);                /* Fahrenheit: 321 * 18 / 10 + 320 = 897 */
    sensor_sample(b, 0, 500);
    assert_int_equal(VALUE(b, 0), 897);
    set_type(b, 0, 3);                   /* a new type: percent again */
    sensor_sample(b, 0, 500);
    assert_int_equal(VALUE(b, 0), 83);
    set_mode(b, 0, 0x00);                /* raw, then back to percent */
    sensor_sample(b, 0, 500);
    set_mode(b, 0, 0x80);
    sensor_sample(b, 0, 500);
    assert_int_equal(VALUE(b, 0), 83);
    brick_free(b);
}

/* A touch sensor pressed `presses` times: released 900, pressed 100, with a stop in the hysteresis band each way. */
static void press(struct rcx *b, u8 n, unsigned presses)
{
    while (presses--) {
        sensor_sample(b, n, 900);
        sensor_sample(b, n, 500);
        sensor_sample(b, n, 100);
        sensor_sample(b, n, 500);
    }
    sensor_sample(b, n, 900);
}

static void transition_and_period_counts(void **state)
{
    struct rcx *b = brick_new();
    (void)state;
    set_type(b, 0, 1);
    set_type(b, 1, 1);
    set_mode(b, 0, 0x40); /* transitions: every change of the boolean */
    set_mode(b, 1, 0x60); /* periods: every completed press-and-release */
    press(b, 0, 5);
    press(b, 1, 5);
    assert_int_equal(VALUE(b, 0), 10);
    assert_int_equal(VALUE(b, 1), 5);
    sensor_sample(b, 0, 100);  /* pressed and held: one more transition, no completed period */
    sensor_sample(b, 1, 100);
    assert_int_equal(VALUE(b, 0), 11);
    assert_int_equal(VALUE(b, 1), 5);
    clear_value(b, 0);
    clear_value(b, 1);
    sensor_sample(b, 0, 900);
    sensor_sample(b, 1, 900);
    assert_int_equal(VALUE(b, 0), 1);
    assert_int_equal(VALUE(b, 1), 1);
    brick_free(b);
}

static void slope_detects_change_rate(void **state)
{
    /* Slope 10: dU over dt = 3 ms (3 samples). Falling faster than 10 -> 1, rising faster -> 0 (spec p. 102),
     * a change of exactly 10 is not enough; above 1023 - 10 it is 0 and below 10 it is 1 whatever the rate. */
    static const struct { u16 raw; s16 expect; } seq[] = {
        { 800, 0 }, { 800, 0 }, { 800, 0 }, { 800, 0 },
        { 795, 0 }, { 790, 0 },               /* -10 over 3 ms: no change */
        { 789, 1 },                           /* -11 over 3 ms */
        { 789, 1 }, { 789, 1 }, { 789, 1 }, { 789, 1 },
        { 792, 1 }, { 795, 1 }, { 798, 1 }, { 801, 1 }, /* rising by 9 per 3 ms: too slow */
        { 801, 1 }, { 801, 1 }, { 801, 1 },
        { 811, 1 },                           /* +10 over 3 ms: not enough */
        { 811, 1 }, { 811, 1 },
        { 822, 0 },                           /* 822 - 811 = 11 */
        { 300, 1 }, { 300, 1 }, { 300, 1 }, { 300, 1 },
        { 303, 1 }, { 306, 1 }, { 309, 1 }, { 312, 1 }, /* steady slow rise keeps the state */
        { 1014, 0 }, { 1014, 0 }, { 1014, 0 }, { 1014, 0 }, /* above 1013 */
        { 1013, 0 }, { 1013, 0 }, { 1013, 0 },
        { 9, 1 },                             /* below 10 (and a fall) */
        { 9, 1 }, { 9, 1 }, { 9, 1 },
        { 10, 1 }, { 10, 1 }, { 10, 1 }, { 10, 1 },
    };
    struct rcx *b = brick_new();
    unsigned i;
    (void)state;
    set_type(b, 2, 1);
    set_mode(b, 2, 0x20 | 10);
    for (i = 0; i < sizeof seq / sizeof seq[0]; i++) {
        sensor_sample(b, 2, seq[i].raw);
        if (BOOL(b, 2) != seq[i].expect || VALUE(b, 2) != seq[i].expect)
            fail_msg("sample %u (raw %u): boolean %d, expected %d", i, seq[i].raw, BOOL(b, 2), seq[i].expect);
    }
    /* The edge clamps alone, from a steady signal: 1014 > 1023 - 10 reads 0 ... */
    set_mode(b, 2, 0x20 | 10);
    assert_int_equal(BOOL(b, 2), 1);
    sensor_sample(b, 2, 1014);
    sensor_sample(b, 2, 1014);
    sensor_sample(b, 2, 1014);
    sensor_sample(b, 2, 1014);
    assert_int_equal(BOOL(b, 2), 0);
    brick_free(b);
}

static void slope_clamps_at_the_ends(void **state)
{
    /* Slope 31: above 1023 - 31 = 992 the boolean is 0 and below 31 it is 1, however slowly the signal got there. */
    struct rcx *b = brick_new();
    unsigned raw;
    (void)state;
    set_type(b, 0, 1);
    set_mode(b, 0, 0x20 | 31);
    sensor_sample(b, 0, 500);
    sensor_sample(b, 0, 500);
    sensor_sample(b, 0, 500);
    sensor_sample(b, 0, 400);                 /* fall of 100: 1 */
    assert_int_equal(BOOL(b, 0), 1);
    for (raw = 410; raw <= 990; raw += 10)    /* 30 per 3 ms: too slow to change it */
        sensor_sample(b, 0, (u16)raw);
    sensor_sample(b, 0, 992);
    sensor_sample(b, 0, 992);
    sensor_sample(b, 0, 992);
    assert_int_equal(BOOL(b, 0), 1);
    sensor_sample(b, 0, 993);
    assert_int_equal(BOOL(b, 0), 0);
    for (raw = 983; raw >= 33; raw -= 10)     /* and slowly down again: stays 0 */
        sensor_sample(b, 0, (u16)raw);
    sensor_sample(b, 0, 31);
    sensor_sample(b, 0, 31);
    sensor_sample(b, 0, 31);
    assert_int_equal(BOOL(b, 0), 0);
    sensor_sample(b, 0, 30);
    assert_int_equal(BOOL(b, 0), 1);
    brick_free(b);
}

static void slope_counts_transitions(void **state)
{
    /* Transition count with a slope counts changes of the dynamic boolean: two sharp presses. */
    static const u16 wave[] = { 900, 900, 900, 900, 600, 600, 600, 600, 900, 900, 900, 900, 600, 600, 600, 600 };
    struct rcx *b = brick_new();
    unsigned i;
    (void)state;
    set_type(b, 0, 1);
    set_mode(b, 0, 0x40 | 20);
    for (i = 0; i < sizeof wave / sizeof wave[0]; i++)
        sensor_sample(b, 0, wave[i]);
    assert_int_equal(VALUE(b, 0), 3); /* falls to 1, rises to 0, falls to 1 */
    brick_free(b);
}

static void bad_operands_change_nothing(void **state)
{
    static const struct { const char *what; u8 bytes[6]; u8 len; } rows[] = {
        { "SetSensorType sensor 3", { 0x32, 0x03, 0x01 }, 3 },
        { "SetSensorType sensor 255", { 0x32, 0xFF, 0x03 }, 3 },
        { "SetSensorType type 5", { 0x32, 0x00, 0x05 }, 3 },
        { "SetSensorType type 255", { 0x32, 0x01, 0xFF }, 3 },
        { "SetSensorMode sensor 3", { 0x42, 0x03, 0x20 }, 3 },
        { "ClearSensorValue 3", { 0xD1, 0x03 }, 2 },
        { "ClearSensorValue 200", { 0xD1, 0xC8 }, 2 },
        { "SetSourceValue type 9", { 0x05, 10, 0x00, 2, 9, 0 }, 6 },
        { "SetSourceValue type -1", { 0x05, 10, 0x01, 2, 0xFF, 0xFF }, 6 },
        { "SetSourceValue mode 256", { 0x05, 11, 0x02, 2, 0x00, 0x01 }, 6 },
        { "SetSourceValue type of input 3", { 0x05, 10, 0x03, 2, 1, 0 }, 6 },
    };
    unsigned i;
    (void)state;
    for (i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        struct rcx *b = brick_new();
        struct rcx_sensor before[RCX_SENSORS];
        struct fake_hal hal_before;
        unsigned n;
        set_type(b, 0, 3);
        set_type(b, 1, 2);
        set_type(b, 2, 4);
        for (n = 0; n < 3; n++)
            sensor_sample(b, (u8)n, (u16)(300 + 200 * n));
        memcpy(before, b->sensor, sizeof before);
        memcpy(&hal_before, fake_hal_of(b), sizeof hal_before);
        brick_cmd(b, rows[i].bytes, rows[i].len, NULL);
        sensor_sample(b, 3, 100);
        sensor_sample(b, 255, 100);
        if (memcmp(before, b->sensor, sizeof before) != 0)
            fail_msg("%s changed a sensor", rows[i].what);
        if (memcmp(&hal_before, fake_hal_of(b), sizeof hal_before) != 0)
            fail_msg("%s reached the hardware", rows[i].what);
        brick_free(b);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(type_sets_default_mode_and_power),
        cmocka_unit_test(boolean_hysteresis_460_562),
        cmocka_unit_test(raw_mode_value_is_the_sample),
        cmocka_unit_test(percent_formula),
        cmocka_unit_test(temperature_table),
        cmocka_unit_test(rotation_counts_both_ways_at_1000_ticks_per_second),
        cmocka_unit_test(rotation_ignores_invalid_levels_and_jumps),
        cmocka_unit_test(clear_and_mode_reset_the_value),
        cmocka_unit_test(converted_values_come_back_after_a_reset),
        cmocka_unit_test(transition_and_period_counts),
        cmocka_unit_test(slope_detects_change_rate),
        cmocka_unit_test(slope_clamps_at_the_ends),
        cmocka_unit_test(slope_counts_transitions),
        cmocka_unit_test(bad_operands_change_nothing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
