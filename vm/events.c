/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The event engine (spec pp. 63, 70-71, 74, 100-105; sources 25, 27-31): 16 events, each one sensor and one
 * event type, evaluated whenever its sensor may have changed. Monitoring tasks are told through the state
 * machine of vm/access.c.
 *
 * One evaluation works out everything that just happened to the event's sensor (as a set of event types: its
 * state moved, its boolean moved, a click completed...) and fires the event when its own type is in that set. The
 * set only ever holds types the spec's table of valid combinations allows on that kind of sensor.
 *
 * Work goes only where events are: each input counts the events watching it and sensor[0] those watching a timer,
 * the message or a counter (struct rcx_sensor), so an input no event watches, or a 10 ms step with no event on the
 * other sensors, costs nothing here, and an evaluation evaluates the events of one sensor only.
 *
 * And only when something may have moved: the events of an input are evaluated after the samples that the sensor
 * engine works out in full (vm/sensors.c: a raw value that moved, or not yet the same SENSOR_DT_MS times), not after
 * the steady ones, which change nothing. An input whose events want its next sample whatever it gives is marked
 * moving (rcx_sensor.quiet), so that it is worked out in full: SetEvent (the first classification), CalibrateEvent
 * and each calibration sample (8 of them, a millisecond apart, then the first classification), any SetSourceValue
 * (a threshold or the hysteresis may have moved: events_look_again()), a value cleared or a mode or type changed
 * (sensor_clear()). That is exact: with the value, the boolean and the thresholds as at the last evaluation, an
 * evaluation changes nothing (the hysteresis is never negative: a range entered holds its value), so the events are
 * as if looked at after every sample. Click timing needs no clock: a click's duration is judged when the state
 * changes. A still input is then at rest (sensors_at_rest()) whether events watch it or not.
 *
 * And a moving input only when its value leaves the range in which no event of it can change (events_window(): each
 * in its state, no boolean edge watched, no calibration): a light sensor's noise or a rotation sensor's count inside
 * the thresholds costs the events nothing (issue 21: 16 events on three inputs moving every millisecond took some
 * 2 800 states a millisecond, now next to none).
 */
#include "rcx_string.h"
#include "rcx.h"
#include "access.h"

#define HAPPENED(type) ((u16)(1u << (type)))

/* Valid combinations (p. 101): the event types each kind of sensor can have. LOW, NORMAL, HIGH, CLICK and
 * DOUBLE_CLICK can happen on every sensor; the others only where the engine computes them: PRESSED, RELEASED,
 * PERIOD and TRANSITION on inputs measured absolutely (slope 0), PERIOD, TRANSITION and CHANGE_RATE on inputs
 * measured dynamically (slope 1-31), MAILBOX on the message. So an event type is valid when SetEvent knows it, and
 * the edges of an input's boolean are reported only as the types its slope allows (boolean_edge below). */
#define VALID_TYPES (HAPPENED(RCX_EVENT_PRESSED) | HAPPENED(RCX_EVENT_RELEASED) | HAPPENED(RCX_EVENT_PERIOD) | \
                     HAPPENED(RCX_EVENT_TRANSITION) | HAPPENED(RCX_EVENT_CHANGE_RATE) | HAPPENED(RCX_EVENT_LOW) | \
                     HAPPENED(RCX_EVENT_NORMAL) | HAPPENED(RCX_EVENT_HIGH) | HAPPENED(RCX_EVENT_CLICK) | \
                     HAPPENED(RCX_EVENT_DOUBLE_CLICK) | HAPPENED(RCX_EVENT_MAILBOX))

/* What an edge of the boolean means, by [slope != 0][new boolean]. */
static const u8 boolean_edge[2][2] = {
    { HAPPENED(RCX_EVENT_TRANSITION) | HAPPENED(RCX_EVENT_RELEASED) | HAPPENED(RCX_EVENT_PERIOD),
      HAPPENED(RCX_EVENT_TRANSITION) | HAPPENED(RCX_EVENT_PRESSED) },
    { HAPPENED(RCX_EVENT_TRANSITION) | HAPPENED(RCX_EVENT_CHANGE_RATE) | HAPPENED(RCX_EVENT_PERIOD),
      HAPPENED(RCX_EVENT_TRANSITION) | HAPPENED(RCX_EVENT_CHANGE_RATE) },
};

/* Default lower and upper thresholds set by SetEvent (p. 71; hysteresis is always 0): physical sensor modes 0-7
 * (bits 5-7 of the sensor mode), then the virtual sensors, the timers sharing the row of the counting modes. */
