/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The engines end to end: each io_*.nqc program here, compiled by the real `nqc -TRCX2`, is downloaded into a host
 * brick as `nqc -d` does and started as `nqc -run` does. Every simulated millisecond this driver feeds each input
 * a raw sample from the test's scripted waveform, runs up to 10 byte codes one at a time, ticks the machine, and
 * logs every change that reaches the hardware (hal_motor, hal_sound) with the millisecond it happened in.
 *
 * Usage: test_io <test name>; CTest runs one name per test (tests/io/CMakeLists.txt).
 * Expected values are worked out from what each program means, the waveform, and the spec's numbers (sensor
 * formulas of rcx-hardware.md §3.3, sound compositions of §3.7, the 60 ms pause of spec p. 99); never from a run.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "brick.h"
#include "fake_hal.h"
#include "rcx_image.h"
#include "lcd_text.h"

#ifndef IO_IMAGE_DIR
#error "IO_IMAGE_DIR must name the folder of the compiled io_*.rcx2.rcx images"
#endif

#define BUDGET 10       /* byte codes per simulated millisecond */
#define MAX_LOG 128

struct timed {
    unsigned ms;
    unsigned a, b, c;   /* sound: Hz; motor: port, mode, level */
};

typedef u16 waveform(unsigned input, unsigned ms);

struct io {
    struct rcx *b;
    struct rcx_image img;
    u8 *file;
    waveform *wave;     /* NULL: every input reads 1023, nothing connected */
    unsigned now;       /* milliseconds since the program was started */
    struct timed sound[MAX_LOG], motor[MAX_LOG];
    unsigned nsound, nmotor, sound_seen;
    u8 mode[3], level[3];
};

static struct io *io_open(const char *name, waveform *wave)
{
    struct io *io = calloc(1, sizeof *io);
    char path[512], err[256];
    size_t size;
    u8 start[2] = { 0x71, 0x00 };

    assert_non_null(io);
    snprintf(path, sizeof path, "%s/%s.rcx2.rcx", IO_IMAGE_DIR, name);
    if (rcx_image_read_file(path, &io->file, &size, err, sizeof err) ||
        rcx_image_parse(&io->img, io->file, size, err, sizeof err))
        fail_msg("%s: %s", path, err);
    io->b = brick_new();
    io->wave = wave;
    if (rcx_image_load(io->b, &io->img, -1, err, sizeof err))
        fail_msg("%s: %s", path, err);
    brick_cmd(io->b, start, 2, NULL);
    return io;
}

static void io_close(struct io *io)
{
    assert_int_equal(fake_hal_of(io->b)->motor_calls, io->nmotor); /* no call hidden between two looks */
    brick_free(io->b);
    free(io->file);
    free(io);
}

static void observe(struct io *io, unsigned t)
{
    struct fake_hal *h = fake_hal_of(io->b);
    unsigned p;
    for (; io->sound_seen < h->sound_calls && io->nsound < MAX_LOG; io->sound_seen++, io->nsound++) {
        io->sound[io->nsound].ms = t;
        io->sound[io->nsound].a = h->sound_log[io->sound_seen];
    }
    for (p = 0; p < 3; p++)
        if ((h->motor_mode[p] != io->mode[p] || h->motor_level[p] != io->level[p]) && io->nmotor < MAX_LOG) {
            struct timed *m = &io->motor[io->nmotor++];
            io->mode[p] = h->motor_mode[p];
            io->level[p] = h->motor_level[p];
            m->ms = t;
            m->a = p;
            m->b = h->motor_mode[p];
            m->c = h->motor_level[p];
        }
}

static void io_run(struct io *io, unsigned ms)
{
    unsigned i;
    while (ms--) {
        for (i = 0; i < 3; i++)
            sensor_sample(io->b, (u8)i, io->wave ? io->wave(i, io->now) : 1023);
        for (i = 0; i < BUDGET && vm_run(io->b, 1); i++)
            observe(io, io->now);
        vm_tick(io->b);
        observe(io, ++io->now);
    }
}

static void io_run_until(struct io *io, unsigned t)
{
    if (t > io->now)
        io_run(io, t - io->now);
}

static s16 io_var(struct io *io, const char *name)
{
    int n = rcx_image_find_var(&io->img, name);
    u8 poll[3] = { 0x12, 0, 0 }, reply[RCX_REPLY_MAX];
    if (n < 0)
        fail_msg("no variable %s", name);
    poll[2] = (u8)n;
    assert_int_equal(brick_cmd(io->b, poll, 3, reply), 3);
    return (s16)(reply[1] | reply[2] << 8);
}

