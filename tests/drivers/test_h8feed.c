/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The brick's sensor_feed() (drivers/h8300/sensorfeed.S, run in the H8/300 simulator) against its reference, the C
 * of vm/sensors.c compiled here for the host: random sensor states (every mode, slopes 0-31, steady or moving, the
 * history, the rotation phase, events watching the input or not, late samples) fed runs of random samples, the
 * whole struct rcx_sensor compared after each, and the calls to the event engine (events_evaluate(),
 * events_window(): stubs on both sides, which record their arguments and the input as it was when called).
 * Then sensor_scan() (in sensorfeed.S too) the same way: three samples, and b->sensors_rest.
 * Also prints the states a moving light sample in percent mode and a rotation sample in angle mode take.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "rcx.h"
#include "hal.h"
#include "h8image.h"
#include "sensorfeed.h"

static const char *image_path, *nm_path;

RCX_STATIC_ASSERT(feed_layout, sizeof(struct rcx_sensor) == 22 && offsetof(struct rcx_sensor, late) == 21
                               && offsetof(struct rcx_sensor, mode) == SF_MODE
                               && offsetof(struct rcx_sensor, number) == SF_NUMBER);

/* What the event engine was told: which function (1 evaluate, 2 window), its byte arguments, and the input then. */
struct call {
    int fn;
    unsigned a, key;
    struct rcx_sensor in;
};
#define MAX_CALLS 6 /* two a sample, three samples a scan */
struct calls {
    int n;
    struct call c[MAX_CALLS];
};
static struct calls host_calls, h8_calls;

/* --- The host: the C reference with the event engine's entry points as stubs. */
static struct rcx host;

static void host_record(int fn, unsigned a, unsigned key, const struct rcx_sensor *in)
{
    struct call *c;

    if (host_calls.n == MAX_CALLS)
        fail_msg("more than %d calls of the event engine", MAX_CALLS);
    c = &host_calls.c[host_calls.n++];
    c->fn = fn;
    c->a = a;
    c->key = key;
    c->in = *in;
}

void events_evaluate(struct rcx *b, u8 left, u8 only)
{
    assert_ptr_equal(b, &host);
    assert_true(only >= 1 && only <= RCX_SENSORS);
    host_record(1, left, only, &b->sensor[only - 1]);
}

void events_window(struct rcx *b, struct rcx_sensor *in, u8 key)
{
    assert_ptr_equal(b, &host);
    host_record(2, (unsigned)(in - b->sensor), key, in);
}

void events_look_again(struct rcx *b) { (void)b; }
void hal_sensor_power(struct rcx *b, u8 input, u8 on) { (void)b, (void)input, (void)on; }

/* --- The simulator: the image, with the event engine's entry points turned into returns; the calls are seen by the
 * trace hook, once the jsr has reached them. The inputs are in the scratch RAM, b where its sensor[] lands there. */
static struct h8 h;
static uint16_t feed_at, scan_at, evaluate_at, window_at;
#define H8_SENSORS H8_SCRATCH
#define H8_B (H8_SENSORS - SF_SENSOR)
#define H8_SENSOR_SIZE 22

static void h8_get(uint16_t a, struct rcx_sensor *s)
{
    s->quiet = h8_read16(&h, a);
    s->value = (s16)h8_read16(&h, (uint16_t)(a + 2));
    s->raw = h8_read16(&h, (uint16_t)(a + 4));
    s->past[0] = h8_read16(&h, (uint16_t)(a + 6));
    s->past[1] = h8_read16(&h, (uint16_t)(a + 8));
    s->lo = (s16)h8_read16(&h, (uint16_t)(a + 10));
    s->hi = (s16)h8_read16(&h, (uint16_t)(a + 12));
    memcpy(&s->type, &h.mem[a + 14], 8); /* type ... late: bytes in the same order */
}

