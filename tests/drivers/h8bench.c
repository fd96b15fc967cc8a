/* SPDX-License-Identifier: MPL-2.0 */
/*
 * `make bench` (tests/bench/firmware.sh): byte codes per second of the firmware image, counted in the H8/300
 * simulator (h8sim.h gives the timing model) on the `x++` loop nqc makes of `while (true) x++;`
 * (SumVar var 0 += 1; SJump back: two byte codes per pass): first function by function (where the states go), then
 * the whole image running in a simulated brick (h8machine.h) with 1 and 9 busy tasks, as the issue measured it.
 *
 * The image's own functions run as the brick runs them: the runtime initialised, the program downloaded and
 * started by direct commands, then vm_run and rt_run timed; the per-millisecond work (the tick interrupt with the
 * ROM's interrupt entry, rt_tick, the samples and buttons) is timed and taken off the 16 MHz first.
 *
 * Usage: h8bench <firmware image (COFF; .srec beside it)> <h8300 nm>
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "h8image.h"
#include "h8machine.h"

#define CLOCK 16000000.0
#define RUNS 2000               /* byte codes timed */
#define BUDGET 40               /* a lone task's chunk between checks of the tick: vm/rcx.h RCX_RUN_CHUNK */
#define IRQ_ENTRY 48            /* interrupt exception (~14 states) + the ROM's trampoline in on-chip ROM (~34) */
#define CMD (H8_SCRATCH)
#define REPLY (H8_SCRATCH + 0x80)

static struct h8 h;
static uint16_t brick;

static const uint8_t loop[] = { 0x24, 0x00, 0x02, 0x01, 0x00, 0x27, 0x86 }; /* nqc -TRCX2 -L: sumv var[0],1; jmp 6 */

static unsigned direct(const uint8_t *cmd, unsigned len)
{
    uint16_t reply = REPLY;
    memcpy(h.mem + CMD, cmd, len);
    return (unsigned)h8_run(&h, "_vm_direct", brick, CMD, (uint16_t)len, &reply, 1) & 0xFF;
}

/* The converter in single mode, over when ADCSR is next read (ADF set, ADST cleared). */
static uint8_t single_conversion(struct h8 *sim, uint16_t a, uint8_t held)
{
    if (a == 0xFFE8 && (held & 0x30) == 0x20)
        held = sim->mem[a] = (uint8_t)((held | 0x80) & ~0x20);
    return held;
}

static unsigned long long timed(const char *fn, uint16_t r0, uint16_t r1)
{
    unsigned long long before = h.states;
    h8_run(&h, fn, r0, r1, 0, NULL, 0);
    return h.states - before;
}

static int get_x(void)
{
    static const uint8_t poll[] = { 0x12, 0x00, 0x00 }; /* Poll source 0 (variable), index 0 */
    if (direct(poll, sizeof poll) != 3)
        return -1;
    return h.mem[REPLY + 1] | h.mem[REPLY + 2] << 8;
}

/* Self states per function while the interpreter runs. */
#define FUNCS 64
struct prof { const char *name; unsigned long long states; };
static struct prof prof[FUNCS], prof_run[FUNCS];
static unsigned long long pc_states[65536];
static void profile(struct h8 *sim, uint16_t pc, unsigned states)
{
    pc_states[pc] += states;
    const char *f = h8_func_at(pc);
    int i;
    (void)sim;
    for (i = 0; i < FUNCS && prof[i].name; i++)
        if (prof[i].name == f)
            break;
    if (i == FUNCS)
        return;
    prof[i].name = f;
    prof[i].states += states;
}

static int by_states(const void *a, const void *b)
{
    unsigned long long x = ((const struct prof *)a)->states, y = ((const struct prof *)b)->states;
    return x < y ? 1 : x > y ? -1 : 0;
}

static void dump(const char *what, unsigned div)
{
    unsigned i;
    qsort(prof, FUNCS, sizeof prof[0], by_states);
    printf("%s:\n", what);
    for (i = 0; i < 25 && prof[i].name; i++)
        printf("  %-24s %8.1f\n", prof[i].name, (double)prof[i].states / div);
}

