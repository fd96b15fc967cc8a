/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Program memory and downloads: MemMap 0x20 (spec p. 13), BeginOfTask 0x25 / BeginOfSub 0x35 (pp. 88-89),
 * ContinueDL 0x45 (p. 90), UploadRam 0x63 (p. 68), and firm0328's observed download rules (reference-firmware.md,
 * "Downloads" and "IR command handling observed").
 *
 * Everything is checked from outside: addresses from the memory map, code bytes through UploadRam, free memory
 * as hosts compute it (word 93 - word 92).
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "brick.h"

#define SEND(b, r, ...) \
    brick_cmd((b), (const u8[]){ __VA_ARGS__ }, sizeof((const u8[]){ __VA_ARGS__ }), (r))

#define W_SUB(p, n) ((p) * 8 + (n))
#define W_TASK(p, n) (40 + (p) * 10 + (n))
#define W_LOG 90
#define W_LOGNEXT 91
#define W_FREE 92
#define W_TOP 93

static const u8 loop_inc0[] = { 0x24, 0x00, 0x02, 0x01, 0x00, 0x27, 0x86 }; /* L: sumv var[0],1 ; jmp L */
static const u8 loop_inc1[] = { 0x24, 0x01, 0x02, 0x01, 0x00, 0x27, 0x86 };

static void memmap(struct rcx *b, u16 w[94])
{
    u8 r[RCX_REPLY_MAX];
    unsigned i;
    assert_int_equal(SEND(b, r, 0x20), 189);
    assert_int_equal(r[0], 0xDF);
    for (i = 0; i < 94; i++)
        w[i] = (u16)(r[1 + 2 * i] << 8 | r[2 + 2 * i]); /* big-endian (p. 13: HI, LO) */
}

static unsigned freemem(struct rcx *b)
{
    u16 w[94];
    memmap(b, w);
    assert_true(w[W_FREE] <= w[W_TOP]);
    return (unsigned)(w[W_TOP] - w[W_FREE]);
}

static void upload(struct rcx *b, u16 addr, u8 *out, unsigned n)
{
    u8 r[RCX_REPLY_MAX];
    while (n) {
        unsigned chunk = n > 150 ? 150 : n;
        assert_int_equal(SEND(b, r, 0x63, (u8)addr, (u8)(addr >> 8), (u8)chunk), chunk + 1);
        memcpy(out, r + 1, chunk);
        out += chunk;
        addr = (u16)(addr + chunk);
        n -= chunk;
    }
}

/* The code at memory-map word `w` equals `code`. */
static void assert_code(struct rcx *b, unsigned w, const u8 *code, unsigned len)
{
    u16 map[94];
    u8 *got = malloc(len + 1);
    assert_non_null(got);
    memmap(b, map);
    upload(b, map[w], got, len);
    assert_memory_equal(got, code, len);
    free(got);
}

static u8 begin(struct rcx *b, int task, u8 n, u16 size)
{
    u8 r[RCX_REPLY_MAX];
    assert_int_equal(SEND(b, r, task ? 0x25 : 0x35, 0, n, 0, (u8)size, (u8)(size >> 8)), 2);
    assert_int_equal(r[0], task ? 0xDA : 0xCA);
    return r[1];
}

/* One 0x45 block; toggles the opcode like nqc does. `sum_delta` corrupts the checksum. */
static u8 block_x(struct rcx *b, u16 seq, const u8 *data, u16 n, u8 sum_delta)
{
    static u8 toggle;
    u8 cmd[6 + 256], r[RCX_REPLY_MAX], sum = 0;
    u16 i;
    assert_true(n <= 250);
    cmd[0] = (u8)(0x45 | toggle);
    toggle ^= 0x08;
    cmd[1] = (u8)seq;
    cmd[2] = (u8)(seq >> 8);
    cmd[3] = (u8)n;
    cmd[4] = (u8)(n >> 8);
    for (i = 0; i < n; i++)
        sum = (u8)(sum + (cmd[5 + i] = data[i]));
    cmd[5 + n] = (u8)(sum + sum_delta); /* 8-bit sum of the data bytes (p. 90) */
    assert_int_equal(brick_cmd(b, cmd, 6u + n, r), 2);
    assert_int_equal(r[0], (u8)~cmd[0]);
    return r[1];
}

