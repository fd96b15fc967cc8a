/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Display engine: the segment image handed to hal_lcd() (rcx-hardware.md §3.6) for each view of SelectDisplay
 * (spec p. 66), ViewSourceValue (p. 97), the watch (p. 51), the program number, running figure, input and output
 * indicators and the runtime's marks. Expected images come from the segment map restated in tests/io/lcd_text.h;
 * numbers are given as the text the glass should read.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <string.h>
#include <cmocka.h>
#include "brick.h"
#include "fake_hal.h"
#include "../io/lcd_text.h"

#define SG LCD_SEG

/* Let the display refresh and return what the LCD shows. */
static const u8 *glass(struct rcx *b)
{
    unsigned ms;
    for (ms = 0; ms < 100; ms++)
        vm_tick(b);
    return fake_hal_of(b)->lcd;
}

static void expect_number(struct rcx *b, const char *text)
{
    const u8 *img = glass(b);
    int bad = lcd_reads(img, text);
    if (bad)
        fail_msg("\"%s\": byte %d of the image is wrong (%02X)", text, bad - 1, img[bad - 1]);
}

/* The watch: its point blinks, so the glass reads `text` or `text` without its point. */
static void expect_watch(struct rcx *b, const char *text)
{
    const u8 *img = glass(b);
    char bare[8];
    unsigned i, j;
    for (i = j = 0; text[i]; i++)
        if (text[i] != '.')
            bare[j++] = text[i];
    bare[j] = 0;
    if (lcd_reads(img, text) && lcd_reads(img, bare))
        fail_msg("the watch does not read \"%s\"", text);
}

static void user_view(struct rcx *b, u8 places, u8 src, u16 value)
{
    u8 c[6] = { 0xE5, 0, places, src, (u8)value, (u8)(value >> 8) };
    brick_cmd(b, c, 6, NULL);
}

static void select_view(struct rcx *b, u8 view)
{
    u8 c[4] = { 0x33, 2, view, 0 };
    brick_cmd(b, c, 4, NULL);
}

static void digits_at_every_position(void **state)
{
    static const unsigned scale[5] = { 0, 1, 10, 100, 1000 };
    char text[8];
    int pos, d, p;
    (void)state;
    for (pos = 1; pos <= 4; pos++)
        for (d = 0; d <= 9; d++) {
            struct rcx *b = brick_new();
            /* Three decimal places light all four positions: digit d at `pos`, zeros elsewhere. */
            user_view(b, 3, 2, (u16)(d * scale[pos]));
            for (p = 4; p >= 1; p--)
                text[4 - p] = (char)(p == pos ? '0' + d : '0');
            text[4] = 0;
            memmove(text + 2, text + 1, 4);
            text[1] = '.';
            expect_number(b, text);
            brick_free(b);
        }
}

static void numbers_signs_points_and_overflow(void **state)
{
    static const struct { u8 places; s16 value; const char *text; } rows[] = {
        { 0, 0, "0" }, { 0, 7, "7" }, { 0, 42, "42" }, { 0, 305, "305" }, { 0, 9999, "9999" },
        { 1, 5, "0.5" }, { 2, 5, "0.05" }, { 3, 5, "0.005" }, { 1, 1234, "123.4" }, { 2, 1234, "12.34" },
        { 3, 1234, "1.234" }, { 2, 100, "1.00" }, { 1, 0, "0.0" },
        { 0, -5, "-5" }, { 0, -42, "-42" }, { 0, -123, "-123" }, { 0, -1234, "-1234" }, { 0, -9999, "-9999" },
        { 2, -5, "-0.05" }, { 3, -5, "-0.005" }, { 1, -1234, "-123.4" },
        { 0, 10000, "----" }, { 0, -10000, "----" }, { 0, 32767, "----" }, { 0, -32768, "----" },
        { 2, 12345, "----" },
    };
    unsigned i;
    (void)state;
    for (i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        struct rcx *b = brick_new();
        user_view(b, rows[i].places, 2, (u16)rows[i].value);
        expect_number(b, rows[i].text);
        brick_free(b);
    }
}

