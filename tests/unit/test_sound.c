/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Sound engine: the 8-entry queue (reference-firmware.md), tones of 31-20 000 Hz in 10 ms units with rests for
 * other frequencies, the six system sounds of rcx-hardware.md §3.7, ClearSound, Mute/Unmute (spec pp. 19, 23-24,
 * 29, 49, 65). The hardware log is read with the millisecond of every hal_sound() call.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <string.h>
#include <cmocka.h>
#include "brick.h"
#include "fake_hal.h"

struct note_event {
    unsigned ms; /* tick after which hal_sound() had been called: 1 = the first tick after the commands */
    unsigned hz;
};

#define MAX_EVENTS 64

/* Tick `ms` milliseconds and collect every hal_sound() call with its time. */
static unsigned listen(struct rcx *b, unsigned ms, struct note_event *ev)
{
    struct fake_hal *h = fake_hal_of(b);
    unsigned t, n = 0, seen = h->sound_calls;
    for (t = 1; t <= ms; t++) {
        vm_tick(b);
        for (; seen < h->sound_calls && n < MAX_EVENTS; seen++, n++) {
            ev[n].ms = t;
            ev[n].hz = h->sound_log[seen];
        }
    }
    return n;
}

static void expect_events(const struct note_event *got, unsigned n, const struct note_event *want, unsigned wn)
{
    unsigned i;
    for (i = 0; i < n && i < wn; i++)
        if (got[i].ms != want[i].ms || got[i].hz != want[i].hz)
            fail_msg("sound event %u: %u Hz at %u ms, expected %u Hz at %u ms", i, got[i].hz, got[i].ms, want[i].hz,
                     want[i].ms);
    if (n != wn)
        fail_msg("%u sound events, expected %u", n, wn);
}

static void tone(struct rcx *b, u16 hz, u8 dur10)
{
    u8 c[4] = { 0x23, (u8)hz, (u8)(hz >> 8), dur10 };
    brick_cmd(b, c, 4, NULL);
}

static void system_sound(struct rcx *b, u8 n)
{
    u8 c[2] = { 0x51, n };
    brick_cmd(b, c, 2, NULL);
}

static void cmd1(struct rcx *b, u8 op)
{
    brick_cmd(b, &op, 1, NULL);
}

static void tones_play_in_order_for_their_durations(void **state)
{
    static const struct note_event want[] = {
        { 1, 440 }, { 501, 880 }, { 701, 880 }, { 711, 0 }, { 721, 31 }, { 731, 20000 }, { 741, 0 },
    };
    struct note_event ev[MAX_EVENTS];
    struct rcx *b = brick_new();
    unsigned n;
    (void)state;
    tone(b, 440, 50);     /* 500 ms */
    tone(b, 880, 20);
    tone(b, 880, 1);      /* the same pitch again is a new note */
    tone(b, 30, 1);       /* below 31 Hz: a 10 ms rest */
    tone(b, 31, 1);
    tone(b, 20000, 1);
    tone(b, 20001, 1);    /* above 20 kHz: a rest at the end, silent already */
    n = listen(b, 1000, ev);
    expect_events(ev, n, want, sizeof want / sizeof want[0]);
    brick_free(b);
}

static void rests_keep_their_place(void **state)
{
    static const struct note_event want[] = { { 1, 500 }, { 101, 0 }, { 151, 1000 }, { 161, 600 }, { 181, 0 } };
    struct note_event ev[MAX_EVENTS];
    struct rcx *b = brick_new();
    unsigned n;
    u8 zero_length[4] = { 0x23, 0xE8, 0x03, 0 };
    (void)state;
    tone(b, 500, 10);
    tone(b, 0, 5);        /* 0 Hz: 50 ms of silence */
    brick_cmd(b, zero_length, 4, NULL); /* duration 0: 10 ms, as firm0328 plays it (reference-firmware.md) */
    tone(b, 600, 2);
    n = listen(b, 400, ev);
    expect_events(ev, n, want, sizeof want / sizeof want[0]);
    brick_free(b);
}

