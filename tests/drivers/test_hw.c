/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The drivers' register-level logic (drivers/hw.c) against the numbers of rcx-hardware.md, restated here
 * literally rather than taken from the code under test.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <string.h>
#include <cmocka.h>
#include "hal.h"
#include "runtime.h"
#include "hw.h"

/* ---- Motors, §3.2 (latch bits confirmed on the emulator, §6) ---- */

static void pwm_patterns_are_the_roms(void **state)
{
    static const u8 reference[8] = { 0x01, 0x11, 0x49, 0x55, 0x6D, 0x77, 0x7F, 0xFF };
    (void)state;
    assert_memory_equal(hw_pwm_pattern, reference, 8);
}

/* The latch bits of one output over `n` milliseconds. */
static void run(struct hw_motors *m, u8 n, u8 mask, u8 *seen)
{
    u8 i;
    for (i = 0; i < n; i++)
        seen[i] = (u8)(hw_motor_step(m) & mask);
}

static void each_level_is_on_level_plus_one_ms_of_eight(void **state)
{
    static const u8 mask[3] = { 0xC0, 0x0C, 0x03 };
    static const u8 fwd[3] = { 0x80, 0x08, 0x02 }, rev[3] = { 0x40, 0x04, 0x01 };
    (void)state;
    for (u8 port = 0; port < 3; port++)
        for (u8 level = 0; level < 8; level++) {
            struct hw_motors m;
            u8 seen[64], on = 0;
            memset(&m, 0, sizeof m);
            hw_motor_set(&m, port, HAL_MOTOR_FWD, level);
            run(&m, 64, 0xFF, seen);
            for (u8 i = 0; i < 64; i++) {
                assert_true(seen[i] == 0 || seen[i] == fwd[port]); /* nothing on the other outputs */
                on += seen[i] != 0;
                if (i >= 8)
                    assert_int_equal(seen[i], seen[i - 8]); /* an 8 ms frame */
            }
            assert_int_equal(on, 8 * (level + 1));
            hw_motor_set(&m, port, HAL_MOTOR_REV, level);
            run(&m, 8, mask[port], seen);
            on = 0;
            for (u8 i = 0; i < 8; i++) {
                assert_true(seen[i] == 0 || seen[i] == rev[port]);
                on += seen[i] != 0;
            }
            assert_int_equal(on, level + 1);
        }
}

static void brake_is_steady_and_float_is_zero(void **state)
{
    struct hw_motors m;
    u8 seen[16];
    (void)state;
    memset(&m, 0, sizeof m);
    hw_motor_set(&m, 0, HAL_MOTOR_BRAKE, 0);
    hw_motor_set(&m, 1, HAL_MOTOR_BRAKE, 3);
    hw_motor_set(&m, 2, HAL_MOTOR_FLOAT, 7);
    run(&m, 16, 0xFF, seen);
    for (u8 i = 0; i < 16; i++)
        assert_int_equal(seen[i], 0xC0 | 0x0C);
    hw_motor_set(&m, 0, HAL_MOTOR_FLOAT, 7);
    hw_motor_set(&m, 1, HAL_MOTOR_FLOAT, 7);
    assert_int_equal(hw_motor_step(&m), 0);
}

/* The outputs engine may repeat hal_motor every millisecond: the duty cycle must not depend on that. */
static void repeating_the_same_setting_keeps_the_duty(void **state)
{
    struct hw_motors m;
    u8 on = 0;
    (void)state;
    memset(&m, 0, sizeof m);
    for (u8 i = 0; i < 80; i++) {
        hw_motor_set(&m, 1, HAL_MOTOR_FWD, 2);
        on += (hw_motor_step(&m) & 0x0C) != 0;
    }
    assert_int_equal(on, 30); /* 3 of every 8 */
}