#define VIRTUAL_TIMER 2
#define VIRTUAL_MESSAGE 8
#define VIRTUAL_COUNTER 9
static const u8 virtual_row[RCX_EVENT_SRC_LAST + 1 - RCX_SENSORS] = {
    VIRTUAL_TIMER, VIRTUAL_TIMER, VIRTUAL_TIMER, VIRTUAL_TIMER, VIRTUAL_MESSAGE,
    VIRTUAL_COUNTER, VIRTUAL_COUNTER, VIRTUAL_COUNTER,
};
static const s16 events_default[10][2] = {
    { 0, 1023 },        /* raw */
    { 0, 1 },           /* boolean */
    { 0, 32767 },       /* transition count; timer */
    { 0, 32767 },       /* period count */
    { 0, 100 },         /* percent of full scale */
    { -200, 700 },      /* Celsius x 10 */
    { -40, 1580 },      /* Fahrenheit x 10 */
    { 0, 32767 },       /* angle steps */
    { 0, 255 },         /* IR message */
    { -32768, 32767 },  /* counter */
};

/* struct rcx_event.source is the KEY of the event's sensor, 0 for a cleared event: so an event is all zeros when it
 * has no sensor, as at power-on, before ClearAllEvents, when no input counts it yet. */
#define KEY(sensor) EVENTS_KEY(sensor)

/* Private flags of struct rcx_event. */
#define F_BOOL 0x01     /* last boolean seen (inputs); the boolean is 0 or 1, so it is that bit */
#define F_OUT 0x02      /* the state has left LOW: a click may be under way (click.left_low is its start) */
#define F_HIGH 0x04     /* ... and has reached HIGH since (set only with F_OUT) */
#define F_FIRST 0x08    /* a click waits for a second one to make a double click (click.last_click) */

/* Bit n of set (0 for n >= 16). A loop: the H8 shifts one bit per instruction. Always inline: a call in the loop of
 * events_evaluate() would cost more than the loop, in the values kept across it. */
static inline __attribute__((always_inline)) u8 bit_of(u16 set, u8 n)
{
    while (n--)
        set >>= 1;
    return (u8)(set & 1u);
}

/* fired + bit when the event's type (0-15: an event evaluated has a sensor, so a type) is in the set `happened`. On
 * the brick one `btst`, which takes the bit number from a register's low 3 bits, on the byte that holds it, and the
 * addition under its branch: bit_of() shifts up to 15 times, and with 16 events on moving inputs that loop cost some
 * 1 000 states a millisecond. */
static inline u16 fire_if(u16 fired, u16 bit, u16 happened, u8 type)
{
#ifdef __H8300__
    /* types 8-15 are in the high byte: moved to the low one (happened is a copy, used no more) */
    __asm__("btst\t#3,%s2\n\tbeq\t1f\n\tmov.b\t%t1,%s1\n1:\tbtst\t%s2,%s1\n\tbeq\t2f\n\tadd.w\t%3,%0\n2:"
            : "+r"(fired), "+r"(happened) : "r"(type), "r"(bit) : "cc");
    return fired;
#else
    return bit_of(happened, type) ? (u16)(fired + bit) : fired; /* bits of distinct events: no carries */
#endif
}

/* Event e starts (d = 1) or stops (d = 0xFF) watching its sensor (e->source, not 0): an input counts its own watchers
 * (and learns its number, for the sensor engine's events_input()), sensor[0] those of the other sensors. The event
 * takes the sensor's default thresholds and an input's boolean, from which edges are counted (no use when it stops:
 * events_set() clears the event right after). */
static void watch(struct rcx *b, struct rcx_event *e, u8 d)
{
    struct rcx_sensor *s = b->sensor;
    u8 n = (u8)(e->source - KEY(0)), row;

    if (n >= RCX_SENSORS) {
        s->others = (u8)(s->others + d);
        row = virtual_row[n - RCX_SENSORS];
    } else {
        s += n;
        s->number = n;
        s->watched = (u8)(s->watched + d);
        row = (u8)(s->mode >> 5);
        e->flags = s->boolean; /* F_BOOL */
    }
    e->lower = events_default[row][0];
    e->upper = events_default[row][1];
}

/* Every input is marked moving: the one that matters is among them, and that costs less than finding it (a sample
 * worked out in full again gives what it gave). */
