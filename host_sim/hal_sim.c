/* SPDX-License-Identifier: MPL-2.0 */
/*
 * hal.h for the virtual RCX: outputs become trace lines, IR bytes go into the simulated room, and the two power
 * calls switch the brick's mode in the main loop.
 *
 * hal_power_off() returns at once here (one thread runs every brick); the brick is then left alone - no ticks, no
 * byte codes, receiver off - until On-Off is pressed in the script.
 */
#include "sim.h"
#include "hal.h"

const char *const sim_motor_dirs[4] = { "float", "rev", "fwd", "brake" }; /* by enum hal_motor_mode */

void hal_motor(struct rcx *b, u8 port, u8 mode, u8 level)
{
    struct sim_brick *sb = sim_brick_of(b);
    unsigned char v = (unsigned char)((mode & 3u) << 3 | (level & 7u));
    if (port >= 3 || sb->motor[port] == v)
        return;
    sb->motor[port] = v;
    trace_line(sb, "\"motor\":\"%c\",\"dir\":\"%s\",\"level\":%u", 'A' + port, sim_motor_dirs[mode & 3u], level & 7u);
}

void hal_sensor_power(struct rcx *b, u8 input, u8 on)
{
    struct sim_brick *sb = sim_brick_of(b);
    if (input >= 3 || sb->sensor_power[input] == (on != 0))
        return;
    sb->sensor_power[input] = on != 0;
    trace_line(sb, "\"sensor_power\":%u,\"on\":%s", input + 1u, on ? "true" : "false");
}

void hal_sound(struct rcx *b, u16 hz)
{
    struct sim_brick *sb = sim_brick_of(b);
    if (hz == sb->sound_hz)
        return;
    trace_flush_sound(sb);
    sb->sound_hz = hz;
    sb->sound_start = sb->sim->room.now;
}

void hal_lcd(struct rcx *b, const u8 *image)
{
    struct sim_brick *sb = sim_brick_of(b);
    char num[16], prog[2], hex[2 * HAL_LCD_BYTES + 1];
    unsigned i, same = sb->lcd_known;

    for (i = 0; i < HAL_LCD_BYTES; i++) {
        same &= sb->lcd[i] == image[i];
        sb->lcd[i] = image[i];
        sprintf(hex + 2 * i, "%02x", image[i]);
    }
    if (same)
        return;
    sb->lcd_known = 1;
    trace_lcd_number(image, num, prog);
    trace_line(sb, "\"lcd\":\"%s\",\"num\":\"%s\",\"prog\":\"%s\"", hex, num, prog);
}

void hal_ir_send(struct rcx *b, const u8 *data, u8 len, u8 mode)
{
    struct sim_brick *sb = sim_brick_of(b);
    char hex[2 * 255 + 1];
    unsigned i;

    room_send(&sb->sim->room, &sb->port, data, len, mode);
    sb->ir_out += len;
    for (i = 0; i < len; i++)
        sprintf(hex + 2 * i, "%02x", data[i]);
    hex[2 * len] = 0;
    if (mode)
        trace_line(sb, "\"ir\":\"%s\",\"mode\":%u", hex, mode);
    else
        trace_line(sb, "\"ir\":\"%s\"", hex);
}

u8 hal_ir_busy(struct rcx *b)
{
    return (u8)room_busy(&sim_brick_of(b)->port);
}

void hal_ir_range(struct rcx *b, u8 far)
{
    struct sim_brick *sb = sim_brick_of(b);
    if (sb->range == far)
        return;
    sb->range = far;
    trace_line(sb, "\"range\":\"%s\"", far ? "far" : "near");
}

void hal_power_off(struct rcx *b)
{
    struct sim_brick *sb = sim_brick_of(b);
    sb->mode = SIM_STANDBY;
    trace_line(sb, "\"power\":\"standby\"");
}

void hal_enter_rom(struct rcx *b)
{
    struct sim_brick *sb = sim_brick_of(b);
    sb->mode = SIM_ROM;
    rom_reset(sb);
    trace_line(sb, "\"rom\":\"boot mode\"");
}
