/* SPDX-License-Identifier: MPL-2.0 */
/*
 * End-to-end program tests: a .nqc program compiled by the real nqc, downloaded into a fresh brick the way
 * `nqc -d` does it, started the way `nqc -run` does it (71 00), run for a stretch of simulated time, and its
 * variables read back with the Poll command (12 00 n) as a host would.
 *
 * Usage: test_programs <program.nqc> <image dir> <RCX2|RCX|Swan>
 * The image is <image dir>/<name>.<rcx2|rcx>.rcx, built by CMake with nqc (tests/programs/CMakeLists.txt).
 *
 * What a program must do is written in its own comment header, one directive per line:
 *   // targets: RCX2 RCX Swan     nqc targets to compile and test for (read by CMake)
 *   // run: 2000                  simulated milliseconds after each start (default 1000)
 *   // starts: 2                  how many times task 0 is started, each followed by the run time (default 1)
 *   // end: idle | running        whether every task must have ended when the time is up (default idle)
 *   // budget: 10                 byte codes per simulated millisecond (default 10; firm0328 manages about 0.4)
 *   // load: 1 other              first download other.<target>.rcx into program slot 1; the program under test
 *                                 then goes into slot 0 (otherwise it is downloaded without selecting a slot)
 *   // expect: x=55 y=-3          expected values; expect(RCX2): ... applies to one target only
 * Values: name=V exact, name=V~T within T of V, name=LO..HI inclusive range. Names are resolved through the
 * image's symbol table (variables only); name[k] is element k of an array, var[n] is variable n itself. RCX 2.0's
 * globals are polled through source 0 (its locals cannot be), Swan's 256 through source 43 (swan-target.md 4).
 * Expectations are worked out from what the source means, never copied from a run.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "brick.h"
#include "rcx_image.h"

#define MAX_EXPECT 64
#define MAX_LOAD 4
#define NAME_LEN 48

struct expect {
    char name[NAME_LEN]; /* identifier, or "" for var[n] */
    int element;         /* array element or raw variable number */
    long lo, hi;
    char text[96];       /* as written, for messages */
};

struct load {
    int slot;
    char program[NAME_LEN];
};

struct spec {
    unsigned run_ms;
    unsigned starts;
    unsigned budget;
    int end_running;
    unsigned nload;
    struct load load[MAX_LOAD];
    unsigned nexpect;
    struct expect expect[MAX_EXPECT];
};

static struct {
    const char *source;
    const char *image_dir;
    const char *target;   /* "RCX2" or "RCX" */
    const char *suffix;   /* "rcx2" or "rcx" */
    char name[NAME_LEN];  /* program name: the source's base name without .nqc */
} args;

/* ---- the comment header ---------------------------------------------------------------------------------- */

static int parse_long(const char **p, long *out)
{
    char *end;
    long v = strtol(*p, &end, 0);
    if (end == *p)
        return -1;
    *p = end;
    *out = v;
    return 0;
}

/* One "name=value" token of an expect line. */
static int parse_expect(struct expect *e, const char *tok, size_t len)
{
    char buf[96];
    const char *p;
    size_t n = 0;
    long v, w;

    if (len >= sizeof buf)
        return -1;
    memcpy(buf, tok, len);
    buf[len] = 0;
    memcpy(e->text, buf, len + 1);
    p = buf;
    while (isalnum((unsigned char)*p) || *p == '_') {
        if (n + 1 >= sizeof e->name)
            return -1;
        e->name[n++] = *p++;
    }
    e->name[n] = 0;
    if (n == 0)
        return -1;
    e->element = 0;
    if (*p == '[') {
        p++;
        if (parse_long(&p, &v) || *p != ']' || v < 0 || v >= RCX_ALL_GLOBALS)
            return -1;
        p++;
        e->element = (int)v;
        if (strcmp(e->name, "var") == 0)
            e->name[0] = 0;  /* var[n]: variable n itself */
    }
    if (*p++ != '=' || parse_long(&p, &v))
        return -1;
    e->lo = e->hi = v;
    if (*p == '~') {
        p++;
        if (parse_long(&p, &w) || w < 0)
            return -1;
        e->lo = v - w;
        e->hi = v + w;
    } else if (p[0] == '.' && p[1] == '.') {
        p += 2;
        if (parse_long(&p, &w) || w < v)
            return -1;
        e->hi = w;
    }
    return *p ? -1 : 0;
}

static void skip_space(const char **p)
{
    while (**p == ' ' || **p == '\t')
        (*p)++;
}

