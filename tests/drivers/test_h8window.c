/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The brick's events_window() (drivers/h8300/eventwindow.S, run in the H8/300 simulator) against its reference, the C
 * of vm/events.c compiled here for the host: random events (sources 0-10 and cleared, types 0-16, states 0-5, the
 * thresholds at and next to the ends of the 16-bit range or anywhere) and keys, lo and hi of the input compared.
 * Then events_look_again() (eventwindow.S too) from random inputs: the inputs and b->sensors_rest compared.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "rcx.h"
#include "access.h"
#include "h8image.h"
#include "sensorfeed.h"

static const char *image_path, *nm_path;

RCX_STATIC_ASSERT(window_layout, sizeof(struct rcx_event) == EV_SIZE && RCX_EVENTS == 16
                                 && sizeof(struct rcx_sensor) == SF_SIZE
                                 && offsetof(struct rcx_event, upper) == EV_UPPER
                                 && offsetof(struct rcx_event, lower) == EV_LOWER
                                 && offsetof(struct rcx, event) - offsetof(struct rcx, sensor) == 66);

/* The rest of the event engine's C links in; events_window() does not reach it. */
void access_input(struct rcx *b, struct rcx_task *t, u8 in) { (void)b, (void)t, (void)in; }

/* The simulator: sensor[] at the scratch RAM, event[] right after it (SF_EVENT - SF_SENSOR on). */
static struct h8 h;
static struct rcx host;
#define H8_SENSORS H8_SCRATCH
#define H8_B (H8_SENSORS - SF_SENSOR)
#define H8_EVENTS (H8_B + SF_EVENT)

static void h8_put_event(unsigned i, const struct rcx_event *e)
{
    uint16_t a = (uint16_t)(H8_EVENTS + i * EV_SIZE);

    memset(&h.mem[a], 0xA5, EV_SIZE); /* the fields not read */
    h.mem[a + EV_SOURCE] = e->source;
    h.mem[a + EV_TYPE] = e->type;
    h.mem[a + EV_STATE] = e->state;
    h8_write16(&h, (uint16_t)(a + EV_UPPER), (uint16_t)e->upper);
    h8_write16(&h, (uint16_t)(a + EV_LOWER), (uint16_t)e->lower);
}

static uint32_t seed = 4321;
static unsigned rnd(unsigned n)
{
    seed = seed * 1103515245u + 12345u;
    return (unsigned)(seed >> 12) % n;
}

/* A threshold: at or next to an end of the range, a small value, or anywhere. */
static s16 threshold(void)
{
    static const s16 ends[] = { -32768, -32767, 32767, 32766, 0, -1, 1 };
    unsigned r = rnd(4);

    if (r == 0)
        return ends[rnd(sizeof ends / sizeof ends[0])];
    if (r < 3)
        return (s16)((int)rnd(201) - 100);
    return (s16)((int)rnd(65536) - 32768);
}

/* Mostly events of the key's input, in a state with a window (types 8-16, states 0-2), so that most runs give one;
 * the rest anything. */
static void random_event(struct rcx_event *e, u8 key, unsigned events)
{
    memset(e, 0, sizeof *e);
    e->source = rnd(3) ? key : (u8)rnd(12);
    e->type = (u8)(rnd(events + 2) ? 8 + rnd(9) : rnd(17));
    e->state = (u8)(rnd(events + 2) ? rnd(3) : rnd(6));
    e->upper = threshold();
    e->lower = rnd(2) ? threshold() : (s16)(e->upper - (int)rnd(50));
}

