/*
 * Reading and writing parameter sources (spec pp. 6-10). Out-of-range indices and unknown sources read as 0 and
 * are never written: a byte code can reach no memory outside the machine through a source.
 */
#include "rcx.h"
#include "sources.h"

/*
 * One 4-byte row per source number: where a plain source lives in the brick (most sources are an array of fields
 * read as they are), and what index range and access the spec allows. One generic reader serves the plain ones;
 * the few computed ones are tested for one by one (a switch would cost the H8/300 a jump table and long branches).
 */
struct source_row {
    u16 offset;     /* of the field for index 0 */
    u8 shape;       /* bits 0-4 stride between indices, SHAPE_WORD, SHAPE_STORE, SHAPE_FIELD */
    u8 limits;      /* bits 0-5 highest index (RCX_ANY: the index is the value), LIMIT_EXISTS, LIMIT_WRITABLE */
};
#define SHAPE_WORD 0x20     /* a 16-bit field, else 8-bit unsigned */
#define SHAPE_STORE 0x40    /* a write stores the value as it is */
#define SHAPE_FIELD 0x80    /* read straight from the field */
#define LIMIT_EXISTS 0x40
#define LIMIT_WRITABLE 0x80
RCX_STATIC_ASSERT(any_fits_limits, RCX_ANY == 0x3F);

#define R LIMIT_EXISTS
#define RW (LIMIT_EXISTS | LIMIT_WRITABLE)
#define STORE SHAPE_STORE
#define RCX_MEMBER(m) (((struct rcx *)0)->m)
#define COMPUTED 0, 0
#define FIELD(field, elem, store)                                                                   \
    (u16)offsetof(struct rcx, field),                                                              \
    (u8)(sizeof RCX_MEMBER(elem) | (sizeof RCX_MEMBER(field) == 2 ? SHAPE_WORD : 0) | (store) | SHAPE_FIELD)

static const struct source_row rows[RCX_SOURCE_COUNT] = {
#define RCX_SRC(num, id, name, max, access, place) [num] = { place, (u8)((max) | (access)) },
#include "sources.def"
#undef RCX_SRC
};

/* The row of a source whose index is in range and whose access allows `need`; NULL otherwise. */
static const struct source_row *row(u8 src, u16 index, u8 need)
{
    const struct source_row *r;
    u8 max;
    if (src >= RCX_SOURCE_COUNT)
        return NULL;
    r = &rows[src];
    max = (u8)(r->limits & RCX_ANY);
    if ((r->limits & need) != need || (max != RCX_ANY && index > max))
        return NULL;
    return r;
}

/* The field of a plain source at an index already checked (<= 47: an 8-bit multiply). */
static u8 *field(struct rcx *b, const struct source_row *r, u16 index)
{
    return (u8 *)b + r->offset + (u8)index * (u8)(r->shape & 0x1F);
}

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
    const struct source_row *r;
    const s16 *v;
    const u8 *p;

    if (src == RCX_SRC_CONST)          /* by far the commonest sources: no table look-up */
        return (s16)index;
    if (src == RCX_SRC_VAR && index < RCX_GLOBALS)
        return b->global[index];
    if ((r = row(src, index, LIMIT_EXISTS)) == NULL)
        return 0;
    if (r->shape & SHAPE_FIELD) {
        p = field(b, r, index);
        return (r->shape & SHAPE_WORD) ? *(const s16 *)(const void *)p : (s16)*p;
    }
    if (src == RCX_SRC_VAR || src == RCX_SRC_INDIRECT) {
        v = var_ref(b, (struct rcx_task *)t, index);
        if (v && src == RCX_SRC_INDIRECT)
            v = var_ref(b, (struct rcx_task *)t, (u16)*v);
        return v ? *v : 0;
    }
    if (src == RCX_SRC_MOTOR)
        return outputs_status(b, (u8)index);
    if (src == RCX_SRC_GLOBAL_MOTOR)
        return outputs_global_status(b, (u8)index);
    if (src == RCX_SRC_RANDOM) {
        /* 0..index inclusive; a range below 1 gives 0. */
        if ((s16)index <= 0)
            return 0;
        return (s16)(next_random(b) % (u16)(index + 1));
    }
    if (src == RCX_SRC_TASK_EVENTS) {
        if (index == RCX_TASKS) /* index 10: the asking task's own events, as nqc reads CurrentEvents() */
            return t ? (s16)t->ev.events : 0;
        return (s16)b->task[index].ev.events;
    }
    if (src == RCX_SRC_TIMER10)
        /* 10 x the 100 ms count plus the 10 ms steps into the current 100 ms tick (reference-firmware.md). */
        return (s16)((u16)(b->timer[index] * 10u + b->step10) & 0x7FFF);
    return RCX_FIRMWARE_VERSION;       /* the last source without a field */
}

