/* Sound (spec pp. 19, 23-24, 29, 49, 65): a queue of notes and system sounds played through hal_sound(). */
#ifndef RCX_SOUND_H
#define RCX_SOUND_H

#include "rcx_types.h"

struct rcx;

struct rcx_sound {
    u8 muted;  /* MuteSound: program sounds ignored, system sounds of the user interface still play */
};

void sound_tone(struct rcx *b, u16 hz, u8 dur10);   /* PlayTone/PlayToneVar from a program or host */
void sound_system(struct rcx *b, u8 sound);         /* PlaySystemSound 0-5 from a program or host */
void sound_ui(struct rcx *b, u8 sound);             /* a system sound of the user interface (never muted) */
void sound_clear(struct rcx *b);                    /* ClearSound */
void sound_mute(struct rcx *b, u8 on);              /* MuteSound / UnmuteSound */
void sound_tick(struct rcx *b);                     /* every 1 ms */

#endif
