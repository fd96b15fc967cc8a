/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The narrow door to the hardware. Everything behind it is a port: drivers/ on the brick, host_sim/ on the host.
 *
 * Outputs go out through these calls; inputs (A/D samples, IR bytes, button edges, battery) come in through the
 * runtime's rt_* functions (src/runtime.h), so data flows one way. Every call names the brick, so the host can run
 * several; the brick's port keeps its own per-brick data behind rcx.port (the machine never touches it).
 * A port may define any of these as a macro or static inline in its own header instead of a function.
 */
#ifndef RCX_HAL_H
#define RCX_HAL_H

#include "rcx_types.h"

struct rcx;

/* Motors: the effective output of port 0-2 (A-C). The driver makes the 8 ms PWM pattern of `level` 0-7
 * (rcx-hardware.md §3.2: level n is on for n+1 ms of every 8). */
enum hal_motor_mode { HAL_MOTOR_FLOAT = 0, HAL_MOTOR_REV = 1, HAL_MOTOR_FWD = 2, HAL_MOTOR_BRAKE = 3 };
void hal_motor(struct rcx *b, u8 port, u8 mode, u8 level);

/* Sensor power for active sensors (light, rotation) on input 0-2. The driver removes it around each conversion. */
void hal_sensor_power(struct rcx *b, u8 input, u8 on);

/* Sound: a square wave of `hz` (31-20 000) until the next call; 0 = silence. Timing is the caller's. */
void hal_sound(struct rcx *b, u16 hz);

/* LCD: show a 9-byte segment image, bit n of byte k = segment k.n of rcx-hardware.md §3.6. */
#define HAL_LCD_BYTES 9
void hal_lcd(struct rcx *b, const u8 *image);

/* IR: queue bytes for transmission, at the line settings of `mode`. hal_ir_busy() is non-zero while bytes are
 * still going out; the receiver hears the brick's own echo, which the runtime ignores. */
#define HAL_IR_4800 0x01     /* 4800 baud instead of 2400 */
#define HAL_IR_76KHZ 0x02    /* carrier 76 kHz instead of 38 kHz */
#define HAL_IR_DUTY25 0x04   /* carrier duty 25 % instead of 50 % */
void hal_ir_send(struct rcx *b, const u8 *data, u8 len, u8 mode);
u8 hal_ir_busy(struct rcx *b);
void hal_ir_range(struct rcx *b, u8 far); /* 0 short, 1 long range */

/* Power: standby until On-Off is pressed (returns after wake-up, everything re-initialised by the port), and the
 * hand-back to the ROM for a firmware download (does not return on the brick). */
void hal_power_off(struct rcx *b);
void hal_enter_rom(struct rcx *b);

#endif