static void bad_motor_arguments_do_no_harm(void **state)
{
    struct hw_motors m, before;
    u8 on = 0;
    (void)state;
    memset(&m, 0, sizeof m);
    before = m;
    hw_motor_set(&m, 3, HAL_MOTOR_FWD, 7);
    hw_motor_set(&m, 255, HAL_MOTOR_FWD, 7);
    assert_memory_equal(&m, &before, sizeof m);
    hw_motor_set(&m, 2, 0xFD, 200); /* mode taken modulo 4 (rev), level capped at full */
    for (u8 i = 0; i < 8; i++)
        on += hw_motor_step(&m) == 0x01;
    assert_int_equal(on, 8);
}

/* ---- A/D, §3.3-3.4 ---- */

static void inputs_map_to_reversed_channels_and_power_bits(void **state)
{
    (void)state;
    assert_int_equal(hw_ad_channel(0), 2); /* input 1 = AN2 / ADDRC */
    assert_int_equal(hw_ad_channel(1), 1);
    assert_int_equal(hw_ad_channel(2), 0); /* input 3 = AN0 / ADDRA */
    assert_int_equal(HW_AD_BATTERY, 3);    /* AN3 / ADDRD */
    assert_int_equal(hw_sensor_power_bit[0], 0x04); /* P6.2 */
    assert_int_equal(hw_sensor_power_bit[1], 0x02);
    assert_int_equal(hw_sensor_power_bit[2], 0x01);
    assert_int_equal(hw_ad_raw10(0xFFC0), 1023);
    assert_int_equal(hw_ad_raw10(0x5080), 0x142);
    assert_int_equal(hw_ad_raw10(0x003F), 0);
}

static void battery_millivolts_follow_the_reference_formula(void **state)
{
    (void)state;
    for (unsigned raw = 0; raw <= 1023; raw++)
        assert_int_equal(hw_battery_mv((u16)raw), (unsigned long)raw * 43988ul / 1560ul);
    assert_int_equal(hw_battery_mv(320), 9023); /* §3.4 examples: 9.02 V, 6.7 V, 6.3 V */
    assert_int_equal(hw_battery_mv(237), 6682);
    assert_int_equal(hw_battery_mv(223), 6288);
    assert_int_equal(hw_battery_mv(0xFFFF), hw_battery_mv(1023)); /* out of range: clamped */
}

/* ---- Sound, §3.7 ---- */

/* The clock TCR0.CKS and STCR.ICKS0 select, from the §3.7 table. */
static unsigned long tone_clock(u8 cks, u8 icks0)
{
    static const unsigned long table[4][2] = { { 0, 0 }, { 2000000, 8000000 }, { 250000, 500000 }, { 15625, 62500 } };
    return table[cks & 3][icks0 & 1];
}

static void every_tone_is_within_0_8_percent(void **state)
{
    (void)state;
    for (unsigned hz = 31; hz <= 20000; hz++) {
        struct hw_tone t;
        unsigned long clk;
        double f, err;
        assert_int_equal(hw_tone((u16)hz, &t), 1);
        assert_int_equal(t.tcr & 0xF8, 0x08); /* clear on compare match A, no interrupts */
        clk = tone_clock(t.tcr, t.icks0);
        assert_true(clk != 0);
        f = (double)clk / (2.0 * (t.tcora + 1));
        err = (f - hz) / hz;
        assert_true(err < 0.008 && err > -0.008); /* clocks 4 apart: TCORA + 1 >= 64 */
        /* the fastest clock that fits: the next faster one would need TCORA above 255 */
        if (clk < 8000000) {
            unsigned long faster = clk == 15625 ? 62500 : clk == 62500 ? 250000 : clk == 250000 ? 500000
                                 : clk == 500000 ? 2000000 : 8000000;
            assert_true((faster + hz) / (2ul * hz) > 256);
        }
    }
}