static void expect_var(struct io *io, const char *name, long lo, long hi)
{
    long v = io_var(io, name);
    if (v < lo || v > hi)
        fail_msg("%s = %ld, expected %ld..%ld", name, v, lo, hi);
}

static int io_idle(struct io *io)
{
    unsigned n;
    for (n = 0; n < RCX_TASKS; n++)
        if (io->b->task[n].state != RCX_TASK_IDLE)
            return 0;
    return 1;
}

static void expect_log(const char *what, const struct timed *got, unsigned n, const struct timed *want, unsigned wn)
{
    unsigned i;
    for (i = 0; i < n && i < wn; i++)
        if (got[i].ms != want[i].ms || got[i].a != want[i].a || got[i].b != want[i].b || got[i].c != want[i].c)
            fail_msg("%s %u: %u/%u/%u at %u ms, expected %u/%u/%u at %u ms", what, i, got[i].a, got[i].b, got[i].c,
                     got[i].ms, want[i].a, want[i].b, want[i].c, want[i].ms);
    if (n != wn)
        fail_msg("%u %s changes, expected %u", n, what, wn);
}

static int during(unsigned t, unsigned from, unsigned to)
{
    return t >= from && t < to;
}

/* ---- touch: presses counted by the program, by transitions and by periods ------------------------------------ */

#define RELEASED 1020
#define PRESSED 150
#define BOUNCE_HI 540   /* inside the 460-562 band: changes nothing */
#define BOUNCE_LO 470

static u16 touch_wave(unsigned input, unsigned t)
{
    unsigned k;
    switch (input) {
    case 0: /* three presses with bounces through the band, then pressed and held from 1 s */
        if (during(t, 100, 200) || during(t, 400, 500) || during(t, 700, 800) || t >= 1000)
            return PRESSED;
        if (during(t, 95, 100) || during(t, 200, 205) || during(t, 395, 400) || during(t, 500, 505))
            return BOUNCE_HI;
        return RELEASED;
    case 1: /* four presses, and glitches into the band that must not count */
        for (k = 0; k < 4; k++)
            if (during(t, 100 + 200 * k, 150 + 200 * k))
                return during(t, 120 + 200 * k, 122 + 200 * k) ? BOUNCE_LO : PRESSED;
        return during(t, 160, 163) || during(t, 560, 562) ? BOUNCE_HI : RELEASED;
    default: /* five complete presses, then one held down: no sixth period */
        for (k = 0; k < 5; k++)
            if (during(t, 1100 + 100 * k, 1150 + 100 * k))
                return PRESSED;
        return t >= 1800 ? PRESSED : RELEASED;
    }
}

static void touch(void **state)
{
    struct io *io = io_open("io_touch", touch_wave);
    (void)state;
    io_run(io, 2500);
    assert_true(io_idle(io));
    expect_var(io, "presses", 3, 3);
    expect_var(io, "held", 1, 1);
    expect_var(io, "edges", 8, 8);   /* four presses, two transitions each */
    expect_var(io, "pulses", 5, 5);  /* the held press has not completed a period */
    io_close(io);
}

/* ---- light and temperature: plateaus and a ramp ---------------------------------------------------------- */

static u16 analog_wave(unsigned input, unsigned t)
{
    switch (input) {
    case 0: return t < 1000 ? 600 : 200;         /* Fahrenheit: 21.0 C = 69.8 F, then below the table */
    case 1:                                      /* light */
        if (t < 1000)
            return 700;
        if (t < 2000)
            return 392;
        return (u16)(t < 2200 ? 700 + (t - 2000) : 900);
    default: return t < 1000 ? 520 : 927;        /* Celsius */
    }
}

static void analog(void **state)
{
    struct io *io = io_open("io_analog", analog_wave);
    struct fake_hal *h = fake_hal_of(io->b);
    (void)state;
    io_run(io, 2500);
    assert_true(io_idle(io));
    expect_var(io, "pct_a", 51, 51);        /* (1023 - 700) * 25 / 156 = 51.8 */
    expect_var(io, "pct_b", 100, 100);      /* raw 392: 100 here, 101 in firm0328 (see vm/sensors.c) */
    expect_var(io, "c_a", 295, 295);        /* (520 * -107 + 85200) / 100 = 295.6 */
    expect_var(io, "c_b", -196, -196);      /* (927 * -175 + 142600) / 100 = -196.25 */
    expect_var(io, "f_a", 698, 698);        /* raw 600: 210 tenths C; 210 * 18 / 10 + 320 */
    expect_var(io, "f_b", 0x7FFF, 0x7FFF);  /* raw 200: outside the table */
    /* The ramp passes below 20 % at raw 899 ((1023 - 899) * 25 / 156 = 19.9), 199 ms into it: 2 199 ms after the
     * timer was cleared, 219 in 10 ms units (220 if the program looks one millisecond late). */
    expect_var(io, "dark_at", 219, 220);
    assert_int_equal(h->sensor_power[0], 0);
    assert_int_equal(h->sensor_power[1], 1);
    assert_int_equal(h->sensor_power[2], 0);
    io_close(io);
}