/* Returns 0, or -1 after printing what is wrong with the line. */
static int parse_directive(struct spec *s, const char *line, unsigned lineno)
{
    const char *p = line + 2, *key, *colon;
    size_t keylen;
    char target[16] = "";
    long v;

    skip_space(&p);
    key = p;
    while (isalpha((unsigned char)*p))
        p++;
    keylen = (size_t)(p - key);
    if (*p == '(') {  /* expect(TARGET): */
        const char *t = ++p;
        while (isalnum((unsigned char)*p))
            p++;
        if (*p != ')' || (size_t)(p - t) >= sizeof target)
            return 0;
        memcpy(target, t, (size_t)(p - t));
        target[p - t] = 0;
        p++;
    }
    colon = p;
    if (*colon != ':')
        return 0;  /* prose, not a directive */
    p = colon + 1;
    skip_space(&p);

#define KEY(k) (keylen == sizeof(k) - 1 && strncmp(key, k, keylen) == 0)
    if (KEY("targets")) {
        return 0;  /* read by CMake */
    } else if (KEY("run") || KEY("starts") || KEY("budget")) {
        if (parse_long(&p, &v) || v < 1 || v > 600000) {
            print_error("%s:%u: bad number\n", args.source, lineno);
            return -1;
        }
        if (KEY("run"))
            s->run_ms = (unsigned)v;
        else if (KEY("starts"))
            s->starts = (unsigned)v;
        else
            s->budget = (unsigned)v;
    } else if (KEY("end")) {
        if (strncmp(p, "idle", 4) == 0)
            s->end_running = 0;
        else if (strncmp(p, "running", 7) == 0)
            s->end_running = 1;
        else {
            print_error("%s:%u: end: idle or running\n", args.source, lineno);
            return -1;
        }
    } else if (KEY("load")) {
        struct load *l = &s->load[s->nload];
        size_t n = 0;
        if (s->nload >= MAX_LOAD || parse_long(&p, &v) || v < 1 || v >= RCX_PROGRAMS) {
            print_error("%s:%u: load: <slot 1-4> <program>\n", args.source, lineno);
            return -1;
        }
        l->slot = (int)v;
        skip_space(&p);
        while (isalnum((unsigned char)*p) || *p == '_') {
            if (n + 1 >= sizeof l->program)
                return -1;
            l->program[n++] = *p++;
        }
        l->program[n] = 0;
        if (!n) {
            print_error("%s:%u: load: program name missing\n", args.source, lineno);
            return -1;
        }
        s->nload++;
    } else if (KEY("expect")) {
        if (target[0] && strcmp(target, args.target) != 0)
            return 0;  /* for the other target */
        for (;;) {
            const char *t;
            skip_space(&p);
            if (!*p || *p == '\n' || *p == '\r')
                break;
            t = p;
            while (*p && *p != ' ' && *p != '\t' && *p != '\n' && *p != '\r')
                p++;
            if (s->nexpect >= MAX_EXPECT || parse_expect(&s->expect[s->nexpect], t, (size_t)(p - t))) {
                print_error("%s:%u: cannot read expectation '%.*s'\n", args.source, lineno, (int)(p - t), t);
                return -1;
            }
            s->nexpect++;
        }
    }
#undef KEY
    return 0;
}

static int read_spec(struct spec *s)
{
    FILE *f = fopen(args.source, "r");
    char line[512];
    unsigned lineno = 0;

    memset(s, 0, sizeof *s);
    s->run_ms = 1000;
    s->starts = 1;
    s->budget = 10;
    if (!f) {
        print_error("cannot open %s\n", args.source);
        return -1;
    }
    while (fgets(line, sizeof line, f)) {
        lineno++;
        if (line[0] == '/' && line[1] == '/' && parse_directive(s, line, lineno)) {
            fclose(f);
            return -1;
        }
    }
    fclose(f);
    if (s->nexpect == 0) {
        print_error("%s: no expect: line for %s\n", args.source, args.target);
        return -1;
    }
    return 0;
}

/* ---- images ---------------------------------------------------------------------------------------------- */

struct loaded {
    u8 *data;
    size_t size;
    struct rcx_image img;
};

static int open_image(struct loaded *l, const char *program)
{
    char path[1024], err[160];
    unsigned want = strcmp(args.target, "RCX2") == 0   ? RCX_IMAGE_TARGET_RCX2
                    : strcmp(args.target, "Swan") == 0 ? RCX_IMAGE_TARGET_SWAN
                                                       : RCX_IMAGE_TARGET_RCX;

    snprintf(path, sizeof path, "%s/%s.%s.rcx", args.image_dir, program, args.suffix);
    if (rcx_image_read_file(path, &l->data, &l->size, err, sizeof err)) {
        print_error("%s\n", err);
        return -1;
    }
    if (rcx_image_parse(&l->img, l->data, l->size, err, sizeof err)) {
        print_error("%s: %s\n", path, err);
        return -1;
    }
    if (l->img.target != want) {
        print_error("%s: target %u in the file, %u expected for %s\n", path, l->img.target, want, args.target);
        return -1;
    }
    return 0;
}

