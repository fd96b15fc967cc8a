/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Sensor processing: every millisecond each input's raw sample becomes its boolean (source 13) and, by mode, its
 * value (source 9). Conversions and thresholds are rcx-hardware.md §3.3 and reference-firmware.md "Sensors".
 *
 * Most samples repeat the ones before (an input with nothing connected, a sensor at rest): once the last
 * SENSOR_DT_MS samples are equal, another equal one cannot change anything, and sensor_sample() returns at once
 * (rcx_sensor.quiet). Only the samples worked out in full are told to the events that watch the input, and only when
 * the value is no longer between lo and hi (vm/events.c events_window()): an event whose input did not move, or moved
 * where nothing can happen to it, costs nothing, and a still input is at rest (sensors_at_rest()) like one no event
 * watches. The event engine marks an input moving when its events want the next sample whatever it gives.
 */
#include "rcx.h"
#include "hal.h"

/* Default mode of each type (spec p. 52): raw, boolean, Celsius, percent, angle. */
static const u8 default_mode[] = {
    SENSOR_MODE_RAW, SENSOR_MODE_BOOL, SENSOR_MODE_CELSIUS, SENSOR_MODE_PERCENT, SENSOR_MODE_ANGLE
};

/* Absolute boolean: 45 % / 55 % of full scale with the band between as hysteresis (spec p. 7). */
#define BOOL_ON_BELOW 460
#define BOOL_OFF_ABOVE 562

/*
 * Percent = (1023 - raw) * 25 / 156, with everything below 393 shown as 100. firm0328 switches at 391 and so reads
 * 101 for raw 391 and 392 (reference-firmware.md); a percentage above 100 is a defect no program can want, so the
 * switch point is moved to where the formula itself reaches 100.
 */
#define PERCENT_FULL_BELOW 393

/*
 * Temperature in tenths of a degree Celsius: trunc((raw * k + d) / 100) on seven straight pieces (rcx-hardware.md
 * §3.3, the rows below are its table's raw start, k and d). The product needs 18 bits, so each row is turned at
 * compile time into 16-bit terms: with B = d + start * k = 100 * q + f (0 <= f < 100) and Y = (raw - start) * -k +
 * 100 - f, the value is E = q + 1 - Y / 100, less one when Y is not a multiple of 100 and E > 0 (trunc toward 0).
 */
struct temp_piece {
    u16 start;      /* first raw value of the piece */
    s16 base;       /* q + 1 */
    u8 slope;       /* -k - 100 (k is -107 ... -261) */
    u8 frac;        /* 100 - f */
};
#define TEMP_B(start, k, d) ((long)(d) + (long)(start) * (k))
#define TEMP_F(start, k, d) ((TEMP_B(start, k, d) % 100 + 100) % 100)
#define TEMP_PIECE(start, k, d) \
    { start, (s16)((TEMP_B(start, k, d) - TEMP_F(start, k, d)) / 100 + 1), (u8)(-(k) - 100), \
      (u8)(100 - TEMP_F(start, k, d)) }
#define TEMP_LOW 290   /* raw below this ... */
#define TEMP_HIGH 927  /* ... or above this has no temperature */
static const struct temp_piece temp_table[] = { /* from the top down */
    TEMP_PIECE(886, -175, 142600),
    TEMP_PIECE(790, -134, 106600),
    TEMP_PIECE(520, -107, 85200),
    TEMP_PIECE(478, -123, 93600),
    TEMP_PIECE(390, -144, 103500),
    TEMP_PIECE(340, -194, 123000),
    TEMP_PIECE(TEMP_LOW, -261, 145200),
};

/* raw: TEMP_LOW ... TEMP_HIGH */
static s16 celsius(u16 raw)
{
    const struct temp_piece *p = temp_table;
    u16 y, q;
    s16 e;

    while (raw < p->start)
        p++;
    y = (u16)((raw - p->start) * (p->slope + 100u) + p->frac);
    q = (u16)(y / 100);
    e = (s16)(p->base - (s16)q);
    if ((u8)((u8)y - (u8)q * 100u) && e > 0) /* y - 100 q is 0-99: low bytes suffice, an 8-bit multiply */
        e--;
    return e;
}