static void tones_match_the_roms_clock_bands(void **state)
{
    static const struct { u16 hz; unsigned long clk; } bands[] = {
        /* §3.7: 31-122 φ/1024, 123-489 φ/256, 490-979 φ/64, 980-3921 φ/32, 3922-20 000 φ/8. Here each band
         * starts where rounding first allows (1-23 Hz lower), and the finer φ/2 is used from 15 595 Hz up. */
        { 31, 15625 }, { 121, 15625 }, { 123, 62500 }, { 487, 62500 }, { 490, 250000 }, { 974, 250000 },
        { 980, 500000 }, { 3898, 500000 }, { 3922, 2000000 }, { 15594, 2000000 }, { 20000, 8000000 },
    };
    struct hw_tone t;
    (void)state;
    for (unsigned i = 0; i < sizeof bands / sizeof bands[0]; i++) {
        assert_int_equal(hw_tone(bands[i].hz, &t), 1);
        assert_int_equal(tone_clock(t.tcr, t.icks0), bands[i].clk);
    }
    assert_int_equal(hw_tone(55, &t), 1); /* §3.7: 55 Hz = N 141 at 15 625 Hz */
    assert_int_equal(t.tcora, 141);
    assert_int_equal(tone_clock(t.tcr, t.icks0), 15625);
}

static void tones_out_of_range_are_rests(void **state)
{
    static const u16 bad[] = { 0, 1, 30, 20001, 40000, 65535 };
    struct hw_tone t;
    (void)state;
    for (unsigned i = 0; i < sizeof bad / sizeof bad[0]; i++)
        assert_int_equal(hw_tone(bad[i], &t), 0);
}

/* ---- IR, §3.8 ---- */

static void baud_rates_are_the_references(void **state)
{
    (void)state;
    assert_int_equal(hw_sci_brr(0), 207);
    assert_int_equal(hw_sci_brr(HAL_IR_76KHZ | HAL_IR_DUTY25), 207);
    assert_int_equal(hw_sci_brr(HAL_IR_4800), 103);
    assert_int_equal(hw_sci_brr(0xFF), 103);
    /* and they are what φ / (32 (N + 1)) says, within 0.2 % */
    assert_true(16000000ul / (32ul * 208) >= 2400 && 16000000ul / (32ul * 208) <= 2405);
    assert_true(16000000ul / (32ul * 104) >= 4800 && 16000000ul / (32ul * 104) <= 4810);
}

/* Carrier frequency and duty in per mille, from the register values as TMR1 uses them (§3.8, §3.9). */
static void carrier_of(u8 mode, unsigned *hz, unsigned *duty)
{
    struct hw_carrier c;
    hw_carrier(mode, &c);
    assert_int_equal(c.tcr, 0x09); /* φ/8 = 2 MHz, cleared on compare match A */
    if ((c.tcsr & 0x0F) == 0x03) { /* toggle on A */
        *hz = 2000000u / (2u * (c.tcora + 1u));
        *duty = 500;
    } else {
        assert_int_equal(c.tcsr & 0x0F, 0x06); /* 1 on A, 0 on B */
        assert_true(c.tcorb < c.tcora);
        *hz = 2000000u / (c.tcora + 1u);
        *duty = 1000u * (c.tcorb + 1u) / (c.tcora + 1u);
    }
}

static void carrier_settings_for_each_mode(void **state)
{
    struct hw_carrier c;
    unsigned hz, duty;
    (void)state;
    hw_carrier(0, &c); /* the ROM's own: TCR 09, TCSR 13, TCORA 26 */
    assert_int_equal(c.tcr, 0x09);
    assert_int_equal(c.tcsr, 0x13);
    assert_int_equal(c.tcora, 26);
    for (u8 mode = 0; mode < 8; mode++) {
        carrier_of(mode, &hz, &duty);
        if (mode & HAL_IR_76KHZ)
            assert_true(hz >= 75000 && hz <= 78000);
        else
            assert_true(hz >= 37000 && hz <= 38500);
        if (mode & HAL_IR_DUTY25)
            assert_true(duty >= 230 && duty <= 270);
        else
            assert_int_equal(duty, 500);
    }
}

/* ---- Buttons, §3.5 ---- */

