/*
 * Events, event monitoring and access control (spec pp. 63, 69-71, 74, 85, 96, 100-107; sources 23, 25, 27-31).
 */
#ifndef RCX_EVENTS_H
#define RCX_EVENTS_H

#include "rcx_types.h"

struct rcx;
struct rcx_task;

struct rcx_event {
    u8 source;      /* 0-2 inputs, 3-6 timers, 7 message, 8-10 counters */
    u8 type;        /* 0-14; RCX_EVENT_NONE when cleared */
    u8 state;       /* source 25 */
    s16 upper;      /* source 28 */
    s16 lower;      /* source 29 */
    s16 hysteresis; /* source 30 */
    s16 duration;   /* source 31, 10 ms units */
    s16 clicks;     /* source 27 */
};

#define RCX_EVENT_NONE 16
#define RCX_EVENT_STATE_UNDEFINED 3

/* Per-task state of monitoring and access control (the state machine of spec p. 107). */
struct rcx_task_events {
    u16 events;     /* source 23: events that ended the last monitoring */
};

void events_init(struct rcx *b);
void events_set(struct rcx *b, u8 ev, u8 source, u8 type);           /* SetEvent, operands checked */
void events_calibrate(struct rcx *b, u8 ev, u8 lower, u8 upper, u8 hyst);
void events_raise(struct rcx *b, u16 mask);                           /* DirectEvent */
void events_clear_all(struct rcx *b);                                 /* ClearAllEvents */
void events_counter_changed(struct rcx *b, u8 n);
void events_message_changed(struct rcx *b);
void events_input(struct rcx *b, u8 n);      /* input n's processed value or boolean may have changed */
void events_tick(struct rcx *b);             /* every 1 ms */

/* Monitoring and access control; `target` is the handler's pc in the task's current code object. */
void events_monitor_enter(struct rcx *b, struct rcx_task *t, u16 mask, u16 target);
void events_monitor_exit(struct rcx *b, struct rcx_task *t);
void access_enter(struct rcx *b, struct rcx_task *t, u8 resources, u16 target);
void access_exit(struct rcx *b, struct rcx_task *t);
void events_task_ended(struct rcx *b, struct rcx_task *t);   /* start/stop/delete: release, forget */
void events_sub_returned(struct rcx *b, struct rcx_task *t); /* EndOfSub: leave regions entered in the sub */

#endif