/*
 * Rotation sensor: four voltage levels per step, read as phases by raw value (rcx-hardware.md §3.3): 960-1023 phase 0,
 * 768-959 phase 1, 320-511 phase 2, 512-767 phase 3; below 320 is no valid level. 0-1-2-3-0 counts up, the reverse
 * down (the sign brickOS uses; firm0328's is not established); a jump of two phases cannot tell the direction and
 * counts nothing. Sampled every millisecond, a step per sample (1 000 steps/s, 62 turns/s) is still counted exactly.
 */
#define PHASE_NONE 4
/* The band edges 320, 512, 768 and 960 are all multiples of 64, so raw / 64 picks the phase. For a 10-bit raw that
 * is the high byte of raw * 4: two additions, where gcc shifts right in a six-step loop. */
const u8 sensor_phase_of[16] = { 4, 4, 4, 4, 4, 2, 2, 2, 3, 3, 3, 3, 1, 1, 1, 0 }; /* also read by sensorfeed.S */
static inline u8 rotation_phase(u16 raw)
{
    raw = (u16)(raw << 2);
    __asm__("" : "+r"(raw)); /* no code: keeps gcc from folding the two steps into raw >> 6, a six-step loop */
    return sensor_phase_of[(u8)(raw >> 8)];
}

struct rcx_sensor *sensor_clear(struct rcx *b, u8 n)
{
    struct rcx_sensor *s;

    if (n >= RCX_SENSORS)
        return NULL;
    s = &b->sensor[n];
    s->value = 0;
    events_look_again(b); /* the events saw the value and the boolean before (SetSensorType clears the boolean) */
    return s;
}

struct rcx_sensor *sensor_set_mode(struct rcx *b, u8 n, u8 mode)
{
    struct rcx_sensor *s = sensor_clear(b, n);

    if (s) {
        s->mode = mode;
        s->phase = rotation_phase(s->raw);
    }
    return s;
}

void sensor_set_type(struct rcx *b, u8 n, u8 type)
{
    struct rcx_sensor *s;
    u16 raw;

    if (type >= sizeof default_mode || !(s = sensor_set_mode(b, n, default_mode[type])))
        return;
    s->type = type;
    s->boolean = 0;
    /* A new type starts with no history: the change rate (and the rotation phase, sensor_set_mode) begin from the
     * latest sample. */
    raw = s->raw;
    s->past[0] = raw;
    s->past[1] = raw;
    /* Light and rotation sensors are active: they take their power from the input (rcx-hardware.md §3.3). */
    hal_sensor_power(b, n, type >= SENSOR_LIGHT);
}

/* The temperature modes, Celsius and Fahrenheit (mode without its slope): out of line, and called by
 * drivers/h8300/sensorfeed.S too. */
s16 sensor_temperature(u8 mode, u16 raw)
{
    s16 v;

    if (raw < TEMP_LOW || raw > TEMP_HIGH)
        return SENSOR_TEMP_INVALID;
    v = celsius(raw);
    if (mode == SENSOR_MODE_FAHRENHEIT)
        v = (s16)(v + v * 4 / 5 + 320); /* the reference's t * 18 / 10 + 320, same result (v * 4 / 5 has v's sign) */
    return v;
}

#ifdef __H8300__
/* On the brick sensor_feed() is drivers/h8300/sensorfeed.S (gcc 3.4's code for the C below took some 690 states a
 * moving sample, issue 21); the C here is its reference (tests/drivers/test_h8feed.c compares the two). */
#include "sensorfeed.h"
#include <stddef.h>
RCX_STATIC_ASSERT(sf_fields, offsetof(struct rcx_sensor, quiet) == SF_QUIET && offsetof(struct rcx_sensor, value)
                             == SF_VALUE && offsetof(struct rcx_sensor, raw) == SF_RAW
                             && offsetof(struct rcx_sensor, past) == SF_PAST && offsetof(struct rcx_sensor, lo) == SF_LO
                             && offsetof(struct rcx_sensor, hi) == SF_HI);
