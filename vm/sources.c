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
#define SHAPE_STORE 0x40    /* a write stores any value as it is (message and counters then tell the events) */
#define SHAPE_FIELD 0x80    /* read straight from the field (without it, the place serves writes only) */
#define LIMIT_EXISTS 0x40
#define LIMIT_WRITABLE 0x80
RCX_STATIC_ASSERT(any_fits_limits, RCX_ANY == 0x3F);

#define R LIMIT_EXISTS
#define RW (LIMIT_EXISTS | LIMIT_WRITABLE)
#define STORE SHAPE_STORE
#define RCX_MEMBER(m) (((struct rcx *)0)->m)
#define COMPUTED 0, 0
#define PLACE(field, elem, store)                                                                   \
    (u16)offsetof(struct rcx, field),                                                              \
    (u8)(sizeof RCX_MEMBER(elem) | (sizeof RCX_MEMBER(field) == 2 ? SHAPE_WORD : 0) | (store))
#define FIELD(field, elem, store) PLACE(field, elem, (store) | SHAPE_FIELD)

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

/* The field of a plain source at an index already checked (<= 47). Both factors are byte variables so that gcc
 * multiplies with one mulxu instead of calling __mulhi3; inlined, it leaves source_get() a register to spare. */
static inline __attribute__((always_inline)) u8 *field(struct rcx *b, const struct source_row *r, u16 index)
{
    u8 stride = r->shape;

    stride &= 0x1F;
    return (u8 *)b + r->offset + (u16)((u8)index * stride);
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

/* The variable a VAR or INDIRECT source names (INDIRECT: the one whose number variable `index` holds); NULL when
 * there is none. The source comes in the high byte and the index (<= 47, checked) in the low one: with three
 * arguments the H8/300 passes all of them in registers. */
static s16 *var_of(struct rcx *b, struct rcx_task *t, u16 src_index)
{
    s16 *v = var_ref(b, t, (u8)src_index);

    if (v && (u8)(src_index >> 8) == RCX_SRC_INDIRECT)
        v = var_ref(b, t, (u16)*v);
    return v;
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
        v = var_of(b, (struct rcx_task *)t, (u16)(src << 8 | index));
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
        u8 i = (u8)index, size = sizeof *t; /* two byte variables: one mulxu; b->task[index] calls __mulhi3 */

        if (index == RCX_TASKS) /* index 10: the asking task's own events, as nqc reads CurrentEvents() */
            return t ? (s16)t->ev.events : 0;
        return (s16)((const struct rcx_task *)((const u8 *)b->task + (u16)(i * size)))->ev.events;
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

    if (src == RCX_SRC_VAR ? index < RCX_GLOBALS : row(src, index, LIMIT_EXISTS) != NULL)
        return source_get(b, NULL, src, index);
    return (s16)-32768;
}

/*
 * The checks come first and the store is shared: most writable sources end in storing the value (or, for the fast
 * timer, a tenth of it) at their place, as a word or a byte by the row.
 */
void source_set(struct rcx *b, struct rcx_task *t, u8 src, u16 index, s16 value)
{
    const struct source_row *r;
    s16 *v;
    u8 *p;

    if ((r = row(src, index, LIMIT_EXISTS | LIMIT_WRITABLE)) == NULL)
        return;
    /* Tested one by one: a switch here costs a 74-byte jump table. */
    if (src == RCX_SRC_VAR || src == RCX_SRC_INDIRECT) {
        if ((v = var_of(b, t, (u16)(src << 8 | index))) != NULL)
            *v = value;
        return;
    }
    if (src == RCX_SRC_RANDOM) {
        if (index == 0) /* writing random 0 seeds the generator */
            b->random = (u16)value ? (u16)value : 0xACE1;
        return;
    }
    /* Thresholds, click counter, UART buffer, message and counters (SHAPE_STORE) take any value; the rest none
     * below 0. */
    if (!(r->shape & SHAPE_STORE)) {
        if (value < 0)
            return;
        if (src == RCX_SRC_PROGRAM) {
            if (value < RCX_PROGRAMS)
                sched_select_program(b, (u8)value, t != NULL);
            return;
        }
        if (src == RCX_SRC_SENSOR_TYPE || src == RCX_SRC_SENSOR_MODE) {
            if (value <= 0xFF) {
                if (src == RCX_SRC_SENSOR_TYPE) /* two calls: tests/firmware/check_stack.sh follows no pointer */
                    sensor_set_type(b, (u8)index, (u8)value);
                else
                    sensor_set_mode(b, (u8)index, (u8)value);
            }
            return;
        }
        if (src == RCX_SRC_TIMER10)
            value = (s16)((u16)value / 10u);
        if (src == RCX_SRC_WATCH) {
            if (value >= 24 * 60)
                return;
            b->watch_ms = 0;
        }
        /* A duration is 50 ms - 327 s (5-32767); timers and hysteresis "must be non-negative". */
        if (src == RCX_SRC_DURATION && value < 5)
            return;
    }
    p = field(b, r, index);
    if (r->shape & SHAPE_WORD)
        *(s16 *)(void *)p = value;
    else
        *p = (u8)value;
    if (src == RCX_SRC_MESSAGE)
        events_message_changed(b);
    if (src == RCX_SRC_COUNTER)
        events_counter_changed(b, (u8)index);
}