static void program_number_digit(void **state)
{
    struct rcx *b = brick_new();
    u8 sel[2] = { 0x91, 0 };
    unsigned slot;
    (void)state;
    for (slot = 0; slot < 5; slot++) {
        u8 want[HAL_LCD_BYTES] = { 0 };
        const u8 *img;
        int s;
        sel[1] = (u8)slot;
        brick_cmd(b, sel, 2, NULL);
        img = glass(b);
        lcd_digit(want, 0, (int)slot + 1); /* slots 0-4 show as 1-5 */
        for (s = 0; s < 7; s++)
            assert_int_equal(lcd_lit(img, lcd_map[0][s]), lcd_lit(want, lcd_map[0][s]));
    }
    brick_free(b);
}

/* Four digits with the leading zero, as firm0328 shows the watch (reference-firmware.md, "The brick's face"). */
static void watch_view(void **state)
{
    struct rcx *b = brick_new();
    u8 set[3] = { 0x22, 12, 34 };
    unsigned ms;
    (void)state;
    expect_watch(b, "00.00");          /* power-on: the watch at 00:00 */
    brick_cmd(b, set, 3, NULL);
    expect_watch(b, "12.34");
    set[1] = 23;
    set[2] = 59;
    user_view(b, 0, 2, 77);
    brick_cmd(b, set, 3, NULL);        /* SetWatch selects the watch (spec p. 51) ... */
    assert_int_equal(b->display.view, DISPLAY_USER); /* ... but not over a program's own view: firm0328 keeps it */
    assert_int_equal(b->watch, 23 * 60 + 59);
    select_view(b, 0);
    expect_watch(b, "23.59");
    select_view(b, 2);
    brick_cmd(b, set, 3, NULL);        /* from an input's view it does */
    expect_watch(b, "23.59");
    for (ms = 0; ms < 60000; ms++)
        vm_tick(b);
    expect_watch(b, "00.00");
    set[1] = 9;
    set[2] = 30;
    brick_cmd(b, set, 3, NULL);
    expect_watch(b, "09.30");
    set[1] = 0;
    set[2] = 5;
    brick_cmd(b, set, 3, NULL);
    expect_watch(b, "00.05");
    brick_free(b);
}

/* The watch's point blinks like a clock's: about 0.78 s lit, 0.78 s dark; the digits stay. */
static void watch_point_blinks(void **state)
{
    struct rcx *b = brick_new();
    struct fake_hal *h = fake_hal_of(b);
    unsigned ms, lit_ms = 0, changes = 0, last_change = 0, period_ok = 0;
    int was = -1;
    (void)state;
    for (ms = 0; ms < 10000; ms++) {
        int now;
        vm_tick(b);
        if (!h->lcd_calls) /* the first image comes at the end of the first 10 ms step */
            continue;
        if (lcd_reads(h->lcd, "00.00") && lcd_reads(h->lcd, "0000"))
            fail_msg("at %u ms the watch reads neither 00.00 nor 0000", ms);
        now = lcd_lit(h->lcd, lcd_point_right_of[3]);
        lit_ms += (unsigned)now;
        if (was >= 0 && now != was) {
            if (changes > 0 && ms - last_change >= 770 && ms - last_change <= 790)
                period_ok++;
            changes++;
            last_change = ms;
        }
        was = now;
    }
    assert_true(changes >= 12);               /* 10 s / 0.78 s */
    assert_int_equal(period_ok, changes - 1); /* every phase 0.77-0.79 s */
    assert_true(lit_ms > 4500 && lit_ms < 5500);
    brick_free(b);
}

