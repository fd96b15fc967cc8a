/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Sensor processing (spec pp. 7, 30, 52-53, 102; sources 9-13; rcx-hardware.md §3.3): types, modes, slopes and the
 * conversions from raw samples. Raw samples arrive once per millisecond per input through sensor_scan().
 */
#ifndef RCX_SENSORS_H
#define RCX_SENSORS_H

#include "rcx_types.h"

struct rcx;

/*
 * Sensor types (source 10) and modes (source 11: mode in bits 5-7, slope in bits 0-4). The value (source 9) of each
 * mode: raw 0-1023; boolean 0/1 (source 13 itself); transitions: changes of the boolean counted; periods: completed
 * 1 -> 0 returns of the boolean (press and release of a touch sensor) counted; percent 0-100; Celsius and
 * Fahrenheit in tenths of a degree, SENSOR_TEMP_INVALID outside the table; angle: rotation steps, 16 per turn.
 * The counts start again from 0 with SetSensorMode and ClearSensorValue. Source 13 is computed in every mode: from
 * the level with slope 0, from the change rate with slope 1-31.
 */
enum sensor_type { SENSOR_NONE = 0, SENSOR_TOUCH, SENSOR_TEMPERATURE, SENSOR_LIGHT, SENSOR_ROTATION };
#define SENSOR_MODE_RAW 0x00
#define SENSOR_MODE_BOOL 0x20
#define SENSOR_MODE_TRANSITIONS 0x40
#define SENSOR_MODE_PERIODS 0x60
#define SENSOR_MODE_PERCENT 0x80
#define SENSOR_MODE_CELSIUS 0xA0
#define SENSOR_MODE_FAHRENHEIT 0xC0
#define SENSOR_MODE_ANGLE 0xE0
#define SENSOR_SLOPE 0x1F

/* Value of the temperature modes outside the range the conversion table covers (raw below 290 or above 927). */
#define SENSOR_TEMP_INVALID 0x7FFF

/* Dynamic measurement compares each sample with the one of this many milliseconds before (spec p. 102: dt = 3 ms). */
#define SENSOR_DT_MS 3

/* rcx_sensor.quiet: what the next sample can change. 0 at power-on, so the first sample is worked out in full. */
#define SENSOR_MOVING 0         /* anything: the last samples differ, or the value, mode or type was reset */
#define SENSOR_STEADY 0x8000    /* | raw: the last SENSOR_DT_MS samples were raw, so another one changes nothing */

struct rcx_sensor {
    u16 quiet;      /* SENSOR_MOVING, or SENSOR_STEADY | raw */
    s16 value;      /* source 9 */
    u16 raw;        /* source 12: last 10-bit sample, the newest of the change rate's history ... */
    u16 past[SENSOR_DT_MS - 1]; /* ... and the ones before it, oldest first */
    s16 lo, hi;     /* while the value stays above lo and below hi, the events that watch the input stay as they
                     * are and are not looked at (vm/events.c events_window(); hi -32768: they look at the next) */
    u8 type;        /* source 10 */
    u8 mode;        /* source 11 */
    u8 boolean;     /* source 13 */
    u8 phase;       /* rotation sensor phase 0-3 of the last valid sample */
    u8 watched;     /* how many events watch this input (kept by vm/events.c) ... */
    u8 number;      /* ... which input it is (set by vm/events.c once one does) ... */
    u8 others;      /* ... and, in sensor[0], how many watch a timer, the message or a counter */
    u8 late;        /* in sensor[0]: the samples being fed are late, newer ones wait (sensor_feed) */
};

void sensor_set_type(struct rcx *b, u8 n, u8 type); /* SetSensorType: type, its default mode, state reset */
struct rcx_sensor *sensor_set_mode(struct rcx *b, u8 n, u8 mode); /* SetSensorMode: value from 0; as sensor_clear */
struct rcx_sensor *sensor_clear(struct rcx *b, u8 n); /* ClearSensorValue; input n, NULL when there is none */
/* New 10-bit samples of the three inputs (raw[0] of input 1 ...), every 1 ms; then sensors_at_rest(). */
void sensor_scan(struct rcx *b, const u16 *raw);
void sensor_feed(struct rcx *b, struct rcx_sensor *s, u16 raw); /* one of them; sensor_sample(): of input n */
/* Nonzero (and so rcx.sensors_rest, until a type, mode, value or an event changes) when a sample of every input
 * equal to its last one would change nothing: all steady (rcx_sensor.quiet; the event engine marks an input moving
 * when its events want a sample). A port that sees its inputs unchanged may then skip sensor_scan() for them. */
u8 sensors_at_rest(struct rcx *b);
/* Also used by the brick's sensor_feed() in assembler (drivers/h8300/sensorfeed.S): the rotation sensor's phase of
 * raw / 64 (4: none), and the value of the temperature modes (mode without its slope). */
extern const u8 sensor_phase_of[16];
s16 sensor_temperature(u8 mode, u16 raw);

#endif