static void h8_put(uint16_t a, const struct rcx_sensor *s)
{
    h8_write16(&h, a, s->quiet);
    h8_write16(&h, (uint16_t)(a + 2), (uint16_t)s->value);
    h8_write16(&h, (uint16_t)(a + 4), s->raw);
    h8_write16(&h, (uint16_t)(a + 6), s->past[0]);
    h8_write16(&h, (uint16_t)(a + 8), s->past[1]);
    h8_write16(&h, (uint16_t)(a + 10), (uint16_t)s->lo);
    h8_write16(&h, (uint16_t)(a + 12), (uint16_t)s->hi);
    memcpy(&h.mem[a + 14], &s->type, 8);
}

static void h8_seen(struct h8 *m, uint16_t pc, unsigned states)
{
    struct call *c;
    int fn = m->pc == evaluate_at ? 1 : m->pc == window_at ? 2 : 0;
    uint16_t in;

    (void)pc, (void)states;
    if (!fn)
        return;
    if (h8_calls.n == MAX_CALLS)
        fail_msg("more than %d calls of the event engine (image)", MAX_CALLS);
    assert_int_equal(m->r[0], H8_B);
    c = &h8_calls.c[h8_calls.n++];
    c->fn = fn;
    c->key = m->r[2] & 0xFF;
    if (fn == 1) {
        c->a = m->r[1] & 0xFF;
        assert_true(c->key >= 1 && c->key <= RCX_SENSORS);
        in = (uint16_t)(H8_SENSORS + (c->key - 1) * H8_SENSOR_SIZE);
    } else {
        in = m->r[1];
        assert_true(in >= H8_SENSORS && (in - H8_SENSORS) % H8_SENSOR_SIZE == 0);
        c->a = (unsigned)(in - H8_SENSORS) / H8_SENSOR_SIZE;
    }
    h8_get(in, &c->in);
}

static void load_image(void)
{
    long f, e, w;

    assert_int_equal(h8_image_load(&h, image_path, nm_path), 0);
    f = h8_sym("_sensor_feed");
    scan_at = (uint16_t)h8_sym("_sensor_scan");
    e = h8_sym("_events_evaluate");
    w = h8_sym("_events_window");
    assert_true(f > 0 && e > 0 && w > 0);
    feed_at = (uint16_t)f;
    evaluate_at = (uint16_t)e;
    window_at = (uint16_t)w;
    h8_write16(&h, evaluate_at, 0x5470); /* rts */
    h8_write16(&h, window_at, 0x5470);
    h.trace = h8_seen;
    memset(&host, 0, sizeof host);
    for (f = 0; f < RCX_SENSORS; f++)
        h8_put((uint16_t)(H8_SENSORS + f * H8_SENSOR_SIZE), &host.sensor[f]);
}

/* --- Random states and samples. */
static uint32_t seed = 12345;
static unsigned rnd(unsigned n)
{
    seed = seed * 1103515245u + 12345u;
    return (unsigned)(seed >> 12) % n;
}

/* A 10-bit sample: anywhere, or near a value that matters (the ends of the boolean's band and of the scale, the
 * percent switch, the phase edges, the temperature table's ends), or one before. */
static u16 sample(const struct rcx_sensor *s)
{
    static const u16 near[] = { 0, 31, 290, 320, 391, 393, 460, 512, 562, 768, 927, 960, 992, 1023 };
    int r = (int)rnd(8);
    int v;

    if (r < 3)
        return (u16)rnd(1024);
    if (r < 5)
        v = near[rnd(sizeof near / sizeof near[0])] + (int)rnd(7) - 3;
    else if (r < 7)
        return rnd(2) ? s->raw : s->past[rnd(2)];
    else
        v = s->raw + (int)rnd(81) - 40;
    return (u16)(v < 0 ? 0 : v > 1023 ? 1023 : v);
}

