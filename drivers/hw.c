/* SPDX-License-Identifier: MPL-2.0 */
/* Register-level logic of the drivers, without register access (hw.h; numbers from rcx-hardware.md §3). */
#include "hal.h"
#include "arith.h"
#include "hw.h"

/* Level n is on for n + 1 ms of every 8, the on-milliseconds spread over the frame (§3.2, the ROM's patterns). */
const u8 hw_pwm_pattern[8] = { 0x01, 0x11, 0x49, 0x55, 0x6D, 0x77, 0x7F, 0xFF };

const u8 hw_sensor_power_bit[3] = { 0x04, 0x02, 0x01 };

void hw_motor_set(struct hw_motors *m, u8 port, u8 mode, u8 level)
{
    static const u8 weight[3] = { 64, 4, 1 }; /* A in bits 7-6, B in 3-2, C in 1-0 */
    u8 *latch = m->latch, bits, keep, pattern, n = 8;

    if (port > 2)
        return;
    if (level > 7)
        level = 7;
    mode &= 3;
    /* A brake shorts the motor: holding is all it does, so it is never pulsed. One phase for all outputs, so that a
     * new level takes over at the next millisecond without restarting a frame. */
    pattern = mode == HAL_MOTOR_BRAKE ? 0xFF : hw_pwm_pattern[level];
    bits = weight[port];
    keep = (u8)~(3 * bits);
    bits = (u8)(mode * bits); /* a byte multiply is one instruction, a shift by a variable a loop */
    do {
        u8 v = (u8)(*latch & keep);

        if (pattern & 1)
            v |= bits;
        *latch++ = v;
        pattern >>= 1;
    } while (--n);
}

/*
 * raw × 43988 / 1560 (§3.4) = raw × 10997 / 390 = raw × 28 + raw × 77 / 390, and raw × 77 / 390 (rounded down)
 * = (raw × 77 / 2) / 195 = (raw × 38 + raw / 2) / 195: at most 39 385 / 195 = 201, a quotient a single 16-by-8-bit
 * division gives. Nothing needs more than 16 bits.
 */
u16 hw_battery_mv(u16 raw10)
{
    u16 x4, x28;

    if (raw10 > 1023)
        raw10 = 1023;
    /* The products by shifts and adds: gcc would call its 16-bit multiply helper for each. */
    x4 = (u16)(raw10 << 2);
    x28 = (u16)((x4 << 3) - x4);                                 /* raw × 32 - raw × 4 */
    return (u16)(x28 + rcx_divu8((u16)(x28 + ((x4 + raw10) << 1) + (raw10 >> 1)), 195)); /* raw × (28 + 10) */
}

/*
 * TMR0 clocks from fastest to slowest (§3.7 table: TCR clock select 9 + i / 2, STCR.ICKS0 1 for even i), each
 * with the lowest tone it can make with an 8-bit TCORA (the rounded clock / 2 hz at most 256: clock / 513, plus
 * one). The fastest usable clock gives the finest steps: the clocks are at most 4 apart, so TCORA + 1 ends up at
 * 64 or more and no tone is off by more than 0.8 %.
 */
static const u16 tone_clock[6][3] = {
    /* lowest tone, clock in Hz as high and low word */
    { 15595, 0x007A, 0x1200 }, /* φ/2,    8 MHz (CKS 01, ICKS0 1) */
    { 3899, 0x001E, 0x8480 },  /* φ/8,    2 MHz (CKS 01, ICKS0 0) */
    { 975, 0x0007, 0xA120 },   /* φ/32, 500 kHz (CKS 10, ICKS0 1) */
    { 488, 0x0003, 0xD090 },   /* φ/64, 250 kHz (CKS 10, ICKS0 0) */
    { 122, 0x0000, 0xF424 },   /* φ/256, 62.5 kHz (CKS 11, ICKS0 1) */
    { 31, 0x0000, 0x3D09 },    /* φ/1024, 15.6 kHz (CKS 11, ICKS0 0) */
};

u8 hw_tone(u16 hz, struct hw_tone *t)
{
    const u16 *c = tone_clock[0];
    u8 i = 2 * 0x09; /* clock i counted from 0x12: TCR 09 + i / 2 is then i / 2 */
    u16 lo, hi;

    if ((u16)(hz - 31) > 20000 - 31)
        return 0; /* the ROM's play-tone range (31-20 000 Hz); outside it a rest */
    for (;;) { /* not while (hz < *c): gcc would then load the first lowest tone twice */
        if (hz >= *c)
            break;
        c += 3;
        i++;
    }
    t->tcr = (u8)(i >> 1); /* 08 = clear on compare match A, plus the clock select */
    t->icks0 = (u8)(~i & 1);
    /* TCORA + 1 = clock / (2 hz), rounded: (clock + hz) / (2 hz), a dividend of up to 23 bits */
    hi = c[1];
    lo = (u16)(c[2] + hz);
    if (lo < hz)
        hi++;
    t->tcora = (u8)(rcx_udiv32_16(lo, (u16)(hz + hz), hi) - 1);
    return 1;
}