static u8 block(struct rcx *b, u16 seq, const u8 *data, u16 n)
{
    return block_x(b, seq, data, n, 0);
}

static u8 *pattern(unsigned len, u8 seed)
{
    u8 *p = malloc(len ? len : 1);
    unsigned i;
    assert_non_null(p);
    for (i = 0; i < len; i++)
        p[i] = (u8)(seed + i * 7 + (i >> 8));
    return p;
}

static int running(const struct rcx *b, u8 n)
{
    return b->task[n].state != RCX_TASK_IDLE;
}

static s16 poll(struct rcx *b, u8 src, u8 idx)
{
    u8 r[RCX_REPLY_MAX];
    assert_int_equal(SEND(b, r, 0x12, src, idx), 3);
    return (s16)(u16)(r[1] | r[2] << 8);
}

static void memmap_layout(void **state)
{
    u8 sub[13], task[45], r[RCX_REPLY_MAX];
    struct rcx *b = brick_new();
    u16 w[94];
    unsigned i;
    (void)state;
    assert_int_equal(SEND(b, r, 0x28), 189);
    assert_int_equal(r[0], 0xD7);                           /* p. 13 */
    memmap(b, w);
    assert_true(w[W_LOG] <= w[W_LOGNEXT] && w[W_LOGNEXT] <= w[W_FREE] && w[W_FREE] < w[W_TOP]);
    for (i = 0; i < sizeof sub; i++)
        sub[i] = (u8)(0x30 + i);
    for (i = 0; i < sizeof task; i++)
        task[i] = (u8)(0xC0 + i);
    SEND(b, NULL, 0x91, 4);
    assert_int_equal(brick_download(b, 0, 5, sub, sizeof sub), 0);
    SEND(b, NULL, 0x91, 2);
    assert_int_equal(brick_download(b, 1, 3, task, sizeof task), 0);
    assert_code(b, W_SUB(4, 5), sub, sizeof sub);          /* word 4 * 8 + 5 */
    assert_code(b, W_TASK(2, 3), task, sizeof task);       /* word 40 + 2 * 10 + 3 */
    brick_free(b);
}

static void free_memory_shrinks_by_download_size(void **state)
{
    static const unsigned sizes[] = { 1, 19, 20, 21, 57, 200 };
    struct rcx *b = brick_new();
    unsigned i, f = freemem(b);
    (void)state;
    for (i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        u8 *code = pattern(sizes[i], (u8)i);
        assert_int_equal(brick_download(b, i & 1, (u8)i, code, sizes[i]), 0);
        f -= sizes[i];
        assert_int_equal(freemem(b), f);
        assert_code(b, (i & 1) ? W_TASK(0, i) : W_SUB(0, i), code, sizes[i]);
        free(code);
    }
    /* BeginOfTask reserves the memory as soon as it is accepted (reference-firmware.md). */
    assert_int_equal(begin(b, 1, 9, 33), 0);
    assert_int_equal(freemem(b), f - 33);
    brick_free(b);
}