RCX_STATIC_ASSERT(three_inputs, RCX_SENSORS == 3);
#ifndef __H8300__ /* on the brick: drivers/h8300/eventwindow.S (offsets checked with events_window()'s below) */
void events_look_again(struct rcx *b)
{
    struct rcx_sensor *s = b->sensor;

    do {
        s->quiet = SENSOR_MOVING;
        s->lo = 0;      /* (not EVENTS_WINDOW_NONE: worked out again) */
        s->hi = -32768; /* no value between lo and hi */
    } while (++s < b->sensor + RCX_SENSORS);
    b->sensors_rest = 0;
}
#endif

/* Spec p. 25: tasks monitoring events are not told. */
void events_clear_all(struct rcx *b)
{
    u8 ev;
    for (ev = 0; ev < RCX_EVENTS; ev++)
        events_set_packed(b, ev, RCX_EVENT_NONE);
}

/* SetEvent: `st` is the source in its high byte, the type in its low byte (events_set(), vm/events.h). */
#define SOURCE ((u8)(st >> 8))
#define TYPE ((u8)st)
void events_set_packed(struct rcx *b, u8 ev, u16 st)
{
    struct rcx_event *e;

    /* 4-6, 13, 15 and above 16 are no event types; 16 clears the event. */
    if (ev >= RCX_EVENTS || SOURCE > RCX_EVENT_SRC_LAST || (TYPE != RCX_EVENT_NONE && !bit_of(VALID_TYPES, TYPE)))
        return;
    e = &b->event[ev];
    if (e->source)
        watch(b, e, 0xFF);
    memset(e, 0, sizeof *e); /* no sensor: KEY 0 */
    e->type = TYPE;
    e->state = RCX_EVENT_STATE_UNDEFINED;
    e->duration = 15; /* 150 ms, the click default of p. 71 */
    if (TYPE == RCX_EVENT_NONE)
        return;
    e->source = KEY(SOURCE);
    watch(b, e, 1);
    events_look_again(b); /* its first classification */
}
#undef SOURCE
#undef TYPE

/* CalibrateEvent (p. 74): ins[1] is the event, ins[2-4] its upper, lower and hysteresis factors. That is the order nqc
 * encodes CalibrateEvent(event, lower, upper, hysteresis) in, and the one programs were written and run with; the
 * spec's table lists lower first. */
void events_calibrate(struct rcx *b, const u8 *ins)
{
    struct rcx_event *e;
    u8 ev = ins[1];

    if (ev >= RCX_EVENTS || !(e = &b->event[ev])->source)
        return; /* a cleared event has no sensor to measure */
    e->state = RCX_EVENT_STATE_CAL_START;
    e->flags &= F_BOOL; /* no click under way: the union now holds the calibration */
    e->u.cal.sum8 = 0;
    e->u.cal.raw_sum = 0;
    e->u.cal.rem = 0;
    memcpy(e->u.cal.pct, ins + 2, sizeof e->u.cal.pct);
    events_look_again(b); /* the samples to come */
}

/* v * f / 256 rounded toward zero, in 16 bits with the H8's 8 x 8 multiply (the low byte's product first: gcc then
 * needs no register saved). */
static s16 fraction(s16 v, u8 f)
{
    u16 s = (u16)(v >> 15), m = (u16)(((u16)v ^ s) - s);
    m = (u16)((((u16)(u8)m * f) >> 8) + (u16)(u8)(m >> 8) * f);
    return (s16)((m ^ s) - s);
}

/* a + b, saturated to the 16-bit range: the wrapped sum moved the wrong way from a when it overflowed. */
static s16 add_sat(s16 a, s16 b)
{
    s16 r = (s16)(u16)((u16)a + (u16)b);

    if (b < 0) {
        if (r > a)
            r = -32768;
    } else if (r < a) {
        r = 32767;
    }
    return r;
}

/* One calibration sample (pp. 74, 103-105) of `in`, the input measured (8 samples; NULL: a virtual sensor, one).
 * UT = Avg + Avg*UTFct/k1 (+ H), LT = Avg - Avg*LTFct/k1 (- H), H = AvgRaw*HFct/k2 for the raw-scale modes and 0
 * otherwise; k1 = 256, k2 = 2048. The average of 8 is kept as the sum of value/8 plus the sum of the remainders, which
 * stays within 16 bits; the raw samples add up to at most 8 x 1023, which leaves the top 3 bits of raw_sum to count
 * them (8 steps of RAW_COUNT_ONE carry out of it). The hysteresis changes only when the thresholds do.
 * The raw-scale modes (pp. 104-105) are raw, percent (reflection), Celsius and Fahrenheit (temperature); the
 * raw-mode formula is lost from the spec (its page is missing) and taken to be the reflection one, since both work on
 * the same A/D scale. */
