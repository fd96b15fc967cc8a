/*
 * `make bench` (tests/bench/firmware.sh): byte codes per second of the firmware image, counted in the H8/300
 * simulator (h8sim.h gives the timing model) on the `x++` loop nqc makes of `while (true) x++;`
 * (SumVar var 0 += 1; SJump back: two byte codes per pass), one task running.
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

#define CLOCK 16000000.0
#define RUNS 2000               /* byte codes timed */
#define BUDGET 8                /* main.c's RUN_BUDGET */
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
static void profile(struct h8 *sim, uint16_t pc, unsigned states)
{
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

int main(int argc, char **argv)
{
    uint8_t begin[6] = { 0x25, 0x00, 0x00, 0x00, sizeof loop, 0x00 }, block[6 + sizeof loop], start[2] = { 0x71, 0 };
    unsigned long long run, loop_pass, per_ms, tick_irq, adi_irq, tick, samples, insns;
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
     * Timed over 100 ms, as some engines do their work every 10 or 50 ms. */
    h.trace = profile;
    tick = 0;
    samples = 0;
    for (i = 0; i < 100; i++) {
        tick += timed("_rt_tick", brick, 0);
        samples += timed("_rt_sensor_sample", brick, 0) + timed("_rt_sensor_sample", brick, 1)
                 + timed("_rt_sensor_sample", brick, 2) + timed("_hw_debounce", H8_SCRATCH, 0);
    }
    h.trace = NULL;
    tick /= 100;
    samples /= 100;
    /* No active sensor (the benchmark has none): the tick takes the finished scan itself (ADF set), no A/D
     * interrupt. An active sensor adds the A/D interrupt. */
    h.mem[0xFFE8] = 0x80; /* ADF */
    tick_irq = timed("_rcx_timer_irq", 0, 0) + IRQ_ENTRY;
    h.mem[0xFFE8] = 0xC0; /* ADF, ADIE: the same entry serves the end of the scan */
    adi_irq = timed("_rcx_timer_irq", 0, 0) + IRQ_ENTRY;
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
    printf("  every millisecond     %5llu states: tick interrupt %llu (with %d of ROM entry), rt_tick %llu,\n"
           "                        samples and buttons %llu: %.1f %% of the CPU (an active sensor adds the A/D\n"
           "                        interrupt, %llu states, %.1f %%)\n",
           per_ms, tick_irq, IRQ_ENTRY, tick, samples, 100.0 * (double)per_ms * 1000.0 / CLOCK,
           adi_irq, 100.0 * (double)adi_irq * 1000.0 / CLOCK);
    printf("  estimate              %5.0f byte codes/s (%.0f x++ per second); goal 20000, firm0328 about 370\n",
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
    return rate >= 20000 ? 0 : 3;
}