/* ---- the whole image running: main(), its interrupts and sleep (h8machine.h) ---- */

static struct h8machine mach;

static int poll_var(struct h8machine *m, uint8_t v, unsigned long long *latency)
{
    uint8_t poll[3] = { 0x12, 0x00, 0 }, reply[3];
    poll[2] = v;
    if (h8m_transact(m, poll, sizeof poll, reply, 3, latency)) {
        fprintf(stderr, "h8bench: no reply to Poll %u (%s)\n", v, m->h.error);
        if (getenv("H8BENCH_DEBUG")) {
            unsigned i;
            for (i = m->nsent > 40 ? m->nsent - 40 : 0; i < m->nsent; i++)
                fprintf(stderr, " %02x@%.1f", m->sent[i], m->sent_at[i] / 16000.0);
            fprintf(stderr, "\nnow %.1f ms\n", m->h.states / 16000.0);
        }
        return -99999;
    }
    return (int16_t)(reply[1] | reply[2] << 8);
}

struct whole { double idle_share, rate, ping_ms; int turned, steps; };

/*
 * A program's inputs and events (issue 21), set up by direct commands before the idle second: `events` events (0:
 * none), on a still touch sensor on input 1 (the table: pressed, released, low, high, then every other type
 * in turn), or with `changing`, spread over three inputs that change every millisecond: a rotation sensor at 1 000
 * steps a second on input 1, noisy light sensors on inputs 2 and 3 (a sweep of 300-900 raw in 400 ms, +-20 each
 * millisecond).
 */
struct load { unsigned events; int changing; };
static unsigned long long stim_from;

static void stimulus(struct h8machine *m, unsigned ch)
{
    unsigned long long t = m->h.states - stim_from;
    if (m->h.states < stim_from)
        return;
    if (ch == 2)                       /* input 1: a step each millisecond, half way between ticks */
        m->ad_raw[2] = h8m_rotation_raw((t + H8M_MS / 2) / H8M_MS);
    else if (ch < 2)                   /* inputs 2 and 3, 100 ms apart in their sweeps */
        m->ad_raw[ch] = h8m_light_sweep_raw(t / H8M_MS + 100 * ch);
}

static int load_setup(struct h8machine *m, const struct load *ld)
{
    static const uint8_t still_types[] = { 0, 1, 8, 10, 2, 3, 7, 9, 11, 12 };
    static const uint8_t changing_types[] = { 8, 9, 10, 11 };
    uint8_t cmd[4];
    unsigned e, i;

    for (i = 0; i < (ld->changing ? 3u : ld->events ? 1u : 0u); i++) {
        cmd[0] = 0x32;                 /* SetSensorType: touch; rotation, light, light */
        cmd[1] = (uint8_t)i;
        cmd[2] = (uint8_t)(!ld->changing ? 1 : i ? 3 : 4);
        if (h8m_transact(m, cmd, 3, NULL, 1, NULL))
            return -1;
    }
    for (e = 0; e < ld->events; e++) {
        cmd[0] = 0x93;                 /* SetEvent e, input, type */
        cmd[1] = (uint8_t)e;
        cmd[2] = (uint8_t)(ld->changing ? e % 3 : 0);
        cmd[3] = ld->changing ? changing_types[e / 3 % sizeof changing_types] : still_types[e % sizeof still_types];
        if (h8m_transact(m, cmd, 4, NULL, 1, NULL))
            return -1;
    }
    if (ld->changing) {
        stim_from = m->tick_at + H8M_MS / 2; /* its steps half way between two ticks, as the stimulus says */
        m->ad_input = stimulus;
    }
    return 0;
}