static void begin_statuses(void **state)
{
    struct rcx *b = brick_new();
    unsigned f = freemem(b);
    u8 z = 0;
    (void)state;
    assert_int_equal(begin(b, 1, 10, 4), 2);               /* illegal task number (p. 88) */
    assert_int_equal(begin(b, 1, 255, 4), 2);
    assert_int_equal(begin(b, 0, 8, 4), 2);                /* illegal subroutine number (p. 89) */
    assert_int_equal(freemem(b), f);
    assert_int_equal(begin(b, 1, 0, (u16)(f + 1)), 1);     /* one byte too many: not enough memory */
    assert_int_equal(begin(b, 0, 7, (u16)(f + 1)), 1);
    assert_int_equal(freemem(b), f);
    assert_int_equal(block(b, 0, &z, 1), 6);               /* nothing was started */
    assert_int_equal(begin(b, 1, 9, (u16)f), 0);           /* exactly the free size (reference-firmware.md) */
    assert_int_equal(freemem(b), 0);
    brick_free(b);
}

static void continue_statuses(void **state)
{
    static const u8 code[] = { 0x14, 0x00, 0x02, 0x05, 0x00 };
    struct rcx *b = brick_new();
    (void)state;
    assert_int_equal(block(b, 1, code, sizeof code), 6);   /* download not active (p. 90) */
    assert_int_equal(block(b, 0, code, sizeof code), 6);
    assert_int_equal(begin(b, 1, 0, sizeof code), 0);
    assert_int_equal(block_x(b, 0, code, sizeof code, 1), 3); /* block checksum error */
    assert_int_equal(block(b, 0, code, sizeof code), 0);   /* still active: the good block is taken */
    assert_int_equal(block(b, 0, code, sizeof code), 6);   /* right after a finished download */
    assert_int_equal(block(b, 1, code, sizeof code), 6);
    assert_code(b, W_TASK(0, 0), code, sizeof code);
    brick_free(b);
}

static void repeated_block_written_once(void **state)
{
    u8 *code = pattern(50, 3);
    struct rcx *b = brick_new();
    unsigned f = freemem(b);
    (void)state;
    assert_int_equal(begin(b, 0, 2, 50), 0);
    assert_int_equal(block(b, 1, code, 20), 0);
    assert_int_equal(block(b, 1, code, 20), 0);            /* re-acknowledged */
    assert_int_equal(block(b, 2, code + 20, 20), 0);
    assert_int_equal(block(b, 2, code + 20, 20), 0);
    assert_int_equal(block(b, 0, code + 40, 10), 0);
    assert_int_equal(freemem(b), f - 50);
    assert_code(b, W_SUB(0, 2), code, 50);
    free(code);
    brick_free(b);
}

static void out_of_order_and_oversize_blocks(void **state)
{
    u8 *code = pattern(70, 9); /* 60 bytes of task, and 10 more for the oversize block */
    struct rcx *b = brick_new();
    u16 w0[94], w1[94];
    (void)state;
    assert_int_equal(begin(b, 1, 1, 60), 0);
    assert_true(block(b, 2, code, 20) != 0);               /* must start with block 1 (p. 90) */
    assert_int_equal(block(b, 1, code, 20), 0);
    assert_true(block(b, 3, code + 20, 20) != 0);          /* block 2 skipped */
    assert_int_equal(block(b, 2, code + 20, 20), 0);
    memmap(b, w0);
    assert_true(block(b, 0, code + 40, 30) != 0);          /* 70 bytes for a 60-byte task */
    memmap(b, w1);
    assert_memory_equal(w0, w1, sizeof w0);
    assert_int_equal(block(b, 0, code + 40, 20), 0);
    assert_code(b, W_TASK(0, 1), code, 60);
    /* A single block larger than the whole announced size. */
    assert_int_equal(begin(b, 0, 0, 10), 0);
    assert_true(block(b, 0, code, 20) != 0);
    assert_int_equal(block(b, 0, code, 10), 0);
    assert_code(b, W_SUB(0, 0), code, 10);
    assert_code(b, W_TASK(0, 1), code, 60);
    free(code);
    brick_free(b);
}

/* A brick with code in several slots and a datalog, and a way to check that none of it moved in content. */
struct scene {
    u8 *sub1, *t0, *t4, *p1t0, log[3 * 4 + 1];
};

