/*
 * The event engine (spec pp. 63, 70-71, 74, 100-105; sources 25, 27-31): 16 events, each one sensor and one
 * event type, evaluated whenever its sensor may have changed. Monitoring tasks are told through the state
 * machine of vm/access.c.
 *
 * One evaluation works out everything that just happened to the event's sensor (as a set of event types: its
 * state moved, its boolean moved, a click completed...) and fires the event when its own type is in that set and
 * the spec's table of valid combinations allows the type on that kind of sensor.
 */
#include "rcx_string.h"
#include "rcx.h"
#include "access.h"

#define HAPPENED(type) ((u16)(1u << (type)))

/* Kinds of sensor, the columns of the "valid combinations" table (p. 101). */
#define K_ABS 0x01      /* input, absolute measurement (slope 0) */
#define K_DYN 0x02      /* input, dynamic measurement (slope 1-31) */
#define K_TIMER 0x04
#define K_MSG 0x08
#define K_COUNTER 0x10
#define K_ALL (K_ABS | K_DYN | K_TIMER | K_MSG | K_COUNTER)

/* Valid combinations (p. 101): per event type, the kinds of sensor it can happen on. */
static const u8 events_valid[RCX_EVENT_MAILBOX + 1] = {
    [RCX_EVENT_PRESSED] = K_ABS,
    [RCX_EVENT_RELEASED] = K_ABS,
    [RCX_EVENT_PERIOD] = K_ABS | K_DYN,
    [RCX_EVENT_TRANSITION] = K_ABS | K_DYN,
    [RCX_EVENT_CHANGE_RATE] = K_DYN,
    [RCX_EVENT_LOW] = K_ALL,
    [RCX_EVENT_NORMAL] = K_ALL,
    [RCX_EVENT_HIGH] = K_ALL,
    [RCX_EVENT_CLICK] = K_ALL,
    [RCX_EVENT_DOUBLE_CLICK] = K_ALL,
    [RCX_EVENT_MAILBOX] = K_MSG,
};

/* Default lower and upper thresholds set by SetEvent (p. 71; hysteresis is always 0): physical sensor modes 0-7
 * (bits 5-7 of the sensor mode), then the virtual sensors. */
#define VIRTUAL_TIMER 8
#define VIRTUAL_MESSAGE 9
#define VIRTUAL_COUNTER 10
static const s16 events_default[11][2] = {
    { 0, 1023 },        /* raw */
    { 0, 1 },           /* boolean */
    { 0, 32767 },       /* transition count */
    { 0, 32767 },       /* period count */
    { 0, 100 },         /* percent of full scale */
    { -200, 700 },      /* Celsius x 10 */
    { -40, 1580 },      /* Fahrenheit x 10 */
    { 0, 32767 },       /* angle steps */
    { 0, 32767 },       /* timer */
    { 0, 255 },         /* IR message */
    { -32768, 32767 },  /* counter */
};

/* Modes whose calibration adds a hysteresis taken from the raw samples (pp. 104-105): raw, percent (reflection),
 * Celsius and Fahrenheit (temperature). The raw-mode formula is lost from the spec (its page is missing); it is
 * taken to be the reflection one, since both work on the same A/D scale. */
#define CAL_HYSTERESIS_MODES 0x71u
#define CAL_SAMPLES_PHYSICAL 8  /* p. 74 */

/* Private flags of struct rcx_event. */
#define F_BOOL 0x01     /* last boolean seen (inputs) */
#define F_OUT 0x02      /* the state has left LOW: a click may be under way (click.left_low is its start) */
#define F_HIGH 0x04     /* ... and has reached HIGH since */
#define F_FIRST 0x08    /* a click waits for a second one to make a double click (click.last_click) */

static void clear(struct rcx_event *e)
{
    memset(e, 0, sizeof *e);
    e->type = RCX_EVENT_NONE;
    e->state = RCX_EVENT_STATE_UNDEFINED;
    e->duration = 15; /* 150 ms, the click default of p. 71 */
}

void events_init(struct rcx *b)
{
    events_clear_all(b);
}

