/* Register-level logic of the drivers, without register access (hw.h; numbers from rcx-hardware.md §3). */
#include "hal.h"
#include "arith.h"
#include "hw.h"

/* Level n is on for n + 1 ms of every 8, the on-milliseconds spread over the frame (§3.2, the ROM's patterns). */
const u8 hw_pwm_pattern[8] = { 0x01, 0x11, 0x49, 0x55, 0x6D, 0x77, 0x7F, 0xFF };

const u8 hw_sensor_power_bit[3] = { 0x04, 0x02, 0x01 };

void hw_motor_set(struct hw_motors *m, u8 port, u8 mode, u8 level)
{
    static const u8 shift[3] = { 6, 2, 0 }; /* A in bits 7-6, B in 3-2, C in 1-0 */

    if (port > 2)
        return;
    mode &= 3;
    if (level > 7)
        level = 7;
    m->bits[port] = (u8)(mode << shift[port]);
    /* A brake shorts the motor: holding is all it does, so it is never pulsed. */
    m->pattern[port] = mode == HAL_MOTOR_BRAKE ? 0xFF : hw_pwm_pattern[level];
}

/* One phase for all outputs, so that a new level takes over at the next millisecond without restarting a frame. */
u8 hw_motor_step(struct hw_motors *m)
{
    u8 phase = m->phase ? m->phase : 1;
    u8 latch = 0;

    if (m->pattern[0] & phase)
        latch = m->bits[0];
    if (m->pattern[1] & phase)
        latch |= m->bits[1];
    if (m->pattern[2] & phase)
        latch |= m->bits[2];
    m->phase = (u8)(phase << 1);
    return latch;
}

/*
 * raw × 43988 / 1560 (§3.4) = raw × 10997 / 390. The product needs 24 bits, formed as raw × 43 × 256 − raw × 11
 * so that no 32-bit multiply helper is linked; the quotient needs 16, so two 8-bit steps of long division do.
 */
u16 hw_battery_mv(u16 raw10)
{
    u16 rem;
    u32 p;

    if (raw10 > 1023)
        raw10 = 1023;
    p = ((u32)(u16)(raw10 * 43u) << 8) - (u16)(raw10 * 11u);
    rem = (u16)(p >> 16); /* at most 171, below the divisor as rcx_udiv8 requires */
    return rcx_udiv8(rcx_udiv8((u16)p, 390, &rem), 390, &rem);
}

/*
 * TMR0 clocks from fastest to slowest (§3.7 table: TCR clock select, STCR.ICKS0), each as 15625 Hz << shift, with
 * the lowest tone it can make with an 8-bit TCORA (the rounded clock / 2 hz at most 256: clock / 513, plus one).
 * The fastest usable clock gives the finest steps: the clocks are at most 4 apart, so TCORA + 1 ends up at 64 or
 * more and no tone is off by more than 0.8 %.
 */
static const struct {
    u16 min_hz;
    u8 shift, tcr;
} tone_clock[6] = {
    { 15595, 9, 0x09 },        /* φ/2,    8 MHz (CKS 01, ICKS0 1) */
    { 3899, 7, 0x09 },         /* φ/8,    2 MHz (CKS 01, ICKS0 0) */
    { 975, 5, 0x0A },          /* φ/32, 500 kHz (CKS 10, ICKS0 1) */
    { 488, 4, 0x0A },          /* φ/64, 250 kHz (CKS 10, ICKS0 0) */
    { 122, 2, 0x0B },          /* φ/256, 62.5 kHz (CKS 11, ICKS0 1) */
    { 31, 0, 0x0B },           /* φ/1024, 15.6 kHz (CKS 11, ICKS0 0) */
};

