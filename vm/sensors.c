/* Sensor types and modes. Value conversion from raw samples is owed to the sensor engine (engine_pending). */
#include "rcx.h"

/* Default mode for each sensor type (spec p. 52): raw, boolean, Celsius, percent, angle. */
static const u8 default_mode[5] = { 0x00, 0x20, 0xA0, 0x80, 0xE0 };

void sensor_set_type(struct rcx *b, u8 n, u8 type)
{
    if (n >= RCX_SENSORS || type >= sizeof default_mode)
        return;
    b->sensor[n].type = type;
    b->sensor[n].mode = default_mode[type];
    b->sensor[n].value = 0;
    b->sensor[n].boolean = 0;
    b->engine_pending++;
}

void sensor_set_mode(struct rcx *b, u8 n, u8 mode)
{
    if (n >= RCX_SENSORS)
        return;
    b->sensor[n].mode = mode;
    b->sensor[n].value = 0;
    b->engine_pending++;
}

void sensor_clear(struct rcx *b, u8 n)
{
    if (n >= RCX_SENSORS)
        return;
    b->sensor[n].value = 0;
    b->engine_pending++;
}

void sensor_sample(struct rcx *b, u8 n, u16 raw)
{
    if (n < RCX_SENSORS)
        b->sensor[n].raw = (u16)(raw & 0x3FF);
}