/* Poll (0x12 source index): a source, index or variable that does not exist for a direct command (no task: no
 * locals) answers 0x8000, as firm0328 does (reference-firmware.md). */
s16 source_poll(struct rcx *b, const u8 *cmd)
{
    u8 src = cmd[1], index = cmd[2];

    if (!row(src, index, LIMIT_EXISTS) || (src == RCX_SRC_VAR && index >= RCX_GLOBALS))
        return (s16)-32768;
    return source_get(b, NULL, src, index);
}

void source_set(struct rcx *b, struct rcx_task *t, u8 src, u16 index, s16 value)
{
    const struct source_row *r;
    s16 *v;
    u8 *p;

    if ((r = row(src, index, LIMIT_EXISTS | LIMIT_WRITABLE)) == NULL)
        return;
    p = field(b, r, index);
    if (r->shape & SHAPE_STORE) {      /* thresholds, click counter, UART buffer: stored as they are */
        if (r->shape & SHAPE_WORD)
            *(s16 *)(void *)p = value;
        else
            *p = (u8)value;
        return;
    }
    /* Tested one by one: a switch here costs a 74-byte jump table. */
    if (src == RCX_SRC_VAR || src == RCX_SRC_INDIRECT) {
        v = var_ref(b, t, index);
        if (v && src == RCX_SRC_INDIRECT)
            v = var_ref(b, t, (u16)*v);
        if (v)
            *v = value;
    } else if (src == RCX_SRC_TIMER || src == RCX_SRC_TIMER10) {
        if (value >= 0)
            b->timer[index] = src == RCX_SRC_TIMER ? (u16)value : (u16)((u16)value / 10u);
    } else if (src == RCX_SRC_RANDOM) {
        if (index == 0) /* writing random 0 seeds the generator */
            b->random = (u16)value ? (u16)value : 0xACE1;
    } else if (src == RCX_SRC_PROGRAM) {
        if (value >= 0 && value < RCX_PROGRAMS)
            sched_select_program(b, (u8)value, t != NULL);
    } else if (src == RCX_SRC_SENSOR_TYPE || src == RCX_SRC_SENSOR_MODE) {
        if (value >= 0 && value <= 0xFF) {
            if (src == RCX_SRC_SENSOR_TYPE)
                sensor_set_type(b, (u8)index, (u8)value);
            else
                sensor_set_mode(b, (u8)index, (u8)value);
        }
    } else if (src == RCX_SRC_WATCH) {
        if (value >= 0 && value < 24 * 60) {
            b->watch = (u16)value;
            b->watch_ms = 0;
        }
    } else if (src == RCX_SRC_MESSAGE) {
        b->message = (u8)value;
        events_message_changed(b);
    } else if (src == RCX_SRC_COUNTER) {
        b->global[index] = value;
        events_counter_changed(b, (u8)index);
    } else {
        /* Hysteresis "must be non-negative"; a duration is 50 ms - 327 s (5-32767). */
        if (value >= (src == RCX_SRC_DURATION ? 5 : 0))
            *(s16 *)(void *)p = value;
    }
}
