/*
 * Reading and writing parameter sources (spec pp. 6-10). Out-of-range indices and unknown sources read as 0 and
 * are never written: a byte code can reach no memory outside the machine through a source.
 */
#include "rcx.h"
#include "sources.h"

#define R 0
#define RW 1
const struct rcx_source_info rcx_sources[RCX_SOURCE_COUNT] = {
#define RCX_SRC(num, id, name, max, access) [num] = { max, 1, access },
#include "sources.def"
#undef RCX_SRC
};
#undef R
#undef RW

s16 *var_ref(struct rcx *b, struct rcx_task *t, u16 n)
{
    if (n < RCX_GLOBALS)
        return &b->global[n];
    if (t && n < RCX_VARS)
        return &t->local[n - RCX_GLOBALS]; /* 32-47 are the asking task's locals */
    return NULL;
}

/* Next value of a 16-bit xorshift generator (period 65535; state never 0). */
static u16 next_random(struct rcx *b)
{
    u16 x = b->random;
    x ^= (u16)(x << 7);
    x ^= (u16)(x >> 9);
    x ^= (u16)(x << 8);
    b->random = x;
    return x;
}

s16 source_get(struct rcx *b, const struct rcx_task *t, u8 src, u16 index)
{
    const s16 *v;

    if (src == RCX_SRC_CONST)          /* by far the commonest source: no table look-up */
        return (s16)index;
    if (src >= RCX_SOURCE_COUNT || !rcx_sources[src].exists || index > rcx_sources[src].max)
        return 0;
    switch (src) {
    case RCX_SRC_VAR:
        v = var_ref(b, (struct rcx_task *)t, index);
        return v ? *v : 0;
    case RCX_SRC_TIMER:
        return (s16)b->timer[index];
    case RCX_SRC_CONST:
        return (s16)index;
    case RCX_SRC_MOTOR:
        return outputs_status(b, (u8)index);
    case RCX_SRC_RANDOM:
        /* 0..index inclusive; a range below 1 gives 0. */
        if ((s16)index <= 0)
            return 0;
        return (s16)(next_random(b) % (u16)(index + 1));
    case RCX_SRC_PROGRAM:
        return b->prog;
    case RCX_SRC_SENSOR_VALUE:
        return b->sensor[index].value;
    case RCX_SRC_SENSOR_TYPE:
        return b->sensor[index].type;
    case RCX_SRC_SENSOR_MODE:
        return b->sensor[index].mode;
    case RCX_SRC_SENSOR_RAW:
        return (s16)b->sensor[index].raw;
    case RCX_SRC_SENSOR_BOOL:
        return b->sensor[index].boolean;
    case RCX_SRC_WATCH:
        return (s16)b->watch;
    case RCX_SRC_MESSAGE:
        return b->message;
    case RCX_SRC_GLOBAL_MOTOR:
        return outputs_global_status(b, (u8)index);
    case RCX_SRC_COUNTER:
        return b->global[index];
    case RCX_SRC_TASK_EVENTS:
        if (index == RCX_TASKS) /* index 10: the asking task's own events, as nqc reads CurrentEvents() */
            return t ? (s16)t->ev.events : 0;
        return (s16)b->task[index].ev.events;
    case RCX_SRC_EVENT_STATE:
        return b->event[index].state;
    case RCX_SRC_TIMER10:
        /* 10 x the 100 ms count plus the 10 ms steps into the current 100 ms tick (reference-firmware.md). */
        return (s16)((u16)(b->timer[index] * 10u + b->step10) & 0x7FFF);
    case RCX_SRC_CLICKS:
        return b->event[index].clicks;
    case RCX_SRC_UPPER:
        return b->event[index].upper;
    case RCX_SRC_LOWER:
        return b->event[index].lower;
    case RCX_SRC_HYSTERESIS:
        return b->event[index].hysteresis;
    case RCX_SRC_DURATION:
        return b->event[index].duration;
    case RCX_SRC_UART:
        return b->uart[index];
    case RCX_SRC_BATTERY:
        return (s16)b->battery_mv;
    case RCX_SRC_FIRMWARE:
        return RCX_FIRMWARE_VERSION;
    case RCX_SRC_INDIRECT:
        v = var_ref(b, (struct rcx_task *)t, index);
        if (!v)
            return 0;
        v = var_ref(b, (struct rcx_task *)t, (u16)*v);
        return v ? *v : 0;
    }
    return 0;
}

void source_set(struct rcx *b, struct rcx_task *t, u8 src, u16 index, s16 value)
{
    s16 *v;

    if (src >= RCX_SOURCE_COUNT || !rcx_sources[src].writable || index > rcx_sources[src].max)
        return;
    switch (src) {
    case RCX_SRC_VAR:
        v = var_ref(b, t, index);
        if (v)
            *v = value;
        break;
    case RCX_SRC_TIMER:
        if (value >= 0)
            b->timer[index] = (u16)value;
        break;
    case RCX_SRC_RANDOM:
        if (index == 0) /* writing random 0 seeds the generator */
            b->random = (u16)value ? (u16)value : 0xACE1;
        break;
    case RCX_SRC_PROGRAM:
        if (value >= 0 && value < RCX_PROGRAMS)
            sched_select_program(b, (u8)value, t != NULL);
        break;
    case RCX_SRC_SENSOR_TYPE:
        if (value >= 0 && value <= 0xFF)
            sensor_set_type(b, (u8)index, (u8)value);
        break;
    case RCX_SRC_SENSOR_MODE:
        if (value >= 0 && value <= 0xFF)
            sensor_set_mode(b, (u8)index, (u8)value);
        break;
    case RCX_SRC_WATCH:
        if (value >= 0 && value < 24 * 60) {
            b->watch = (u16)value;
            b->watch_ms = 0;
        }
        break;
    case RCX_SRC_MESSAGE:
        b->message = (u8)value;
        events_message_changed(b);
        break;
    case RCX_SRC_COUNTER:
        b->global[index] = value;
        events_counter_changed(b, (u8)index);
        break;
    case RCX_SRC_TIMER10:
        if (value >= 0)
            b->timer[index] = (u16)((u16)value / 10u);
        break;
    case RCX_SRC_CLICKS:
        b->event[index].clicks = value;
        break;
    case RCX_SRC_UPPER:
        b->event[index].upper = value;
        break;
    case RCX_SRC_LOWER:
        b->event[index].lower = value;
        break;
    case RCX_SRC_HYSTERESIS:
        if (value >= 0) /* "must be non-negative" */
            b->event[index].hysteresis = value;
        break;
    case RCX_SRC_DURATION:
        if (value >= 5) /* 50 ms - 327 s */
            b->event[index].duration = value;
        break;
    case RCX_SRC_UART:
        b->uart[index] = (u8)value;
        break;
    case RCX_SRC_INDIRECT:
        v = var_ref(b, t, index);
        if (v && (v = var_ref(b, t, (u16)*v)) != NULL)
            *v = value;
        break;
    }
}