static void random_sensor(struct rcx_sensor *s, unsigned n)
{
    s->type = (u8)rnd(5);
    s->mode = (u8)(rnd(8) << 5);
    if (rnd(2))
        s->mode |= (u8)(1 + rnd(31));
    s->raw = (u16)rnd(1024);
    s->past[0] = rnd(3) ? (u16)rnd(1024) : s->raw;
    s->past[1] = rnd(3) ? (u16)rnd(1024) : s->raw;
    s->quiet = rnd(2) ? SENSOR_MOVING : (u16)(SENSOR_STEADY | (rnd(2) ? s->raw : rnd(1024)));
    s->value = (s16)(rnd(3) ? (int)rnd(201) - 100 : (int)rnd(65536) - 32768);
    s->boolean = (u8)rnd(2);
    s->phase = (u8)rnd(5);
    s->watched = rnd(2) ? 0 : (u8)(1 + rnd(16));
    s->number = (u8)n;
    s->lo = rnd(8) ? (s16)(s->value - (int)rnd(20)) : EVENTS_WINDOW_NONE; /* (an event watching every sample) */
    s->hi = rnd(4) ? (s16)(s->value + (int)rnd(20)) : -32768;
    s->others = (u8)rnd(3);
    s->late = (u8)(n == 0 && rnd(4) == 0);
}

static void expect_same(unsigned step)
{
    struct rcx_sensor got;
    unsigned i, c;

    for (i = 0; i < RCX_SENSORS; i++) {
        h8_get((uint16_t)(H8_SENSORS + i * H8_SENSOR_SIZE), &got);
        if (memcmp(&got, &host.sensor[i], sizeof got)) {
            const struct rcx_sensor *w = &host.sensor[i];
            fail_msg("step %u input %u: image quiet %04X value %d raw %u past %u %u lo %d hi %d boolean %u phase %u; "
                     "C quiet %04X value %d raw %u past %u %u lo %d hi %d boolean %u phase %u (mode %02X)", step, i,
                     got.quiet, got.value, got.raw, got.past[0], got.past[1], got.lo, got.hi, got.boolean, got.phase,
                     w->quiet, w->value, w->raw, w->past[0], w->past[1], w->lo, w->hi, w->boolean, w->phase, w->mode);
        }
    }
    assert_int_equal(h8_calls.n, host_calls.n);
    for (c = 0; c < (unsigned)host_calls.n; c++) {
        assert_int_equal(h8_calls.c[c].fn, host_calls.c[c].fn);
        assert_int_equal(h8_calls.c[c].a, host_calls.c[c].a);
        assert_int_equal(h8_calls.c[c].key, host_calls.c[c].key);
        assert_memory_equal(&h8_calls.c[c].in, &host_calls.c[c].in, sizeof(struct rcx_sensor));
    }
}

/* One sample of input n in both; returns the states the image took. */
static unsigned long long feed_both(unsigned n, u16 raw)
{
    unsigned long long before = h.states;

    host_calls.n = h8_calls.n = 0;
    sensor_feed(&host, &host.sensor[n], raw);
    if (h8_call(&h, feed_at, H8_B, (uint16_t)(H8_SENSORS + n * H8_SENSOR_SIZE), raw, NULL, 0, 100000) < 0)
        fail_msg("simulator: %s", h.error);
    return h.states - before;
}

static void random_inputs(void **state)
{
    unsigned round, i, step = 0, events = 0, calls = 0;

    (void)state;
    load_image();
    for (round = 0; round < 20000; round++) {
        for (i = 0; i < RCX_SENSORS; i++) {
            random_sensor(&host.sensor[i], i);
            h8_put((uint16_t)(H8_SENSORS + i * H8_SENSOR_SIZE), &host.sensor[i]);
        }
        for (i = 0; i < 12; i++, step++) {
            unsigned n = rnd(RCX_SENSORS);
            feed_both(n, sample(&host.sensor[n]));
            expect_same(step);
            events += host_calls.n > 0;
            calls += (unsigned)host_calls.n;
        }
    }
    /* The runs must have reached the event engine often, both ways (evaluated, and late). */
    assert_true(events > step / 20);
    print_message("%u samples, %u with calls of the event engine (%u calls)\n", step, events, calls);
}