static struct rcx *scene_new(struct scene *s)
{
    struct rcx *b = brick_new();
    s->sub1 = pattern(23, 1);
    s->t0 = pattern(41, 2);
    s->t4 = pattern(8, 3);
    s->p1t0 = pattern(30, 4);
    SEND(b, NULL, 0x91, 1);
    assert_int_equal(brick_download(b, 1, 0, s->p1t0, 30), 0);
    SEND(b, NULL, 0x91, 0);
    assert_int_equal(brick_download(b, 0, 1, s->sub1, 23), 0);
    assert_int_equal(brick_download(b, 1, 0, s->t0, 41), 0);
    assert_int_equal(brick_download(b, 1, 4, s->t4, 8), 0);
    SEND(b, NULL, 0x52, 10, 0);
    SEND(b, NULL, 0x14, 3, 0x02, 0x34, 0x12);
    SEND(b, NULL, 0x62, 0x00, 0x03);
    SEND(b, NULL, 0x62, 0x01, 0x02);
    SEND(b, NULL, 0x62, 0x00, 0x01);
    assert_int_equal(SEND(b, s->log, 0xA4, 0, 0, 4, 0), 13);
    return b;
}

static void scene_check(struct rcx *b, struct scene *s)
{
    u8 log[RCX_REPLY_MAX];
    assert_code(b, W_SUB(0, 1), s->sub1, 23);
    assert_code(b, W_TASK(0, 0), s->t0, 41);
    assert_code(b, W_TASK(0, 4), s->t4, 8);
    assert_code(b, W_TASK(1, 0), s->p1t0, 30);
    assert_int_equal(SEND(b, log, 0xA4, 0, 0, 4, 0), 13);
    assert_memory_equal(log + 1, s->log + 1, 12);
}

static void scene_free(struct rcx *b, struct scene *s)
{
    free(s->sub1);
    free(s->t0);
    free(s->t4);
    free(s->p1t0);
    brick_free(b);
}

static void abandoned_download(void **state)
{
    struct scene s;
    struct rcx *b = scene_new(&s);
    u8 *code = pattern(40, 5), *again = pattern(37, 6);
    unsigned f = freemem(b);
    (void)state;
    /* Task 2 had code; a new download of it is abandoned halfway by a BeginOfTask for task 6. */
    assert_int_equal(brick_download(b, 1, 2, again, 37), 0);
    assert_int_equal(begin(b, 1, 2, 40), 0);
    assert_int_equal(block(b, 1, code, 20), 0);
    assert_int_equal(begin(b, 1, 6, 5), 0);
    assert_int_equal(block(b, 0, code, 5), 0);
    assert_int_equal(freemem(b), f - 5);                   /* task 2 holds nothing any more */
    brick_start(b, 2);
    assert_false(running(b, 2));
    scene_check(b, &s);
    assert_code(b, W_TASK(0, 6), code, 5);
    /* Abandoned by a BeginOfSub as well. */
    assert_int_equal(begin(b, 0, 4, 40), 0);
    assert_int_equal(block(b, 1, code, 20), 0);
    assert_int_equal(begin(b, 0, 5, 3), 0);
    assert_int_equal(block(b, 0, code, 3), 0);
    assert_int_equal(freemem(b), f - 8);
    scene_check(b, &s);
    free(code);
    free(again);
    scene_free(b, &s);
}

/*
 * Found by fuzz_download (corpus/download/regress-begin-bad-number): a BeginOfTask refused for its number kept an
 * unfinished download alive while one refused for memory abandoned it. Any new BeginOfTask/Sub, accepted or not,
 * ends the unfinished download: its slot is empty and later blocks are answered "not active" (status 6).
 */