/*
 * As the table was measured on an emulated brick: `busy` tasks run `while (true) x++;` while task 0 waits on
 * the brick's own clock and samples x before and after 500 ms (its first Wait also puts it on the 10 ms grid); the
 * host reads the samples back with Poll. Before the program, one second with nothing to do gives the share of the
 * CPU that the millisecond costs; while the tasks spin, a ping is timed from its last byte to the reply.
 */
static int whole_image(const char *image, const char *nm, unsigned busy, int swan, const struct load *ld,
                       struct whole *w)
{
    static const uint8_t rcx2_code[] = { 0x24, 0x00, 0x02, 0x01, 0x00, 0x27, 0x86 };
    static const uint8_t swan_code[] = { 0x48, 0x00, 0x01, 0x27, 0x84 }; /* nqc -TSwan -L: sumgb gvar[0], 1; jmp 6 */
    const uint8_t *busy_code = swan ? swan_code : rcx2_code;
    unsigned busy_size = swan ? sizeof swan_code : sizeof rcx2_code;
    static const uint8_t tail[] = { 0x43, 0x02, 40, 0x00,                 /* Wait 400 ms: the pings */
                                    0x14, 0x01, 0x00, 0x00, 0x00,         /* var 1 = x */
                                    0x43, 0x02, 50, 0x00,                 /* Wait 500 ms */
                                    0x14, 0x02, 0x00, 0x00, 0x00,         /* var 2 = x */
                                    0x50 };                               /* StopAllTasks */
    static const uint8_t ping[] = { 0x10 }, start[] = { 0x71, 0x00 };
    struct h8machine *m = &mach;
    uint8_t code[64];
    unsigned k = 0, i;
    unsigned long long t0, s0, ts, lat, worst = 0;
    int x1, x2;

    if (h8m_boot(m, image, nm) || h8m_run(m, 600 * H8M_MS) /* past the double beep it starts with */
        || load_setup(m, ld))
        goto failed;
    t0 = m->h.states;
    s0 = m->slept;
    memset(prof, 0, sizeof prof);
    m->h.trace = getenv("H8BENCH_PROFILE") ? profile : NULL;
    if (h8m_run(m, t0 + H8M_CLOCK))
        goto failed;
    m->h.trace = NULL;
    if (getenv("H8BENCH_PROFILE"))
        dump("idle second, per ms", 1000);
    if (getenv("H8BENCH_PCS")) {
        unsigned a;
        for (a = 0; a < 65536; a++)
            if (pc_states[a] && !strcmp(h8_func_at((uint16_t)a), getenv("H8BENCH_PCS")))
                printf("  %04x %8.1f\n", a, pc_states[a] / 1000.0);
    }
    w->idle_share = 1.0 - (double)(m->slept - s0) / (double)(m->h.states - t0);
    for (i = 1; i <= busy; i++) {
        code[k++] = 0x71;
        code[k++] = (uint8_t)i;
        if (h8m_download_task(m, (uint8_t)i, busy_code, busy_size))
            goto failed;
    }
    memcpy(code + k, tail, sizeof tail);
    if (h8m_download_task(m, 0, code, k + sizeof tail) || h8m_transact(m, start, 2, NULL, 1, NULL))
        goto failed;
    ts = m->h.states;
    h8m_run(m, ts + 50 * H8M_MS);
    for (i = 0; i < 2; i++) {
        if (h8m_transact(m, ping, 1, NULL, 1, &lat))
            goto failed;
        if (lat > worst)
            worst = lat;
    }
    memset(prof, 0, sizeof prof);
    m->h.trace = getenv("H8BENCH_PROFILE") ? profile : NULL;
    if (h8m_run(m, ts + 1100 * H8M_MS))
        goto failed;
    m->h.trace = NULL;
    if (getenv("H8BENCH_PROFILE"))
        dump("busy, per ms", 1000);
    x1 = poll_var(m, 1, NULL);
    x2 = poll_var(m, 2, NULL);
    w->steps = w->turned = 0;
    if (ld->changing) {                /* the rotation sensor's count against the steps it made */
        uint8_t poll[3] = { 0x12, 9, 0 }, reply[3];
        m->ad_input = NULL;            /* the sensor stops here: the steps it made, then the count it shows */
        w->steps = (int)((m->h.states - stim_from + H8M_MS / 2) / H8M_MS);
        if (h8m_transact(m, poll, sizeof poll, reply, 3, NULL))
            goto failed;
        w->turned = (int16_t)(reply[1] | reply[2] << 8);
    }
    if (x1 <= 0 || x2 <= x1) {
        fprintf(stderr, "h8bench: x was %d, then %d\n", x1, x2);
        return -1;
    }
    w->rate = 2.0 * (x2 - x1) / 0.5;
    w->ping_ms = 1000.0 * (double)worst / (double)H8M_CLOCK;
    return 0;
failed:
    fprintf(stderr, "h8bench: the whole image: %s\n", m->h.error[0] ? m->h.error : "no reply");
    return -1;
}