static void queue_holds_eight(void **state)
{
    struct note_event ev[MAX_EVENTS];
    struct rcx *b = brick_new();
    unsigned i, n;
    (void)state;
    for (i = 0; i < 10; i++)
        tone(b, (u16)(100 * (i + 1)), 1); /* 100 ... 1000 Hz: the last two find the queue full */
    n = listen(b, 200, ev);
    assert_int_equal(n, 9);
    for (i = 0; i < 8; i++) {
        assert_int_equal(ev[i].ms, 1 + 10 * i);
        assert_int_equal(ev[i].hz, 100 * (i + 1));
    }
    assert_int_equal(ev[8].ms, 81);
    assert_int_equal(ev[8].hz, 0);

    for (i = 0; i < 8; i++)
        tone(b, 1000, 10);                /* full again; the note playing holds its entry until it ends */
    listen(b, 1, ev);
    tone(b, 2000, 10);                    /* dropped */
    listen(b, 100, ev);                   /* first note over at 101: one entry free */
    tone(b, 3000, 10);
    n = listen(b, 800, ev);
    assert_int_equal(n, 8);               /* 7 more notes of 1000 Hz, then 3000 Hz, then silence */
    assert_int_equal(ev[6].hz, 3000);
    assert_int_equal(ev[6].ms, 700);
    assert_int_equal(ev[7].hz, 0);
    brick_free(b);
}

static void system_sound_compositions(void **state)
{
    /* rcx-hardware.md §3.7 for the pitches, firm0328's note lengths (reference-firmware.md, "The brick's face"), in
     * ms; each followed by a 1 kHz marker tone to time the sound's end. */
    static const struct { u8 sound; unsigned count; struct note_event ev[14]; } rows[] = {
        { 0, 3, { { 1, 1984 }, { 21, 0 }, { 61, 1000 } } },
        { 1, 5, { { 1, 996 }, { 161, 0 }, { 221, 996 }, { 381, 0 }, { 441, 1000 } } },
        { 2, 11, { { 1, 1389 }, { 71, 1295 }, { 141, 1196 }, { 211, 1096 }, { 281, 996 }, { 351, 893 },
                   { 421, 796 }, { 491, 694 }, { 561, 598 }, { 631, 498 }, { 701, 1000 } } },
        { 3, 11, { { 1, 498 }, { 71, 598 }, { 141, 694 }, { 211, 796 }, { 281, 893 }, { 351, 996 },
                   { 421, 1096 }, { 491, 1196 }, { 561, 1295 }, { 631, 1389 }, { 701, 1000 } } },
        { 4, 2, { { 1, 99 }, { 1001, 1000 } } },
        { 5, 11, { { 1, 498 }, { 41, 598 }, { 81, 694 }, { 121, 796 }, { 161, 893 }, { 201, 996 },
                   { 241, 1096 }, { 281, 1196 }, { 321, 1295 }, { 361, 1389 }, { 401, 1000 } } },
    };
    unsigned i;
    (void)state;
    for (i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        struct note_event ev[MAX_EVENTS], want[16];
        struct rcx *b = brick_new();
        unsigned n, c = rows[i].count;
        system_sound(b, rows[i].sound);
        tone(b, 1000, 1);
        n = listen(b, 1200, ev);
        memcpy(want, rows[i].ev, c * sizeof want[0]);
        want[c].ms = want[c - 1].ms + 10; /* end of the marker */
        want[c].hz = 0;
        expect_events(ev, n, want, c + 1);
        brick_free(b);
    }
}

static void system_sound_is_one_queue_entry(void **state)
{
    struct note_event ev[MAX_EVENTS];
    struct rcx *b = brick_new();
    unsigned i, n;
    (void)state;
    system_sound(b, 2);                   /* ten notes, one entry */
    for (i = 0; i < 8; i++)
        tone(b, (u16)(100 * (i + 1)), 1); /* seven fit */
    n = listen(b, 1000, ev);
    assert_int_equal(n, 10 + 7 + 1);
    assert_int_equal(ev[10].hz, 100);
    assert_int_equal(ev[16].hz, 700);
    assert_int_equal(ev[17].hz, 0);
    assert_int_equal(ev[17].ms, 771);     /* ten steps of 70 ms, seven tones of 10 ms */
    brick_free(b);
}

/* The last hal_sound() call was 0, made just now (outside any tick). */
static void expect_silenced_now(struct rcx *b, unsigned calls_before)
{
    struct fake_hal *h = fake_hal_of(b);
    assert_int_equal(h->sound_calls, calls_before + 1);
    assert_int_equal(h->sound_log[calls_before], 0);
}

static void clear_sound_silences_at_once(void **state)
{
    static const struct note_event first[] = { { 1, 440 } }, after[] = { { 1, 660 }, { 11, 0 } };
    struct note_event ev[MAX_EVENTS];
    struct rcx *b = brick_new();
    unsigned n, calls;
    (void)state;
    tone(b, 440, 100);
    tone(b, 550, 100);
    system_sound(b, 4);
    n = listen(b, 49, ev);
    expect_events(ev, n, first, 1);
    calls = fake_hal_of(b)->sound_calls;
    cmd1(b, 0x80);                        /* ClearSound: queue emptied, the tone stops now */
    expect_silenced_now(b, calls);
    tone(b, 660, 1);
    n = listen(b, 300, ev);
    expect_events(ev, n, after, 2);
    brick_free(b);
}