/* ---- rotation at 1 000 steps per second ---------------------------------------------------------------- */

static const u16 phase_raw[4] = { 1000, 860, 420, 640 }; /* one raw value inside each band of §3.3 */

/* Position in steps of the sensor on input 1: still, 1 000 steps forward, still, 400 back, still, 16 forward. */
static long position_1(unsigned t)
{
    if (t < 100)
        return 0;
    if (t < 1100)
        return (long)t - 99;
    if (t < 1500)
        return 1000;
    if (t < 1900)
        return 1000 - ((long)t - 1499);
    if (t < 2500)
        return 600;
    return t < 2516 ? 600 + ((long)t - 2499) : 616;
}

static u16 rotation_wave(unsigned input, unsigned t)
{
    long p = 0;
    if (input == 0)
        p = position_1(t);
    else if (input == 2)
        p = t < 100 ? 0 : t < 3100 ? -((long)t - 99) : -3000; /* backwards for three seconds */
    else
        return 1023;
    return phase_raw[((p % 4) + 4) % 4];
}

static void rotation(void **state)
{
    struct io *io = io_open("io_rotation", rotation_wave);
    (void)state;
    io_run(io, 3800);
    assert_true(io_idle(io));
    expect_var(io, "at800", 89, 90);        /* step 800 comes at 899 ms */
    expect_var(io, "top", 1000, 1000);
    expect_var(io, "bottom", 600, 600);
    expect_var(io, "again", 16, 16);        /* cleared at about 2.4 s, then 16 steps */
    expect_var(io, "backwards", -3000, -3000);
    io_close(io);
}

/* ---- sound ------------------------------------------------------------------------------------------- */

static void sound(void **state)
{
    static const struct timed want[] = {
        /* nqc's download ends with system sound 5, fast sweep up: ten steps of 40 ms from 498 Hz (firm0328's
         * note lengths, reference-firmware.md) */
        { 1, 498, 0, 0 }, { 41, 598, 0, 0 }, { 81, 694, 0, 0 }, { 121, 796, 0, 0 }, { 161, 893, 0, 0 },
        { 201, 996, 0, 0 }, { 241, 1096, 0, 0 }, { 281, 1196, 0, 0 }, { 321, 1295, 0, 0 }, { 361, 1389, 0, 0 },
        { 401, 440, 0, 0 },            /* PlayTone(440, 20): 200 ms */
        { 601, 0, 0, 0 },              /* PlayTone(0, 10): 100 ms rest */
        { 701, 1984, 0, 0 },           /* key click: 20 ms of 1984 Hz ... */
        { 721, 0, 0, 0 },              /* ... and 40 ms of silence */
        { 761, 880, 0, 0 },            /* PlayTone(880, 5) */
        { 811, 0, 0, 0 },
        /* Wait(200) ends at 2 000 ms: muted, two sounds ignored, unmuted, the tone from the variable */
        { 2001, 660, 0, 0 },
        { 2101, 0, 0, 0 },
    };
    struct io *io = io_open("io_sound", NULL);
    (void)state;
    io_run(io, 2500);
    assert_true(io_idle(io));
    expect_log("sound", io->sound, io->nsound, want, sizeof want / sizeof want[0]);
    io_close(io);
}

/* ---- display ----------------------------------------------------------------------------------------- */

static u16 display_wave(unsigned input, unsigned t)
{
    (void)t;
    return input == 0 ? 520 : input == 1 ? 150 : 1023; /* 29.5 C on input 1; input 2 (no type) reads pressed */
}

static void expect_glass(struct io *io, unsigned t, const char *text)
{
    const u8 *img;
    int bad;
    io_run_until(io, t);
    img = fake_hal_of(io->b)->lcd;
    bad = lcd_reads(img, text);
    if (bad)
        fail_msg("at %u ms the LCD does not read \"%s\" (byte %d: %02X)", t, text, bad - 1, img[bad - 1]);
}

/* The watch: its point blinks (reference-firmware.md), so either reading is right. */
static void expect_watch(struct io *io, unsigned t, const char *with_point, const char *without)
{
    const u8 *img;
    io_run_until(io, t);
    img = fake_hal_of(io->b)->lcd;
    if (lcd_reads(img, with_point) && lcd_reads(img, without))
        fail_msg("at %u ms the LCD reads neither \"%s\" nor \"%s\"", t, with_point, without);
}