static void input_views_and_marks(void **state)
{
    const int *selected = lcd_input_selected, *active = lcd_input_active;
    struct rcx *b = brick_new();
    u8 type[3] = { 0x32, 0, 2 };
    const u8 *img;
    int i;
    (void)state;
    img = glass(b);
    for (i = 0; i < 3; i++)
        assert_false(lcd_lit(img, selected[i]) || lcd_lit(img, active[i]));
    brick_cmd(b, type, 3, NULL);       /* input 1: temperature */
    sensor_sample(b, 0, 520);          /* 29.5 C (trunc of 29560 / 100 tenths) */
    sensor_sample(b, 1, 700);
    select_view(b, 1);
    expect_number(b, "29.5");          /* tenths shown with one decimal place */
    img = glass(b);
    assert_true(lcd_lit(img, selected[0]));
    assert_false(lcd_lit(img, selected[1]) || lcd_lit(img, selected[2]));
    select_view(b, 2);                 /* input 2: no type set, raw value */
    expect_number(b, "700");
    img = glass(b);
    assert_true(lcd_lit(img, selected[1]) && !lcd_lit(img, selected[0]));
    type[1] = 2;
    type[2] = 4;
    brick_cmd(b, type, 3, NULL);       /* input 3: rotation */
    select_view(b, 3);
    sensor_sample(b, 2, 1000);         /* phases 0, 1, 0, 3: up, down, down = -1 */
    sensor_sample(b, 2, 860);
    sensor_sample(b, 2, 1000);
    sensor_sample(b, 2, 640);
    expect_number(b, "-1");
    img = glass(b);
    assert_true(lcd_lit(img, selected[2]));
    for (i = 0; i < 3; i++)            /* 520, 700, 640: none reads pressed */
        assert_false(lcd_lit(img, active[i]));
    brick_free(b);
}

/*
 * An input's mark is lit while the input reads pressed, its boolean value with the usual thresholds, whatever its
 * type and also with none (reference-firmware.md, "The brick's face": lit at raw 100 and 300, dark at 700 and 1023).
 */
static void input_marks_follow_the_boolean(void **state)
{
    static const struct { u16 raw; int lit; } steps[] = {
        { 1023, 0 }, { 100, 1 }, { 700, 0 }, { 300, 1 }, { 500, 1 }, /* 460-562: no change */
        { 1023, 0 }, { 500, 0 },
    };
    static const u8 types[] = { 0, 1, 3, 2 }; /* none, touch, light, temperature */
    unsigned t, i, n;
    (void)state;
    for (t = 0; t < sizeof types; t++) {
        struct rcx *b = brick_new();
        u8 type[3] = { 0x32, 0, types[t] };
        for (n = 0; n < 3; n++) {
            type[1] = (u8)n;
            brick_cmd(b, type, 3, NULL);
        }
        for (i = 0; i < sizeof steps / sizeof steps[0]; i++) {
            const u8 *img;
            for (n = 0; n < 3; n++)
                sensor_sample(b, (u8)n, n == 1 ? 1023 : steps[i].raw); /* input 2 stays released */
            img = glass(b);
            if (lcd_lit(img, lcd_input_active[0]) != steps[i].lit || lcd_lit(img, lcd_input_active[2]) != steps[i].lit)
                fail_msg("type %u, raw %u: input marks %d/%d, expected %d", types[t], steps[i].raw,
                         lcd_lit(img, lcd_input_active[0]), lcd_lit(img, lcd_input_active[2]), steps[i].lit);
            assert_false(lcd_lit(img, lcd_input_active[1]));
        }
        brick_free(b);
    }
}

