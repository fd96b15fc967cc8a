/* Placeholder: the event engine is owed (engine_pending counts its uses). */
#include "rcx.h"

void events_init(struct rcx *b)
{
    u8 i;
    for (i = 0; i < RCX_EVENTS; i++) {
        b->event[i].type = RCX_EVENT_NONE;
        b->event[i].state = RCX_EVENT_STATE_UNDEFINED;
        b->event[i].duration = 15; /* 150 ms, the click default of spec p. 71 */
    }
}

void events_set(struct rcx *b, u8 ev, u8 source, u8 type)
{
    b->event[ev].source = source;
    b->event[ev].type = type;
    b->engine_pending++;
}
void events_calibrate(struct rcx *b, u8 ev, u8 lower, u8 upper, u8 hyst)
{
    (void)ev; (void)lower; (void)upper; (void)hyst; b->engine_pending++;
}
void events_raise(struct rcx *b, u16 mask) { (void)mask; b->engine_pending++; }
void events_clear_all(struct rcx *b) { b->engine_pending++; }
void events_counter_changed(struct rcx *b, u8 n) { (void)n; b->engine_pending++; }
void events_message_changed(struct rcx *b) { b->engine_pending++; }
void events_input(struct rcx *b, u8 n) { (void)b; (void)n; }
void events_tick(struct rcx *b) { (void)b; }
void events_monitor_enter(struct rcx *b, struct rcx_task *t, u16 mask, u16 target)
{
    (void)t; (void)mask; (void)target; b->engine_pending++;
}
void events_monitor_exit(struct rcx *b, struct rcx_task *t) { (void)t; b->engine_pending++; }
void events_task_ended(struct rcx *b, struct rcx_task *t) { (void)b; (void)t; }
void events_sub_returned(struct rcx *b, struct rcx_task *t) { (void)b; (void)t; }
