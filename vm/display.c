/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The LCD image: program number, running figure, input and output indicators, the number of the selected view and
 * the runtime's marks, recomposed every DISPLAY_REFRESH_MS and sent only when it changed.
 */
#include "rcx_string.h"
#include "rcx.h"
#include "hal.h"
#include "sources.h"

#define S DISPLAY_SEG
#define BODY S(0, 1) /* the figure's body, always lit: where a table entry must light nothing new */

/*
 * The segments drawn, by lit(): first g, a, b, c, d, e, f (g first: position 5 has nothing else) of digit positions
 * 0 (program number) and 1-4 (1 rightmost), rcx-hardware.md §3.6, then position 5: only the minus sign left of a
 * four-digit number. Then single ones: the mark of each view (input 1-3 selected, output A-C selected; the watch and
 * the user view have none: their entries light the figure's body, which is lit anyway); the decimal point for 0-3
 * decimal places (none: the body again, shared with the user view), right of digit 2, 3, 4, then for the watch's four
 * digits the point lit, and dark; input 1-3 pressed; the arrows of output A-C driven in reverse, and forward; the IR
 * mark.
 */
static const u8 segs[] = {
    S(1, 5), S(1, 4), S(2, 5), S(2, 7), S(1, 7), S(4, 7), S(4, 5),
    S(0, 5), S(0, 4), S(4, 1), S(4, 3), S(0, 7), S(5, 7), S(5, 5),
    S(1, 1), S(1, 0), S(5, 1), S(5, 3), S(1, 3), S(6, 7), S(6, 5),
    S(3, 1), S(3, 0), S(8, 1), S(8, 3), S(3, 3), S(8, 7), S(8, 5),
    S(3, 5), S(3, 4), S(7, 1), S(7, 3), S(3, 7), S(7, 7), S(7, 5),
    S(7, 6),
    BODY, S(6, 0), S(5, 4), S(4, 4), S(7, 2), S(0, 6), S(1, 6),
    BODY, S(5, 6), S(6, 6), S(8, 6), S(6, 6), BODY,
    S(6, 1), S(5, 0), S(2, 4),
    S(3, 6), S(1, 2), S(4, 6),
    S(3, 2), S(4, 2), S(2, 6),
    DISPLAY_MARK_IR_LOW,
};
#define DIGIT 7         /* * position */
#define VIEW_SELECTED 36 /* + view */
#define POINT 42        /* + places1 (decimal places + 1) */
#define WATCH_POINT 4   /* places1 - 1 of the watch; + 1: dark */
#define INPUT_PRESSED 49
#define OUTPUT_REV 52   /* + output; + 3: forward */
#define IR 58
RCX_STATIC_ASSERT(segs_as_counted, sizeof segs == IR + 1 && VIEW_SELECTED == 5 * DIGIT + 1 &&
                                   VIEW_SELECTED + DISPLAY_USER == POINT + 1);

/* Seven-segment shapes of 0-9, bit 0 = g, bit 1 = a ... bit 6 = f (a minus sign is g alone: lit() of a position's
 * first segment). */
static const u8 font[10] = { 0x7E, 0x0C, 0x37, 0x1F, 0x4D, 0x5B, 0x7B, 0x0E, 0x7F, 0x5F };

/* The figure's segments are all in image byte 0: walking is arms (bit 0), body (1) and two legs (3); standing is body
 * and one leg (2). */
#define FIGURE_WALKING 0x0B
#define FIGURE_STANDING 0x06

/*
 * The image being composed. It is scratch, valid only during display_tick(), so it need not live in struct rcx (all
 * bricks run on one thread); at a fixed address every segment is lit without a pointer to pass around.
 */
static u8 work[DISPLAY_BYTES] RCX_SCRATCH;

static void lit(u8 k)
{
    u8 seg = segs[k];

#ifdef __H8300__ /* bset takes the bit number from a register's low three bits: no table of bits, no shift loop */
    __asm__ __volatile__("bset\t%X1,@%T0" : : "r"(work + (seg >> 3)), "r"(seg) : "memory");
#else
    work[seg >> 3] |= (u8)(1u << (seg & 7));
#endif
}

/* A glyph at the digit position whose segments start at segs[k] (k = position * DIGIT). */
static void digit(u8 k, u8 glyph)
{
    u8 shape = font[glyph];

    do /* (every glyph lights something) */
        if (shape & 1)
            lit(k);
    while (k++, shape >>= 1);
}

/*
 * A signed number in positions 1-4 with the point segs[POINT + places1]: leading zeros dropped except those the
 * decimal point needs ("0.05") and the watch's ("00.00"), the minus sign (the middle segment, first of a position's)
 * left of the first digit. Magnitudes above 9999 show as "----": a clamped 9999 would look like a real reading.
 */