/* Spec p. 25: tasks monitoring events are not told. */
void events_clear_all(struct rcx *b)
{
    struct rcx_event *e;
    for (e = b->event; e < b->event + RCX_EVENTS; e++)
        clear(e);
}

/* The row of events_default for a sensor, which also picks its calibration formula. */
static u8 sensor_class(const struct rcx *b, u8 source)
{
    if (source < RCX_SENSORS)
        return (u8)(b->sensor[source].mode >> 5);
    if (source < RCX_EVENT_SRC_MESSAGE)
        return VIRTUAL_TIMER;
    return source == RCX_EVENT_SRC_MESSAGE ? VIRTUAL_MESSAGE : VIRTUAL_COUNTER;
}

void events_set(struct rcx *b, u8 ev, u8 source, u8 type)
{
    struct rcx_event *e;
    const s16 *d;

    if (ev >= RCX_EVENTS || source > RCX_EVENT_SRC_LAST)
        return;
    e = &b->event[ev];
    if (type != RCX_EVENT_NONE && (type > RCX_EVENT_MAILBOX || !events_valid[type]))
        return; /* 4-6, 13, 15 and above 16 are no event types */
    clear(e);
    if (type == RCX_EVENT_NONE)
        return;
    d = events_default[sensor_class(b, source)];
    e->source = source;
    e->type = type;
    e->lower = d[0];
    e->upper = d[1];
    /* Edges are counted from here on, not from whatever the input did before. */
    if (source < RCX_SENSORS && b->sensor[source].boolean)
        e->flags = F_BOOL;
}

void events_calibrate(struct rcx *b, u8 ev, u8 lower, u8 upper, u8 hyst)
{
    struct rcx_event *e;

    if (ev >= RCX_EVENTS || (e = &b->event[ev])->type == RCX_EVENT_NONE)
        return; /* a cleared event has no sensor to measure */
    e->state = RCX_EVENT_STATE_CAL_START;
    e->flags &= F_BOOL;
    memset(&e->u, 0, sizeof e->u);
    e->u.cal.pct[0] = lower;
    e->u.cal.pct[1] = upper;
    e->u.cal.pct[2] = hyst;
}

/* v * f / 256 rounded toward zero, in 16 bits with the H8's 8 x 8 multiply. */
static s16 fraction(s16 v, u8 f)
{
    u16 m = (u16)(v < 0 ? 0u - (u16)v : (u16)v);
    m = (u16)((u16)(u8)(m >> 8) * f + (((u16)(u8)m * f) >> 8));
    return (s16)(v < 0 ? 0u - m : m);
}

/* a + b, saturated to the 16-bit range. */
static s16 add_sat(s16 a, s16 b)
{
    s16 r = (s16)(u16)((u16)a + (u16)b);
    if ((a ^ r) & (b ^ r) & 0x8000)
        r = a < 0 ? -32768 : 32767;
    return r;
}

/* One calibration sample (pp. 74, 103-105). UT = Avg + Avg*UTFct/k1 (+ H), LT = Avg - Avg*LTFct/k1 (- H),
 * H = AvgRaw*HFct/k2 for the raw-scale modes and 0 otherwise; k1 = 256, k2 = 2048 (H is (AvgRaw*HFct/256)/8).
 * The average of 8 is kept as the sum of value/8 plus the sum of the remainders, which stays within 16 bits. */
static void calibrate_sample(struct rcx *b, struct rcx_event *e, s16 avg)
{
    u8 mode = sensor_class(b, e->source);
    s16 h = 0;

    e->state = RCX_EVENT_STATE_CAL_BUSY;
    if (mode < 8) {
        e->u.cal.sum8 = (s16)(e->u.cal.sum8 + (avg >> 3));
        e->u.cal.rem = (u8)(e->u.cal.rem + (avg & 7));
        e->u.cal.raw_sum = (u16)(e->u.cal.raw_sum + b->sensor[e->source].raw);
        if (++e->u.cal.count < CAL_SAMPLES_PHYSICAL)
            return;
        avg = (s16)(e->u.cal.sum8 + (e->u.cal.rem >> 3));
        if ((CAL_HYSTERESIS_MODES >> mode) & 1)
            h = (s16)((u16)fraction((s16)(e->u.cal.raw_sum >> 3), e->u.cal.pct[2]) >> 3);
    }
    e->lower = add_sat(add_sat(avg, (s16)-fraction(avg, e->u.cal.pct[0])), (s16)-h);
    e->upper = add_sat(add_sat(avg, fraction(avg, e->u.cal.pct[1])), h);
    e->hysteresis = h;
    e->flags &= F_BOOL;
    e->state = RCX_EVENT_STATE_UNDEFINED;
}

