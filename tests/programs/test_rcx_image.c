/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The .rcx reader and loader on good and bad input.
 *
 * Usage: test_rcx_image <image with subroutines and tasks> <second image>
 * Both are real nqc output (CMake passes subs.rcx2.rcx and arith.rcx.rcx). Every corrupt variant is parsed from a
 * buffer of exactly its own size, so a read past the end is a heap overflow that the sanitizer build reports.
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

static const char *good_path, *second_path;

struct file {
    u8 *data;
    size_t size;
};

static struct file read_or_die(const char *path)
{
    struct file f;
    char err[160];
    if (rcx_image_read_file(path, &f.data, &f.size, err, sizeof err))
        fail_msg("%s", err);
    return f;
}

/* Parse a copy of `size` bytes held in a buffer of exactly that size (freed again: img is not usable after). */
static int parse_exact(const u8 *data, size_t size, struct rcx_image *img, char *err, size_t errlen)
{
    u8 *copy = malloc(size ? size : 1);
    int rc;
    assert_non_null(copy);
    if (size)
        memcpy(copy, data, size);
    rc = rcx_image_parse(img, copy, size, err, errlen);
    /* An accepted image must only point inside the buffer. */
    if (rc == 0) {
        unsigned i;
        for (i = 0; i < img->chunk_count; i++) {
            assert_true(img->chunk[i].code >= copy);
            assert_true(img->chunk[i].code + img->chunk[i].length <= copy + size);
        }
        for (i = 0; i < img->symbol_count; i++) {
            const u8 *name = (const u8 *)img->symbol[i].name;
            assert_true(name >= copy && name < copy + size);
            assert_non_null(memchr(name, 0, (size_t)(copy + size - name)));
        }
    }
    free(copy);
    return rc;
}

static void expect_rejected(const u8 *data, size_t size, const char *what)
{
    struct rcx_image img;
    char err[160] = "";
    if (parse_exact(data, size, &img, err, sizeof err) == 0)
        fail_msg("%s: accepted", what);
    if (!err[0])
        fail_msg("%s: rejected without a message", what);
}

/* ---- a small image built by hand ------------------------------------------------------------------------- */

static size_t put16(u8 *p, unsigned v)
{
    p[0] = (u8)v;
    p[1] = (u8)(v >> 8);
    return 2;
}

/*
 * Header + one task 0 of `len` bytes (code = `fill`) + one variable symbol "x" at index 5. For len 5 the bytes are:
 * 0 "RCXI", 4 version, 6 chunks, 8 symbols, 10 target, 11 zero, 12 chunk type, 13 number, 14 length, 16 code
 * and padding, 24 symbol type, 25 index, 26 length, 28 'x', 29 zero; 30 in all.
 */
static size_t build(u8 *out, unsigned len, u8 fill)
{
    size_t n = 0, padded = (len + 3u) & ~3u;
    memcpy(out, "RCXI", 4);
    n = 4;
    n += put16(out + n, 0x0102);
    n += put16(out + n, 1);
    n += put16(out + n, 1);
    out[n++] = 3;
    out[n++] = 0;
    out[n++] = 0;  /* task */
    out[n++] = 0;  /* number */
    n += put16(out + n, len);
    memset(out + n, fill, len);
    memset(out + n + len, 0, padded - len);
    n += padded;
    out[n++] = 2;  /* variable */
    out[n++] = 5;
    n += put16(out + n, 2);
    out[n++] = 'x';
    out[n++] = 0;
    return n;
}

/* ---- tests ----------------------------------------------------------------------------------------------- */

static void parses_nqc_output(void **state)
{
    struct file f = read_or_die(good_path), g = read_or_die(second_path);
    struct rcx_image img;
    char err[160];
    unsigned i, tasks = 0, subs = 0;
    (void)state;

    assert_int_equal(rcx_image_parse(&img, f.data, f.size, err, sizeof err), 0);
    assert_int_equal(img.version, 0x0102);
    assert_int_equal(img.target, RCX_IMAGE_TARGET_RCX2);
    for (i = 0; i < img.chunk_count; i++) {
        if (img.chunk[i].type == RCX_CHUNK_TASK)
            tasks++;
        else
            subs++;
    }
    /* subs.nqc: main and t2; step, slow and clip */
    assert_int_equal(tasks, 2);
    assert_int_equal(subs, 3);
    assert_int_equal(img.chunk[0].type, RCX_CHUNK_SUB); /* nqc writes subroutines first */
    assert_int_equal(rcx_image_find_var(&img, "calls"), 0);
    assert_int_equal(rcx_image_find_var(&img, "acc"), 1);
    assert_int_equal(rcx_image_find_var(&img, "no_such"), -1);

    assert_int_equal(rcx_image_parse(&img, g.data, g.size, err, sizeof err), 0);
    assert_int_equal(img.target, RCX_IMAGE_TARGET_RCX);
    assert_int_equal(img.chunk_count, 1);
    /* every nqc main begins by setting all outputs to full power, forward */
    assert_true(img.chunk[0].length >= 6);
    assert_memory_equal(img.chunk[0].code, "\x13\x07\x02\x07\xe1\x87", 6);
    free(f.data);
    free(g.data);
}

