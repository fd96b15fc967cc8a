/* SPDX-License-Identifier: MPL-2.0 */
/*
 * rcxsim, the virtual RCX: options, the bricks' power-on, and the main loop that advances simulated time one
 * millisecond at a time (rt_tick, A/D samples, rt_run with the byte-code budget of that millisecond).
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "sim.h"
#include "rcx_image.h"
#include "net.h"
#include "panel.h"
#include "tower.h"

/* Where the program memory would sit in the brick's RAM: the top of 8000-EFFF (memory map, UploadRam). */
#define SIM_ARENA_ADDR ((u16)(0xF000u - RCX_ARENA_SIZE))

/* The brick model of firm0328's speed (reference-firmware.md, "Tasks and timing"): a scheduler pass over n
 * running tasks costs about 2.45 ms + n x 0.245 ms, which reproduces the measured 185 x++ loops/s for one task
 * and about 1 000 in total for ten. */
#define PASS_US 2450
#define BYTECODE_US 245

static volatile sig_atomic_t stop_signal;

static void on_signal(int sig)
{
    (void)sig;
    stop_signal = 1;
}

static void usage(FILE *f)
{
    fputs("usage: rcxsim [options]\n"
          "  -h, --help         this list, and exit\n"
          "  --version          the version of OpenRCX, and exit\n"
          "  --tty PATH         a serial IR tower on a pseudo-terminal, PATH a symlink to it; once per brick\n"
          "  --bricks N         N bricks (1-8) in one IR room\n"
          "  --speed X          X times real time (default 1)\n"
          "  --fast             as fast as possible\n"
          "  --rate N|brick     byte codes per simulated ms, or the brick's own speed (default)\n"
          "  --script FILE      timed inputs (sensor, button, battery, ir, quit)\n"
          "  --trace FILE|-     JSON lines: motors, sound, LCD, sensor power, IR bytes sent, power, ROM\n"
          "  --load [B@]F.rcx[:SLOT]  preload an nqc image into brick B (default 0), program slot 1-5\n"
          "  --rom              start in the ROM's download mode (no firmware)\n"
          "  --duration MS      stop after MS simulated milliseconds\n"
          "  --panel PORT       the bricks live in a browser at http://127.0.0.1:PORT/ (0: any free port)\n"
          "  --panel-bind ADDR  the address the panel listens on (default 127.0.0.1, loopback only)\n"
          "  --tcp [ADDR:]PORT  be the IR hub of NQC 4's -Stcp and brickEmu (default 127.0.0.1:" NET_DEFAULT_PORT
          ", 0: any port)\n"
          "  --tcp-tower [ADDR:]PORT  an IR tower over TCP facing one brick alone; once per brick (0: any port)\n"
          "  --tcp-join HOST:PORT  the bricks join the IR hub there (brickEmu's ir-server, rcxsim --tcp)\n"
          "  --world SCENE      each brick drives a robot of the scene (a .json file or a shipped scene's name)\n",
          f);
}

/* The options that take a value, and what the value must be: for the one-line refusals. */
static const char *value_wanted(const char *option)
{
    static const char *const wanted[][2] = {
        { "--tty", "a path for the tower's link, once per brick (at most 8)" },
        { "--bricks", "a number of bricks, 1-8" },
        { "--speed", "a factor above 0" },
        { "--rate", "a number of byte codes above 0, or brick" },
        { "--script", "a file" },
        { "--trace", "a file, or - for the standard output" },
        { "--load", "[B@]FILE.rcx[:SLOT] with SLOT 1-5 (at most 64 images)" },
        { "--duration", "a number of milliseconds above 0" },
        { "--panel", "a port, 0-65535" },
        { "--panel-bind", "an IPv4 or IPv6 address" },
        { "--tcp-join", "HOST:PORT of an IR hub" },
        { "--tcp-tower", "[ADDR:]PORT for a brick's tower, once per brick (at most 8)" },
        { "--world", "a scene file or the name of a shipped scene" },
    };
    size_t i;
    for (i = 0; i < sizeof wanted / sizeof wanted[0]; i++)
        if (strcmp(option, wanted[i][0]) == 0)
            return wanted[i][1];
    return NULL;
}