int main(int argc, char **argv)
{
    uint8_t begin[6] = { 0x25, 0x00, 0x00, 0x00, sizeof loop, 0x00 }, block[6 + sizeof loop], start[2] = { 0x71, 0 };
    unsigned long long run, loop_pass, per_ms, tick_irq, adi_irq, tick, samples, insns, before;
    unsigned i, sum = 0;
    int x0, x1;
    double per_code, in_loop, avail, rate;

    if (argc != 3) {
        fprintf(stderr, "usage: %s <firmware image> <h8300 nm>\n", argv[0]);
        return 2;
    }
    if (h8_image_load(&h, argv[1], argv[2]))
        return 1;
    brick = (uint16_t)h8_sym("_brick");
    h8_run(&h, "_rt_init", brick, brick, 0, NULL, 0);

    block[0] = 0x45; /* the single, and so last, block: number 0 */
    block[1] = block[2] = 0;
    block[3] = sizeof loop;
    block[4] = 0;
    for (i = 0; i < sizeof loop; i++)
        sum += block[5 + i] = loop[i];
    block[5 + sizeof loop] = (uint8_t)sum;
    if (direct(begin, sizeof begin) != 2 || h.mem[REPLY + 1] || direct(block, sizeof block) != 2 || h.mem[REPLY + 1]) {
        fprintf(stderr, "h8bench: the image refused the download\n");
        return 1;
    }
    direct(start, sizeof start);

    h8_run(&h, "_vm_run", brick, 2, 0, NULL, 0); /* warm: the task is past its first pass */
    x0 = get_x();
    insns = h.insns;
    h.trace = profile;
    run = timed("_vm_run", brick, RUNS);
    h.trace = NULL;
    qsort(prof, FUNCS, sizeof prof[0], by_states);
    memcpy(prof_run, prof, sizeof prof);
    memset(prof, 0, sizeof prof);
    insns = h.insns - insns;
    x1 = get_x();
    if (x0 < 0 || x1 - x0 != RUNS / 2) {
        fprintf(stderr, "h8bench: x went from %d to %d in %d byte codes, expected +%d\n", x0, x1, RUNS, RUNS / 2);
        return 1;
    }

    /* One main-loop pass: the drivers' receive and mode checks, then rt_run with the budget. */
    loop_pass = timed("_sci_drain", brick, 0) + timed("_sci_service", 0, 0) + timed("_rt_run", brick, BUDGET);

    /* Each millisecond: the two interrupts (each with the ROM's entry), rt_tick, 3 samples and a button poll.
     * Timed over 100 ms, as some engines do their work every 10 or 50 ms. rt_tick is inline (runtime.h): its
     * calls, of which ir_tick is not due with the link quiet. */
    h.trace = profile;
    tick = 0;
    samples = 0;
    for (i = 0; i < 100; i++) {
        tick += timed("_vm_tick", brick, 0) + timed("_ui_tick", brick, 0);
        h.mem[REPLY] = h.mem[REPLY + 2] = h.mem[REPLY + 4] = 0x03; /* three inputs at 1023: nothing connected */
        h.mem[REPLY + 1] = h.mem[REPLY + 3] = h.mem[REPLY + 5] = 0xFF;
        samples += timed("_sensor_scan", brick, REPLY);
        before = h.states; /* the buttons' pins looked at, a millisecond later each time */
        h8_run(&h, "_hw_debounce", H8_SCRATCH, 0, (uint16_t)i, NULL, 0);
        samples += h.states - before;
    }
    h.trace = NULL;
    tick /= 100;
    samples /= 100;
    /* No active sensor (the benchmark has none): the tick reads the scan that runs on (ADF, ADST, SCAN, AN0-AN3).
     * An active sensor adds its own conversion, awaited in the tick (at most 266 states, here over at the first
     * look: single_conversion). */
    h.mem[0xFFE8] = 0xB3;
    tick_irq = timed("_rcx_timer_irq", 0, 0) + IRQ_ENTRY;
    h.mem[0xFFE8] = 0xB3;
    h.mem[(uint16_t)h8_sym("_drv_sensor_power")] = 0x01;
    h.io_read = single_conversion;
    adi_irq = timed("_rcx_timer_irq", 0, 0) + IRQ_ENTRY + 266 - tick_irq;
    h.io_read = NULL;
    h.mem[(uint16_t)h8_sym("_drv_sensor_power")] = 0;
    per_ms = tick_irq + tick + samples;

    per_code = (double)run / RUNS;
    in_loop = (double)loop_pass / BUDGET;
    avail = CLOCK - 1000.0 * (double)per_ms;
    rate = avail / in_loop;
    printf("firmware on the 16 MHz brick (H8/300 simulator; code and data in external RAM), x++ loop, 1 task:\n");
    printf("  vm_run                %5.0f states per byte code, %.1f instructions (%.1f states each)\n", per_code,
           (double)insns / RUNS, (double)run / (double)insns);
    printf("  main loop             %5.0f states per byte code (rt_run, budget %d, with the loop's own checks)\n",
           in_loop, BUDGET);
    printf("  a ticked millisecond  %5llu states: tick interrupt %llu (with %d of ROM entry), rt_tick %llu,\n"
           "                        samples and buttons %llu: %.1f %% of the CPU (an active sensor adds its\n"
           "                        conversion in the tick, %llu states, %.1f %%)\n",
           per_ms, tick_irq, IRQ_ENTRY, tick, samples, 100.0 * (double)per_ms * 1000.0 / CLOCK,
           adi_irq, 100.0 * (double)adi_irq * 1000.0 / CLOCK);
    printf("  estimate              %5.0f byte codes/s (%.0f x++ per second); per-function estimate\n",
           rate, rate / 2);
    printf("  where the states go (self states of each function):\n    %-30s %-30s\n",
           "vm_run, per byte code", "each millisecond");
    qsort(prof, FUNCS, sizeof prof[0], by_states);
    for (i = 0; i < 12 && (prof_run[i].name || prof[i].name); i++) {
        char a[40] = "", b[40] = "";
        if (prof_run[i].name)
            snprintf(a, sizeof a, "%-22s %6.0f", prof_run[i].name, (double)prof_run[i].states / RUNS);
        if (prof[i].name)
            snprintf(b, sizeof b, "%-22s %6.0f", prof[i].name, (double)prof[i].states / 100);
        printf("    %-30s %-30s\n", a, b);
    }
    {
        static const struct load none = { 0, 0 }, loads[4] = { { 4, 0 }, { 16, 0 }, { 4, 1 }, { 16, 1 } };
        static const char *const load_name[4] = { "4 events, still input", "16 events, still input",
                                                  "4 events, 3 inputs changing", "16 events, 3 inputs changing" };
        static const unsigned floor[4] = { 48000, 45000, 0, 30000 };
        struct whole one, ten, swan, ev[4];
        int has_swan = h8_sym("_swan_exec") >= 0; /* an image with Swan's programs (issue 16) */
        if (whole_image(argv[1], argv[2], 1, 0, &none, &one) || whole_image(argv[1], argv[2], 9, 0, &none, &ten) ||
            (has_swan && whole_image(argv[1], argv[2], 1, 1, &none, &swan)))
            return 1;
        for (i = 0; i < 4; i++)
            if (whole_image(argv[1], argv[2], 1, 0, &loads[i], &ev[i]))
                ev[i].rate = -1;       /* the brick went deaf (images before issue 21) */
        printf("the whole image in a simulated brick (main loop, interrupts, sleep, IR at 2400 Bd; h8machine.h),\n"
               "measured as on the emulated RCX: x++ tasks, a task samples x over 500 ms of the brick's clock:\n");
        printf("  1 busy task      %6.0f byte codes/s (%5.0f x++/s)  floor >= 50000; firm0328 366 (183)\n",
               one.rate, one.rate / 2);
        printf("  9 busy tasks     %6.0f byte codes/s (%5.0f x++/s)  firm0328 3054 (1527)\n",
               ten.rate, ten.rate / 2);
        if (has_swan)
            printf("  Swan, 1 task     %6.0f byte codes/s (%5.0f x++/s)  nqc -TSwan: sumgb + jmp; goal: the RCX 2.0 "
                   "x++/s above\n", swan.rate, swan.rate / 2);
        else
            printf("  Swan, 1 task     not in this image (built with RCX_IMAGE_SWAN=OFF)\n");
        printf("  nothing to do    %6.1f %% of the CPU every millisecond  floor <= 8 %% (most of them skipped: "
               "rt_quiet)\n", 100 * one.idle_share);
        printf("  ping while busy  %.1f ms (1 task), %.1f ms (9 tasks) from its last byte to the reply; "
               "floor <= 30 ms\n", one.ping_ms, ten.ping_ms);
        printf("a lone x++ task with events (issue 21; rotation at 1 000 steps/s on input 1, noisy light on 2 "
               "and 3):\n");
        for (i = 0; i < 4; i++) {
            if (ev[i].rate < 0) {
                printf("  %-28s no reply: the brick is deaf\n", load_name[i]);
                continue;
            }
            printf("  %-28s %6.0f byte codes/s", load_name[i], ev[i].rate);
            if (floor[i])
                printf("  floor >= %u", floor[i]);
            if (loads[i].changing)
                printf("; rotation counted %d of %d steps", ev[i].turned, ev[i].steps);
            printf("\n");
        }
        if (ev[1].rate >= 0)
            printf("  idle, 16 events on a still input  %.1f %% of the CPU  floor <= 9 %%\n", 100 * ev[1].idle_share);
        if (ev[3].rate >= 0)
            printf("  ping under the worst load (16 events, 3 inputs changing)  %.1f ms  floor <= 30 ms\n",
                   ev[3].ping_ms);
        printf("cost model (h8sim.h): external RAM 3 states a byte, 6 a word or instruction word (8-bit bus); on-chip\n"
               "  RAM and ROM 2; registers 3 a byte, 6 a word; +1 fetch per branch, jump, call, return; interrupt\n"
               "  14 + the ROM's entry (push r6, jsr, pop r6, rte). The per-function estimate above leaves out the\n"
               "  loop's own code, main()'s clock checks and the whole-pass effects: the whole image is the figure.\n"
               "  brickEmu counts the same costs (external RAM 2+1 states a byte, 2+4 a word; on-chip RAM, ROM 2;\n"
               "  registers as external RAM); the same programs there (x++ tasks sampled over 1 s of the brick's clock)\n"
               "  gave, for the images of 089cb74 and 9709fa6: 1 task 19 030 and 33 920, 9 tasks 7 146 and 7 866 byte\n"
               "  codes/s; this simulator 18 900 and 33 600, 6 984 and 7 724 (within 3 %%). The issue's 59 600 for 9\n"
               "  tasks on 089cb74 was not reproduced: its emulation measured 7 146.\n");
        if (one.rate < 50000)
            return 3;
    }
    return 0;
}