static void buttons_are_active_low_on_their_pins(void **state)
{
    (void)state;
    assert_int_equal(hw_buttons(0xFF, 0xFF), 0);
    assert_int_equal(hw_buttons(0x00, 0x00), 0x0F);
    assert_int_equal(hw_buttons(0xFF & ~0x02, 0xFF), 1u << RT_BUTTON_ONOFF); /* P4.1 */
    assert_int_equal(hw_buttons(0xFF & ~0x04, 0xFF), 1u << RT_BUTTON_RUN);   /* P4.2 */
    assert_int_equal(hw_buttons(0xFF, 0xFF & ~0x40), 1u << RT_BUTTON_VIEW);  /* P7.6 */
    assert_int_equal(hw_buttons(0xFF, 0xFF & ~0x80), 1u << RT_BUTTON_PRGM);  /* P7.7 */
    assert_int_equal(hw_buttons(0x06 | 0x00, 0xC0), 0);                      /* other pins do not count */
}

/* n looks a millisecond apart on the clock `now`. */
static u8 now;
static u8 feed(struct hw_debounce *d, u8 raw, unsigned n)
{
    u8 changed = 0;
    while (n--)
        changed |= hw_debounce(d, raw, now++);
    return changed;
}

static void debounce_needs_a_steady_level(void **state)
{
    struct hw_debounce d;
    (void)state;
    memset(&d, 0, sizeof d);
    assert_int_equal(feed(&d, 0, 100), 0);
    for (u8 i = 1; i < HW_DEBOUNCE_MS; i++) /* a bounce at every level up to the last sample */
        assert_int_equal(feed(&d, 1, i) | hw_debounce(&d, 0, now++), 0);
    assert_int_equal(feed(&d, 1, HW_DEBOUNCE_MS - 1), 0);
    assert_int_equal(hw_debounce(&d, 1, now++), 1); /* exactly the HW_DEBOUNCE_MS-th steady sample */
    assert_int_equal(d.state, 1);
    assert_int_equal(feed(&d, 1, 100), 0);
    assert_int_equal(feed(&d, 0, HW_DEBOUNCE_MS - 1), 0);
    assert_int_equal(hw_debounce(&d, 0, now++), 1);
    assert_int_equal(d.state, 0);
}

/* Issue 15 item 6: the time counts, not the looks. A main loop catching up on milliseconds looks many times within
 * microseconds (the clock unchanged, or a millisecond on): a bounce seen then is no press. */
static void debounce_counts_time_not_looks(void **state)
{
    struct hw_debounce d;
    u8 t = 250; /* across the clock's wrap */
    unsigned i;
    (void)state;
    memset(&d, 0, sizeof d);
    for (i = 0; i < 100; i++) /* 100 looks down within 2 ms, then one up */
        assert_int_equal(hw_debounce(&d, 1, (u8)(t + i / 50)), 0);
    assert_int_equal(hw_debounce(&d, 0, (u8)(t + 2)), 0);
    for (i = 0; i < 100; i++) /* down again: HW_DEBOUNCE_MS - 1 ms from the first look of it on */
        assert_int_equal(hw_debounce(&d, 1, (u8)(t + 3 + i * (HW_DEBOUNCE_MS - 2) / 99)), 0);
    assert_int_equal(hw_debounce(&d, 1, (u8)(t + 3 + HW_DEBOUNCE_MS - 1)), 1);
    assert_int_equal(d.state, 1);
}

static void a_second_button_restarts_the_count(void **state)
{
    struct hw_debounce d;
    (void)state;
    memset(&d, 0, sizeof d);
    assert_int_equal(feed(&d, 0x02, HW_DEBOUNCE_MS - 2), 0);
    assert_int_equal(feed(&d, 0x0A, HW_DEBOUNCE_MS - 1), 0);
    assert_int_equal(hw_debounce(&d, 0x0A, now++), 0x0A);
}

/* ---- LCD, §3.6 ---- */

