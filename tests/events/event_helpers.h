/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Helpers shared by the event tests (tests/unit/test_events.c, tests/events/test_calibration.c): direct commands
 * as a host sends them, inputs set by hand, and a watching task.
 *
 * Events are watched the way a program would: task 0 monitors all 16 (ENTER EV); when it is alerted its machine
 * has left EV and source 23 holds what fired. Input values are set by hand and handed to events_input(), as the
 * sensor engine does after each sample, so these tests do not depend on the sensor conversions.
 */
#ifndef TEST_EVENT_HELPERS_H
#define TEST_EVENT_HELPERS_H

#include "brick.h"
#include "access.h"

#define LO(x) ((u8)((unsigned)(x) & 0xFFu))
#define HI(x) ((u8)(((unsigned)(x) >> 8) & 0xFFu))

enum { PRESSED = 0, RELEASED = 1, PERIOD = 2, TRANSITION = 3, CHANGE_RATE = 7, LOW = 8, NORMAL = 9, HIGH = 10,
       CLICK = 11, DOUBLE = 12, MAILBOX = 14, CLEAR = 16 };
enum { SRC_TIMER0 = 3, SRC_MESSAGE = 7, SRC_COUNTER0 = 8 };
enum { S_LOW = 0, S_NORMAL = 1, S_HIGH = 2, S_UNDEFINED = 3, S_CAL_START = 4, S_CAL_BUSY = 5 };

static inline void cmd(struct rcx *b, const u8 *bytes, unsigned len) { brick_cmd(b, bytes, len, NULL); }

static inline s16 poll(struct rcx *b, u8 src, u8 index)
{
    u8 c[3] = { 0x12, src, index }, reply[RCX_REPLY_MAX];
    assert_int_equal(brick_cmd(b, c, 3, reply), 3);
    return (s16)(u16)(reply[1] | reply[2] << 8);
}

static inline void set_source(struct rcx *b, u8 src, u8 index, s16 value)
{
    u8 c[6] = { 0x05, src, index, 2, LO(value), HI(value) };
    cmd(b, c, 6);
}

static inline void set_event(struct rcx *b, u8 ev, u8 sensor, u8 type)
{
    u8 c[4] = { 0x93, ev, sensor, type };
    cmd(b, c, 4);
}

static inline void limits(struct rcx *b, u8 ev, s16 lower, s16 upper, s16 hyst)
{
    set_source(b, 29, ev, lower);
    set_source(b, 28, ev, upper);
    set_source(b, 30, ev, hyst);
}

static inline void sensor_mode(struct rcx *b, u8 n, u8 mode)
{
    u8 c[3] = { 0x42, n, mode };
    cmd(b, c, 3);
}

/* Input n now reads `value` / `boolean` (and `raw`): what the sensor engine leaves after a sample. */
static inline void input(struct rcx *b, u8 n, s16 value, u8 boolean, u16 raw)
{
    b->sensor[n].value = value;
    b->sensor[n].boolean = boolean;
    b->sensor[n].raw = raw;
    events_input(b, n);
}

static inline void counter(struct rcx *b, u8 n, s16 value) { set_source(b, 21, n, value); }

static inline void ms(struct rcx *b, unsigned n)
{
    while (n--)
        vm_tick(b);
}

static inline void arm(struct rcx *b)
{
    b->task[0].ev.events = 0;
    brick_enter_ev(b, &b->task[0], 0xFFFF, 0x40);
}

/* The events that alerted the watching task since the last call (0: none), watching again afterwards. */
static inline u16 fired(struct rcx *b)
{
    u16 f = b->task[0].ev.state == ACCESS_NONE ? (u16)poll(b, 23, 0) : 0;
    arm(b);
    return f;
}

static inline struct rcx *brick(void)
{
    struct rcx *b = brick_new();
    arm(b);
    return b;
}


#endif
