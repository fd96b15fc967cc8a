/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Sound (spec pp. 19, 23-24, 29, 49, 65, 106; rcx-hardware.md §3.7): a queue of tones and system sounds played
 * through hal_sound().
 */
#ifndef RCX_SOUND_H
#define RCX_SOUND_H

#include "rcx_types.h"

struct rcx;

#define SOUND_QUEUE 8          /* entries; further requests are dropped, as firm0328 does */
#define SOUND_SYSTEM_SOUNDS 6  /* 0 click, 1 beep-beep, 2 sweep down, 3 sweep up, 4 error buzz, 5 fast sweep up */
#define SOUND_MIN_HZ 31        /* tones outside 31-20 000 Hz are rests of their duration */
#define SOUND_MAX_HZ 20000

/* One queue entry: a tone (`len` in 10 ms, `hz` 0 for a rest), or when `len` is 0 a system sound, `hz` then being
 * the place of its next note in sound.c's table. */
struct sound_entry {
    u16 hz;
    u8 len;
};

struct rcx_sound {
    struct sound_entry queue[SOUND_QUEUE]; /* (first: at the address of the whole, the most used field) */
    u16 left;      /* milliseconds left of the current note; 0 = none started */
    u16 sounding;  /* the frequency hal_sound() was last given */
    u8 muted;      /* MuteSound: program sounds ignored, system sounds of the user interface still play */
    u8 count;      /* entries queued from queue[0], the playing one included */
};

void sound_tone(struct rcx *b, u16 hz, u8 dur10);   /* PlayTone/PlayToneVar from a program or host */
void sound_system(struct rcx *b, u8 sound);         /* PlaySystemSound 0-5 from a program or host */
void sound_ui(struct rcx *b, u8 sound);             /* a system sound of the user interface (never muted) */
void sound_clear(struct rcx *b);                    /* ClearSound: queue emptied, silence at once */
/* MuteSound / UnmuteSound: muting also clears the queue. A macro, for its one caller: shorter than a call. */
#define sound_mute(b, on) do { if (((b)->sound.muted = (on)) != 0) sound_clear(b); } while (0)
void sound_tick(struct rcx *b);                     /* every 1 ms */

#endif