static void start_firmware(struct sim_brick *b)
{
    b->mode = SIM_FIRMWARE;
    b->k.vm.port = b;
    memset(b->motor, 0xFF, sizeof b->motor);
    b->lcd_known = 0;
    rt_init(&b->k, SIM_ARENA_ADDR);
    rt_battery(&b->k, (u16)b->battery_mv);
    trace_line(b, "\"power\":\"on\"");
}

/* A byte off the air reaches the brick's receiver: the firmware's, or the ROM's. In standby the receiver is off. */
static void brick_hear(struct room_port *p, unsigned char byte, int error)
{
    struct sim_brick *b = (struct sim_brick *)(void *)((char *)p - offsetof(struct sim_brick, port));
    if (b->mode != SIM_STANDBY)
        b->ir_in++;
    if (b->mode == SIM_FIRMWARE)
        rt_ir_byte(&b->k, byte, (u8)error);
    else if (b->mode == SIM_ROM)
        rom_byte(b, byte, error);
}

static struct sim_brick *new_brick(struct sim *s, int index, int rom)
{
    struct sim_brick *b = calloc(1, sizeof *b);
    if (!b)
        abort();
    b->sim = s;
    b->index = index;
    b->raw[0] = b->raw[1] = b->raw[2] = 1023; /* nothing plugged in: the pull-up reads high */
    b->battery_mv = 9000;
    b->range = 0xFF;
    b->port.hear = brick_hear;
    b->port.hears_self = 1;     /* its own echo (rcx-hardware.md §3.8) */
    room_join(&s->room, &b->port);
    if (rom) {
        b->mode = SIM_ROM;
        rom_reset(b);
        trace_line(b, "\"rom\":\"waiting for firmware\"");
    } else {
        start_firmware(b);
    }
    return b;
}

static int load_image(struct sim *s, const char *spec)
{
    char path[4096], err[256];
    const char *colon;
    int brick = 0, slot = -1, status = 0;
    struct rcx_image *img;
    u8 *data;
    size_t size;

    if (strchr(spec, '@') && spec[0] >= '0' && spec[0] <= '9') {
        brick = atoi(spec);
        spec = strchr(spec, '@') + 1;
    }
    colon = strrchr(spec, ':');
    if (colon && colon[1] && strspn(colon + 1, "0123456789") == strlen(colon + 1)) {
        if (colon[1] < '1' || colon[1] > '5' || colon[2]) {
            fprintf(stderr, "rcxsim: --load %s: no program slot %s (slots are 1-5)\n", spec, colon + 1);
            return -1;
        }
        slot = colon[1] - '1';
    } else {
        colon = NULL;
    }
    snprintf(path, sizeof path, "%.*s", colon ? (int)(colon - spec) : (int)strlen(spec), spec);
    if (brick < 0 || brick >= s->nbricks || s->brick[brick]->mode != SIM_FIRMWARE) {
        fprintf(stderr, "rcxsim: --load %s: no brick %d running the firmware\n", spec, brick);
        return -1;
    }
    img = malloc(sizeof *img);
    if (!img)
        abort();
    data = NULL;
    if (rcx_image_read_file(path, &data, &size, err, sizeof err) || rcx_image_parse(img, data, size, err, sizeof err) ||
        rcx_image_load(&s->brick[brick]->k.vm, img, slot, err, sizeof err)) {
        fprintf(stderr, "rcxsim: --load %s: %s\n", path, err);
        status = -1;
    }
    free(data);
    free(img);
    return status;
}