/* Click bookkeeping on a state change (p. 102): a click is LOW -> HIGH -> LOW within the duration; a double click
 * is a click that starts within the duration after the previous click ended. Returns what happened. */
static u16 click(struct rcx *b, struct rcx_event *e, u8 from, u8 to)
{
    u16 now = b->ticks10, happened = 0, dur = (u16)e->duration;

    if (from == RCX_EVENT_STATE_LOW) {
        e->u.click.left_low = now;
        e->flags = (u8)((e->flags & ~F_HIGH) | F_OUT);
    }
    if (to == RCX_EVENT_STATE_HIGH)
        e->flags |= F_HIGH;
    if (to == RCX_EVENT_STATE_LOW && (e->flags & (F_OUT | F_HIGH)) == (F_OUT | F_HIGH)) {
        if ((u16)(now - e->u.click.left_low) <= dur) {
            e->clicks = (s16)(u16)((u16)e->clicks + 1u);
            happened = HAPPENED(RCX_EVENT_CLICK);
            if ((e->flags & F_FIRST) && (u16)(e->u.click.left_low - e->u.click.last_click) <= dur) {
                happened |= HAPPENED(RCX_EVENT_DOUBLE_CLICK);
                e->flags &= (u8)~F_FIRST;
            } else {
                e->flags |= F_FIRST;
                e->u.click.last_click = now;
            }
        }
        e->flags &= (u8)~(F_OUT | F_HIGH);
    }
    return happened;
}

/* Evaluate event e against its sensor's present value; `happened` brings what the caller already knows (a
 * mailbox). Returns non-zero when the event fires. */
static u8 evaluate(struct rcx *b, struct rcx_event *e, u16 happened)
{
    u8 s = e->source, from = e->state, to, kind, type;
    s16 value, up, lo;
    u16 enter;

    if (s < RCX_SENSORS) {
        const struct rcx_sensor *in = &b->sensor[s];
        value = in->value;
        kind = (in->mode & 0x1F) ? K_DYN : K_ABS;
        if ((u8)(in->boolean != 0) != (e->flags & F_BOOL)) {
            e->flags ^= F_BOOL;
            happened |= HAPPENED(RCX_EVENT_TRANSITION) | HAPPENED(RCX_EVENT_CHANGE_RATE) |
                        ((e->flags & F_BOOL) ? HAPPENED(RCX_EVENT_PRESSED)
                                             : HAPPENED(RCX_EVENT_RELEASED) | HAPPENED(RCX_EVENT_PERIOD));
        }
    } else if (s < RCX_EVENT_SRC_MESSAGE) {
        value = (s16)b->timer[s - RCX_EVENT_SRC_TIMER];
        kind = K_TIMER;
    } else if (s == RCX_EVENT_SRC_MESSAGE) {
        value = b->message;
        kind = K_MSG;
    } else {
        value = b->global[s - RCX_EVENT_SRC_COUNTER];
        kind = K_COUNTER;
    }
    if (from >= RCX_EVENT_STATE_CAL_START) {
        calibrate_sample(b, e, value);
        return 0;
    }
    /* Hysteresis widens the range being left (reference-firmware.md): HIGH holds while value > upper - h, LOW while
     * value < lower + h. Moved thresholds stop at the 16-bit limits. */
    up = e->upper;
    lo = e->lower;
    if (from == RCX_EVENT_STATE_HIGH)
        up = add_sat(up, (s16)-e->hysteresis);
    else if (from == RCX_EVENT_STATE_LOW)
        lo = add_sat(lo, e->hysteresis);
    if (value > up) {
        to = RCX_EVENT_STATE_HIGH;
        enter = HAPPENED(RCX_EVENT_HIGH);
    } else if (value < lo) {
        to = RCX_EVENT_STATE_LOW;
        enter = HAPPENED(RCX_EVENT_LOW);
    } else {
        to = RCX_EVENT_STATE_NORMAL;
        enter = HAPPENED(RCX_EVENT_NORMAL);
    }
    if (to != from) {
        e->state = to;
        /* The first classification after SetEvent or a calibration is not a change of range. */
        if (from != RCX_EVENT_STATE_UNDEFINED)
            happened |= (u16)(enter | click(b, e, from, to));
    }
    for (type = e->type; type; type--)
        happened >>= 1;
    return (u8)(happened & 1 & (events_valid[e->type] & kind ? 1 : 0));
}

