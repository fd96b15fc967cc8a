/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The register-level logic of the brick's drivers, kept apart from the register writes so that the host can test
 * it against rcx-hardware.md: PWM patterns, A/D mapping, battery, tone dividers, baud rate and carrier, debounce,
 * LCD command bytes and the IR receive ring. Compiled into the firmware and into tests/drivers/.
 */
#ifndef RCX_HW_H
#define RCX_HW_H

#include "rcx_types.h"

/* Motors (§3.2). One latch byte for all three outputs, two bits each; speed is an 8 ms on/off pattern per level. */
extern const u8 hw_pwm_pattern[8];
struct hw_motors {
    u8 latch[8];    /* the latch byte of each millisecond of the 8, all outputs together: a setting is worked out
                     * here once, so that the tick interrupt only has to look its byte up */
    u8 phase;       /* the millisecond of the 8 that comes next (0-7) */
};
void hw_motor_set(struct hw_motors *m, u8 port, u8 mode, u8 level);
/* The latch byte for the next millisecond: what the tick interrupt does (drivers/h8300/irq.s), for the host. */
static inline u8 hw_motor_step(struct hw_motors *m)
{
    u8 latch = m->latch[m->phase & 7];

    m->phase = (u8)((m->phase + 1) & 7);
    return latch;
}

/* A/D (§3.3, §3.4). Inputs are numbered 0-2 as in hal.h (brick inputs 1-3) and wired in reverse. */
#define HW_AD_BATTERY 3                                /* AN3 */
#define hw_ad_channel(input) ((u8)(2 - (input)))       /* input 0 = AN2 ... input 2 = AN0 */
extern const u8 hw_sensor_power_bit[3];             /* input 0 = P6.2 ... input 2 = P6.0 */
#define hw_ad_raw10(addr) ((u16)((addr) >> 6))         /* the result sits in bits 15-6 */
u16 hw_battery_mv(u16 raw10);

/* Sound on TMR0 (§3.7): f = clock / (2 (TCORA + 1)), the fastest clock that keeps TCORA within 8 bits. */
struct hw_tone {
    u8 tcr;     /* clear on match A | clock select */
    u8 tcora;
    u8 icks0;   /* STCR bit 0 */
};
u8 hw_tone(u16 hz, struct hw_tone *t); /* 0: out of range (31-20 000 Hz), play silence */

/* IR (§3.8): SCI baud rate and the TMR1 carrier for hal_ir_send's mode bits. */
struct hw_carrier {
    u8 tcr, tcsr, tcora, tcorb;
};
u8 hw_sci_brr(u8 mode);
void hw_carrier(u8 mode, struct hw_carrier *c);

/* Buttons (§3.5): On-Off, Run, View, Prgm as bits 0-3 (the order of enum rt_button), 1 = pressed. */
#define HW_BUTTONS 4
#define HW_DEBOUNCE_MS 10
#define hw_buttons(p4, p7) ((u8)((((u8)~(p4) >> 1) & 3) | (((u8)~(p7) >> 4) & 0x0C)))
struct hw_debounce {
    u8 state;   /* accepted button bits */
    u8 cand;    /* differing bits being timed */
    u8 since;   /* the clock (ms, modulo 256) when `cand` was first seen */
};
/* A look at the buttons at `now` (ms, modulo 256): the bits that changed state, 0 most of the time. */
u8 hw_debounce(struct hw_debounce *d, u8 raw, u8 now);

/* LCD (§3.6): PCF8566 at bus address 7C. A frame is the byte sequence between START and STOP. */
#define HW_LCD_BYTES 9
#define HW_LCD_FRAME_MAX (4 + HW_LCD_BYTES)
/* PCF8566 commands (§3.6): MODE SET 48 = enabled, 1:4 multiplex, 1/3 bias (40 = disabled); DEVICE SELECT E0 =
 * sub-address 0; LOAD DATA POINTER 2i = image byte i. Bit 7 of a command means another command follows; the last
 * one has it clear and display bytes follow, the data pointer advancing by itself. */
#define HW_LCD_ADDRESS 0x7C
#define HW_LCD_MODE_ON 0x48
#define HW_LCD_MODE_OFF 0x40
#define HW_LCD_SELECT 0x60
#define HW_LCD_MORE 0x80
u8 hw_lcd_on_frame(const u8 *image, u8 *frame); /* enable, then the whole image */
/* Display off (standby). Inline: its one caller on the brick stores two bytes for less than a call costs. */
static inline u8 hw_lcd_off_frame(u8 *frame)
{
    frame[0] = HW_LCD_ADDRESS;
    frame[1] = HW_LCD_MODE_OFF;
    return 2;
}
void hw_lcd_send(const u8 *frame, u8 n); /* lcdbus.c: START, the bytes, STOP; the bus must idle with SCL, SDA high */

/* IR receive ring (§3.8): filled by the receive interrupts, drained by the main loop. */
#define HW_RX_SIZE 32 /* a power of two; 130 ms of bytes at 2400 Bd, where the main loop comes by every few ms */
struct hw_rx { /* volatile: one side runs in an interrupt, the other must see each slot before freeing it */
    volatile u8 head, tail;             /* free-running: head - tail bytes waiting */
    volatile u8 data[HW_RX_SIZE];
    volatile u8 error[HW_RX_SIZE];      /* non-zero: that byte came with a parity, framing or overrun error */
};
void hw_rx_put(struct hw_rx *r, u8 byte, u8 error);
u8 hw_rx_get(struct hw_rx *r, u8 *byte);  /* 0 empty, 1 byte, 2 byte with error (or bytes lost before it) */

#endif