static void random_events(void **state)
{
    unsigned run, i, windows = 0, none = 0;
    long w;

    (void)state;
    assert_int_equal(h8_image_load(&h, image_path, nm_path), 0);
    w = h8_sym("_events_window");
    assert_true(w > 0);
    for (run = 0; run < 200000; run++) {
        unsigned n = rnd(RCX_SENSORS), events = 1 + rnd(16);
        u8 key = rnd(8) ? EVENTS_KEY(n) : (u8)rnd(12);
        struct rcx_sensor *in = &host.sensor[n];
        uint16_t in_at = (uint16_t)(H8_SENSORS + n * SF_SIZE);
        s16 lo, hi;

        for (i = 0; i < RCX_EVENTS; i++) {
            random_event(&host.event[i], key, events);
            if (i >= events)
                host.event[i].source = (u8)(key + 1); /* another input's */
            h8_put_event(i, &host.event[i]);
        }
        in->lo = 0x1111;
        in->hi = 0x2222;
        h8_write16(&h, (uint16_t)(in_at + SF_LO), 0x1111);
        h8_write16(&h, (uint16_t)(in_at + SF_HI), 0x2222);
        events_window(&host, in, key);
        if (h8_call(&h, (uint16_t)w, H8_B, in_at, key, NULL, 0, 100000) < 0)
            fail_msg("simulator: %s", h.error);
        lo = (s16)h8_read16(&h, (uint16_t)(in_at + SF_LO));
        hi = (s16)h8_read16(&h, (uint16_t)(in_at + SF_HI));
        if (lo != in->lo || hi != in->hi)
            fail_msg("run %u (key %u, %u events): image lo %d hi %d, C lo %d hi %d", run, key, events, lo, hi, in->lo,
                     in->hi);
        if (in->lo == EVENTS_WINDOW_NONE)
            none++;
        else if (in->lo > -32768 || in->hi < 32767)
            windows++;
    }
    /* Both kinds of result, often. */
    assert_true(windows > run / 4 && none > run / 10);
    print_message("%u runs: %u windows, %u with none\n", run, windows, none);
}

/* events_look_again(): each input's fields as the C leaves them, the image's other bytes as they were. b->sensors_rest
 * lands beyond the scratch RAM, on the image's RAM vectors (no interrupt is taken here). */
static void looks_again(void **state)
{
    const uint16_t rest_at = H8_B + SF_REST;
    uint8_t before[RCX_SENSORS * SF_SIZE];
    unsigned run, i, a;
    long f;

    (void)state;
    assert_int_equal(h8_image_load(&h, image_path, nm_path), 0);
    f = h8_sym("_events_look_again");
    assert_true(f > 0);
    for (run = 0; run < 1000; run++) {
        for (a = 0; a < sizeof before; a++)
            before[a] = h.mem[H8_SENSORS + a] = (uint8_t)rnd(256);
        for (i = 0; i < RCX_SENSORS; i++) {
            struct rcx_sensor *s = &host.sensor[i];
            uint16_t at = (uint16_t)(H8_SENSORS + i * SF_SIZE);
            s->quiet = h8_read16(&h, (uint16_t)(at + SF_QUIET));
            s->lo = (s16)h8_read16(&h, (uint16_t)(at + SF_LO));
            s->hi = (s16)h8_read16(&h, (uint16_t)(at + SF_HI));
        }
        host.sensors_rest = h.mem[rest_at] = (u8)(1 + rnd(255));
        h.mem[H8_EVENTS] = 0x5A;
        events_look_again(&host);
        if (h8_call(&h, (uint16_t)f, H8_B, 0, 0, NULL, 0, 100000) < 0)
            fail_msg("simulator: %s", h.error);
        assert_int_equal(h.mem[rest_at], host.sensors_rest);
        for (i = 0; i < RCX_SENSORS; i++) {
            const struct rcx_sensor *s = &host.sensor[i];
            uint16_t at = (uint16_t)(H8_SENSORS + i * SF_SIZE);
            assert_int_equal(h8_read16(&h, (uint16_t)(at + SF_QUIET)), s->quiet);
            assert_int_equal(h8_read16(&h, (uint16_t)(at + SF_LO)), (u16)s->lo);
            assert_int_equal(h8_read16(&h, (uint16_t)(at + SF_HI)), (u16)s->hi);
            for (a = 0; a < SF_SIZE; a++)
                if (a != SF_QUIET && a != SF_QUIET + 1 && a != SF_LO && a != SF_LO + 1 && a != SF_HI && a != SF_HI + 1)
                    assert_int_equal(h.mem[at + a], before[i * SF_SIZE + a]);
        }
        assert_int_equal(h.mem[H8_EVENTS], 0x5A); /* nothing past sensor[] */
    }
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(random_events),
        cmocka_unit_test(looks_again),
    };
    if (h8_image_args(argc, argv, &image_path, &nm_path))
        return 2;
    return cmocka_run_group_tests(tests, NULL, NULL);
}