#define RAW_COUNT_ONE 0x2000
enum { PCT_UPPER, PCT_LOWER, PCT_HYST }; /* struct rcx_event_cal.pct: CalibrateEvent's operands in order */
static void calibrate_sample(struct rcx_sensor *in, struct rcx_event *e, s16 avg)
{
    struct rcx_event_cal *c = &e->u.cal;
    u8 m;

    e->state = RCX_EVENT_STATE_CAL_BUSY;
    if (in) {
        in->quiet = SENSOR_MOVING; /* the next sample: the calibration's, or after the last the first classification */
        c->rem = (u8)(c->rem + (avg & 7));
        c->sum8 = (s16)(c->sum8 + (avg >> 3));
        c->raw_sum = (u16)(c->raw_sum + in->raw + RAW_COUNT_ONE);
        if (c->raw_sum >= RAW_COUNT_ONE)
            return; /* fewer than 8 samples */
        avg = (s16)(c->sum8 + (c->rem >> 3));
        m = (u8)(in->mode & ~SENSOR_SLOPE);
        if ((u8)(m - SENSOR_MODE_BOOL) <= SENSOR_MODE_PERIODS - SENSOR_MODE_BOOL || m == SENSOR_MODE_ANGLE)
            c->raw_sum = 0; /* boolean, transitions, periods, angle: no raw-scale mode */
    }
    /* No raw samples (a virtual sensor, or not a raw-scale mode): H = 0. Otherwise AvgRaw*HFct/2048 with AvgRaw the
     * sum/8 rounded down: (8 AvgRaw)*HFct/256 then /64, the same, one shift less; that /64 as *4 then /256 (a byte
     * move), since (8 AvgRaw)*HFct/256 is below 8 184. */
    e->hysteresis = (u8)((u16)((u16)fraction((s16)(c->raw_sum & ~7u), c->pct[PCT_HYST]) << 2) >> 8);
    e->upper = add_sat(add_sat(avg, fraction(avg, c->pct[PCT_UPPER])), e->hysteresis);
    /* Avg*LTFct/k1 lies between 0 and Avg, so only the hysteresis can take the lower threshold further. It is 0 but
     * in the raw-scale modes, whose values are -200 or more: with the 8th sample one of them, Avg is above -28 700
     * and H at most 127, so nothing to saturate. */
    e->lower = (s16)(avg - fraction(avg, c->pct[PCT_LOWER]) - e->hysteresis);
    e->state = RCX_EVENT_STATE_UNDEFINED; /* the click flags went at CalibrateEvent: nothing to clear here */
}

/* A change of state from `from` (known) to `to`: the range entered, and the click bookkeeping (p. 102): a click is
 * LOW -> HIGH -> LOW within the duration; a double click is a click that starts within the duration after the
 * previous click ended. Returns the event types that happened, all of them 8-15: bit n is type 8 + n. */
#define TYPE_8(type) ((u8)(1u << ((type) - 8)))
RCX_STATIC_ASSERT(states_are_types, RCX_EVENT_STATE_LOW == 0 && RCX_EVENT_STATE_NORMAL == 1 &&
                  RCX_EVENT_STATE_HIGH == 2 && RCX_EVENT_LOW == 8 && RCX_EVENT_NORMAL == 9 && RCX_EVENT_HIGH == 10);
static u8 changed(struct rcx *b, struct rcx_event *e, u8 from, u8 to)
{
    u16 now = b->ticks10;
    u8 f = e->flags, happened = (u8)(to + 1 + (to >> 1)); /* 1 << to: LOW, NORMAL, HIGH follow the states */

    if (to == RCX_EVENT_STATE_LOW) {
        if ((f & F_HIGH) && (u16)(now - e->u.click.left_low) <= (u16)e->duration) {
            e->clicks = (s16)(u16)((u16)e->clicks + 1u); /* wraps, as the firmware's counters do */
            happened |= TYPE_8(RCX_EVENT_CLICK);
            f ^= F_FIRST; /* cleared if this click was waiting to be the second one */
            if (!(f & F_FIRST) && (u16)(e->u.click.left_low - e->u.click.last_click) <= (u16)e->duration) {
                happened |= TYPE_8(RCX_EVENT_DOUBLE_CLICK);
            } else { /* this one waits for a second one */
                f |= F_FIRST;
                e->u.click.last_click = now;
            }
        }
        /* Leaving LOW again starts the next click afresh, so the progress can go in any case. */
        f &= (u8)~(F_OUT | F_HIGH);
    } else {
        if (from == RCX_EVENT_STATE_LOW) {
            e->u.click.left_low = now;
            f |= F_OUT;
        }
        if (to == RCX_EVENT_STATE_HIGH && (f & F_OUT))
            f |= F_HIGH;
    }
    e->flags = f;
    return happened;
}

