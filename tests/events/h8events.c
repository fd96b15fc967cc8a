/* SPDX-License-Identifier: MPL-2.0 */
/*
 * What events cost the brick (issue 21 item 1), measured on the firmware image running whole in the simulated brick
 * (tests/drivers/h8machine.h): for each case the CPU share of an idle second (no task running) and the byte codes a
 * second of a lone `while (true) x++;` task, with the events set up by direct commands as a host would:
 *   - no events;
 *   - 4 events on a touch sensor that does not move (pressed, released, low, high);
 *   - 16 events on that touch sensor (every type an input has, some twice);
 *   - 16 events on 3 inputs that change every millisecond: a rotation sensor turning at 1 000 steps/s (its count
 *     checked afterwards: no step lost), a light sensor in percent mode with noise on every sample, and a light
 *     sensor in raw mode with slope 10 (change rate) on a triangle wave;
 *   - 16 events on the timers and the counters (no floor in the issue: what the 10 ms look at them costs).
 * With --check it exits non-zero when a figure misses the floor (or the brick stops answering); --still
 * measures and checks the cases with still inputs only (the test events.h8_still_inputs).
 * H8EVENTS_PROFILE=1 prints where each idle millisecond's states go (H8EVENTS_PCS=function: its instructions too);
 * H8EVENTS_MOVING=n sets up only the first n events of the moving case.
 *
 * Usage: h8events <firmware image (COFF; .srec beside it)> <h8300 nm> [--check | --still]
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "h8image.h"
#include "h8machine.h"

static struct h8machine m;
static const char *image, *nm;

/* ---- inputs that move (the channel of input n is AN(2 - n)) ---- */

#define STEP (H8M_CLOCK / 1000)
static unsigned long long moving_from, moving_until;   /* 0: the inputs keep their level */
static const uint16_t rotation_level[4] = { 1000, 860, 400, 640 }; /* phases 0-3 (rcx-hardware.md §3.3) */

/* The steps half way between the ticks, so that each millisecond's sample is one step on (as test_h8machine.c). */
static void moving(struct h8machine *mm, unsigned ch)
{
    unsigned long long t = mm->h.states < moving_until ? mm->h.states : moving_until, k;
    if (!moving_from || t < moving_from)
        return;
    k = (t - moving_from) / STEP;
    if (ch == 2)                                        /* input 1: rotation */
        mm->ad_raw[ch] = rotation_level[k & 3];
    else if (ch == 1)                                   /* input 2: light, noise of 0-31 raw on 700 */
        mm->ad_raw[ch] = (uint16_t)(700 + ((k * 2654435761u) >> 7 & 31));
    else if (ch == 0)                                   /* input 3: a triangle of 300-900, 20 a millisecond */
        mm->ad_raw[ch] = (uint16_t)(300 + 20 * (k % 60 < 30 ? k % 30 : 30 - k % 30));
}

/* ---- direct commands ---- */

static int cmd(const uint8_t *c, unsigned n, uint8_t *reply, unsigned len, unsigned long long *latency)
{
    if (h8m_transact(&m, c, n, reply, len, latency)) {
        fprintf(stderr, "h8events: no reply to %02x at %.1f ms\n", c[0], (double)m.h.states / H8M_MS);
        return -1;
    }
    return 0;
}

static int cmd3(uint8_t a, uint8_t b, uint8_t c)
{
    uint8_t x[3] = { a, b, c };
    return cmd(x, 3, NULL, 1, NULL);
}

static int set_event(uint8_t ev, uint8_t sensor, uint8_t type)
{
    uint8_t x[4] = { 0x93, ev, sensor, type };
    return cmd(x, 4, NULL, 1, NULL);
}

/* SetSourceValue of source src index i to a constant. */
static int set_source(uint8_t src, uint8_t i, int16_t v)
{
    uint8_t x[6] = { 0x05, src, i, 2, (uint8_t)v, (uint8_t)((uint16_t)v >> 8) };
    return cmd(x, 6, NULL, 1, NULL);
}

static int poll(uint8_t src, uint8_t i, int *value)
{
    uint8_t x[3] = { 0x12, src, i }, r[3];
    if (cmd(x, 3, r, 3, NULL))
        return -1;
    *value = (int16_t)(r[1] | r[2] << 8);
    return 0;
}

/* ---- the cases ---- */

enum { NONE, FOUR_STATIC, SIXTEEN_STATIC, SIXTEEN_MOVING, SIXTEEN_VIRTUAL, CASES };
static const char *const case_name[CASES] = {
    "no events", "4 events, static input", "16 events, static input", "16 events, 3 inputs moving",
    "16 on timers and counters",
};
/* The floors: byte codes/s of the lone task, the idle CPU share in %; none for the timers and counters. */
static const double floor_rate[CASES] = { 50000, 48000, 45000, 30000, 0 };
static const double ceiling_idle[CASES] = { 9, 9, 9, 100, 100 };