static void output_views_and_arrows(void **state)
{
    const int *selected = lcd_output_selected, *fwd = lcd_output_fwd, *rev = lcd_output_rev;
    struct rcx *b = brick_new();
    u8 c[4];
    const u8 *img;
    int i;
    (void)state;
    img = glass(b);
    for (i = 0; i < 3; i++)
        assert_false(lcd_lit(img, selected[i]) || lcd_lit(img, fwd[i]) || lcd_lit(img, rev[i]));
    c[0] = 0x21; c[1] = 0x87;          /* all on, forward */
    brick_cmd(b, c, 2, NULL);
    c[0] = 0xE1; c[1] = 0x02;          /* B reverse */
    brick_cmd(b, c, 2, NULL);
    c[0] = 0x13; c[1] = 0x04; c[2] = 2; c[3] = 3; /* C power 3 */
    brick_cmd(b, c, 4, NULL);
    select_view(b, 6);
    expect_number(b, "4");             /* running: power + 1, as firm0328 shows it (reference-firmware.md) */
    img = glass(b);
    assert_true(lcd_lit(img, fwd[0]) && !lcd_lit(img, rev[0]));
    assert_true(lcd_lit(img, rev[1]) && !lcd_lit(img, fwd[1]));
    assert_true(lcd_lit(img, fwd[2]) && !lcd_lit(img, rev[2]));
    assert_true(lcd_lit(img, selected[2]) && !lcd_lit(img, selected[0]) && !lcd_lit(img, selected[1]));
    select_view(b, 4);
    expect_number(b, "8");
    img = glass(b);
    assert_true(lcd_lit(img, selected[0]) && !lcd_lit(img, selected[2]));
    c[0] = 0x21; c[1] = 0x41;          /* A off: no arrow, and 0 */
    brick_cmd(b, c, 2, NULL);
    expect_number(b, "0");
    c[1] = 0x02;                       /* B float: no arrow, and 0 */
    brick_cmd(b, c, 2, NULL);
    select_view(b, 5);
    expect_number(b, "0");
    img = glass(b);
    assert_false(lcd_lit(img, fwd[0]) || lcd_lit(img, rev[0]));
    assert_false(lcd_lit(img, fwd[1]) || lcd_lit(img, rev[1]));
    assert_true(lcd_lit(img, fwd[2]));
    brick_free(b);
}

/* The figure walks while a task runs or waits, changing frame every 260 ms, steadily (reference-firmware.md). */
static void running_figure(void **state)
{
    static const u8 wait_loop[] = { 0x43, 0x02, 0x0A, 0x00, 0x27, 0x85 }; /* Wait 10; jump back to the Wait */
    struct rcx *b = brick_new();
    struct fake_hal *h = fake_hal_of(b);
    unsigned ms, seen[3] = { 0, 0, 0 }, changes = 0, last_change = 0;
    u8 stop_all = 0x50;
    int last = 1;
    (void)state;
    assert_int_equal(lcd_figure(glass(b)), 1);
    assert_int_equal(brick_download(b, 1, 0, wait_loop, sizeof wait_loop), 0);
    brick_start(b, 0);
    for (ms = 0; ms < 3000; ms++) {    /* the task waits almost all the time: it still counts as running */
        vm_run(b, 10);
        vm_tick(b);
        seen[lcd_figure(h->lcd)]++;
        if (lcd_figure(h->lcd) != last) {
            if (changes > 0 && ms - last_change != 260)
                fail_msg("the figure changed %u ms after the change before, not 260", ms - last_change);
            changes++;
            last_change = ms;
        }
        last = lcd_figure(h->lcd);
    }
    assert_int_equal(seen[0], 0);
    assert_true(seen[2] > 1200 && seen[1] > 1200);
    assert_true(changes >= 10);        /* 3 s / 0.26 s */
    brick_cmd(b, &stop_all, 1, NULL);
    assert_int_equal(lcd_figure(glass(b)), 1);
    for (ms = 0; ms < 1000; ms++)
        vm_tick(b);
    assert_int_equal(lcd_figure(h->lcd), 1);
    brick_free(b);
}