/* The state `value` puts event e in. Hysteresis widens the range being left (reference-firmware.md): HIGH holds
 * while value > upper - h, LOW while value < lower + h; for the other thresholds h is 0. Moved thresholds stop at
 * the 16-bit limits. */
static u8 classify(const struct rcx_event *e, s16 value)
{
    s16 upper = e->upper, lower = e->lower, h = e->hysteresis;

    if (h) { /* 0 unless SetSourceValue or CalibrateEvent set it: then the thresholds are as they are */
        if (e->state == RCX_EVENT_STATE_HIGH)
            upper = add_sat(upper, (s16)-h);
        if (e->state == RCX_EVENT_STATE_LOW)
            lower = add_sat(lower, h);
    }
    if (value > upper)
        return RCX_EVENT_STATE_HIGH;
    if (value < lower)
        return RCX_EVENT_STATE_LOW;
    return RCX_EVENT_STATE_NORMAL;
}

/* Evaluate event e against its sensor's present value, for an evaluation of `only` (a KEY, or ANY: the timers, the
 * message and the counters). Only events_message_changed() asks for the message: a mailbox event happened. Returns
 * the event types that happened (bit n: type n); the event fires when its own is one of them. */
#define ANY EVENTS_ANY /* above every KEY */
static u16 evaluate(struct rcx *b, struct rcx_event *e, u8 only)
{
    struct rcx_sensor *in = NULL;
    u8 s = (u8)(e->source - KEY(0)), to, from, bo;
    u16 happened = 0;
    s16 value;

    if (s < RCX_SENSORS) {
        in = &b->sensor[s];
        value = in->value;
        bo = in->boolean; /* 0 or 1 */
        if ((u8)(bo ^ e->flags) & F_BOOL) {
            e->flags ^= F_BOOL;
            happened = boolean_edge[(in->mode & SENSOR_SLOPE) != 0][bo];
        }
    } else if (s == RCX_EVENT_SRC_MESSAGE) {
        value = b->message;
        if (only != ANY) /* events_message_changed() */
            happened = HAPPENED(RCX_EVENT_MAILBOX);
    } else { /* timer[s - 3] or global[s - 8] (counters), both 16-bit */
        value = *(const s16 *)(const void *)((const u8 *)b + 2u * s +
                                             (s < RCX_EVENT_SRC_MESSAGE
                                                  ? offsetof(struct rcx, timer) - 2u * RCX_EVENT_SRC_TIMER
                                                  : offsetof(struct rcx, global) - 2u * RCX_EVENT_SRC_COUNTER));
    }
    from = e->state;
    if (from >= RCX_EVENT_STATE_CAL_START) {
        calibrate_sample(in, e, value);
        return 0;
    }
    to = classify(e, value);
    e->state = to;
    /* The first classification after SetEvent or a calibration is not a change of range. */
    if (to != from && from != RCX_EVENT_STATE_UNDEFINED)
        happened |= (u16)((u16)changed(b, e, from, to) << 8);
    return happened;
}

/* Evaluate the events watching the sensor whose KEY is `only` (ANY: any timer, the message or a counter) and tell the
 * tasks. `left` is how many there are, when known (events_set() keeps the counts of each input and of the other
 * sensors), so that the loop can stop at the last one; 0 when not known: all 16 are looked at. */
RCX_STATIC_ASSERT(virtual_sensors_are_words, sizeof(((struct rcx *)0)->timer[0]) == 2 &&
                  sizeof(((struct rcx *)0)->global[0]) == 2);
void events_evaluate(struct rcx *b, u8 left, u8 only)
{
    struct rcx_event *e = b->event;
    u16 bit = 1, fired = 0, happened;
    u8 k;

    do {
        k = e->source;
        if (k == only || (only == ANY && k > KEY(RCX_SENSORS - 1))) {
            if ((happened = evaluate(b, e, only)) != 0)
                fired = fire_if(fired, bit, happened, e->type);
            if (!--left)
                break;
        }
        e++;
    } while (bit <<= 1);
    if (fired)
        events_raise(b, fired);
}

