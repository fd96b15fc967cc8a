/*
 * The LCD image: program number, running figure, input and output indicators, the number of the selected view and
 * the runtime's marks, recomposed every DISPLAY_REFRESH_MS and sent only when it changed.
 */
#include "rcx_string.h"
#include "rcx.h"
#include "hal.h"
#include "sources.h"

#define S DISPLAY_SEG

/* Segments a-g of digit positions 0 (program number) and 1-4 (1 rightmost), rcx-hardware.md §3.6. Position 5 is
 * only the minus sign left of a four-digit number; its other entries repeat that segment and are never used. */
static const u8 digit_segs[6][7] = {
    { S(1, 4), S(2, 5), S(2, 7), S(1, 7), S(4, 7), S(4, 5), S(1, 5) },
    { S(0, 4), S(4, 1), S(4, 3), S(0, 7), S(5, 7), S(5, 5), S(0, 5) },
    { S(1, 0), S(5, 1), S(5, 3), S(1, 3), S(6, 7), S(6, 5), S(1, 1) },
    { S(3, 0), S(8, 1), S(8, 3), S(3, 3), S(8, 7), S(8, 5), S(3, 1) },
    { S(3, 4), S(7, 1), S(7, 3), S(3, 7), S(7, 7), S(7, 5), S(3, 5) },
    { S(7, 6), S(7, 6), S(7, 6), S(7, 6), S(7, 6), S(7, 6), S(7, 6) },
};

/* Seven-segment shapes of 0-9 and the minus, bit 0 = a ... bit 6 = g. */
static const u8 font[11] = { 0x3F, 0x06, 0x5B, 0x4F, 0x66, 0x6D, 0x7D, 0x07, 0x7F, 0x6F, 0x40 };
#define MINUS 10

/* Decimal point for 1, 2, 3 decimal places: right of digit 2, 3, 4. */
static const u8 point_segs[3] = { S(5, 6), S(6, 6), S(8, 6) };

/* Indicators: the marks of views 1-6 (input 1-3 selected, output A-C selected), then input 1-3 active (a sensor type
 * is set), output A-C reverse arrows, forward arrows, and the figure: walking (arms, body, two legs), standing (body,
 * one leg). */
static const u8 marks[] = {
    S(6, 0), S(5, 4), S(4, 4), S(7, 2), S(0, 6), S(1, 6),
    S(6, 1), S(5, 0), S(2, 4),
    S(3, 6), S(1, 2), S(4, 6),
    S(3, 2), S(4, 2), S(2, 6),
    S(0, 0), S(0, 1), S(0, 3),
    S(0, 1), S(0, 2),
};
#define VIEW_SELECTED 0 /* + view - 1 */
#define INPUT_ACTIVE 6
#define OUTPUT_REV 9
#define OUTPUT_FWD 12
#define FIGURE_WALKING 15
#define FIGURE_STANDING 18

static void lit(u8 *img, u8 seg)
{
    img[seg >> 3] |= (u8)(1u << (seg & 7));
}

static void lit_list(u8 *img, const u8 *segs, u8 n)
{
    while (n--)
        lit(img, *segs++);
}

static void digit(u8 *img, u8 pos, u8 glyph)
{
    const u8 *segs = digit_segs[pos];
    u8 shape = font[glyph];
    for (; shape; shape >>= 1, segs++)
        if (shape & 1)
            lit(img, *segs);
}

/*
 * A signed number in positions 1-4 with `places` decimals (0-3): leading zeros dropped except those the decimal
 * point needs ("0.05"), the minus sign in the middle segment left of the first digit. Magnitudes above 9999 show as
 * "----": a clamped 9999 would look like a real reading.
 */