/* sensor_scan(): the three inputs fed (the raw samples in the scratch RAM after them), then sensors_at_rest() in
 * b->sensors_rest (which lands beyond the scratch RAM, on the image's RAM vectors: no interrupt is taken here). */
static void random_scans(void **state)
{
    const uint16_t raw_at = H8_SENSORS + RCX_SENSORS * H8_SENSOR_SIZE, rest_at = H8_B + SF_REST;
    unsigned round, i, rest = 0;
    u16 raw[RCX_SENSORS];

    (void)state;
    load_image();
    for (round = 0; round < 30000; round++) {
        for (i = 0; i < RCX_SENSORS; i++) {
            struct rcx_sensor *s = &host.sensor[i];
            random_sensor(s, i);
            if (rnd(2)) /* steady, and a sample that keeps it so: the inputs all at rest often */
                s->quiet = (u16)(SENSOR_STEADY | s->raw), s->past[0] = s->past[1] = s->raw;
            h8_put((uint16_t)(H8_SENSORS + i * H8_SENSOR_SIZE), s);
            raw[i] = rnd(3) ? s->raw : sample(s);
            h8_write16(&h, (uint16_t)(raw_at + 2 * i), raw[i]);
        }
        host.sensors_rest = (u8)(2 + rnd(2));
        h.mem[rest_at] = host.sensors_rest;
        host_calls.n = h8_calls.n = 0;
        sensor_scan(&host, raw);
        if (h8_call(&h, scan_at, H8_B, raw_at, 0, NULL, 0, 100000) < 0)
            fail_msg("simulator: %s", h.error);
        expect_same(round);
        assert_int_equal(h.mem[rest_at], host.sensors_rest);
        rest += host.sensors_rest;
    }
    assert_true(rest > round / 20 && rest < round - round / 20);
    print_message("%u scans, %u with the inputs at rest\n", round, rest);
}

/* Every raw value in every mode from a moving state, without slope and with each slope. */
static void every_raw_every_mode(void **state)
{
    unsigned mode, raw;

    (void)state;
    load_image();
    for (mode = 0; mode < 256; mode++)
        for (raw = 0; raw < 1024; raw += mode & 0x1F ? 7 : 1) {
            struct rcx_sensor *s = &host.sensor[1];
            random_sensor(s, 1);
            s->mode = (u8)mode;
            s->quiet = SENSOR_MOVING;
            h8_put(H8_SENSORS + H8_SENSOR_SIZE, s);
            feed_both(1, (u16)raw);
            expect_same(mode << 10 | raw);
        }
}

/* The states of the two samples the brick works out every millisecond under issue 21's load (no event to call). */
static void states_of_moving_samples(void **state)
{
    struct rcx_sensor *s = &host.sensor[2];
    unsigned long long light = 0, angle = 0;
    unsigned i;

    (void)state;
    load_image();
    memset(s, 0, sizeof *s);
    s->mode = SENSOR_MODE_PERCENT;
    h8_put(H8_SENSORS + 2 * H8_SENSOR_SIZE, s);
    for (i = 0; i < 64; i++) {
        light += feed_both(2, (u16)(600 + (i & 1) * 7 + (i & 8)));
        expect_same(i);
    }
    s->mode = SENSOR_MODE_ANGLE;
    h8_put(H8_SENSORS + 2 * H8_SENSOR_SIZE, s);
    for (i = 0; i < 64; i++) {
        static const u16 phases[] = { 1000, 850, 400, 600 };
        angle += feed_both(2, phases[i & 3]);
        expect_same(i);
    }
    print_message("states a sample: light in percent mode %llu, rotation in angle mode %llu\n", light / 64, angle / 64);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(random_inputs),
        cmocka_unit_test(random_scans),
        cmocka_unit_test(every_raw_every_mode),
        cmocka_unit_test(states_of_moving_samples),
    };
    if (h8_image_args(argc, argv, &image_path, &nm_path))
        return 2;
    return cmocka_run_group_tests(tests, NULL, NULL);
}