static void every_truncation_rejected(void **state)
{
    struct file f = read_or_die(good_path);
    size_t len;
    char what[64];
    (void)state;
    for (len = 0; len < f.size; len++) {
        snprintf(what, sizeof what, "first %lu of %lu bytes", (unsigned long)len, (unsigned long)f.size);
        expect_rejected(f.data, len, what);
    }
    free(f.data);
}

static void corrupt_fields_rejected(void **state)
{
    u8 base[64], b[80];
    size_t n = build(base, 5, 0x24);
    struct rcx_image img;
    char err[160];
    (void)state;

    assert_int_equal(n, 30);
    assert_int_equal(parse_exact(base, n, &img, err, sizeof err), 0);
    assert_int_equal(rcx_image_parse(&img, base, n, err, sizeof err), 0);   /* img points into base now */
    assert_int_equal(img.chunk[0].length, 5);
    assert_int_equal(rcx_image_find_var(&img, "x"), 5);

#define MUTATE(off, val, what) do { memcpy(b, base, n); b[off] = (u8)(val); expect_rejected(b, n, what); } while (0)
    MUTATE(0, 'X', "bad signature");
    MUTATE(4, 0x03, "format version 0103");
    MUTATE(6, 2, "two chunks announced, one present");
    MUTATE(7, 1, "257 chunks");
    MUTATE(8, 2, "two symbols announced, one present");
    MUTATE(9, 0xFF, "65281 symbols");
    MUTATE(10, 1, "target CM");
    MUTATE(10, 4, "target Spybotics");
    MUTATE(11, 1, "non-zero header byte 11");
    MUTATE(12, 2, "chunk type 2 (sound)");
    MUTATE(13, RCX_TASKS, "task number 10");
    MUTATE(14, 0x20, "chunk longer than the file");
    MUTATE(15, 0xFF, "chunk length 0xFF05");
    MUTATE(24, 3, "symbol type 3");
    MUTATE(25, RCX_VARS, "variable 48");
    MUTATE(26, 1, "symbol length 1 (no name)");
    MUTATE(26, 0, "symbol length 0");
    MUTATE(26, 3, "symbol name running past the end");
    MUTATE(27, 1, "symbol length 258");
    MUTATE(29, 'y', "symbol name without its zero");
    MUTATE(28, 0, "zero inside a symbol name");
#undef MUTATE

    /* a subroutine number that only a task may have */
    memcpy(b, base, n);
    b[12] = 1;
    b[13] = RCX_SUBS;
    expect_rejected(b, n, "subroutine number 8");

    /* bytes after the last symbol */
    memcpy(b, base, n);
    b[n] = 0;
    expect_rejected(b, n + 1, "trailing byte");

    /* the same task twice */
    {
        u8 two[96];
        size_t m = 0;
        memcpy(two, base, 12);
        two[6] = 2;
        two[8] = 0;
        m = 12;
        memcpy(two + m, base + 12, 12);   /* task 0, 5 bytes + 3 padding */
        m += 12;
        memcpy(two + m, base + 12, 12);
        m += 12;
        expect_rejected(two, m, "task 0 twice");
        two[m - 12 + 1] = 1;              /* task 1: now acceptable */
        assert_int_equal(parse_exact(two, m, &img, err, sizeof err), 0);
        assert_int_equal(img.chunk_count, 2);
    }
}

static void byte_flips_never_overrun(void **state)
{
    static const u8 masks[] = { 0x01, 0x02, 0x80, 0xFF };
    struct file f = read_or_die(good_path);
    u8 *b = malloc(f.size);
    struct rcx_image img;
    char err[160];
    size_t i, m;
    unsigned rejected = 0;
    (void)state;

    assert_non_null(b);
    for (i = 0; i < f.size; i++)
        for (m = 0; m < sizeof masks; m++) {
            memcpy(b, f.data, f.size);
            b[i] ^= masks[m];
            if (parse_exact(b, f.size, &img, err, sizeof err))
                rejected++;
        }
    assert_true(rejected > 0);
    free(b);
    free(f.data);
}

