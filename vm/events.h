/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Events, event monitoring and access control (spec pp. 63, 69-71, 74, 85, 96, 100-107; sources 23, 25, 27-31).
 * The event engine is vm/events.c; the monitoring/access-control state machine of p. 107 is vm/access.c
 * (its states and inputs are in vm/access.h).
 */
#ifndef RCX_EVENTS_H
#define RCX_EVENTS_H

#include "rcx_types.h"
#include "rcx_limits.h"
#include "access.h"

struct rcx;
struct rcx_task;

/* Event sensors as SetEvent numbers them (spec pp. 70, 100). */
#define RCX_EVENT_SRC_TIMER 3     /* 3-6: timers 0-3 */
#define RCX_EVENT_SRC_MESSAGE 7
#define RCX_EVENT_SRC_COUNTER 8   /* 8-10: counters 0-2 */
#define RCX_EVENT_SRC_LAST 10

/* Event types (spec p. 70); 4-6, 13 and 15 do not exist. */
#define RCX_EVENT_PRESSED 0
#define RCX_EVENT_RELEASED 1
#define RCX_EVENT_PERIOD 2
#define RCX_EVENT_TRANSITION 3
#define RCX_EVENT_CHANGE_RATE 7
#define RCX_EVENT_LOW 8           /* enter low; 9 normal and 10 high follow the state numbers */
#define RCX_EVENT_NORMAL 9
#define RCX_EVENT_HIGH 10
#define RCX_EVENT_CLICK 11
#define RCX_EVENT_DOUBLE_CLICK 12
#define RCX_EVENT_MAILBOX 14
#define RCX_EVENT_NONE 16         /* SetEvent type 16 clears the event */

/* Event states, source 25 (spec p. 8). */
#define RCX_EVENT_STATE_LOW 0
#define RCX_EVENT_STATE_NORMAL 1
#define RCX_EVENT_STATE_HIGH 2
#define RCX_EVENT_STATE_UNDEFINED 3
#define RCX_EVENT_STATE_CAL_START 4
#define RCX_EVENT_STATE_CAL_BUSY 5

struct rcx_event {
    u8 source;      /* 1 + the sensor: 0-2 inputs, 3-6 timers, 7 message, 8-10 counters; 0 when cleared */
    u8 type;        /* see RCX_EVENT_*; RCX_EVENT_NONE when cleared */
    u8 state;       /* source 25 */
    u8 flags;       /* private to events.c: last boolean, click progress */
    s16 upper;      /* source 28 */
    s16 lower;      /* source 29 */
    s16 hysteresis; /* source 30 */
    s16 duration;   /* source 31, 10 ms units */
    s16 clicks;     /* source 27 */
    union {         /* click timing and calibration never run at the same time */
        struct {
            u16 left_low;   /* rcx.ticks10 when the state last left LOW */
            u16 last_click; /* rcx.ticks10 at the end of a click still waiting for its double */
        } click;
        struct rcx_event_cal {
            s16 sum8;       /* of the values sampled so far, each divided by 8 (rem: the remainders) */
            u16 raw_sum;    /* of the raw samples (inputs only), and in its top 3 bits how many */
            u8 rem;
            u8 pct[3];      /* CalibrateEvent's operands: upper, lower, hysteresis factors */
        } cal;
    } u;
};

/* Per-task state of monitoring and access control (the state machine of spec p. 107). */
struct rcx_task_events {
    u16 events;     /* source 23: events that ended the last monitoring */
    u16 mon;        /* events being monitored (MON) */
    u16 ev_pc;      /* EV: exit label of event monitoring ... */
    u16 ac_pc;      /* AC: ... and of access control, each a pc in the code object it was entered in */
    u8 ev_sub;      /* (pairs in the order of the EV and AC inputs, which index them: vm/access.c) */
    u8 ac_sub;
    u8 rc;          /* RC: resources held */
    u8 state;       /* ACCESS_NONE ... ACCESS_AC_EV (vm/access.h) */
};

void events_clear_all(struct rcx *b);                                 /* ClearAllEvents */
static inline void events_init(struct rcx *b) { events_clear_all(b); } /* power-on: every event cleared */
/* SetEvent, operands checked. Source and type travel as the two bytes of one word: a fourth argument would go on the
 * stack. */
#define events_set(b, ev, source, type) events_set_packed(b, ev, (u16)((u16)(u8)(source) << 8 | (u8)(type)))
void events_set_packed(struct rcx *b, u8 ev, u16 source_type);
void events_calibrate(struct rcx *b, const u8 *ins);                  /* CalibrateEvent: its byte code */
void events_raise(struct rcx *b, u16 mask);                           /* DirectEvent */

