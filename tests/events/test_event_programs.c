/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Event and access-control programs compiled by the real nqc (-TRCX2), downloaded into a fresh brick as `nqc -d`
 * does, started as `nqc -run` does, and run on simulated time with scripted inputs; their variables are then
 * polled (12 00 n) as a host would.
 *
 * Usage: test_event_programs <program.nqc> <image.rcx>
 * Directives in the program's comment header:
 *   // run: 1000        simulated milliseconds (default 1000), 10 byte codes per millisecond
 *   // script: name     inputs applied every millisecond (see scripts[] below)
 *   // expect: x=1 y=2..5
 * Expected values come from what the program means under the spec, worked out by hand in its header.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "brick.h"
#include "rcx_image.h"

#define MAX_EXPECT 32

struct expect {
    char name[40];
    long lo, hi;
};

static struct {
    const char *source, *image;
    unsigned run_ms;
    char script[16];
    unsigned nexpect;
    struct expect expect[MAX_EXPECT];
} t;

/* ---- scripts: what the outside world does at millisecond `ms` ------------------------------------------------- */

/* A touch switch on input 1 (index 0): pressed (raw 100, below the 45 % boolean threshold) 100-199, 300-399 and
 * 500-599 ms, released (raw 1000) otherwise. Samples go through the sensor engine, which tells the event engine. */
static void script_touch(struct rcx *b, unsigned ms)
{
    unsigned phase = ms % 200;
    sensor_sample(b, 0, (u16)(ms >= 100 && ms < 600 && phase >= 100 ? 100 : 1000));
}

/* A light sensor on input 2 (index 1) reading raw 500. */
static void script_light(struct rcx *b, unsigned ms)
{
    (void)ms;
    sensor_sample(b, 1, 500);
}

/* The host sends IR message 7 at 100 ms (nqc -msg 7: InternMessage), again at 200 ms, then ClearPBMessage. */
static void script_mail(struct rcx *b, unsigned ms)
{
    static const u8 msg7[] = { 0xF7, 7 }, clear[] = { 0x90 };
    if (ms == 100 || ms == 200)
        brick_cmd(b, msg7, sizeof msg7, NULL);
    else if (ms == 300)
        brick_cmd(b, clear, sizeof clear, NULL);
}

static const struct {
    const char *name;
    void (*step)(struct rcx *b, unsigned ms);
} scripts[] = {
    { "touch", script_touch },
    { "light", script_light },
    { "mail", script_mail },
};

/* ---- header ------------------------------------------------------------------------------------------------ */

static void parse_expect(const char *p)
{
    char name[40];
    long lo, hi;
    int used;
    while (sscanf(p, " %39[A-Za-z0-9_]=%ld%n", name, &lo, &used) == 2) {
        p += used;
        hi = lo;
        if (p[0] == '.' && p[1] == '.') {
            char *end;
            hi = strtol(p + 2, &end, 10);
            p = end;
        }
        if (t.nexpect >= MAX_EXPECT)
            fail_msg("too many expectations");
        strcpy(t.expect[t.nexpect].name, name);
        t.expect[t.nexpect].lo = lo;
        t.expect[t.nexpect].hi = hi;
        t.nexpect++;
    }
}

static void read_header(void)
{
    char line[256];
    FILE *f = fopen(t.source, "r");
    if (!f)
        fail_msg("cannot open %s", t.source);
    t.run_ms = 1000;
    while (fgets(line, sizeof line, f) && strncmp(line, "//", 2) == 0) {
        if (sscanf(line, "// run: %u", &t.run_ms) == 1)
            continue;
        if (sscanf(line, "// script: %15s", t.script) == 1)
            continue;
        if (strncmp(line, "// expect:", 10) == 0)
            parse_expect(line + 10);
    }
    fclose(f);
    if (t.nexpect == 0)
        fail_msg("%s: no expectations", t.source);
}

/* ---- the run ----------------------------------------------------------------------------------------------- */

static s16 poll_var(struct rcx *b, u8 n)
{
    u8 cmd[3] = { 0x12, 0, n }, reply[RCX_REPLY_MAX];
    assert_int_equal(brick_cmd(b, cmd, sizeof cmd, reply), 3);
    return (s16)(u16)(reply[1] | reply[2] << 8);
}

static void run_program(void **state)
{
    void (*step)(struct rcx *, unsigned) = NULL;
    struct rcx_image *img = malloc(sizeof *img);
    struct rcx *b = brick_new();
    char err[160];
    u8 *data;
    size_t size;
    unsigned ms, i, failures = 0;
    (void)state;

    read_header();
    for (i = 0; i < sizeof scripts / sizeof scripts[0]; i++)
        if (strcmp(t.script, scripts[i].name) == 0)
            step = scripts[i].step;
    if (t.script[0] && !step)
        fail_msg("unknown script '%s'", t.script);
    if (!img || rcx_image_read_file(t.image, &data, &size, err, sizeof err) ||
        rcx_image_parse(img, data, size, err, sizeof err) || rcx_image_load(b, img, -1, err, sizeof err))
        fail_msg("%s: %s", t.image, err);
    brick_start(b, 0);
    for (ms = 0; ms < t.run_ms; ms++) {
        if (step)
            step(b, ms);
        vm_run(b, 10);
        vm_tick(b);
    }
    for (i = 0; i < t.nexpect; i++) {
        int n = rcx_image_find_var(img, t.expect[i].name);
        s16 v;
        if (n < 0 || n >= RCX_GLOBALS)
            fail_msg("no global variable '%s'", t.expect[i].name);
        v = poll_var(b, (u8)n);
        if (v < t.expect[i].lo || v > t.expect[i].hi) {
            print_error("%s = %d, expected %ld..%ld\n", t.expect[i].name, v, t.expect[i].lo, t.expect[i].hi);
            failures++;
        }
    }
    free(data);
    free(img);
    brick_free(b);
    if (failures)
        fail_msg("%u of %u values wrong", failures, t.nexpect);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = { cmocka_unit_test(run_program) };
    if (argc != 3) {
        fprintf(stderr, "usage: %s <program.nqc> <image.rcx>\n", argv[0]);
        return 2;
    }
    t.source = argv[1];
    t.image = argv[2];
    return cmocka_run_group_tests(tests, NULL, NULL);
}
