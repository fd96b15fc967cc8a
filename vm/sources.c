/* SPDX-License-Identifier: MPL-2.0 */
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
    u8 limits;      /* bits 0-5 highest index (RCX_ANY: the index is the value; UP_TO_255), LIMIT_EXISTS,
                       LIMIT_WRITABLE */
};
#define SHAPE_WORD 0x20     /* a 16-bit field, else 8-bit unsigned */
#define SHAPE_STORE 0x40    /* a write stores any value as it is (message and counters then tell the events) */
#define SHAPE_FIELD 0x80    /* read straight from the field (without it, the place serves writes only) */
#define LIMIT_EXISTS 0x40
#define LIMIT_WRITABLE 0x80
RCX_STATIC_ASSERT(any_fits_limits, RCX_ANY == 0x3F); /* (and no source's highest index is 62: UP_TO_255) */
RCX_STATIC_ASSERT(rows_37_44, RCX_SOURCE_COUNT == (RCX_SWAN ? RCX_SRC_GLOBAL_IND + 1 : RCX_SRC_INDIRECT + 1));

#define R LIMIT_EXISTS
#define RW (LIMIT_EXISTS | LIMIT_WRITABLE)
#define SW LIMIT_WRITABLE /* exists only for a Swan program's tasks (row(): swan) */
#define UP_TO_255 0x3E /* highest index 255: the variables of Swan's build (var_ref() decides further) */
#define VAR_MAX (RCX_SWAN ? UP_TO_255 : 47) /* sources 0 and 36 (and 43-44, which have their row) */
#define STORE SHAPE_STORE
#define RCX_MEMBER(m) (((struct rcx *)0)->m)
#define COMPUTED 0, 0
#define PLACE(field, elem, store)                                                                   \
    (u16)offsetof(struct rcx, field),                                                              \
    (u8)(sizeof RCX_MEMBER(elem) | (sizeof RCX_MEMBER(field) == 2 ? SHAPE_WORD : 0) | (store))
#define FIELD(field, elem, store) PLACE(field, elem, (store) | SHAPE_FIELD)

/* Rows 0-36. Sources 37-44 (Swan's build) are computed and take any index, as Constant (37-42, read-only) and
 * Variable (43-44, writable) do: row() gives those rows for them. After the rows, Swan's message parameter, source 15
 * index 1: a word beside the message, a row of its own (stride 0: index 1 is the field itself), which row() gives
 * for that index. */
#define ROWS (RCX_SRC_INDIRECT + 1)
#define MSG_PARAM_ROW ROWS
static const struct source_row rows[ROWS + RCX_SWAN] = {
#define RCX_SRC_ROWS /* (sources.def: no rows for 37-44) */
#define RCX_SRC(num, id, name, max, access, place) [num] = { place, (u8)((max) | (access)) },
#include "sources.def"
#undef RCX_SRC
#undef RCX_SRC_ROWS
#if RCX_SWAN
    [MSG_PARAM_ROW] = { (u16)offsetof(struct rcx, msg_param), SHAPE_WORD | SHAPE_STORE | SHAPE_FIELD, 1 | SW },
#endif
};

/* The row of a source that exists for the asker (task t; NULL: a host) at an index in range; NULL otherwise. For the
 * task of a Swan program (rcx.swan: decided when its download completed) Swan's sources (SW) exist too. A write needs
 * LIMIT_WRITABLE besides. */