static void loads_into_chosen_slot(void **state)
{
    struct file f = read_or_die(good_path);
    struct rcx_image img;
    struct rcx *b = brick_new();
    char err[160];
    unsigned i;
    (void)state;

    assert_int_equal(rcx_image_parse(&img, f.data, f.size, err, sizeof err), 0);
    assert_int_equal(rcx_image_load(b, &img, 2, err, sizeof err), 0);
    assert_int_equal(b->prog, 2);
    for (i = 0; i < img.chunk_count; i++) {
        const struct rcx_chunk *ch = &img.chunk[i];
        u8 obj = ch->type == RCX_CHUNK_TASK ? rcx_obj_task(2, ch->number) : rcx_obj_sub(2, ch->number);
        assert_int_equal(mem_obj_size(b, obj), ch->length);
        assert_memory_equal(mem_obj_code(b, obj), ch->code, ch->length);
        assert_int_equal(mem_obj_size(b, (u8)(obj - 2 * RCX_SLOT_OBJS)), 0); /* slot 0 untouched */
    }
    brick_free(b);
    free(f.data);
}

static void reload_replaces_program(void **state)
{
    struct file f = read_or_die(good_path), g = read_or_die(second_path);
    struct rcx_image big, small;
    struct rcx *b = brick_new();
    char err[160];
    (void)state;

    assert_int_equal(rcx_image_parse(&big, f.data, f.size, err, sizeof err), 0);
    assert_int_equal(rcx_image_parse(&small, g.data, g.size, err, sizeof err), 0);
    assert_int_equal(rcx_image_load(b, &big, -1, err, sizeof err), 0);
    assert_true(mem_obj_size(b, rcx_obj_task(0, 1)) > 0);
    assert_true(mem_obj_size(b, rcx_obj_sub(0, 2)) > 0);
    brick_start(b, 0);
    brick_run_ms(b, 5, 10);
    assert_int_equal(rcx_image_load(b, &small, -1, err, sizeof err), 0);   /* stops the running program first */
    assert_int_equal(b->task[0].state, RCX_TASK_IDLE);
    assert_int_equal(mem_obj_size(b, rcx_obj_task(0, 0)), small.chunk[0].length);
    assert_int_equal(mem_obj_size(b, rcx_obj_task(0, 1)), 0);
    assert_int_equal(mem_obj_size(b, rcx_obj_sub(0, 2)), 0);
    brick_free(b);
    free(f.data);
    free(g.data);
}

static void load_refused_when_memory_is_short(void **state)
{
    const unsigned len = RCX_ARENA_SIZE + 4u;
    u8 *data = malloc(len + 64);
    struct rcx_image img;
    struct rcx *b = brick_new();
    char err[160] = "";
    size_t n;
    (void)state;

    assert_non_null(data);
    n = build(data, len, 0x10);
    assert_int_equal(rcx_image_parse(&img, data, n, err, sizeof err), 0);
    assert_int_equal(rcx_image_load(b, &img, -1, err, sizeof err), -1);
    assert_non_null(strstr(err, "status 1"));   /* BeginOfTask: not enough memory */
    assert_int_equal(mem_obj_size(b, rcx_obj_task(0, 0)), 0);
    assert_int_equal(rcx_image_load(b, &img, RCX_PROGRAMS, err, sizeof err), -1);  /* no slot 5 */
    brick_free(b);
    free(data);
}

static void missing_file_reported(void **state)
{
    u8 *data;
    size_t size;
    char err[160] = "";
    (void)state;
    assert_int_equal(rcx_image_read_file("/nonexistent/program.rcx", &data, &size, err, sizeof err), -1);
    assert_null(data);
    assert_true(err[0] != 0);
    expect_rejected((const u8 *)"", 0, "empty file");
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(parses_nqc_output),
        cmocka_unit_test(every_truncation_rejected),
        cmocka_unit_test(corrupt_fields_rejected),
        cmocka_unit_test(byte_flips_never_overrun),
        cmocka_unit_test(loads_into_chosen_slot),
        cmocka_unit_test(reload_replaces_program),
        cmocka_unit_test(load_refused_when_memory_is_short),
        cmocka_unit_test(missing_file_reported),
    };
    if (argc != 3) {
        fprintf(stderr, "usage: %s <image> <second image>\n", argv[0]);
        return 2;
    }
    good_path = argv[1];
    second_path = argv[2];
    return cmocka_run_group_tests_name("programs.loader", tests, NULL, NULL);
}