static void mute_ignores_program_sounds_only(void **state)
{
    static const struct note_event first[] = { { 1, 440 } }, click[] = { { 1, 1984 }, { 21, 0 } },
                                   after[] = { { 1, 770 }, { 11, 0 } };
    struct note_event ev[MAX_EVENTS];
    struct rcx *b = brick_new();
    unsigned n, calls;
    u8 set_var[5] = { 0x14, 3, 2, 0xB8, 0x01 }, tone_var[3] = { 0x02, 3, 5 };
    (void)state;
    tone(b, 440, 100);
    tone(b, 440, 100);
    n = listen(b, 10, ev);
    expect_events(ev, n, first, 1);
    calls = fake_hal_of(b)->sound_calls;
    cmd1(b, 0xD0);                        /* MuteSound: empties the queue and silences */
    expect_silenced_now(b, calls);
    tone(b, 660, 10);                     /* program sounds are ignored while muted */
    system_sound(b, 1);
    brick_cmd(b, set_var, 5, NULL);
    brick_cmd(b, tone_var, 3, NULL);
    sound_ui(b, 0);                       /* a button click still sounds */
    n = listen(b, 300, ev);
    expect_events(ev, n, click, 2);
    cmd1(b, 0xE0);                        /* UnmuteSound */
    tone(b, 770, 1);
    n = listen(b, 100, ev);
    expect_events(ev, n, after, 2);
    brick_free(b);
}

static void tone_from_a_variable(void **state)
{
    static const struct note_event want[] = { { 1, 440 }, { 51, 0 }, { 101, 523 }, { 111, 0 } };
    struct note_event ev[MAX_EVENTS];
    struct rcx *b = brick_new();
    unsigned n;
    u8 v440[5] = { 0x14, 7, 2, 0xB8, 0x01 }, vneg[5] = { 0x14, 8, 2, 0xFB, 0xFF }, v523[5] = { 0x14, 9, 2, 0x0B, 0x02 };
    u8 p7[3] = { 0x02, 7, 5 }, p8[3] = { 0x02, 8, 5 }, p9[3] = { 0x02, 9, 1 };
    (void)state;
    brick_cmd(b, v440, 5, NULL);
    brick_cmd(b, vneg, 5, NULL);          /* -5: 65531 Hz, out of range, a rest */
    brick_cmd(b, v523, 5, NULL);
    brick_cmd(b, p7, 3, NULL);
    brick_cmd(b, p8, 3, NULL);
    brick_cmd(b, p9, 3, NULL);
    n = listen(b, 300, ev);
    expect_events(ev, n, want, sizeof want / sizeof want[0]);
    brick_free(b);
}

static void bad_operands_change_nothing(void **state)
{
    static const struct { const char *what; u8 bytes[4]; u8 len; } rows[] = {
        { "PlaySystemSound 6", { 0x51, 0x06 }, 2 },
        { "PlaySystemSound 255", { 0x51, 0xFF }, 2 },
        { "PlayToneVar variable 48", { 0x02, 48, 10 }, 3 },
        { "PlayToneVar variable 200", { 0x02, 200, 10 }, 3 },
        { "PlayToneVar local variable from a host", { 0x02, 40, 10 }, 3 },
    };
    unsigned i;
    (void)state;
    for (i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        struct rcx *b = brick_new();
        struct rcx_sound before;
        tone(b, 440, 10);
        vm_tick(b);
        memcpy(&before, &b->sound, sizeof before);
        brick_cmd(b, rows[i].bytes, rows[i].len, NULL);
        sound_ui(b, 6);
        if (memcmp(&before, &b->sound, sizeof before) != 0)
            fail_msg("%s changed the sound queue", rows[i].what);
        brick_free(b);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(tones_play_in_order_for_their_durations),
        cmocka_unit_test(rests_keep_their_place),
        cmocka_unit_test(queue_holds_eight),
        cmocka_unit_test(system_sound_compositions),
        cmocka_unit_test(system_sound_is_one_queue_entry),
        cmocka_unit_test(clear_sound_silences_at_once),
        cmocka_unit_test(mute_ignores_program_sounds_only),
        cmocka_unit_test(tone_from_a_variable),
        cmocka_unit_test(bad_operands_change_nothing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
