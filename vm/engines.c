/*
 * Placeholders for the engines of the next issue (sensors, outputs, sound, display, events, access control, IR).
 * Each one records that its effect is still owed; see engines.h. Monitoring that never fires and access that
 * is always granted are what a program observes when no event happens and no other task competes.
 */
#include "engines.h"

#define OWED(b) ((b)->engine_pending++)

void engine_outputs_changed(struct rcx *b) { OWED(b); }
void engine_sound_tone(struct rcx *b, u16 hz, u8 dur10) { (void)hz; (void)dur10; OWED(b); }
void engine_sound_system(struct rcx *b, u8 sound) { (void)sound; OWED(b); }
void engine_sound_clear(struct rcx *b) { OWED(b); }
void engine_display_view(struct rcx *b, u8 view) { (void)view; OWED(b); }
void engine_display_user(struct rcx *b, u8 precision, u8 src, u16 index)
{
    (void)precision; (void)src; (void)index; OWED(b);
}
void engine_sensor_changed(struct rcx *b, u8 n) { (void)n; OWED(b); }
void engine_event_set(struct rcx *b, u8 ev, u8 source, u8 type)
{
    b->event[ev].source = source;
    b->event[ev].type = type;
    OWED(b);
}
void engine_event_calibrate(struct rcx *b, u8 ev, u8 lower, u8 upper, u8 hyst)
{
    (void)ev; (void)lower; (void)upper; (void)hyst; OWED(b);
}
void engine_event_raise(struct rcx *b, u16 mask) { (void)mask; OWED(b); }
void engine_events_clear(struct rcx *b) { OWED(b); }
void engine_counter_changed(struct rcx *b, u8 n) { (void)n; OWED(b); }
void engine_message_changed(struct rcx *b) { OWED(b); }
void engine_monitor_enter(struct rcx *b, struct rcx_task *t, u16 mask, u16 target)
{
    (void)t; (void)mask; (void)target; OWED(b);
}
void engine_monitor_exit(struct rcx *b, struct rcx_task *t) { (void)t; OWED(b); }
void engine_access_enter(struct rcx *b, struct rcx_task *t, u8 resources, u16 target)
{
    (void)t; (void)resources; (void)target; OWED(b);
}
void engine_access_exit(struct rcx *b, struct rcx_task *t) { (void)t; OWED(b); }
void engine_task_ended(struct rcx *b, struct rcx_task *t) { (void)b; (void)t; }
void engine_sub_returned(struct rcx *b, struct rcx_task *t) { (void)b; (void)t; }
void engine_send_message(struct rcx *b, u8 message) { (void)message; OWED(b); }
void engine_send_uart(struct rcx *b, u8 start, u8 size) { (void)start; (void)size; OWED(b); }
void engine_remote(struct rcx *b, u16 bits) { (void)bits; OWED(b); }
