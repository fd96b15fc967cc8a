/* SPDX-License-Identifier: MPL-2.0 */
#include "rcx.h"
#include "fake_hal.h"

struct fake_hal *fake_hal_of(struct rcx *b)
{
    return (struct fake_hal *)b->port;
}

void hal_motor(struct rcx *b, u8 port, u8 mode, u8 level)
{
    struct fake_hal *h = fake_hal_of(b);
    if (port < 3) {
        h->motor_mode[port] = mode;
        h->motor_level[port] = level;
    }
    h->motor_calls++;
}

void hal_sensor_power(struct rcx *b, u8 input, u8 on)
{
    if (input < 3)
        fake_hal_of(b)->sensor_power[input] = on;
}

void hal_sound(struct rcx *b, u16 hz)
{
    struct fake_hal *h = fake_hal_of(b);
    h->sound_hz = hz;
    if (h->sound_calls < FAKE_LOG)
        h->sound_log[h->sound_calls] = hz;
    h->sound_calls++;
}

void hal_lcd(struct rcx *b, const u8 *image)
{
    struct fake_hal *h = fake_hal_of(b);
    unsigned i;
    for (i = 0; i < HAL_LCD_BYTES; i++)
        h->lcd[i] = image[i];
    h->lcd_calls++;
}

void hal_ir_send(struct rcx *b, const u8 *data, u8 len, u8 mode)
{
    struct fake_hal *h = fake_hal_of(b);
    unsigned i;
    for (i = 0; i < len && h->ir_len < FAKE_IR_LOG; i++)
        h->ir[h->ir_len++] = data[i];
    h->ir_mode = mode;
}

u8 hal_ir_busy(struct rcx *b)
{
    return fake_hal_of(b)->ir_busy;
}

void hal_ir_range(struct rcx *b, u8 far)
{
    fake_hal_of(b)->ir_far = far;
}

void hal_power_off(struct rcx *b)
{
    fake_hal_of(b)->power_offs++;
}

void hal_enter_rom(struct rcx *b)
{
    fake_hal_of(b)->rom_entries++;
}