static void number(u8 *img, s16 v, u8 places)
{
    u16 u = v < 0 ? (u16)(0u - (u16)v) : (u16)v;
    u8 pos = 1;

    if (u > DISPLAY_MAX) {
        for (; pos <= 4; pos++)
            digit(img, pos, MINUS);
        return;
    }
    do {
        digit(img, pos++, (u8)(u % 10));
        u /= 10;
    } while (u || pos <= places + 1);
    if (places)
        lit(img, point_segs[places - 1]);
    if (v < 0)
        digit(img, pos, MINUS);
}

static u8 program_running(const struct rcx *b)
{
    const struct rcx_task *t;
    for (t = b->task; t < b->task + RCX_TASKS; t++)
        if (t->state != RCX_TASK_IDLE)
            return 1;
    return 0;
}

static void compose(struct rcx *b, u8 *img)
{
    const struct rcx_display *d = &b->display;
    u8 i, mode, view = d->view, places = 0;
    s16 v;

    memcpy(img, d->marks, DISPLAY_BYTES);
    digit(img, 0, (u8)(b->prog + 1));
    /* The running figure walks (alternating with standing every 320 ms) while any task runs or waits. */
    if (program_running(b) && (b->ticks10 & 0x20))
        lit_list(img, marks + FIGURE_WALKING, 3);
    else
        lit_list(img, marks + FIGURE_STANDING, 2);
    for (i = 0; i < RCX_SENSORS; i++) {
        if (b->sensor[i].type != SENSOR_NONE)
            lit(img, marks[INPUT_ACTIVE + i]);
        mode = outputs_mode(b, i);
        if (mode == HAL_MOTOR_REV)
            lit(img, marks[OUTPUT_REV + i]);
        if (mode == HAL_MOTOR_FWD)
            lit(img, marks[OUTPUT_FWD + i]);
    }
    if (view - 1u < DISPLAY_USER - 1u)
        lit(img, marks[VIEW_SELECTED + view - 1]);
    if (view == DISPLAY_WATCH) {
        v = (s16)(b->watch + b->watch / 60 * 40); /* hours * 100 + minutes: shown as hh.mm */
        places = 2;
    } else if (view <= DISPLAY_INPUT_3) {
        i = (u8)(view - DISPLAY_INPUT_1);
        v = b->sensor[i].value;
        if ((u8)(b->sensor[i].mode - SENSOR_MODE_CELSIUS) < 0x40) /* Celsius, Fahrenheit: tenths */
            places = 1;
    } else if (view <= DISPLAY_OUTPUT_C) {
        v = (s16)(outputs_status(b, (u8)(view - DISPLAY_OUTPUT_A)) & RCX_MOTOR_POWER);
    } else {
        /* Reading the random source would advance the program's random sequence at every refresh. */
        v = d->user_source == RCX_SRC_RANDOM ? 0 : source_get(b, NULL, d->user_source, d->user_index);
        places = d->user_precision;
    }
    number(img, v, places);
}

void display_view(struct rcx *b, u8 view)
{
    if (view <= DISPLAY_USER)
        b->display.view = view;
}

/* nqc's SetUserDisplay sends only this command, so it selects the user view as well. */
void display_user(struct rcx *b, u8 precision, u8 src, u16 index)
{
    if (precision > 3)
        return;
    b->display.user_precision = precision;
    b->display.user_source = src;
    b->display.user_index = index;
    b->display.view = DISPLAY_USER;
}

void display_mark(struct rcx *b, u8 seg, u8 on)
{
    u8 *m = b->display.marks;
    if (seg >= DISPLAY_BYTES * 8)
        return;
    m[seg >> 3] &= (u8)~(1u << (seg & 7));
    if (on)
        lit(m, seg);
}

void display_tick(struct rcx *b)
{
    u8 *img = b->display.work;

    if (++b->display.clock < DISPLAY_REFRESH_MS)
        return;
    b->display.clock = 0;
    compose(b, img);
    if (memcmp(img, b->display.shown, DISPLAY_BYTES)) {
        memcpy(b->display.shown, img, DISPLAY_BYTES);
        hal_lcd(b, img);
    }
}