/* An input (script or panel) takes effect now. */
static void apply(struct sim *s, const struct sim_event *ev)
{
    struct sim_brick *b = s->brick[ev->brick];
    switch (ev->kind) {
    case EV_SENSOR:
        b->raw[ev->a] = (unsigned short)ev->b;
        break;
    case EV_BUTTON:
        b->buttons = (unsigned char)(ev->b ? b->buttons | 1u << ev->a : b->buttons & ~(1u << ev->a));
        if (b->mode == SIM_STANDBY && ev->a == RT_BUTTON_ONOFF && ev->b) {
            b->mode = SIM_FIRMWARE; /* the press that wakes the brick is not seen by the firmware */
            trace_line(b, "\"power\":\"on\"");
        } else if (b->mode == SIM_FIRMWARE) {
            rt_button(&b->k, (u8)ev->a, (u8)ev->b);
        }
        break;
    case EV_BATTERY:
        b->battery_mv = (unsigned)ev->a;
        if (b->mode == SIM_FIRMWARE)
            rt_battery(&b->k, (u16)ev->a);
        break;
    case EV_IR:
        room_send(&s->room, &s->script, ev->bytes, (unsigned)ev->nbytes, 0);
        break;
    case EV_QUIT:
        s->quit = 1;
        break;
    case EV_PLACE:
        sim_world_place(s, ev);
        break;
    }
}

static unsigned running_tasks(const struct rcx *vm)
{
    unsigned n = 0, m = vm->runmask;
    for (; m; m &= m - 1)
        n++;
    return n;
}

/* One simulated millisecond of one brick. */
static void step(struct sim *s, struct sim_brick *b)
{
    unsigned n, cost, budget;

    if (b->mode == SIM_ROM) {
        if (rom_tick(b))
            start_firmware(b);
        return;
    }
    if (b->mode != SIM_FIRMWARE)
        return;
    rt_tick(&b->k);
    rt_sensor_scan(&b->k, b->raw);
    if (s->rate) {
        rt_run(&b->k, (u16)s->rate);
        return;
    }
    n = running_tasks(&b->k.vm);
    if (n == 0) {
        b->credit_us = 0;
        rt_run(&b->k, 0);
        return;
    }
    cost = PASS_US / n + BYTECODE_US;
    b->credit_us += 1000;
    budget = (unsigned)b->credit_us / cost;
    b->credit_us -= (long)(rt_run(&b->k, (u16)budget) * cost);
    if (b->credit_us > (long)cost)
        b->credit_us = cost; /* tasks that waited do not save up time */
}

static double wall_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec / 1e9;
}

/* Hold the loop back to `speed` x real time; links that receive bytes wake it early. */
static void pace(struct sim *s, double wall_start)
{
    struct pollfd fds[ROOM_MAX_PORTS + 8];
    double ahead = (double)s->room.now / 1e6 / s->speed - (wall_seconds() - wall_start);
    int n;

    if (ahead < 0.0005)
        return;
    n = room_fds(&s->room, fds, (int)(sizeof fds / sizeof fds[0]));
    if (poll(fds, (nfds_t)n, (int)(ahead * 1000 + 0.5)) < 0 && errno != EINTR)
        s->quit = 1;
}

static int run(struct sim *s, sim_us duration)
{
    double wall_start = wall_seconds();
    unsigned poll_every = s->speed <= 0 ? 64 : s->speed > 5 ? (unsigned)(s->speed / 5) : 1, ms = 0;
    int i;

    while (!s->quit && !stop_signal) {
        room_advance(&s->room, s->room.now);
        while (s->next_event < s->nevents && s->events[s->next_event].at <= s->room.now)
            apply(s, &s->events[s->next_event++]);
        if (s->quit)
            break;
        if (s->room.links && ms++ % poll_every == 0)
            room_poll(&s->room);
        if (s->panel) {
            struct sim_event in[PANEL_QUEUE];
            unsigned n = panel_take_inputs(s->panel, in), k;
            for (k = 0; k < n; k++)
                apply(s, &in[k]);
            panel_sync(s->panel, s, n);
        }
        sim_world_step(s);
        for (i = 0; i < s->nbricks; i++)
            step(s, s->brick[i]);
        if (duration && s->room.now >= duration)
            break;
        s->room.now += 1000;
        if (s->speed > 0)
            pace(s, wall_start);
    }
    return 0;
}

