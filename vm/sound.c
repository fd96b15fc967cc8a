/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The sound queue. A system sound takes one queue entry, however many notes it has: the sweeps have ten, and
 * queued note by note they would not fit the eight entries, let alone leave room for a program's own tones.
 * The entry playing is always queue[0]; when it is over the others move up one place.
 */
#include "rcx_string.h"
#include "rcx.h"
#include "hal.h"

/* Tones of the system sounds (rcx-hardware.md §3.7): the ten sweep steps from high to low, click, buzz, and a rest. */
static const u16 sound_tones[] = { 1389, 1295, 1196, 1096, 996, 893, 796, 694, 598, 498, 1984, 99, 0 };
#define TONE_BEEP 4   /* 996 Hz, also a sweep step */
#define TONE_CLICK 10
#define TONE_BUZZ 11
#define REST 12

/* Note lengths in 10 ms, by the length code of a note; code 0 ends a system sound. A note is its tone and length
 * code in one byte, the code in the low three bits (fewer shifts to take the tone than a nibble). */
static const u8 note_lengths[] = { 0, 2, 4, 16, 6, 7, 100 };
#define NOTE(tone, code) ((u8)((tone) << 3 | (code)))
RCX_STATIC_ASSERT(notes_fit, sizeof note_lengths <= 8 && sizeof sound_tones / sizeof sound_tones[0] <= 32);
#define SWEEP(code, a, b, c, d, e, f, g, h, i, j) NOTE(a, code), NOTE(b, code), NOTE(c, code), NOTE(d, code), \
    NOTE(e, code), NOTE(f, code), NOTE(g, code), NOTE(h, code), NOTE(i, code), NOTE(j, code)

/*
 * The system sounds, numbered as nqc's SOUND_* constants and rcx-hardware.md §3.7, as notes from system_start[n]
 * to the next 0. Spec p. 29 lists 2 as "sweep up" and 3 as "sweep down"; the ROM tables and nqc both have 2 falling
 * and 3 rising, and programs are written against nqc. The note lengths are firm0328's (reference-firmware.md), each
 * 10 ms longer than §3.7's; the pitches are the exact ones. The 0 in front is where a tone's entry points once its
 * one note has started.
 */
#define NO_NOTES 0
static const u8 system_notes[] = {
    0,
    NOTE(TONE_CLICK, 1), NOTE(REST, 2), 0,                                   /* key click: 20 ms, 40 ms silence */
    NOTE(TONE_BEEP, 3), NOTE(REST, 4), NOTE(TONE_BEEP, 3), NOTE(REST, 4), 0, /* beep-beep: 160 ms on, 60 off, twice */
    SWEEP(5, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9), 0,                               /* sweep down: 70 ms per step */
    SWEEP(5, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0), 0,                               /* sweep up */
    NOTE(TONE_BUZZ, 6), 0,                                                   /* error buzz: 1 s */
    SWEEP(2, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0), 0,                               /* fast sweep up: 40 ms per step */
};
static const u8 system_start[SOUND_SYSTEM_SOUNDS] = { 1, 4, 9, 20, 31, 33 };
RCX_STATIC_ASSERT(system_notes_as_counted, sizeof system_notes == 44); /* system_start[] follows these lengths */

static void enqueue(struct rcx *b, u16 hz, u8 len)
{
    struct rcx_sound *s = &b->sound;
    u8 n = s->count;
    struct sound_entry *e = &s->queue[n];

    if (n < SOUND_QUEUE) {
        e->hz = hz;
        e->len = len;
        s->count = (u8)(n + 1);
    }
}

/* Duration 0 plays 10 ms, as firm0328 does (reference-firmware.md). */
void sound_tone(struct rcx *b, u16 hz, u8 dur10)
{
    if (!dur10)
        dur10 = 1;
    if (hz < SOUND_MIN_HZ || hz > SOUND_MAX_HZ)
        hz = 0;
    if (!b->sound.muted)
        enqueue(b, hz, dur10);
}

void sound_ui(struct rcx *b, u8 sound)
{
    if (sound < SOUND_SYSTEM_SOUNDS)
        enqueue(b, system_start[sound], 0);
}

void sound_system(struct rcx *b, u8 sound)
{
    if (!b->sound.muted)
        sound_ui(b, sound);
}

/* Start a note of hz (each note, even at the pitch before), or silence (0) unless silent already. */
static void play(struct rcx *b, u16 hz)
{
    u16 was = b->sound.sounding;

    b->sound.sounding = hz;
    if (hz || was)
        hal_sound(b, hz);
}

void sound_clear(struct rcx *b)
{
    b->sound.left = 0;
    b->sound.count = 0;
    play(b, 0);
}

/*
 * An entry is a tone while its `len` is not 0; a system sound's entry has `hz` at its next note in system_notes[],
 * and a tone's entry becomes one with no notes left once its note has started.
 */
void sound_tick(struct rcx *b)
{
    struct rcx_sound *s = &b->sound;
    u16 hz;
    u8 len, code;

    if (s->left && --s->left)
        return;
    for (; s->count; s->count--, memmove(s->queue, s->queue + 1, sizeof s->queue - sizeof s->queue[0])) {
        hz = s->queue[0].hz;
        len = s->queue[0].len;
        if (len) {
            s->queue[0].hz = NO_NOTES;
            s->queue[0].len = 0;
        } else {
            code = system_notes[hz];
            hz = sound_tones[code >> 3];
            len = note_lengths[code & 7];
            s->queue[0].hz++;
        }
        if (len) {
            play(b, hz);
            s->left = (u16)(len * 10u);
            return;
        }
    }
    sound_clear(b); /* the queue ran out (left and count are 0 already): silence */
}