static void refused_begin_ends_unfinished_download(void **state)
{
    static const u8 code[20] = { 0x24, 0x00, 0x02, 0x01, 0x00 };
    unsigned refusal;
    (void)state;
    for (refusal = 0; refusal < 3; refusal++) {
        struct rcx *b = brick_new();
        assert_int_equal(begin(b, 1, 3, 40), 0);
        assert_int_equal(block(b, 1, code, 20), 0);
        if (refusal == 0)
            assert_int_equal(begin(b, 1, 10, 5), 2);       /* task number 10 */
        else if (refusal == 1)
            assert_int_equal(begin(b, 0, 8, 5), 2);        /* subroutine number 8 */
        else
            assert_int_equal(begin(b, 1, 4, 0xFFF0), 1);   /* more than the memory */
        assert_int_equal(mem_obj_size(b, rcx_obj_task(0, 3)), 0);
        assert_int_equal(block(b, 0, code, 20), 6);
        brick_free(b);
    }
}

static void not_runnable_until_last_block(void **state)
{
    static const u8 code[] = { 0x14, 0x07, 0x02, 0x01, 0x00, 0x14, 0x07, 0x02, 0x02, 0x00, 0x14, 0x07, 0x02,
                               0x03, 0x00, 0x14, 0x07, 0x02, 0x04, 0x00, 0x27, 0x81 }; /* var[7] = 1..4; loop */
    struct rcx *b = brick_new();
    (void)state;
    assert_int_equal(brick_download(b, 1, 3, loop_inc1, sizeof loop_inc1), 0);
    assert_int_equal(begin(b, 1, 0, sizeof code), 0);
    assert_int_equal(block(b, 1, code, 20), 0);
    brick_start(b, 0);
    assert_false(running(b, 0));
    /* The download stays active through other commands and silence (reference-firmware.md). */
    SEND(b, NULL, 0x10);
    SEND(b, NULL, 0x50);
    SEND(b, NULL, 0x61, 0x03);
    brick_run_ms(b, 3000, 5);
    brick_start(b, 0);
    assert_false(running(b, 0));
    assert_int_equal(poll(b, 0, 7), 0);
    assert_int_equal(block(b, 0, code + 20, 2), 0);
    brick_start(b, 0);
    assert_true(running(b, 0));
    brick_run_ms(b, 10, 5);
    assert_int_equal(poll(b, 0, 7), 4);
    brick_free(b);
}

static void replacing_code_keeps_running_tasks(void **state)
{
    u8 *old2 = pattern(30, 7), *new2 = pattern(75, 8), *sub0 = pattern(12, 9), *sub0b = pattern(3, 10);
    struct rcx *b = brick_new();
    s16 v0, v1;
    (void)state;
    assert_int_equal(brick_download(b, 0, 0, sub0, 12), 0);
    assert_int_equal(brick_download(b, 1, 0, loop_inc0, sizeof loop_inc0), 0);
    assert_int_equal(brick_download(b, 1, 2, old2, 30), 0);
    assert_int_equal(brick_download(b, 1, 5, loop_inc1, sizeof loop_inc1), 0);
    brick_start(b, 0);
    brick_start(b, 5);
    brick_run_ms(b, 10, 4);
    assert_int_equal(brick_download(b, 1, 2, new2, 75), 0); /* replace task 2 with longer code */
    assert_int_equal(brick_download(b, 0, 0, sub0b, 3), 0); /* and sub 0 with shorter code */
    assert_true(running(b, 0));
    assert_true(running(b, 5));
    assert_code(b, W_TASK(0, 0), loop_inc0, sizeof loop_inc0);
    assert_code(b, W_TASK(0, 5), loop_inc1, sizeof loop_inc1);
    assert_code(b, W_TASK(0, 2), new2, 75);
    assert_code(b, W_SUB(0, 0), sub0b, 3);
    /* Both tasks keep executing their own loops: equal shares, one increment per two byte codes. */
    v0 = poll(b, 0, 0);
    v1 = poll(b, 0, 1);
    brick_run_ms(b, 10, 4);
    assert_int_equal(poll(b, 0, 0) - v0, 10);
    assert_int_equal(poll(b, 0, 1) - v1, 10);
    free(old2);
    free(new2);
    free(sub0);
    free(sub0b);
    brick_free(b);
}