int main(int argc, char **argv)
{
    static struct sim sim;
    struct sim *s = &sim;
    const char *ttys[SIM_MAX_BRICKS], *loads[64], *script = NULL, *trace = NULL, *panel_bind = "127.0.0.1";
    const char *tcp = NULL, *tcp_join = NULL, *tcp_towers[SIM_MAX_BRICKS], *world = NULL;
    int ntcp_towers = 0, nttys = 0, nloads = 0, rom = 0, i, status = 0;
    long panel_port = -1;
    sim_us duration = 0;

    s->nbricks = 1;
    s->speed = 1;
    for (i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--fast") == 0) {
            s->speed = 0;
        } else if (strcmp(a, "--rom") == 0) {
            rom = 1;
        } else if (strcmp(a, "--tcp") == 0) {
            tcp = v && v[0] != '-' ? argv[++i] : ""; /* the value is optional */
        } else if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            usage(stdout);
            return 0;
        } else if (strcmp(a, "--version") == 0) {
            puts("rcxsim (OpenRCX) " RCXSIM_VERSION);
            return 0;
        } else if (!value_wanted(a)) {
            fprintf(stderr, "rcxsim: %s: %s\n", a,
                    a[0] == '-' ? "unknown option (rcxsim --help lists them)"
                                : "unexpected argument (options start with --)");
            return 2;
        } else if (!v) {
            fprintf(stderr, "rcxsim: %s: needs %s\n", a, value_wanted(a));
            return 2;
        } else {
            i++;
            if (strcmp(a, "--tty") == 0 && nttys < SIM_MAX_BRICKS) {
                ttys[nttys++] = v;
            } else if (strcmp(a, "--bricks") == 0 && atoi(v) >= 1 && atoi(v) <= SIM_MAX_BRICKS) {
                s->nbricks = atoi(v);
            } else if (strcmp(a, "--speed") == 0 && atof(v) > 0) {
                s->speed = atof(v);
            } else if (strcmp(a, "--rate") == 0 && (strcmp(v, "brick") == 0 || atoi(v) > 0)) {
                s->rate = strcmp(v, "brick") == 0 ? 0 : (unsigned)atoi(v);
            } else if (strcmp(a, "--script") == 0) {
                script = v;
            } else if (strcmp(a, "--trace") == 0) {
                trace = v;
            } else if (strcmp(a, "--load") == 0 && nloads < 64) {
                loads[nloads++] = v;
            } else if (strcmp(a, "--panel") == 0 && sim_parse_number(v, 0, 65535, &panel_port) == 0) {
                ;
            } else if (strcmp(a, "--panel-bind") == 0) {
                panel_bind = v;
            } else if (strcmp(a, "--tcp-join") == 0) {
                tcp_join = v;
            } else if (strcmp(a, "--tcp-tower") == 0 && ntcp_towers < SIM_MAX_BRICKS) {
                tcp_towers[ntcp_towers++] = v;
            } else if (strcmp(a, "--world") == 0) {
                world = v;
            } else if (strcmp(a, "--duration") == 0 && atol(v) > 0) {
                duration = (sim_us)atol(v) * 1000;
            } else {
                fprintf(stderr, "rcxsim: %s %s: expected %s\n", a, v, value_wanted(a));
                return 2;
            }
        }
    }
    if (tcp && tcp_join) {
        fprintf(stderr, "rcxsim: --tcp and --tcp-join: the room is either the hub or joins one\n");
        return 2;
    }
    if (world && sim_world_open(s, world))
        return 2;
    if (nttys > s->nbricks || ntcp_towers > s->nbricks) {
        fprintf(stderr, "rcxsim: %s: %d given, more than the %d brick%s (--bricks N)\n",
                nttys > s->nbricks ? "--tty" : "--tcp-tower", nttys > s->nbricks ? nttys : ntcp_towers, s->nbricks,
                s->nbricks == 1 ? "" : "s");
        return 2;
    }
    if (trace) {
        s->trace = strcmp(trace, "-") == 0 ? stdout : fopen(trace, "w");
        if (!s->trace) {
            fprintf(stderr, "rcxsim: --trace %s: %s\n", trace, strerror(errno));
            return 2;
        }
        setvbuf(s->trace, NULL, _IOLBF, 0); /* lines appear as they happen: others watch the trace live */
    }
    signal(SIGINT, on_signal);
    signal(SIGTERM, on_signal);
    signal(SIGHUP, on_signal);
    signal(SIGPIPE, SIG_IGN);
    if (script && script_load(s, script))
        return 2;
    for (i = 0; i < s->nbricks; i++)
        s->brick[i] = new_brick(s, i, rom);
    for (i = 0; i < nloads && status == 0; i++)
        status = load_image(s, loads[i]);
    /* The panel first: once a tower's link exists, everything is up. */
    if (status == 0 && panel_port >= 0) {
        char err[256];
        s->panel = panel_start(s, panel_bind, (unsigned)panel_port, err, sizeof err);
        if (!s->panel) {
            fprintf(stderr, "rcxsim: --panel %ld: %s\n", panel_port, err);
            status = 1;
        }
    }
    for (i = 0; i < nttys && status == 0; i++) {
        if (tower_open(&s->room, ttys[i], &s->brick[i]->port)) {
            fprintf(stderr, "rcxsim: --tty %s: %s\n", ttys[i], strerror(errno));
            status = 1;
        } else {
            fprintf(stderr, "rcxsim: IR tower of brick %d at %s (tty)\n", i, ttys[i]);
        }
    }
    for (i = 0; i < ntcp_towers && status == 0; i++) {
        char err[512], what[64];
        snprintf(what, sizeof what, "IR tower of brick %d", i);
        if (net_hub_open(&s->room, tcp_towers[i], &s->brick[i]->port, what, err, sizeof err)) {
            fprintf(stderr, "rcxsim: --tcp-tower %s: %s\n", tcp_towers[i], err);
            status = 1;
        }
    }
    room_join(&s->room, &s->script);
    if (status == 0 && (tcp || tcp_join)) {
        char err[512];
        if (tcp ? net_hub_open(&s->room, tcp, NULL, "IR hub", err, sizeof err)
                : net_join(&s->room, tcp_join, err, sizeof err)) {
            fprintf(stderr, "rcxsim: %s %s: %s\n", tcp ? "--tcp" : "--tcp-join", tcp ? tcp : tcp_join, err);
            status = 1;
        }
    }
    if (status == 0 && !s->room.links && !s->panel && !script && !duration)
        fprintf(stderr, "rcxsim: nothing can reach the brick (no --tty, --tcp, --tcp-tower, --tcp-join, --panel or "
                        "--script): it runs alone until stopped; rcxsim --help lists the ways in\n");
    if (status == 0)
        run(s, duration);
    if (s->panel)
        panel_stop(s->panel);
    sim_world_set(s, NULL); /* before the bricks it reads go */
    for (i = 0; i < s->nbricks; i++) {
        trace_flush_sound(s->brick[i]);
        free(s->brick[i]);
    }
    if (s->trace && status == 0)
        fprintf(s->trace, "{\"t\":%llu,\"end\":\"%s\"}\n", s->room.now / 1000,
                s->quit ? "quit" : stop_signal ? "signal" : "duration");
    room_close(&s->room);
    if (s->trace && s->trace != stdout)
        fclose(s->trace);
    free(s->events);
    return status ? 2 : 0;
}