/* The IR mark (the lower arc) is lit for a moment, 0.25-0.8 s, whenever the IR layer reports activity. */
static void ir_mark_lit_for_a_moment(void **state)
{
    struct rcx *b = brick_new();
    struct fake_hal *h = fake_hal_of(b);
    unsigned ms, lit = 0, first = 0;
    (void)state;
    assert_false(lcd_lit(glass(b), SG(6, 2)));
    display_ir_activity(b);
    for (ms = 0; ms < 2000; ms++) {
        vm_tick(b);
        if (lcd_lit(h->lcd, SG(6, 2))) {
            if (!lit)
                first = ms;
            else if (first + lit != ms)
                fail_msg("the IR mark went dark and came back");
            lit++;
        }
    }
    assert_true(lit && first < DISPLAY_REFRESH_MS); /* at the next refresh */
    assert_true(lit >= 250 && lit <= 800);
    assert_false(lcd_lit(h->lcd, SG(6, 3)));
    brick_free(b);
}

static void runtime_marks(void **state)
{
    static const struct { u8 mark; int seg; } rows[] = {
        { DISPLAY_MARK_BATTERY, SG(4, 0) }, { DISPLAY_MARK_IR_LOW, SG(6, 2) }, { DISPLAY_MARK_IR_HIGH, SG(6, 3) },
        { DISPLAY_MARK_LOG_Q0, SG(2, 0) }, { DISPLAY_MARK_LOG_Q1, SG(2, 1) }, { DISPLAY_MARK_LOG_Q2, SG(2, 3) },
        { DISPLAY_MARK_LOG_Q3, SG(2, 2) }, { DISPLAY_MARK_DOT0, SG(6, 4) }, { DISPLAY_MARK_DOT1, SG(8, 0) },
        { DISPLAY_MARK_DOT2, SG(8, 4) }, { DISPLAY_MARK_DOT3, SG(7, 0) }, { DISPLAY_MARK_DOT4, SG(7, 4) },
    };
    unsigned i, j;
    (void)state;
    for (i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        struct rcx *b = brick_new();
        u8 before[HAL_LCD_BYTES];
        const u8 *img;
        memcpy(before, glass(b), sizeof before);
        assert_false(lcd_lit(before, rows[i].seg));
        display_mark(b, rows[i].mark, 1);
        img = glass(b);
        for (j = 0; j < HAL_LCD_BYTES * 8; j++)
            assert_int_equal(lcd_lit(img, (int)j), lcd_lit(before, (int)j) || (int)j == rows[i].seg);
        display_mark(b, rows[i].mark, 0);
        assert_memory_equal(glass(b), before, HAL_LCD_BYTES);
        brick_free(b);
    }
}

static void lcd_written_only_on_change(void **state)
{
    struct rcx *b = brick_new();
    struct fake_hal *h = fake_hal_of(b);
    unsigned ms;
    (void)state;
    select_view(b, 2);                  /* not the watch: its point blinks */
    for (ms = 1; ms <= DISPLAY_REFRESH_MS && !h->lcd_calls; ms++)
        vm_tick(b);
    assert_int_equal(h->lcd_calls, 1);  /* the first image within one refresh period */
    for (ms = 0; ms < 5000; ms++)
        vm_tick(b);
    assert_int_equal(h->lcd_calls, 1);  /* nothing changed */
    sensor_sample(b, 0, 1000);
    select_view(b, 1);
    for (ms = 1; ms <= DISPLAY_REFRESH_MS && h->lcd_calls == 1; ms++)
        vm_tick(b);
    assert_int_equal(h->lcd_calls, 2);
    for (ms = 0; ms < 1000; ms++) {
        sensor_sample(b, 0, 1000);       /* same value every millisecond */
        vm_tick(b);
    }
    assert_int_equal(h->lcd_calls, 2);
    brick_free(b);
}

