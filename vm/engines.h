/*
 * The engines behind byte codes that the foundation decodes but does not yet carry out in full:
 * outputs to hal.h, sound, display, events, event monitoring, access control and IR transmission.
 *
 * Each hook is called by the interpreter or a direct command with operands already decoded and range-checked.
 * Until an engine is written, its hook only counts the call in `rcx.engine_pending`, so a test can tell that the
 * byte code reached the right place and that its effect is still owed. An engine replaces its hooks here.
 */
#ifndef RCX_ENGINES_H
#define RCX_ENGINES_H

#include "rcx.h"

/* Outputs: motor registers changed (apply them to the hardware, with the direction-change pause). */
void engine_outputs_changed(struct rcx *b);

/* Sound. */
void engine_sound_tone(struct rcx *b, u16 hz, u8 dur10);
void engine_sound_system(struct rcx *b, u8 sound);
void engine_sound_clear(struct rcx *b);

/* Display: view 0-7, or the user view of source/value with a decimal point position. */
void engine_display_view(struct rcx *b, u8 view);
void engine_display_user(struct rcx *b, u8 precision, u8 src, u16 index);

/* Sensors: type or mode changed, value cleared. */
void engine_sensor_changed(struct rcx *b, u8 n);

/* Events. */
void engine_event_set(struct rcx *b, u8 ev, u8 source, u8 type);
void engine_event_calibrate(struct rcx *b, u8 ev, u8 lower, u8 upper, u8 hyst);
void engine_event_raise(struct rcx *b, u16 mask);
void engine_events_clear(struct rcx *b);
void engine_counter_changed(struct rcx *b, u8 n);
void engine_message_changed(struct rcx *b);

/* Event monitoring and access control for task t; `target` is the handler's pc in the current code object. */
void engine_monitor_enter(struct rcx *b, struct rcx_task *t, u16 mask, u16 target);
void engine_monitor_exit(struct rcx *b, struct rcx_task *t);
void engine_access_enter(struct rcx *b, struct rcx_task *t, u8 resources, u16 target);
void engine_access_exit(struct rcx *b, struct rcx_task *t);
void engine_task_ended(struct rcx *b, struct rcx_task *t); /* stop/delete/restart: release resources */
void engine_sub_returned(struct rcx *b, struct rcx_task *t);

/* IR transmission. */
void engine_send_message(struct rcx *b, u8 message);
void engine_send_uart(struct rcx *b, u8 start, u8 size);
void engine_remote(struct rcx *b, u16 bits);

#endif