static int download(struct rcx *b, struct loaded *l, const char *program, int slot)
{
    char err[160];
    if (open_image(l, program))
        return -1;
    if (rcx_image_load(b, &l->img, slot, err, sizeof err)) {
        print_error("%s.%s.rcx: %s\n", program, args.suffix, err);
        return -1;
    }
    return 0;
}

/* ---- the test -------------------------------------------------------------------------------------------- */

static s16 poll_var(struct rcx *b, u8 n)
{
    u8 cmd[3] = { 0x12, 0x00, 0 }, reply[RCX_REPLY_MAX];
    if (strcmp(args.target, "Swan") == 0)
        cmd[1] = 43;                   /* a Swan global */
    cmd[2] = n;
    assert_int_equal(brick_cmd(b, cmd, sizeof cmd, reply), 3);
    return (s16)(u16)(reply[1] | (reply[2] << 8));
}

static int tasks_busy(const struct rcx *b)
{
    unsigned n, busy = 0;
    for (n = 0; n < RCX_TASKS; n++)
        if (b->task[n].state != RCX_TASK_IDLE)
            busy++;
    return (int)busy;
}

static void run_program(void **state)
{
    struct spec spec;
    struct loaded main_image, extra[MAX_LOAD];
    struct rcx *b;
    unsigned i, failed = 0;
    int busy;

    (void)state;
    memset(&main_image, 0, sizeof main_image);
    memset(extra, 0, sizeof extra);
    assert_int_equal(read_spec(&spec), 0);

    b = brick_new();
    for (i = 0; i < spec.nload; i++)
        assert_int_equal(download(b, &extra[i], spec.load[i].program, spec.load[i].slot), 0);
    assert_int_equal(download(b, &main_image, args.name, spec.nload ? 0 : -1), 0);

    for (i = 0; i < spec.starts; i++) {
        brick_start(b, 0);  /* nqc -run: 71 00 */
        brick_run_ms(b, spec.run_ms, spec.budget);
    }

    busy = tasks_busy(b);
    if (!spec.end_running && busy) {
        print_error("%s [%s]: %d task(s) still running or waiting after %u ms\n", args.name, args.target, busy,
                    spec.run_ms);
        failed++;
    } else if (spec.end_running && !busy) {
        print_error("%s [%s]: every task has ended, 'end: running' expected\n", args.name, args.target);
        failed++;
    }

    for (i = 0; i < spec.nexpect; i++) {
        const struct expect *e = &spec.expect[i];
        int n = e->element;
        s16 v;
        if (e->name[0]) {
            int base = rcx_image_find_var(&main_image.img, e->name);
            if (base < 0) {
                print_error("%s: the image names no variable '%s'\n", args.name, e->name);
                failed++;
                continue;
            }
            n += base;
        }
        if (n >= (strcmp(args.target, "Swan") == 0 ? RCX_ALL_GLOBALS : RCX_GLOBALS)) {
            print_error("%s: '%s' is variable %d, a task local that cannot be polled\n", args.name, e->text, n);
            failed++;
            continue;
        }
        v = poll_var(b, (u8)n);
        if (v < e->lo || v > e->hi) {
            print_message("%s [%s]: %s WRONG: variable %d is %d\n", args.name, args.target, e->text, n, v);
            failed++;
        } else {
            print_message("%s [%s]: %s ok: %d\n", args.name, args.target, e->text, v);
        }
    }

    brick_free(b);
    free(main_image.data);
    for (i = 0; i < spec.nload; i++)
        free(extra[i].data);
    if (failed)
        fail_msg("%s [%s]: %u check(s) failed", args.name, args.target, failed);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = { cmocka_unit_test(run_program) };
    const char *base, *dot;
    char group[128];
    size_t n;

    if (argc != 4 || (strcmp(argv[3], "RCX2") != 0 && strcmp(argv[3], "RCX") != 0 && strcmp(argv[3], "Swan") != 0)) {
        fprintf(stderr, "usage: %s <program.nqc> <image dir> <RCX2|RCX|Swan>\n", argv[0]);
        return 2;
    }
    args.source = argv[1];
    args.image_dir = argv[2];
    args.target = argv[3];
    args.suffix = strcmp(argv[3], "RCX2") == 0 ? "rcx2" : strcmp(argv[3], "Swan") == 0 ? "swan" : "rcx";
    base = strrchr(args.source, '/');
    base = base ? base + 1 : args.source;
    dot = strrchr(base, '.');
    n = dot ? (size_t)(dot - base) : strlen(base);
    if (n >= sizeof args.name)
        n = sizeof args.name - 1;
    memcpy(args.name, base, n);
    args.name[n] = 0;
    snprintf(group, sizeof group, "programs.%s.%s", args.name, args.suffix);
    return cmocka_run_group_tests_name(group, tests, NULL, NULL);
}