static void delete_and_redownload_compacts(void **state)
{
    u8 *a = pattern(33, 11), *bb = pattern(64, 12), *c = pattern(17, 13), *d = pattern(21, 14),
       *b2 = pattern(90, 15), *fill;
    struct rcx *b = brick_new();
    unsigned f0 = freemem(b), f;
    (void)state;
    assert_int_equal(brick_download(b, 1, 1, a, 33), 0);
    assert_int_equal(brick_download(b, 1, 2, bb, 64), 0);
    assert_int_equal(brick_download(b, 1, 3, c, 17), 0);
    assert_int_equal(brick_download(b, 0, 6, d, 21), 0);
    assert_int_equal(SEND(b, NULL, 0x61, 2), 1);
    assert_int_equal(freemem(b), f0 - 33 - 17 - 21);       /* no hole is left behind */
    assert_code(b, W_TASK(0, 1), a, 33);
    assert_code(b, W_TASK(0, 3), c, 17);
    assert_code(b, W_SUB(0, 6), d, 21);
    assert_int_equal(brick_download(b, 1, 2, b2, 90), 0);
    assert_int_equal(freemem(b), f0 - 33 - 90 - 17 - 21);
    assert_code(b, W_TASK(0, 1), a, 33);
    assert_code(b, W_TASK(0, 2), b2, 90);
    assert_code(b, W_TASK(0, 3), c, 17);
    assert_code(b, W_SUB(0, 6), d, 21);
    /* After deleting, all free memory is usable by one download. */
    assert_int_equal(SEND(b, NULL, 0x61, 1), 1);
    f = freemem(b);
    fill = pattern(f, 16);
    assert_int_equal(brick_download(b, 1, 9, fill, f), 0);
    assert_int_equal(freemem(b), 0);
    assert_code(b, W_TASK(0, 9), fill, f);
    assert_code(b, W_TASK(0, 2), b2, 90);
    free(a);
    free(bb);
    free(c);
    free(d);
    free(b2);
    free(fill);
    brick_free(b);
}

static void fill_memory_then_refuse(void **state)
{
    struct rcx *b = brick_new();
    unsigned f = freemem(b);
    u8 *code = pattern(f, 17);
    u16 w[94];
    (void)state;
    assert_int_equal(brick_download(b, 1, 0, code, f), 0);
    memmap(b, w);
    assert_int_equal(w[W_FREE], w[W_TOP]);
    assert_code(b, W_TASK(0, 0), code, f);                 /* down to the last byte */
    assert_int_equal(begin(b, 0, 0, 1), 1);
    assert_int_equal(begin(b, 1, 1, 1), 1);
    assert_int_equal(begin(b, 1, 2, 0xFFFF), 1);
    assert_int_equal(freemem(b), 0);
    assert_code(b, W_TASK(0, 0), code, f);
    SEND(b, NULL, 0x61, 0);
    assert_int_equal(freemem(b), f);
    free(code);
    brick_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(memmap_layout),
        cmocka_unit_test(free_memory_shrinks_by_download_size),
        cmocka_unit_test(begin_statuses),
        cmocka_unit_test(continue_statuses),
        cmocka_unit_test(repeated_block_written_once),
        cmocka_unit_test(out_of_order_and_oversize_blocks),
        cmocka_unit_test(abandoned_download),
        cmocka_unit_test(refused_begin_ends_unfinished_download),
        cmocka_unit_test(not_runnable_until_last_block),
        cmocka_unit_test(replacing_code_keeps_running_tasks),
        cmocka_unit_test(delete_and_redownload_compacts),
        cmocka_unit_test(fill_memory_then_refuse),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