static int set_up(unsigned which)
{
    static const uint8_t sixteen_static[16] = { 0, 1, 2, 3, 7, 8, 9, 10, 11, 12, 8, 9, 10, 11, 0, 1 };
    static const uint8_t moving_events[16][2] = {       /* input, type */
        { 0, 8 }, { 0, 9 }, { 0, 10 }, { 0, 11 }, { 0, 3 }, { 0, 2 },
        { 1, 8 }, { 1, 9 }, { 1, 10 }, { 1, 11 }, { 1, 12 },
        { 2, 7 }, { 2, 3 }, { 2, 2 }, { 2, 10 }, { 2, 8 },
    };
    unsigned i;

    if (which == FOUR_STATIC || which == SIXTEEN_STATIC) {
        if (cmd3(0x32, 0, 1))                           /* touch sensor on input 1 */
            return -1;
        for (i = 0; i < (which == FOUR_STATIC ? 4u : 16u); i++)
            if (set_event((uint8_t)i, 0, which == FOUR_STATIC ? (uint8_t)(i < 2 ? i : 6 + i) : sixteen_static[i]))
                return -1;
    } else if (which == SIXTEEN_VIRTUAL) {            /* timers 0-3 and counters 0-2, ranges and clicks */
        for (i = 0; i < 16; i++)
            if (set_event((uint8_t)i, (uint8_t)(i < 8 ? 3 + i % 4 : 8 + i % 3), (uint8_t)(8 + i % 4)))
                return -1;
    } else if (which == SIXTEEN_MOVING) {
        if (cmd3(0x32, 0, 4) || cmd3(0x42, 0, 0xE0) ||  /* rotation, angle */
            cmd3(0x32, 1, 3) || cmd3(0x42, 1, 0x80) ||  /* light, percent */
            cmd3(0x32, 2, 3) || cmd3(0x42, 2, 0x0A))    /* light, raw, slope 10 */
            return -1;
        m.ad_input = moving;
        moving_from = m.tick_at + STEP / 2;
        moving_until = ~0ull;
        for (i = 0; i < (getenv("H8EVENTS_MOVING") ? (unsigned)atoi(getenv("H8EVENTS_MOVING")) : 16u); i++)
            if (set_event((uint8_t)i, moving_events[i][0], moving_events[i][1]))
                return -1;
        /* The light's range flips with the noise: 50-53 percent around thresholds 51 and 52. */
        for (i = 6; i <= 10; i++)
            if (set_source(29, (uint8_t)i, 51) || set_source(28, (uint8_t)i, 52))
                return -1;
        if (set_source(28, 14, 800) || set_source(29, 15, 400))
            return -1;
    }
    return 0;
}

/* Self states per function (H8EVENTS_PROFILE). */
#define FUNCS 64
static struct { const char *name; unsigned long long states; } prof[FUNCS];
static unsigned long long pc_states[65536];
static void profile(struct h8 *sim, uint16_t pc, unsigned states)
{
    const char *f = h8_func_at(pc);
    int i;
    (void)sim;
    pc_states[pc] += states;
    for (i = 0; i < FUNCS && prof[i].name && prof[i].name != f; i++)
        ;
    if (i < FUNCS) {
        prof[i].name = f;
        prof[i].states += states;
    }
}

static void dump_profile(void)
{
    int i, j;
    for (i = 0; i < FUNCS && prof[i].name; i++)
        for (j = i + 1; j < FUNCS && prof[j].name; j++)
            if (prof[j].states > prof[i].states) {
                const char *n = prof[i].name;
                unsigned long long s = prof[i].states;
                prof[i] = prof[j];
                prof[j].name = n;
                prof[j].states = s;
            }
    for (i = 0; i < 12 && prof[i].name; i++)
        printf("      %-24s %7.1f states/ms\n", prof[i].name, (double)prof[i].states / 1000);
    memset(prof, 0, sizeof prof);
    if (getenv("H8EVENTS_PCS"))                         /* states per instruction of one function */
        for (i = 0; i < 65536; i++)
            if (pc_states[i] && !strcmp(h8_func_at((uint16_t)i), getenv("H8EVENTS_PCS")))
                printf("        %04x %8.1f\n", i, (double)pc_states[i] / 1000);
    memset(pc_states, 0, sizeof pc_states);
}

struct figures { double idle, rate, ping_ms; int steps, counted; };