u8 hw_tone(u16 hz, struct hw_tone *t)
{
    u8 i = 0;
    u16 rem;
    u32 n;

    if (hz < 31 || hz > 20000)
        return 0; /* the ROM's play-tone range; outside it a rest */
    while (hz < tone_clock[i].min_hz)
        i++;
    /* TCORA + 1 = clock / (2 hz), rounded; below 257, so its 16 bits come out of two long-division steps. */
    n = ((u32)15625 << tone_clock[i].shift) + hz;
    rem = (u16)(n >> 16);
    t->tcora = (u8)(rcx_udiv8(rcx_udiv8((u16)n, (u16)(2 * hz), &rem), (u16)(2 * hz), &rem) - 1);
    t->tcr = tone_clock[i].tcr; /* 08 = clear on compare match A, plus the clock select */
    t->icks0 = (u8)(i & 1 ? 0 : 1);
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
    u8 fast = (u8)(mode & HAL_IR_76KHZ);

    c->tcr = 0x09;
    if (mode & HAL_IR_DUTY25) {
        c->tcsr = 0x16; /* output 1 on A, 0 on B (bit 4 reads as 1) */
        c->tcora = fast ? 25 : 53;
        c->tcorb = fast ? 6 : 13;
    } else {
        c->tcsr = 0x13; /* toggle on A */
        c->tcora = fast ? 12 : 26;
        c->tcorb = 0xFF;
    }
}

/*
 * A change is accepted once the same buttons have differed from the accepted state for HW_DEBOUNCE_MS samples in a
 * row; any bounce back, or another button changing meanwhile, starts the count again.
 */
u8 hw_debounce(struct hw_debounce *d, u8 raw)
{
    u8 diff = (u8)(raw ^ d->state);

    if (diff != d->cand) {
        d->cand = diff;
        d->count = 0;
    }
    if (!diff || ++d->count < HW_DEBOUNCE_MS)
        return 0;
    d->state = raw;
    d->cand = 0;
    d->count = 0;
    return diff;
}

/*
 * PCF8566 commands (§3.6): MODE SET 48 = enabled, 1:4 multiplex, 1/3 bias (40 = disabled); DEVICE SELECT E0 =
 * sub-address 0; LOAD DATA POINTER 2i = image byte i. Bit 7 of a command means another command follows; the last
 * one has it clear and display bytes follow, the data pointer advancing by itself. Every update sends the mode and
 * the whole image (0.5 ms): the display engine calls only when something changed, and a controller that lost its
 * state for any reason is set right by the next update.
 */
#define LCD_ADDRESS 0x7C
#define LCD_MODE_ON 0x48
#define LCD_MODE_OFF 0x40
#define LCD_SELECT 0x60
#define LCD_MORE 0x80

u8 hw_lcd_on_frame(const u8 *image, u8 *frame)
{
    u8 i;

    frame[0] = LCD_ADDRESS;
    frame[1] = LCD_MORE | LCD_MODE_ON;
    frame[2] = LCD_MORE | LCD_SELECT;
    frame[3] = 0;
    for (i = 0; i < HW_LCD_BYTES; i++)
        frame[4 + i] = image[i];
    return 4 + HW_LCD_BYTES;
}

u8 hw_lcd_off_frame(u8 *frame)
{
    frame[0] = LCD_ADDRESS;
    frame[1] = LCD_MODE_OFF;
    return 2;
}

/* When the ring is full the newest byte stays and is marked bad: the IR layer then drops the packet it was in. */
void hw_rx_put(struct hw_rx *r, u8 byte, u8 error)
{
    u8 i = r->head;

    if ((u8)(i - r->tail) >= HW_RX_SIZE) {
        r->error[(u8)(i - 1) & (HW_RX_SIZE - 1)] = 1;
        return;
    }
    r->data[i & (HW_RX_SIZE - 1)] = byte;
    r->error[i & (HW_RX_SIZE - 1)] = error;
    r->head = (u8)(i + 1);
}

/* The slot is read completely before `tail` frees it for the interrupt. */
u8 hw_rx_get(struct hw_rx *r, u8 *byte)
{
    u8 i = r->tail, got;

    if (i == r->head)
        return 0;
    *byte = r->data[i & (HW_RX_SIZE - 1)];
    got = (u8)(r->error[i & (HW_RX_SIZE - 1)] ? 2 : 1);
    r->tail = (u8)(i + 1);
    return got;
}