/* After an evaluation of input `in`'s events (KEY `key`): the values that leave each of them in its state with no
 * hysteresis, which only widens the range being left (LOW below lower, NORMAL from lower to upper, HIGH above upper),
 * as bounds not included. While the value stays between them, looking at the events changes nothing (click timing
 * is judged when a state changes, and a boolean's edge fires only an event of types 0-7), so the sensor engine does not
 * look (vm/sensors.c). An event of types 0-7 leaves no value: it looks at every sample, and lo is then
 * EVENTS_WINDOW_NONE: the sensor engine does not ask again until the events change (events_look_again()). One
 * calibrating or not yet classified leaves none for now, but lo is not EVENTS_WINDOW_NONE: the window is worked out
 * again once it has its state. A lower threshold of -32768 leaves none either (lower - 1 wraps), which costs no more
 * than a look at every sample. A pass of its own rather than in events_evaluate(): there it cost more bytes
 * than here, in the registers it took. */
#ifdef __H8300__
/* On the brick events_window() is drivers/h8300/eventwindow.S (some 40 bytes fewer than gcc 3.4's code for the C
 * below); the C here is its reference (tests/drivers/test_h8window.c compares the two). */
#include "sensorfeed.h"
#include <stddef.h>
RCX_STATIC_ASSERT(ew_layout, offsetof(struct rcx, event) == SF_EVENT && sizeof(struct rcx_event) == EV_SIZE
                             && RCX_EVENTS == 16 && offsetof(struct rcx_event, source) == EV_SOURCE
                             && offsetof(struct rcx_event, type) == EV_TYPE
                             && offsetof(struct rcx_event, state) == EV_STATE
                             && offsetof(struct rcx_event, upper) == EV_UPPER
                             && offsetof(struct rcx_event, lower) == EV_LOWER);
RCX_STATIC_ASSERT(ew_states, RCX_EVENT_LOW == 8 && RCX_EVENT_STATE_LOW == 0 && RCX_EVENT_STATE_NORMAL == 1
                             && RCX_EVENT_STATE_HIGH == 2 && EVENTS_WINDOW_NONE == SF_WINDOW_NONE);
RCX_STATIC_ASSERT(ew_look_again, offsetof(struct rcx, sensors_rest) == SF_REST && SENSOR_MOVING == 0
                                 && sizeof(struct rcx_sensor) == SF_SIZE && offsetof(struct rcx_sensor, lo) == SF_LO
                                 && offsetof(struct rcx_sensor, hi) == SF_HI); /* events_look_again */
#else
void events_window(struct rcx *b, struct rcx_sensor *in, u8 key)
{
    struct rcx_event *e = b->event;
    s16 lo = -32768, hi = 32767, l, u;

    do {
        if (e->source != key)
            continue;
        if (e->type < RCX_EVENT_LOW) {
            lo = EVENTS_WINDOW_NONE; /* none, as long as the events stay as they are: the rest need not be looked at */
            hi = -32768;
            break;
        }
        if (e->state > RCX_EVENT_STATE_HIGH) {
            hi = -32768; /* none for now (calibrating, not yet classified): worked out again at the next evaluation */
            break;
        }
        l = e->lower;
        u = e->upper;
        if (e->state == RCX_EVENT_STATE_HIGH) {
            l = u;
            u = 32767;
        } else if (e->state == RCX_EVENT_STATE_LOW) {
            u = l;
            l = -32768;
        } else {
            l = (s16)(l - 1);
            if (u != 32767) /* the upper limit of many a mode (counts, angle): not to be lost */
                u = (s16)(u + 1);
        }
        if (l > lo)
            lo = l;
        if (u < hi)
            hi = u;
    } while (++e < b->event + RCX_EVENTS);
    in->lo = lo;
    in->hi = hi;
}
#endif /* __H8300__ */

/* Spec p. 63: behave as if these events had happened. Every task monitoring one of them takes its EV exit; the
 * events that reached it are kept for source 23. */
void events_raise(struct rcx *b, u16 mask)
{
    struct rcx_task *t = b->task;

    do
        if (ACCESS_HAS_EV(t->ev.state) && (t->ev.mon & mask)) {
            t->ev.events = (u16)(t->ev.mon & mask);
            access_input(b, t, ACCESS_IN_EV);
        }
    while (++t < b->task + RCX_TASKS);
}