static void display(void **state)
{
    struct io *io = io_open("io_display", display_wave);
    const u8 *img = fake_hal_of(io->b)->lcd;
    u8 one[HAL_LCD_BYTES] = { 0 };
    int s;
    (void)state;
    expect_glass(io, 250, "-1.23");         /* SetUserDisplay(shown, 2) with shown = -123 */
    lcd_digit(one, 0, 1);                   /* program slot 0 shows as 1 */
    for (s = 0; s < 7; s++)
        assert_int_equal(lcd_lit(img, lcd_map[0][s]), lcd_lit(one, lcd_map[0][s]));
    expect_glass(io, 750, "29.5");          /* SelectDisplay(DISPLAY_SENSOR_1): Celsius in tenths */
    assert_true(lcd_lit(img, lcd_input_selected[0]));
    /* An input's mark is lit while it reads pressed, whatever its type (reference-firmware.md): not input 1 at raw
     * 520, but input 2 at raw 150 though it has no type. */
    assert_false(lcd_lit(img, lcd_input_active[0]) || lcd_lit(img, lcd_input_active[2]));
    assert_true(lcd_lit(img, lcd_input_active[1]));
    expect_watch(io, 1250, "07.45", "0745"); /* SetWatch(7, 45) selects the watch: four digits */
    assert_false(lcd_lit(img, lcd_input_selected[0]));
    expect_glass(io, 1750, "5");            /* output B, power 4, running backwards: power + 1 */
    assert_true(lcd_lit(img, lcd_output_selected[1]) && lcd_lit(img, lcd_output_rev[1]));
    assert_false(lcd_lit(img, lcd_output_fwd[1]));
    for (s = 0; io->now < 2240; s |= 1 << lcd_figure(img))
        io_run(io, 1);
    assert_int_equal(s, 1 << 1 | 1 << 2);   /* the program is waiting, yet running: the figure walks */
    expect_glass(io, 2250, "43.21");        /* back to the user view, which follows the variable */
    io_run_until(io, 2700);
    assert_true(io_idle(io));
    assert_int_equal(lcd_figure(img), 1);   /* standing once the program has ended */
    io_close(io);
}

/* ---- motors ------------------------------------------------------------------------------------------ */

enum { A, B, C };
enum { FLOAT = HAL_MOTOR_FLOAT, REV = HAL_MOTOR_REV, FWD = HAL_MOTOR_FWD, BRAKE = HAL_MOTOR_BRAKE };

static void motors(void **state)
{
    static const struct timed want[] = {
        { 0, A, BRAKE, 7 },            /* power-on: all braked (reference-firmware.md) */
        { 0, B, BRAKE, 7 },
        { 0, C, BRAKE, 7 },            /* ... and C stays so: SetGlobalOutput(OUT_C, OUT_OFF); On(OUT_C) */
        { 0, A, FWD, 7 },              /* OnFwd(OUT_A) */
        { 0, B, FWD, 2 },              /* SetMaxPower(OUT_B, 2); On(OUT_B) */
        { 500, A, BRAKE, 7 },          /* Rev(OUT_A): 60 ms braked ... */
        { 560, A, REV, 7 },            /* ... then backwards */
        { 1000, A, REV, 3 },           /* SetPower(OUT_A, 3) */
        { 1000, A, BRAKE, 7 },         /* SetGlobalDirection(OUT_A, OUT_REV): forward again, after the pause */
        { 1060, A, FWD, 3 },
        { 1500, A, BRAKE, 7 },         /* Off(OUT_A) */
        { 1500, C, FLOAT, 0 },         /* SetGlobalOutput(OUT_C, OUT_FLOAT) */
        { 2000, C, FWD, 7 },           /* SetGlobalOutput(OUT_C, OUT_ON): its own state, on and forward */
        { 2000, B, FLOAT, 0 },         /* Float(OUT_B) */
    };
    struct io *io = io_open("io_motors", NULL);
    (void)state;
    io_run(io, 2500);
    assert_true(io_idle(io));
    expect_log("motor", io->motor, io->nmotor, want, sizeof want / sizeof want[0]);
    io_close(io);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(touch),
        cmocka_unit_test(analog),
        cmocka_unit_test(rotation),
        cmocka_unit_test(sound),
        cmocka_unit_test(display),
        cmocka_unit_test(motors),
    };
    if (argc > 1)
        cmocka_set_test_filter(argv[1]);
    return cmocka_run_group_tests(tests, NULL, NULL);
}