static void lcd_frames_carry_the_commands_and_the_image(void **state)
{
    u8 image[9], frame[HW_LCD_FRAME_MAX];
    static const u8 on_head[4] = { 0x7C, 0xC8, 0xE0, 0x00 }; /* address, mode set (more), select 0 (more), ptr 0 */
    (void)state;
    for (u8 i = 0; i < 9; i++)
        image[i] = (u8)(0x11 * (i + 1));
    assert_int_equal(hw_lcd_on_frame(image, frame), 13);
    assert_memory_equal(frame, on_head, 4);
    assert_memory_equal(frame + 4, image, 9);

    assert_int_equal(hw_lcd_off_frame(frame), 2);
    assert_int_equal(frame[0], 0x7C);
    assert_int_equal(frame[1], 0x40);
}

/* ---- IR receive ring ---- */

static void ring_keeps_order_and_error_marks(void **state)
{
    static struct hw_rx r;
    u8 byte;
    (void)state;
    memset(&r, 0, sizeof r);
    assert_int_equal(hw_rx_get(&r, &byte), 0);
    for (unsigned round = 0; round < 300; round++) { /* indexes wrap several times */
        hw_rx_put(&r, (u8)round, (u8)(round % 7 == 0));
        hw_rx_put(&r, (u8)~round, 0);
        assert_int_equal(hw_rx_get(&r, &byte), round % 7 == 0 ? 2 : 1);
        assert_int_equal(byte, (u8)round);
        assert_int_equal(hw_rx_get(&r, &byte), 1);
        assert_int_equal(byte, (u8)~round);
        assert_int_equal(hw_rx_get(&r, &byte), 0);
    }
}

static void a_full_ring_marks_the_loss(void **state)
{
    static struct hw_rx r;
    u8 byte;
    (void)state;
    memset(&r, 0, sizeof r);
    for (unsigned i = 0; i < HW_RX_SIZE + 5; i++)
        hw_rx_put(&r, (u8)i, 0);
    for (unsigned i = 0; i < HW_RX_SIZE - 1; i++) {
        assert_int_equal(hw_rx_get(&r, &byte), 1);
        assert_int_equal(byte, i);
    }
    assert_int_equal(hw_rx_get(&r, &byte), 2); /* the last one kept stands for the lost ones */
    assert_int_equal(byte, HW_RX_SIZE - 1);
    assert_int_equal(hw_rx_get(&r, &byte), 0);
    hw_rx_put(&r, 0x55, 0); /* and the ring works on */
    assert_int_equal(hw_rx_get(&r, &byte), 1);
    assert_int_equal(byte, 0x55);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(pwm_patterns_are_the_roms),
        cmocka_unit_test(each_level_is_on_level_plus_one_ms_of_eight),
        cmocka_unit_test(brake_is_steady_and_float_is_zero),
        cmocka_unit_test(repeating_the_same_setting_keeps_the_duty),
        cmocka_unit_test(bad_motor_arguments_do_no_harm),
        cmocka_unit_test(inputs_map_to_reversed_channels_and_power_bits),
        cmocka_unit_test(battery_millivolts_follow_the_reference_formula),
        cmocka_unit_test(every_tone_is_within_0_8_percent),
        cmocka_unit_test(tones_match_the_roms_clock_bands),
        cmocka_unit_test(tones_out_of_range_are_rests),
        cmocka_unit_test(baud_rates_are_the_references),
        cmocka_unit_test(carrier_settings_for_each_mode),
        cmocka_unit_test(buttons_are_active_low_on_their_pins),
        cmocka_unit_test(debounce_needs_a_steady_level),
        cmocka_unit_test(debounce_counts_time_not_looks),
        cmocka_unit_test(a_second_button_restarts_the_count),
        cmocka_unit_test(lcd_frames_carry_the_commands_and_the_image),
        cmocka_unit_test(ring_keeps_order_and_error_marks),
        cmocka_unit_test(a_full_ring_marks_the_loss),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