RCX_STATIC_ASSERT(sf_bytes, offsetof(struct rcx_sensor, mode) == SF_MODE
                            && offsetof(struct rcx_sensor, boolean) == SF_BOOLEAN
                            && offsetof(struct rcx_sensor, phase) == SF_PHASE
                            && offsetof(struct rcx_sensor, watched) == SF_WATCHED
                            && offsetof(struct rcx_sensor, number) == SF_NUMBER);
RCX_STATIC_ASSERT(sf_none, SF_WINDOW_NONE == EVENTS_WINDOW_NONE);
RCX_STATIC_ASSERT(sf_scan, sizeof(struct rcx_sensor) == SF_SIZE && offsetof(struct rcx, sensors_rest) == SF_REST
                           && RCX_SENSORS == 3 && SENSOR_MOVING == 0); /* and sensor_scan */
RCX_STATIC_ASSERT(sf_late, offsetof(struct rcx, sensor[0].late) == SF_LATE && EVENTS_KEY(1) == 2
                           && SENSOR_DT_MS == 3);
RCX_STATIC_ASSERT(sf_modes, SENSOR_MODE_PERCENT == 0x80 && SENSOR_MODE_ANGLE == 0xE0 && SENSOR_MODE_BOOL == 0x20
                            && SENSOR_MODE_TRANSITIONS == 0x40 && SENSOR_SLOPE == 0x1F && PHASE_NONE == 4
                            && BOOL_ON_BELOW == 460 && BOOL_OFF_ABOVE == 562 && SENSOR_STEADY == 0x8000);
#else
/* x * 25 / 156 for x = 1023 - raw, 0-630: x * 10503 / 65536, the same for every such x (25 / 156 = 0.1602564...,
 * 10503 / 65536 = 0.1602631...: the error stays below 1/156, the least fraction the exact quotient can have). Worked
 * out with the H8's 8 x 8 multiply on the bytes h and l of x, 10503 being 41 * 256 + 7:
 * x * 10503 / 65536 = h * 41 + (l * 41 + h * 7 + l * 7 / 256) / 256, each division rounded down. The division and
 * 16-bit multiply it replaces cost some 400 states a sample of a moving light sensor (issue 21). */
static s16 percent(u16 x)
{
    u8 l = (u8)x, h = (u8)(x >> 8);

    return (s16)((u16)h * 41u + (((u16)l * 41u + (u16)h * 7u + (((u16)l * 7u) >> 8)) >> 8));
}

/* The converting modes: percent, Celsius, Fahrenheit. */
static s16 converted(u8 mode, u16 raw)
{
    if (mode == SENSOR_MODE_PERCENT)
        return raw < PERCENT_FULL_BELOW ? 100 : percent(raw ^ 1023u); /* 1023 - raw */
    return sensor_temperature(mode, raw);
}

/*
 * Boolean of dynamic measurement (spec p. 102): near either end of the scale it follows the level; otherwise a rise
 * of more than `slope` within dt reads 0 and a fall of more than `slope` reads 1 (a falling raw value is a press),
 * anything slower leaves it as it was. The spec's "dU/dt < slope then TRUE" can only mean a fall steeper than slope:
 * read literally, every steady signal would be TRUE and no change would ever be detected.
 */
static u8 boolean_of(const struct rcx_sensor *s, u16 raw, u16 then)
{
    u8 slope = (u8)(s->mode & SENSOR_SLOPE);

    if (!slope) {
        if (raw < BOOL_ON_BELOW)
            return 1;
        if (raw > BOOL_OFF_ABOVE)
            return 0;
    } else {
        if (raw > 1023u - slope || (s16)(raw - then) > slope)
            return 0;
        if (raw < slope || (s16)(then - raw) > slope)
            return 1;
    }
    return s->boolean;
}

/* Angle mode: the count v moved by the step from the last valid sample's phase to raw's. The phase is followed in
 * this mode only (a light sensor's samples are spared the work); SetSensorMode and SetSensorType take it afresh from
 * the last sample. */
static s16 turn(struct rcx_sensor *s, s16 v, u16 raw)
{
    u8 phase = rotation_phase(raw), was = s->phase, d = (u8)((phase - was) & 3);

    if (phase == PHASE_NONE)
        return v;
    s->phase = phase;
    /* The change of phase (mod 4) since the last valid sample: 1 a step up, 3 a step down; a jump of two phases cannot
     * tell the direction and counts nothing. */
    if (was != PHASE_NONE && d & 1)
        v = (s16)(v + 2 - d);
    return v;
}