static const struct source_row *row(const struct rcx *b, const struct rcx_task *t, u8 src, u16 index)
{
    const struct source_row *r;
    u8 max, limits;
    if (src >= RCX_SOURCE_COUNT)
        return NULL;
#if RCX_SWAN
    if (src >= ROWS)
        src = src >= RCX_SRC_GLOBAL ? RCX_SRC_VAR : RCX_SRC_CONST;
    else if (src == RCX_SRC_MESSAGE && index) /* (its row's limit is 1) */
        src = MSG_PARAM_ROW;
#endif
    r = &rows[src];
    limits = r->limits;
    if (!(limits & LIMIT_EXISTS) && !(RCX_SWAN && (limits & LIMIT_WRITABLE) && t && b->swan[b->prog]))
        return NULL;
    max = (u8)(limits & RCX_ANY);
    if (max != RCX_ANY && index > (max == UP_TO_255 ? 0xFFu : max))
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

/* 0-31 the globals; from a task 32-47 its locals (globals 32 + 16 t ... in an RCX 2.0 program, the globals themselves
 * in a Swan one: t->local_base) and 48-255 the globals, in both (swan-target.md 4). */
s16 *var_ref(struct rcx *b, const struct rcx_task *t, u16 n)
{
    if (n >= RCX_GLOBALS) {
        if (!t || n >= RCX_ALL_GLOBALS)
            return NULL;
        if (n < RCX_VARS)
            n = (u16)(n + t->local_base);
    }
    return &b->global[n];
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

/* The variable a VAR, INDIRECT, GLOBAL or GLOBAL_IND source names (the indirect ones: the one whose number variable
 * `index` holds); NULL when there is none. 43/44 are Swan's globals: from any task, and a host, without the overlay.
 * The source comes in the high byte and the index in the low one (the caller checks it is below 256): with three
 * arguments the H8/300 passes all of them in registers. */
static s16 *var_of(struct rcx *b, const struct rcx_task *t, u16 src_index)
{
    u8 src = (u8)(src_index >> 8);
    u16 n = (u8)src_index;

    if (RCX_SWAN && src >= RCX_SRC_GLOBAL)
        t = b->task;                   /* any task: 48-255 are the globals; 32-47 of task 0 too (local_base 0) */
    if (src == RCX_SRC_INDIRECT || (RCX_SWAN && src == RCX_SRC_GLOBAL_IND)) {
        const s16 *v = var_ref(b, t, n);
        if (!v)
            return NULL;
        n = (u16)*v;
    }
    return var_ref(b, t, n);
}
#define IS_VARIABLE(src) ((src) == RCX_SRC_VAR || (src) == RCX_SRC_INDIRECT || (RCX_SWAN && (src) >= RCX_SRC_GLOBAL))
RCX_STATIC_ASSERT(event_fields, offsetof(struct rcx_event, source) == 0 && offsetof(struct rcx_event, type) == 1);
RCX_STATIC_ASSERT(variable_sources, RCX_SRC_GLOBAL_IND == RCX_SRC_GLOBAL + 1 && RCX_SRC_GLOBAL_IND == 44);

#if RCX_SWAN
/* Datalog read-back (37-42, firm0332): the type or value of entry n, or byte n; entry 0 is the header (type 0xFF,
 * entries used including it). The even sources take n itself, the odd ones (NQC's "Ind") from variable n, which the
 * caller reads. */
static s16 log_read(const struct rcx *b, u8 src, u16 n)
{
    const u8 *log = b->arena + b->obj_start[RCX_OBJS];
    u16 used = b->log_count;

    if (src < RCX_SRC_LOG_BYTE_IND) {  /* entry n: from here on its first byte */
        if (n >= used)
            return 0;
        n = (u16)(n * 3u);
        if (src >= RCX_SRC_LOG_VALUE_IND)
            return (s16)RCX_LE16(log + n + 1);
    } else if (n >= (u16)(used * 3u)) {
        return 0;
    }
    return log[n];
}

/* Swan's system settings (24) that OpenRCX has; -1 for the others, which keep what was written (SHAPE_STORE). */
static s16 system_live(struct rcx *b, const struct rcx_task *t, u8 i)
{
    if (i == 0)
        return (s16)b->battery_mv;
    if (i == 3)                        /* (only a task asks: source 24 is a Swan program's) */
        return (s16)(t - b->task);
    if (i == 13)
        return b->tx_range;
    if (i == 20)
        return b->power_down_min;
    if (i == 31)
        return vm_sounding(b) ? 1 : 0;
    if (i == 33)
        return b->sound.count;
    if (i == 38)
        return b->log_size ? (s16)(b->log_size - 1) : 0;
    return -1;
}
#endif

#if RCX_SWAN
/*
 * Swan's motor powers (5 signed, 16 0-127, 32 0-7; 7 brake power is only kept): each source keeps what was written
 * through it (its field), and the output's RCX 2.0 power becomes the nearest of the 8 levels, level = (p x 7 + 63) /
 * 127 on the 128 scale, a signed one's direction too (0 keeps it). Values beyond the scale give the end of it.
 */
static const u8 motor_bit[RCX_MOTORS] = { 1, 2, 4 }; /* 1 << motor, without a shift loop */
static void swan_power(struct rcx *b, u8 src, u8 motor, s16 value)
{
    u16 m = (u16)value;                /* the magnitude */
    u8 p;
    u16 change;

    if (value < 0) {
        if (src != RCX_SRC_POWER_SIGNED)
            return;
        m = (u16)(0u - m);
    }
    p = m < 127 ? (u8)m : 127;         /* (else the end of the scale) */
    if (src != RCX_SRC_POWER8)
        p = (u8)((u16)(p * 57u + 454u) >> 10); /* = (p x 7 + 63) / 127 for every p 0-127: no division helper */
    else if (p > 7)
        p = 7;
    change = OUTPUTS_CHANGE(RCX_MOTOR_POWER, p);
    if (src == RCX_SRC_POWER_SIGNED && value)
        change |= OUTPUTS_CHANGE(RCX_MOTOR_FWD, value > 0 ? RCX_MOTOR_FWD : 0);
    outputs_update(b, motor_bit[motor], change);
}

/* A system setting (24) was written: it is kept (and read back if OpenRCX has no such setting: system_live()); those
 * OpenRCX has that a program may change take it too (13 IR range 0/1, 20 power-down minutes, 38 a new datalog). Out
 * of line: source_set() is then short enough for more of its jumps to be short ones. */
static __attribute__((noinline)) void system_write(struct rcx *b, u8 i, s16 value)
{
    if (i == 38) {
        if (value >= 0)
            datalog_set(b, (u16)value);
    } else if (i == 13) {
        if ((u16)value <= 1)
            b->tx_range = (u8)value;
    } else if (i == 20) {
        if ((u16)value <= 0xFF) {
            b->power_down_min = (u8)value;
            b->idle_reset = 1;
        }
    }
}
#endif

s16 source_get(struct rcx *b, const struct rcx_task *t, u8 src, u16 index)
{
    const struct source_row *r;
    const s16 *v;
    const u8 *p;

    if (src == RCX_SRC_CONST)          /* by far the commonest sources: no table look-up */
        return (s16)index;
    if ((src == RCX_SRC_VAR && index < RCX_GLOBALS) || (RCX_SWAN && src == RCX_SRC_GLOBAL && index < RCX_ALL_GLOBALS))
        return b->global[index];
    if ((r = row(b, t, src, index)) == NULL)
        return 0;
    p = field(b, r, index);            /* (a computed source's row may name a field too) */
    /* The computed sources, in the order that gave the shortest code (the variables before 37-42). */
#if RCX_SWAN
    if (src == RCX_SRC_SYSTEM) {
        s16 live = system_live(b, t, (u8)index);
        if (live >= 0)
            return live;
    }
#endif
    if (r->shape & SHAPE_FIELD)
        return (r->shape & SHAPE_WORD) ? *(const s16 *)(const void *)p : (s16)*p;
    if (IS_VARIABLE(src)) {
        v = var_of(b, t, (u16)(src << 8 | index)); /* (rows: index below 256) */
        return v ? *v : 0;
    }
    if (src == RCX_SRC_RANDOM) {
        /* 0..index inclusive; a range below 1 gives 0. */
        if ((s16)index <= 0)
            return 0;
        return (s16)(next_random(b) % (u16)(index + 1));
    }
    if (src == RCX_SRC_GLOBAL_MOTOR)
        return outputs_global_status(b, (u8)index);
    if (src == RCX_SRC_MOTOR)
        return outputs_status(b, (u8)index);
#if RCX_SWAN
    if (src >= RCX_SRC_LOG_TYPE_IND) {
        if (src & 1) {                 /* (n from variable n) */
            v = var_ref(b, t, index);
            index = v ? (u16)*v : 0xFFFFu; /* no such variable: no such entry */
        }
        return log_read(b, src, index);
    }
    if (src == RCX_SRC_MS_TIMER)       /* the field is the base */
        return (s16)((u16)(b->ms_now - *(const u16 *)(const void *)p) & 0x7FFF);
#endif
    if (src == RCX_SRC_TASK_EVENTS) {
        u8 i = (u8)index, size = sizeof *t; /* two byte variables: one mulxu; b->task[index] calls __mulhi3 */

        if (index == RCX_TASKS) /* index 10: the asking task's own events, as nqc reads CurrentEvents() */
            return t ? (s16)t->ev.events : 0;
        return (s16)((const struct rcx_task *)((const u8 *)b->task + (u16)(i * size)))->ev.events;
    }
#if RCX_SWAN
    if (src == RCX_SRC_EVENT_SRC)      /* EST_*; 16 (EST_SENSOR_UNUSED) when the event is cleared */
        return *p ? (s16)(*p - 1) : 16;
#endif
    if (src == RCX_SRC_TIMER10)
        /* 10 x the 100 ms count plus the 10 ms steps into the current 100 ms tick (reference-firmware.md). */
        return (s16)((u16)(*(const u16 *)(const void *)p * 10u + b->step10) & 0x7FFF);
    return RCX_FIRMWARE_VERSION;       /* the last source without a field */
}

/* Poll (0x12 source index): a source, index or variable that does not exist for a direct command (no task: no
 * locals) answers 0x8000, as firm0328 does (reference-firmware.md). */
s16 source_poll(struct rcx *b, const u8 *cmd)
{
    u8 src = cmd[1], index = cmd[2];

    /* 0: 0-31; 36: 0-47 (32-47 read 0 from a host), as firm0328 answers (the rows allow more for a Swan task) */
    if ((src == RCX_SRC_VAR && index >= RCX_GLOBALS) || (RCX_SWAN && src == RCX_SRC_INDIRECT && index >= RCX_VARS)
        || !row(b, NULL, src, index))
        return (s16)-32768;
    return source_get(b, NULL, src, index);
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

    if ((r = row(b, t, src, index)) == NULL || !(r->limits & LIMIT_WRITABLE))
        return;
    /* Tested one by one: a switch here costs a 74-byte jump table. */
    if (src == RCX_SRC_RANDOM) {
        if (index == 0) /* writing random 0 seeds the generator */
            b->random = (u16)value ? (u16)value : 0xACE1;
        return;
    }
    if (IS_VARIABLE(src)) {
        if ((v = var_of(b, t, (u16)(src << 8 | index))) != NULL) /* (rows: index below 256) */
            *v = value;
        return;
    }
#if RCX_SWAN
    if (src == RCX_SRC_POWER_SIGNED || src == RCX_SRC_POWER128 || src == RCX_SRC_POWER8)
        swan_power(b, src, (u8)index, value); /* (then stored: read back as written) */
#endif
    /* Thresholds, click counter, UART buffer, message and counters (SHAPE_STORE) take any value; the rest none
     * below 0, and those of a byte (program, sensor type and mode, event type and source) none above 255. Then each
     * source in turn, in the order that gives the shortest code. */
    if (!(r->shape & SHAPE_STORE)) {
        if (value < 0 || (!(r->shape & SHAPE_WORD) && value > 0xFF))
            return;
        if (src == RCX_SRC_PROGRAM) {
            if (value < RCX_PROGRAMS)
                sched_select_program(b, (u8)value, t != NULL);
            return;
        }
        if (src == RCX_SRC_WATCH) {
            if (value >= 24 * 60)
                return;
            b->watch_ms = 0;
        }
        if (src == RCX_SRC_SENSOR_TYPE || src == RCX_SRC_SENSOR_MODE) {
            if (src == RCX_SRC_SENSOR_TYPE) /* two calls: tests/firmware/check_stack.sh follows no pointer */
                sensor_set_type(b, (u8)index, (u8)value);
            else
                sensor_set_mode(b, (u8)index, (u8)value);
            return;
        }
#if RCX_SWAN
        if (src == RCX_SRC_MS_TIMER)   /* its field is the base it counts from */
            value = (s16)(b->ms_now - (u16)value);
        if (src == RCX_SRC_EVENT_TYPE || src == RCX_SRC_EVENT_SRC) {
            /* SetEvent with the other of the two as it is; the rows' fields are event[index].type and .source */
            const struct rcx_event *e = &b->event[(u8)index];
            u8 k = e->source ? (u8)(e->source - 1) : 0, type = e->type;
            if (src == RCX_SRC_EVENT_SRC)
                k = (u8)value;
            else
                type = (u8)value;
            events_set(b, (u8)index, k, type); /* (it checks the rest) */
            return;
        }
#endif
        /* A duration is 50 ms - 327 s (5-32767); timers and hysteresis "must be non-negative". */
        if (src == RCX_SRC_DURATION && value < 5)
            return;
        if (src == RCX_SRC_TIMER10)
            value = (s16)((u16)value / 10u);
    }
    p = field(b, r, index);
    if (r->shape & SHAPE_WORD)
        *(s16 *)(void *)p = value;
    else
        *p = (u8)value;
    if (src == RCX_SRC_MESSAGE && (!RCX_SWAN || !index)) /* (index 1: Swan's parameter, no event) */
        events_message_changed(b);
#if RCX_SWAN
    if (src == RCX_SRC_SYSTEM)
        system_write(b, (u8)index, value);
#endif
    if (src == RCX_SRC_COUNTER)
        events_counter_changed(b, (u8)index);
    /* A threshold or the hysteresis of an input's event may have moved: its next sample is looked at. Asked of any
     * store here, which costs fewer bytes than the test and no more than an extra look (which changes nothing). */
    events_look_again(b);
}