/* N = φ / (32 B) − 1 (§3.8): 207 for 2400 Bd, 103 for 4800 Bd. */
u8 hw_sci_brr(u8 mode)
{
    return mode & HAL_IR_4800 ? 103 : 207;
}

/*
 * TMR1 on φ/8 = 2 MHz, cleared on compare match A. 50 % duty: the output toggles on each match, 2 (TCORA + 1)
 * counts per period; 38 kHz is the ROM's TCORA 26 (37.04 kHz), 76 kHz is TCORA 12 (76.9 kHz). 25 % duty: the
 * output goes high on match A and low on match B, TCORA + 1 counts per period and TCORB + 1 of them high, at the
 * same two frequencies: 54 counts with 14 high (25.9 %), 26 counts with 7 high (26.9 %). Which level lights the
 * LED is not established; high is taken as "on" (rcx-hardware.md §3.8 leaves it open).
 */
void hw_carrier(u8 mode, struct hw_carrier *c)
{
    static const u8 setting[4][4] = {
        /* TCR, TCSR, TCORA, TCORB */
        { 0x09, 0x13, 26, 0xFF }, /* 38 kHz, 50 %: toggle on A */
        { 0x09, 0x13, 12, 0xFF }, /* 76 kHz, 50 % */
        { 0x09, 0x16, 53, 13 },   /* 38 kHz, 25 %: output 1 on A, 0 on B (bit 4 reads as 1) */
        { 0x09, 0x16, 25, 6 },    /* 76 kHz, 25 % */
    };
    const u8 *s = setting[(mode & (HAL_IR_76KHZ | HAL_IR_DUTY25)) >> 1];
    u8 *d = (u8 *)c, n = 4; /* the struct's bytes, in the table's order */

    do
        *d++ = *s++;
    while (--n);
}

/*
 * A change is accepted once the same buttons have differed from the accepted state at every look for
 * HW_DEBOUNCE_MS - 1 ms of the clock since the first (at a look a millisecond, the HW_DEBOUNCE_MS-th look); any
 * bounce back, or another button changing meanwhile, starts the time again. Time, not looks: a main loop that
 * catches up on milliseconds looks several times within microseconds.
 */
u8 hw_debounce(struct hw_debounce *d, u8 raw, u8 now)
{
    u8 diff = (u8)(raw ^ d->state);

    if (diff != d->cand) {
        d->cand = diff;
        d->since = now;
    }
    if (!diff || (u8)(now - d->since) < HW_DEBOUNCE_MS - 1)
        return 0; /* the usual case, every millisecond: nothing written */
    d->state = raw;
    d->cand = 0;
    return diff;
}

/* Every update sends the mode and the whole image (0.5 ms): the display engine calls only when something changed,
 * and a controller that lost its state for any reason is set right by the next update. */
u8 hw_lcd_on_frame(const u8 *image, u8 *frame)
{
    static const u8 head[4] = { HW_LCD_ADDRESS, HW_LCD_MORE | HW_LCD_MODE_ON, HW_LCD_MORE | HW_LCD_SELECT, 0 };
    const u8 *s = head;
    u8 n = 4 + HW_LCD_BYTES;

    do { /* one loop, its source switched to the image once the head is copied */
        *frame++ = *s++;
        if (n == HW_LCD_BYTES + 1)
            s = image;
    } while (--n);
    return 4 + HW_LCD_BYTES;
}

/* When the ring is full the newest byte stays and is marked bad: the IR layer then drops the packet it was in. */
void hw_rx_put(struct hw_rx *r, u8 byte, u8 error)
{
    u8 i = r->head;

    if ((u8)(i - r->tail) < HW_RX_SIZE) {
        r->data[i & (HW_RX_SIZE - 1)] = byte;
        r->head = (u8)(i + 1); /* the interrupt's own doing: the main loop reads nothing until it returns */
    } else {
        i--;
        error = 1;
    }
    r->error[i & (HW_RX_SIZE - 1)] = error;
}

/* The slot is read completely before `tail` frees it for the interrupt. */
u8 hw_rx_get(struct hw_rx *r, u8 *byte)
{
    u8 t = r->tail, got = 0;

    if (t != r->head) {
        u8 i = t & (HW_RX_SIZE - 1);

        *byte = r->data[i];
        got = (u8)(r->error[i] ? 2 : 1);
        r->tail = (u8)(t + 1);
    }
    return got;
}
