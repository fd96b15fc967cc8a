/* SPDX-License-Identifier: MPL-2.0 */
/*
 * A recording implementation of hal.h for host tests: every output call is remembered per brick (rcx.port), so a
 * test can assert exactly what the hardware would have been told.
 */
#ifndef TEST_FAKE_HAL_H
#define TEST_FAKE_HAL_H

#include "rcx_types.h"
#include "hal.h"

#define FAKE_LOG 256
#define FAKE_IR_LOG 2048 /* several framed replies: a memory map alone is 383 bytes on the air */

struct fake_hal {
    u8 motor_mode[3], motor_level[3];  /* last hal_motor() per port */
    u16 motor_calls;
    u8 sensor_power[3];
    u16 sound_hz;                      /* current tone, 0 = silent */
    u16 sound_log[FAKE_LOG];           /* every hal_sound() argument, in order */
    u16 sound_calls;
    u8 lcd[HAL_LCD_BYTES];
    u16 lcd_calls;
    u8 ir[FAKE_IR_LOG];                /* every byte handed to hal_ir_send(), in order */
    u16 ir_len;
    u8 ir_mode;                        /* mode of the last hal_ir_send() */
    u8 ir_busy;                        /* what hal_ir_busy() answers */
    u8 ir_far;
    u16 power_offs, rom_entries;
};

/* The fake of a brick made by brick_new() (tests/support/brick.h). */
struct fake_hal *fake_hal_of(struct rcx *b);

#endif