/* Evaluate every event on sensors from..to and tell the tasks. */
static void evaluate_sources(struct rcx *b, u8 from, u8 to, u16 happened)
{
    struct rcx_event *e = b->event;
    u16 bit, fired = 0;

    for (bit = 1; bit; bit <<= 1, e++)
        if (e->type != RCX_EVENT_NONE && e->source >= from && e->source <= to && evaluate(b, e, happened))
            fired |= bit;
    if (fired)
        events_raise(b, fired);
}

/* Spec p. 63: behave as if these events had happened. Every task monitoring one of them takes its EV exit; the
 * events that reached it are kept for source 23. */
void events_raise(struct rcx *b, u16 mask)
{
    struct rcx_task *t;

    for (t = b->task; t < b->task + RCX_TASKS; t++)
        if (ACCESS_HAS_EV(t->ev.state) && (t->ev.mon & mask)) {
            t->ev.events = (u16)(t->ev.mon & mask);
            access_input(b, t, ACCESS_IN_EV, 0, 0);
        }
}

void events_counter_changed(struct rcx *b, u8 n)
{
    u8 s = (u8)(RCX_EVENT_SRC_COUNTER + n);
    if (n < RCX_COUNTERS)
        evaluate_sources(b, s, s, 0);
}

/* Every message received, set or cleared is a mailbox event (p. 103; reference-firmware.md for the clear). */
void events_message_changed(struct rcx *b)
{
    evaluate_sources(b, RCX_EVENT_SRC_MESSAGE, RCX_EVENT_SRC_MESSAGE, HAPPENED(RCX_EVENT_MAILBOX));
}

void events_input(struct rcx *b, u8 n)
{
    if (n < RCX_SENSORS)
        evaluate_sources(b, n, n, 0);
}

/* Timers, the message and the counters can also change through byte codes that do not tell the engine (SetVar on
 * variables 0-2, ClearTimer, the timers' own tick): they are looked at on the 10 ms grid that Wait and the click
 * durations use, right after each 100 ms timer step. */
void events_tick(struct rcx *b)
{
    if (b->ms == 0)
        evaluate_sources(b, RCX_EVENT_SRC_TIMER, RCX_EVENT_SRC_LAST, 0);
}

void events_monitor_enter(struct rcx *b, struct rcx_task *t, u16 mask, u16 target)
{
    access_input(b, t, ACCESS_IN_ENTER_EV, mask, target);
}

void events_monitor_exit(struct rcx *b, struct rcx_task *t)
{
    access_input(b, t, ACCESS_IN_EXIT_EV, 0, 0);
}

void events_task_ended(struct rcx *b, struct rcx_task *t)
{
    access_input(b, t, ACCESS_IN_END, 0, 0);
}

/* EndOfSub (p. 26, p. 107): regions entered inside the subroutine being left are exited, as the spec says on
 * p. 26 ("exits them ... releasing the resources"). The p. 107 note names the AC input for access regions, but AC
 * jumps to the region's label - back inside the subroutine, which is what the note wants to prevent - so
 * EXIT AC is sent instead. */
void events_sub_returned(struct rcx *b, struct rcx_task *t)
{
    if (ACCESS_HAS_AC(t->ev.state) && t->ev.ac_sub == t->sub)
        access_input(b, t, ACCESS_IN_EXIT_AC, 0, 0);
    if (ACCESS_HAS_EV(t->ev.state) && t->ev.ev_sub == t->sub)
        access_input(b, t, ACCESS_IN_EXIT_EV, 0, 0);
}