static void user_view_sources(void **state)
{
    struct rcx *b = brick_new();
    u8 set_var[5] = { 0x14, 9, 2, 0xD2, 0x04 }; /* var 9 = 1234 */
    u8 select_slot[2] = { 0x91, 2 };
    u16 seed;
    (void)state;
    brick_cmd(b, set_var, 5, NULL);
    user_view(b, 1, 0, 9);               /* ViewSourceValue selects the user view (nqc's SetUserDisplay) */
    expect_number(b, "123.4");
    set_var[3] = 0x85;                   /* var 9 = 1157: the view follows the source */
    brick_cmd(b, set_var, 5, NULL);
    expect_number(b, "115.7");
    select_view(b, 0);
    expect_watch(b, "00.00");
    select_view(b, 7);                   /* back to the same user selection */
    expect_number(b, "115.7");
    user_view(b, 0, 0, 40);              /* a local variable cannot be shown (spec p. 97): 0 */
    expect_number(b, "0");
    brick_cmd(b, select_slot, 2, NULL);
    user_view(b, 0, 8, 0);               /* source 8, the program slot */
    expect_number(b, "2");
    seed = b->random;
    user_view(b, 0, 4, 100);             /* random: shown as 0 and never drawn for the display */
    expect_number(b, "0");
    assert_int_equal(b->random, seed);
    brick_free(b);
}

static void bad_operands_change_nothing(void **state)
{
    static const struct { const char *what; u8 bytes[6]; u8 len; } rows[] = {
        { "SelectDisplay 8", { 0x33, 0x02, 0x08, 0x00 }, 4 },
        { "SelectDisplay -1", { 0x33, 0x02, 0xFF, 0xFF }, 4 },
        { "SelectDisplay 256", { 0x33, 0x02, 0x00, 0x01 }, 4 },
        { "ViewSourceValue precision 4", { 0xE5, 0x00, 0x04, 0x00, 0x00, 0x00 }, 6 },
        { "ViewSourceValue precision 255", { 0xE5, 0x00, 0xFF, 0x02, 0x00, 0x00 }, 6 },
        { "SetWatch 24:00", { 0x22, 0x18, 0x00 }, 3 },
        { "SetWatch 0:60", { 0x22, 0x00, 0x3C }, 3 },
    };
    unsigned i;
    (void)state;
    for (i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        struct rcx *b = brick_new();
        struct rcx_display before;
        u8 img[HAL_LCD_BYTES];
        user_view(b, 2, 2, 4321);
        select_view(b, 3);
        memcpy(img, glass(b), sizeof img);
        memcpy(&before, &b->display, sizeof before);
        brick_cmd(b, rows[i].bytes, rows[i].len, NULL);
        display_view(b, 8);
        display_user(b, 4, 2, 1);
        display_mark(b, DISPLAY_BYTES * 8, 1);
        display_mark(b, 0xFF, 1);
        if (memcmp(&before, &b->display, sizeof before) != 0)
            fail_msg("%s changed the display state", rows[i].what);
        if (memcmp(img, glass(b), sizeof img) != 0)
            fail_msg("%s changed the glass", rows[i].what);
        brick_free(b);
    }
}

/*
 * The digits are worked out again only when what they show may have changed (vm/display.c): a brick doing random
 * things must show, millisecond by millisecond, what one that works them out at every refresh shows (the record of
 * what they were worked out from is wiped every millisecond: rcx_display.digits_places1, display.h).
 */