static __attribute__((noinline)) void number(s16 v, u8 places1)
{
    u16 u = v < 0 ? (u16)(0u - (u16)v) : (u16)v, q;
    u8 k = DIGIT, d;

    if (u > DISPLAY_MAX) {
        for (; k <= 4 * DIGIT; k += DIGIT)
            lit(k);
        return;
    }
    lit((u8)(POINT + places1));
    if (places1 > 4) /* digits shown at least */
        places1 = 4;
    places1 *= DIGIT;
    do {
        q = u / 10;
        d = (u8)((u8)u - (u8)q * 10u); /* u % 10 without a second division */
        u = q;
        digit(k, d);
        k += DIGIT;
    } while (u || k <= places1);
    if (v < 0)
        lit(k);
}

RCX_STATIC_ASSERT(idle_is_0, RCX_TASK_IDLE == 0);

u8 program_running(const struct rcx *b)
{
    const struct rcx_task *t = b->task;
    u8 n = RCX_TASKS, any = RCX_TASK_IDLE;

    do
        any |= t++->state;
    while (--n);
    return any;
}

/*
 * The view's number is worked out again only when it or its decimal places changed: its divisions and its four
 * digits cost far more than the rest, which is composed at every refresh (the program number's one digit too).
 */
static void compose(struct rcx *b)
{
    const struct rcx_sensor *s;
    u8 i, wire, view, places1;
    s16 v;

    view = b->display.view;
    /* `places1` (decimal places + 1) is set after any call, so that it need not be kept across one. */
    if (view == DISPLAY_WATCH) {
        v = (s16)(b->watch + (u8)(b->watch / 60) * 40u); /* hours * 100 + minutes: shown as hh.mm */
        /* The point blinks: lit in the first three frames (phase / 3 frames is 0), dark in the others (1). */
        places1 = (u8)(WATCH_POINT + 1 + b->display.phase / (3 * DISPLAY_FRAME_STEPS));
    } else if (view <= DISPLAY_INPUT_3) {
        s = &b->sensor[view - DISPLAY_INPUT_1];
        v = s->value;
        places1 = (u8)(1 + ((u8)(s->mode - SENSOR_MODE_CELSIUS) < 0x40)); /* Celsius, Fahrenheit: tenths */
    } else if (view <= DISPLAY_OUTPUT_C) {
        /* 0 while the output is not running, power + 1 (1-8) while it is, as firm0328 shows it. */
        i = outputs_status(b, (u8)(view - DISPLAY_OUTPUT_A));
        v = (i & RCX_MOTOR_ON) ? (s16)((i & RCX_MOTOR_POWER) + 1) : 0;
        places1 = 1;
    } else {
        /* Reading the random source would advance the program's random sequence at every refresh. */
        v = b->display.user_source == RCX_SRC_RANDOM ? 0
                                                    : source_get(b, NULL, b->display.user_source, b->display.user_index);
        places1 = (u8)(b->display.user_precision + 1);
    }
    if (v != b->display.digits_v || places1 != b->display.digits_places1) {
        b->display.digits_v = v;
        b->display.digits_places1 = places1;
        memset(work, 0, DISPLAY_BYTES);
        number(v, b->display.digits_places1); /* read back: kept across the calls it would cost a spill */
        memcpy(b->display.digits, work, DISPLAY_BYTES);
    }
    for (i = 0; i < DISPLAY_BYTES; i++)
        work[i] = (u8)(b->display.marks[i] | b->display.digits[i]);
    digit(0, (u8)(b->prog + 1));
    /* The running figure walks (alternating with standing every frame) while any task runs or waits. */
    if ((u8)(b->display.phase / DISPLAY_FRAME_STEPS) & 1 && program_running(b))
        work[0] |= FIGURE_WALKING;
    else
        work[0] |= FIGURE_STANDING;
    if (b->display.ir && --b->display.ir) /* counted down here, once a refresh */
        lit(IR);
    for (i = INPUT_PRESSED; i < INPUT_PRESSED + RCX_SENSORS; i++)
        if (b->sensor[i - INPUT_PRESSED].boolean)
            lit(i);
    for (i = OUTPUT_REV; i < OUTPUT_REV + RCX_MOTORS; i++) {
        wire = outputs_applied(b, i - OUTPUT_REV);
        if (wire & RCX_MOTOR_ON) /* driven: an arrow */
            lit((u8)(wire & RCX_MOTOR_FWD ? i + 3 : i));
    }
    lit((u8)(VIEW_SELECTED + b->display.view));
}

RCX_STATIC_ASSERT(refresh_is_every_other_10ms_step, DISPLAY_REFRESH_MS == 20);

/* At the end of every other 10 ms step of the machine's clock (vm_tick), the first after power-on among them. */
void display_tick(struct rcx *b)
{
    u8 *p, *w, diff;

    b->display.phase = (u8)((u8)(b->display.phase + 1) % (6 * DISPLAY_FRAME_STEPS));
    compose(b);
    /* Copied into shown[], told only when some byte differed. */
    p = b->display.shown;
    w = work;
    diff = 0;
    do {
        diff |= (u8)(*p ^ *w);
        *p++ = *w++;
    } while (w != work + DISPLAY_BYTES);
    if (diff)
        hal_lcd(b, b->display.shown);
}
