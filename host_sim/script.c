/* SPDX-License-Identifier: MPL-2.0 */
/*
 * --script FILE: timed inputs, one per line ('#' starts a comment):
 *   <ms> [@<brick>] sensor <1-3> raw <0-1023>
 *   <ms> [@<brick>] button <onoff|run|view|prgm> <down|up>
 *   <ms> [@<brick>] battery <mV>
 *   <ms> ir <hex bytes>            (sent into the room at 2400 baud, as a remote control would)
 *   <ms> quit
 *   <ms> place <robot|obstacle> <index> <x mm> <y mm> <heading degrees>   (with --world: moves it there)
 * Lines may come in any order; events at the same time keep their order.
 */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include "sim.h"

const char *const sim_button_names[SIM_BUTTONS] = { "onoff", "run", "view", "prgm" };

static int fail(const char *path, int line, const char *what)
{
    fprintf(stderr, "rcxsim: --script %s:%d: %s\n", path, line, what);
    return -1;
}

int sim_word_index(const char *w, const char *const *list, int n)
{
    int i;
    for (i = 0; i < n; i++)
        if (strcmp(w, list[i]) == 0)
            return i;
    return -1;
}

int sim_parse_number(const char *w, long lo, long hi, long *out)
{
    char *end;
    long v;
    if (!w)
        return -1;
    v = strtol(w, &end, 10);
    if (*w == 0 || *end || v < lo || v > hi)
        return -1;
    *out = v;
    return 0;
}

static int parse_line(struct sim *s, char *text, struct sim_event *ev, const char *path, int line)
{
    static const char *const kinds[] = { "sensor", "button", "battery", "ir", "quit", "place" };
    static const char *const things[] = { "obstacle", "robot" };
    static const char *const edges[] = { "up", "down" };
    char *w[300];
    int n = 0, k, at = 1;
    long v;

    for (w[n] = strtok(text, " \t\r\n"); w[n] && n < 299; w[++n] = strtok(NULL, " \t\r\n"))
        ;
    if (n == 0)
        return 0;
    memset(ev, 0, sizeof *ev);
    if (sim_parse_number(w[0], 0, 1000L * 3600 * 24 * 365, &v))
        return fail(path, line, "expected a time in ms");
    ev->at = (sim_us)v * 1000;
    if (n > 1 && w[1][0] == '@') {
        if (sim_parse_number(w[1] + 1, 0, s->nbricks - 1, &v))
            return fail(path, line, "no such brick");
        ev->brick = (int)v;
        at = 2;
    }
    if (at >= n || (k = sim_word_index(w[at], kinds, 6)) < 0)
        return fail(path, line, "expected sensor, button, battery, ir, quit or place");
    ev->kind = k;
    switch (ev->kind) {
    case EV_SENSOR:
        if (n != at + 4 || sim_parse_number(w[at + 1], 1, 3, &v) || strcmp(w[at + 2], "raw"))
            return fail(path, line, "expected: sensor <1-3> raw <0-1023>");
        ev->a = (int)v - 1;
        if (sim_parse_number(w[at + 3], 0, 1023, &v))
            return fail(path, line, "raw value out of 0-1023");
        ev->b = (int)v;
        break;
    case EV_BUTTON:
        if (n != at + 3 || (ev->a = sim_word_index(w[at + 1], sim_button_names, SIM_BUTTONS)) < 0 ||
            (ev->b = sim_word_index(w[at + 2], edges, 2)) < 0)
            return fail(path, line, "expected: button <onoff|run|view|prgm> <down|up>");
        break;
    case EV_BATTERY:
        if (n != at + 2 || sim_parse_number(w[at + 1], 0, SIM_BATTERY_MAX_MV, &v))
            return fail(path, line, "expected: battery <mV>");
        ev->a = (int)v;
        break;
    case EV_IR:
        for (k = at + 1; k < n; k++) {
            char *end;
            unsigned long byte = strtoul(w[k], &end, 16);
            if (*end || byte > 255 || ev->nbytes >= (int)sizeof ev->bytes)
                return fail(path, line, "expected hex bytes (at most 256)");
            ev->bytes[ev->nbytes++] = (unsigned char)byte;
        }
        if (ev->nbytes == 0)
            return fail(path, line, "expected hex bytes");
        break;
    case EV_QUIT:
        if (n != at + 1)
            return fail(path, line, "expected nothing after quit");
        break;
    case EV_PLACE:
        if (!s->world)
            return fail(path, line, "place needs --world");
        if (n != at + 6 || (ev->a = sim_word_index(w[at + 1], things, 2)) < 0 ||
            sim_parse_number(w[at + 2], 0, 63, &v))
            return fail(path, line, "expected: place <robot|obstacle> <index> <x mm> <y mm> <heading degrees>");
        ev->b = (int)v;
        for (k = 0; k < 3; k++) {
            char *end;
            ev->pose[k] = strtod(w[at + 3 + k], &end);
            if (*end || end == w[at + 3 + k] || !(ev->pose[k] > -1e6 && ev->pose[k] < 1e6))
                return fail(path, line, "expected numbers for x, y and heading");
        }
        break;
    }
    return 1;
}

int script_load(struct sim *s, const char *path)
{
    FILE *f = fopen(path, "r");
    char text[4096];
    int line = 0, cap = 0;

    if (!f) {
        fprintf(stderr, "rcxsim: --script %s: %s\n", path, strerror(errno));
        return -1;
    }
    while (fgets(text, sizeof text, f)) {
        struct sim_event ev;
        char *hash = strchr(text, '#');
        int r;
        line++;
        if (hash)
            *hash = 0;
        r = parse_line(s, text, &ev, path, line);
        if (r < 0) {
            fclose(f);
            return -1;
        }
        if (r == 0)
            continue;
        if (s->nevents == cap) {
            cap = cap ? 2 * cap : 64;
            s->events = realloc(s->events, (size_t)cap * sizeof *s->events);
            if (!s->events)
                abort();
        }
        s->events[s->nevents++] = ev;
    }
    fclose(f);
    /* Insertion sort: stable, so equal times keep the file's order (scripts are short). */
    for (line = 1; line < s->nevents; line++) {
        struct sim_event ev = s->events[line];
        int j;
        for (j = line; j > 0 && s->events[j - 1].at > ev.at; j--)
            s->events[j] = s->events[j - 1];
        s->events[j] = ev;
    }
    return 0;
}