/* Task 0 starts the x++ task 1, and samples x after 400 ms and again 500 ms later on the brick's clock; a ping is
 * timed while task 1 spins (as tests/drivers/h8bench.c measures a lone task). */
static int measure(unsigned which, struct figures *f)
{
    static const uint8_t busy[] = { 0x24, 0x00, 0x02, 0x01, 0x00, 0x27, 0x86 };
    static const uint8_t task0[] = { 0x71, 0x01,
                                     0x43, 0x02, 40, 0x00,               /* Wait 400 ms */
                                     0x14, 0x01, 0x00, 0x00, 0x00,       /* var 1 = x */
                                     0x43, 0x02, 50, 0x00,               /* Wait 500 ms */
                                     0x14, 0x02, 0x00, 0x00, 0x00,       /* var 2 = x */
                                     0x50 };                             /* StopAllTasks */
    static const uint8_t ping[] = { 0x10 }, start[] = { 0x71, 0x00 };
    unsigned long long t0, s0, lat;
    int x1, x2;

    memset(f, 0, sizeof *f);
    moving_from = 0;
    m.ad_input = NULL;
    if (h8m_boot(&m, image, nm) || h8m_run(&m, 600 * H8M_MS) || set_up(which) || h8m_run(&m, m.h.states + 50 * H8M_MS))
        return -1;
    t0 = m.h.states;
    s0 = m.slept;
    m.h.trace = getenv("H8EVENTS_PROFILE") ? profile : NULL;
    if (h8m_run(&m, t0 + H8M_CLOCK))
        return -1;
    m.h.trace = NULL;
    f->idle = 100.0 * (1.0 - (double)(m.slept - s0) / (double)(m.h.states - t0));
    if (getenv("H8EVENTS_PROFILE")) {
        printf("    %s, idle:\n", case_name[which]);
        dump_profile();
    }
    if (h8m_download_task(&m, 1, busy, sizeof busy) || h8m_download_task(&m, 0, task0, sizeof task0) ||
        cmd(start, 2, NULL, 1, NULL))
        return -1;
    t0 = m.h.states;
    if (h8m_run(&m, t0 + 100 * H8M_MS) || cmd(ping, 1, NULL, 1, &lat))
        return -1;
    f->ping_ms = (double)lat / H8M_MS;
    if (h8m_run(&m, t0 + 1100 * H8M_MS) || poll(0, 1, &x1) || poll(0, 2, &x2))
        return -1;
    if (x1 <= 0 || x2 <= x1) {
        fprintf(stderr, "h8events: x was %d, then %d\n", x1, x2);
        return -1;
    }
    f->rate = 2.0 * (x2 - x1) / 0.5;
    if (which == SIXTEEN_MOVING) {                      /* the rotation stops; every step counted? */
        moving_until = m.h.states;
        if (h8m_run(&m, m.h.states + 20 * H8M_MS) || poll(9, 0, &f->counted))
            return -1;
        f->steps = (int16_t)(uint16_t)((moving_until - moving_from) / STEP);
    }
    return 0;
}

int main(int argc, char **argv)
{
    int still = argc == 4 && !strcmp(argv[3], "--still"), check = still || (argc == 4 && !strcmp(argv[3], "--check"));
    int bad = 0;
    unsigned i;

    if (argc != 3 && !check) {
        fprintf(stderr, "usage: %s <firmware image> <h8300 nm> [--check | --still]\n", argv[0]);
        return 2;
    }
    image = argv[1];
    nm = argv[2];
    printf("events on the whole image in the simulated brick (h8machine.h): idle CPU share (no task) and a lone\n"
           "x++ task's byte codes/s, against the floors of issue 21\n");
    for (i = 0; i < (still ? (unsigned)SIXTEEN_MOVING : (unsigned)CASES); i++) {
        struct figures f;
        if (measure(i, &f)) {
            printf("  %-28s the brick stopped answering (%s)\n", case_name[i], m.h.error[0] ? m.h.error : "no reply");
            bad = 1;
            continue;
        }
        printf("  %-28s idle %5.1f %% (%5.0f states/ms; ceiling %2.0f %%)  task %6.0f byte codes/s (floor %5.0f)"
               "  ping %.1f ms", case_name[i], f.idle, f.idle * 160, ceiling_idle[i], f.rate, floor_rate[i],
               f.ping_ms);
        if (i == SIXTEEN_MOVING)
            printf("  rotation %d of %d steps", f.counted, f.steps);
        printf("\n");
        if (f.rate < floor_rate[i] || f.idle > ceiling_idle[i] || f.counted != f.steps || f.ping_ms > 30)
            bad = 1;
    }
    return check && bad ? 1 : 0;
}
