/*
 * Sensor processing (spec pp. 52-53, sources 9-13; rcx-hardware.md §3.3): types, modes, slopes, conversions.
 * Raw samples arrive once per millisecond per input through sensor_sample().
 */
#ifndef RCX_SENSORS_H
#define RCX_SENSORS_H

#include "rcx_types.h"

struct rcx;

struct rcx_sensor {
    u8 type;        /* source 10: 0 none, 1 touch, 2 temperature, 3 light, 4 rotation */
    u8 mode;        /* source 11: mode in bits 5-7, slope in bits 0-4 */
    u16 raw;        /* source 12: last 10-bit sample */
    s16 value;      /* source 9 */
    u8 boolean;     /* source 13 */
};

void sensor_set_type(struct rcx *b, u8 n, u8 type); /* SetSensorType: type and its default mode */
void sensor_set_mode(struct rcx *b, u8 n, u8 mode); /* SetSensorMode */
void sensor_clear(struct rcx *b, u8 n);              /* ClearSensorValue */
void sensor_sample(struct rcx *b, u8 n, u16 raw);    /* a new 10-bit sample of input n, every 1 ms */

#endif