static void image_follows_every_change(void **state)
{
    static const u8 wait_loop[] = { 0x43, 0x02, 0x05, 0x00, 0x27, 0x85 }; /* Wait 50 ms; jump back */
    static const u8 marks_used[] = { DISPLAY_MARK_BATTERY, DISPLAY_MARK_IR_HIGH, DISPLAY_MARK_LOG_Q2, DISPLAY_MARK_DOT1 };
    struct rcx *br[2] = { brick_new(), brick_new() };
    unsigned ms, seed = 12345;
    (void)state;
    for (unsigned i = 0; i < 2; i++)
        assert_int_equal(brick_download(br[i], 1, 0, wait_loop, sizeof wait_loop), 0);
    for (ms = 0; ms < 60000; ms++) {
        unsigned r;
        seed = seed * 1103515245u + 12345u;
        r = (seed >> 8) & 0xFFFF;
        for (unsigned i = 0; i < 2; i++) {
            struct rcx *b = br[i];
            u8 c[6];
            switch (r % 64) {
            case 0: c[0] = 0x32; c[1] = (u8)(r >> 6 & 3); c[2] = (u8)(r >> 8 & 7); brick_cmd(b, c, 3, NULL); break;
            case 1: c[0] = 0x42; c[1] = (u8)(r >> 6 & 3); c[2] = (u8)(r >> 8); brick_cmd(b, c, 3, NULL); break;
            case 2: c[0] = 0x21; c[1] = (u8)((r >> 6 & 7) | (r >> 9 & 3) << 6); brick_cmd(b, c, 2, NULL); break;
            case 3: c[0] = 0xE1; c[1] = (u8)((r >> 6 & 7) | (r >> 9 & 3) << 6); brick_cmd(b, c, 2, NULL); break;
            case 4: c[0] = 0x13; c[1] = (u8)(r >> 6 & 7); c[2] = 2; c[3] = (u8)(r >> 9 & 7); brick_cmd(b, c, 4, NULL);
                break;
            case 5: select_view(b, (u8)(r >> 6 & 7)); break;
            case 6: user_view(b, (u8)(r >> 6 & 3), 0, (u16)(r >> 8 & 3)); break;
            case 7: c[0] = 0x14; c[1] = (u8)(r >> 6 & 3); c[2] = 2; c[3] = (u8)(r >> 8); c[4] = (u8)(r >> 3);
                brick_cmd(b, c, 5, NULL); break;
            case 8: brick_start(b, 0); break;
            case 9: c[0] = 0x50; brick_cmd(b, c, 1, NULL); break;
            case 10: display_ir_activity(b); break;
            case 11: display_mark(b, marks_used[r >> 6 & 3], (u8)(r >> 8 & 1)); break;
            case 12: c[0] = 0x22; c[1] = (u8)(r >> 6 & 15); c[2] = (u8)(r >> 10 & 31); brick_cmd(b, c, 3, NULL); break;
            case 13: c[0] = 0x91; c[1] = (u8)(r >> 6 & 3); brick_cmd(b, c, 2, NULL); break;
            default: break;
            }
            if (r % 4 == 0)
                sensor_sample(b, (u8)(r >> 2 & 3), (u16)(seed >> 16 & 0x3FF));
            if (i == 1)
                b->display.digits_places1 = 0; /* what the digits were worked out from, forgotten */
            vm_run(b, 4);
            vm_tick(b);
        }
        if (memcmp(fake_hal_of(br[0])->lcd, fake_hal_of(br[1])->lcd, HAL_LCD_BYTES) != 0)
            fail_msg("at %u ms the image was not composed again", ms);
    }
    assert_int_equal(fake_hal_of(br[0])->lcd_calls, fake_hal_of(br[1])->lcd_calls);
    brick_free(br[0]);
    brick_free(br[1]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(digits_at_every_position),
        cmocka_unit_test(numbers_signs_points_and_overflow),
        cmocka_unit_test(program_number_digit),
        cmocka_unit_test(watch_view),
        cmocka_unit_test(watch_point_blinks),
        cmocka_unit_test(input_views_and_marks),
        cmocka_unit_test(input_marks_follow_the_boolean),
        cmocka_unit_test(output_views_and_arrows),
        cmocka_unit_test(running_figure),
        cmocka_unit_test(ir_mark_lit_for_a_moment),
        cmocka_unit_test(runtime_marks),
        cmocka_unit_test(lcd_written_only_on_change),
        cmocka_unit_test(user_view_sources),
        cmocka_unit_test(bad_operands_change_nothing),
        cmocka_unit_test(image_follows_every_change),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