RCX_STATIC_ASSERT(sensor_dt_ms_is_3, SENSOR_DT_MS == 3); /* past[] is moved by hand below and in sensor_set_type() */

/* A sample is worked out only when raw changed or has not been the same for SENSOR_DT_MS samples yet
 * (rcx_sensor.quiet): one that may change something. */
void sensor_feed(struct rcx *b, struct rcx_sensor *s, u16 raw)
{
    u8 was, mode;
    s16 v;
    u16 then, last;

    raw |= SENSOR_STEADY;
    if (raw == s->quiet)
        return; /* steady: see sensor_scan() */
    then = s->past[0];
    last = s->raw; /* the samples of the last SENSOR_DT_MS ms, oldest first */
    s->quiet = raw;
    raw &= 0x3FF;
    s->past[0] = s->past[1];
    s->past[1] = last;
    if (raw != last || raw != s->past[0])
        s->quiet = SENSOR_MOVING;
    was = s->boolean;
    s->boolean = boolean_of(s, raw, then);
    v = s->value;
    mode = (u8)(s->mode & ~SENSOR_SLOPE);
    /* The modes of sensors that move all the time (light, rotation) first. */
    if (mode >= SENSOR_MODE_PERCENT) {
        if (mode != SENSOR_MODE_ANGLE)
            v = converted(mode, raw);
        else
            v = turn(s, v, raw);
    } else if (mode == SENSOR_MODE_RAW) {
        v = (s16)raw;
    } else if (mode == SENSOR_MODE_BOOL) {
        v = s->boolean;
    } else if (mode == SENSOR_MODE_TRANSITIONS) {
        v = (s16)(v + (s->boolean ^ was)); /* booleans are 0 or 1 */
    } else {                               /* periods */
        v = (s16)(v + (was > s->boolean)); /* a period ends at each 1 -> 0 */
    }
    s->value = v;
    s->raw = raw;
    /* A late sample (newer ones wait behind it: the brick fell behind) keeps its value and rotation step, but its
     * events are told only of the newest, which is worked out in full for them: an overloaded brick evaluates its
     * events less often and loses no rotation step (issue 21). */
    if (s->watched && (v <= s->lo || v >= s->hi)) {
        if (b->sensor[0].late) { /* the events look at the next sample, whatever it gives */
            s->quiet = SENSOR_MOVING;
            s->hi = -32768;
        } else {
            /* Something may happen to the events (events_input(), with the input at hand); then between lo and
             * hi nothing more can. */
            events_evaluate(b, s->watched, EVENTS_KEY(s->number));
            if (s->lo != EVENTS_WINDOW_NONE) /* (an event watches every sample: it still does) */
                events_window(b, s, EVENTS_KEY(s->number));
        }
    }
}

#endif /* __H8300__ */

/* On the brick sensor_scan() with sensors_at_rest() in it is in drivers/h8300/sensorfeed.S: the C is its reference. */
#ifndef __H8300__
/* A sample equal to the SENSOR_DT_MS ones before it changes nothing: the change rate is 0, and the rotation phase,
 * the boolean and the value are the ones the last of them gave (the boolean of a steady signal is a function of
 * the level and of the boolean before, and that function keeps its own result): sensor_feed() returns at once. One
 * call for the three inputs, as the brick's scan gives them (issue 21: a call a sample, through the runtime, cost some
 * 200 states). */
void sensor_scan(struct rcx *b, const u16 *raw)
{
    struct rcx_sensor *s = b->sensor;

    do
        sensor_feed(b, s, *raw++);
    while (++s < b->sensor + RCX_SENSORS);
    sensors_at_rest(b);
}

RCX_STATIC_ASSERT(moving_is_0, SENSOR_MOVING == 0 && RCX_SENSORS == 3);
u8 sensors_at_rest(struct rcx *b)
{
    u8 rest = 0;

    if (b->sensor[0].quiet && b->sensor[1].quiet && b->sensor[2].quiet)
        rest = 1;
    b->sensors_rest = rest;
    return rest;
}
#endif /* __H8300__ */
