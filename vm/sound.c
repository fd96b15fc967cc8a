/*
 * The sound queue. A system sound takes one queue entry, however many notes it has: the sweeps have ten, and
 * queued note by note they would not fit the eight entries, let alone leave room for a program's own tones.
 */
#include "rcx.h"
#include "hal.h"

/* Tones of the system sounds (rcx-hardware.md §3.7): the ten sweep steps from high to low, then click and buzz. */
static const u16 sound_tones[] = { 1389, 1295, 1196, 1096, 996, 893, 796, 694, 598, 498, 1984, 99 };
#define TONE_CLICK 10
#define TONE_BUZZ 11
#define TONE_BEEP 4   /* 996 Hz, also a sweep step */

/* A system sound: `count` notes from sound_tones[first] on, `stride` apart, each `len` long and followed by a rest
 * of `gap` if gap is not 0. Lengths in 10 ms. */
struct system_sound {
    u8 first;
    s8 stride;
    u8 count;
    u8 len;
    u8 gap;
};

/* Numbered as nqc's SOUND_* constants and rcx-hardware.md §3.7. Spec p. 29 lists 2 as "sweep up" and 3 as "sweep
 * down"; the ROM tables and nqc both have 2 falling and 3 rising, and programs are written against nqc. */
static const struct system_sound system_sounds[SOUND_SYSTEM_SOUNDS] = {
    { TONE_CLICK, 0, 1, 1, 3 },   /* key click: 10 ms, 30 ms silence */
    { TONE_BEEP, 0, 2, 15, 5 },   /* beep-beep: 150 ms on, 50 ms off, twice */
    { 0, 1, 10, 6, 0 },           /* sweep down: 60 ms per step */
    { 9, -1, 10, 6, 0 },          /* sweep up */
    { TONE_BUZZ, 0, 1, 100, 0 },  /* error buzz: 1 s */
    { 9, -1, 10, 3, 0 },          /* fast sweep up: 30 ms per step */
};

static void enqueue(struct rcx *b, u16 hz, u8 len)
{
    struct rcx_sound *s = &b->sound;
    struct sound_entry *e = &s->queue[(s->head + s->count) & (SOUND_QUEUE - 1)];
    if (s->count < SOUND_QUEUE) {
        e->hz = hz;
        e->len = len;
        s->count++;
    }
}

void sound_tone(struct rcx *b, u16 hz, u8 dur10)
{
    if (b->sound.muted || !dur10)
        return;
    if (hz < SOUND_MIN_HZ || hz > SOUND_MAX_HZ)
        hz = 0;
    enqueue(b, hz, dur10);
}

void sound_ui(struct rcx *b, u8 sound)
{
    if (sound < SOUND_SYSTEM_SOUNDS)
        enqueue(b, sound, 0);
}

void sound_system(struct rcx *b, u8 sound)
{
    if (!b->sound.muted)
        sound_ui(b, sound);
}

static void play(struct rcx *b, u16 hz)
{
    if (hz || b->sound.sounding)
        hal_sound(b, hz);
    b->sound.sounding = hz != 0;
}

void sound_clear(struct rcx *b)
{
    b->sound.count = 0;
    b->sound.step = 0;
    b->sound.left = 0;
    if (b->sound.sounding)
        play(b, 0);
}

void sound_mute(struct rcx *b, u8 on)
{
    b->sound.muted = on;
    if (on)
        sound_clear(b);
}

/* Note `step` of entry e: its length in 10 ms (0 once the entry is over) and its frequency in *hz. */
static u8 note(const struct sound_entry *e, u8 step, u16 *hz)
{
    const struct system_sound *d;
    u8 k = step, t;

    if (e->len) {
        *hz = e->hz;
        return step ? 0 : e->len;
    }
    d = &system_sounds[e->hz];
    if (d->gap) {
        k >>= 1;
        if (step & 1) {
            *hz = 0;
            return k < d->count ? d->gap : 0;
        }
    }
    if (k >= d->count)
        return 0;
    for (t = d->first; k; k--)
        t = (u8)(t + d->stride);
    *hz = sound_tones[t];
    return d->len;
}

void sound_tick(struct rcx *b)
{
    struct rcx_sound *s = &b->sound;
    u16 hz = 0;
    u8 len;

    if (s->left) {
        if (--s->left)
            return;
        s->step++;
    }
    while (s->count) {
        len = note(&s->queue[s->head], s->step, &hz);
        if (len) {
            play(b, hz);
            s->left = (u16)(len * 10u);
            return;
        }
        s->head = (u8)((s->head + 1) & (SOUND_QUEUE - 1));
        s->count--;
        s->step = 0;
    }
    if (s->sounding)
        play(b, 0);
}