/* The engine looks at the events watching a sensor whenever that sensor may have changed: events_evaluate() takes the
 * events whose sensor's KEY (its SetEvent number + 1) is `only`, or with EVENTS_ANY those of the timers, the message
 * and the counters; `left` is how many there are, 0 when not known (vm/events.c). The notifications below are inline,
 * so that each costs its caller one call. */
#define EVENTS_KEY(sensor) ((u8)((sensor) + 1))
#define EVENTS_ANY 0xFE /* above every KEY */
void events_evaluate(struct rcx *b, u8 left, u8 only);
struct rcx_sensor;
/* Sets in->lo and in->hi (vm/sensors.h): between them, values of input `in` (KEY `key`) change nothing for its
 * events; lo EVENTS_WINDOW_NONE (and hi -32768) when one of them looks at every sample whatever its state. */
void events_window(struct rcx *b, struct rcx_sensor *in, u8 key);
#define EVENTS_WINDOW_NONE 32767
static inline void events_counter_changed(struct rcx *b, u8 n)
{
    if (n < RCX_COUNTERS)
        events_evaluate(b, 0, (u8)(EVENTS_KEY(RCX_EVENT_SRC_COUNTER) + n));
}
/* Every message received, set or cleared is a mailbox event (p. 103; reference-firmware.md for the clear). */
static inline void events_message_changed(struct rcx *b) { events_evaluate(b, 0, EVENTS_KEY(RCX_EVENT_SRC_MESSAGE)); }
/* events_input(b, n): input n's processed value or boolean may have changed (inline, in rcx.h: it needs struct rcx). */
/* The events of every input must look at its next sample even if the input does not move (vm/events.c): an event was
 * set or calibrated, a threshold or the hysteresis may have moved (SetSourceValue). (The timers, the message and the
 * counters are looked at every 10 ms anyway.) */
void events_look_again(struct rcx *b);
/* Timers, the message and the counters can also change through byte codes that do not tell the engine (SetVar on
 * variables 0-2, ClearTimer, the timers' own tick): they are looked at on the 10 ms grid that Wait and the click
 * durations use, right after each 100 ms timer step (vm_tick calls this at the end of each 10 ms step, once the
 * timers have moved on and before the tasks the step wakes run), when an event watches one of them (sensor[0]
 * counts those). A macro: struct rcx is not complete here. */
#define events_tick(b)                                                          \
    do {                                                                        \
        if ((b)->sensor[0].others)                                              \
            events_evaluate(b, (b)->sensor[0].others, EVENTS_ANY);              \
    } while (0)

/* Monitoring and access control. ENTER EV and ENTER AC are the byte code at ins (S/LEnterEventCheck or
 * EnterAccessControl), `target` its label: the handler's pc in the task's current code object. The inputs without
 * operands (ExitEventCheck, ExitAccessControl: op_exit in vm/ops.c) are one call of the state machine
 * (access_input(), vm/access.h), made in place. */
void access_enter(struct rcx *b, struct rcx_task *t, const u8 *ins, u16 target);
/* START, STOP, DELETE TASK: RELEASE RC, GO NONE, in place (a macro: struct rcx_task is not complete here). */
#define events_task_ended(b, t) ((void)(b), (void)(*(u16 *)(void *)&(t)->ev.rc = 0)) /* RC and state: one word */
RCX_STATIC_ASSERT(rc_state_word, offsetof(struct rcx_task_events, rc) % 2 == 0 && ACCESS_NONE == 0 &&
                  offsetof(struct rcx_task_events, state) == offsetof(struct rcx_task_events, rc) + 1);
/* EndOfSub (p. 26, p. 107): regions entered inside the subroutine being left are exited, as the spec says on p. 26
 * ("exits them ... releasing the resources"). The p. 107 note names the AC input for access regions, but AC jumps to
 * the region's label - back inside the subroutine, which is what the note wants to prevent - so EXIT AC is sent
 * instead. In a state without the region the input changes nothing (p. 107), so the labels alone decide. A macro,
 * for struct rcx_task is not complete here; its one caller is in vm/interp.c. */
#define events_sub_returned(b, t)                                      \
    do {                                                               \
        if ((t)->ev.ac_sub == (t)->sub)                                \
            access_input(b, t, ACCESS_IN_EXIT_AC);                     \
        if ((t)->ev.ev_sub == (t)->sub)                                \
            access_input(b, t, ACCESS_IN_EXIT_EV);                     \
    } while (0)

#endif
