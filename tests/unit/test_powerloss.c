/* SPDX-License-Identifier: MPL-2.0 */
/*
 * A download interrupted at every block boundary (the host goes away, the tower is unplugged, the batteries of the
 * laptop die) leaves the brick answering, every other program intact, and the failed slot empty or whole.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <string.h>
#include <cmocka.h>
#include "brick.h"

#define BLOCK 20

static void fill(u8 *p, unsigned n, u8 seed)
{
    unsigned i;
    for (i = 0; i < n; i++)
        p[i] = (u8)(seed + 3 * i);
}

/* Send BeginOfTask and the first `blocks` of the 20-byte blocks of `code`, then stop. */
static void partial(struct rcx *b, u8 task, const u8 *code, unsigned len, unsigned blocks)
{
    u8 begin[6] = { 0x25, 0, task, 0, (u8)len, (u8)(len >> 8) }, r[RCX_REPLY_MAX];
    unsigned k;
    assert_int_equal(brick_cmd(b, begin, 6, r), 2);
    assert_int_equal(r[1], 0);
    for (k = 0; k < blocks; k++) {
        u8 blk[6 + BLOCK], sum = 0;
        unsigned i, off = k * BLOCK, n = len - off < BLOCK ? len - off : BLOCK;
        u16 seq = off + n >= len ? 0 : (u16)(k + 1);
        blk[0] = (u8)(0x45 | (k & 1 ? 0x08 : 0));
        blk[1] = (u8)seq;
        blk[2] = (u8)(seq >> 8);
        blk[3] = (u8)n;
        blk[4] = 0;
        for (i = 0; i < n; i++)
            sum = (u8)(sum + (blk[5 + i] = code[off + i]));
        blk[5 + n] = sum;
        assert_int_equal(brick_cmd(b, blk, 6 + n, r), 2);
        assert_int_equal(r[1], 0);
    }
}

static void snapshot(struct rcx *b, u8 *mm)
{
    u8 cmd = 0x20;
    assert_int_equal(brick_cmd(b, &cmd, 1, mm), 189);
}

static int answers(struct rcx *b)
{
    u8 ping = 0x10, r[4];
    return brick_cmd(b, &ping, 1, r) == 1 && r[0] == 0xEF;
}

static void interrupted_at_every_block(void **state)
{
    u8 code[95], other[33], replacement[40];
    unsigned blocks = (sizeof code + BLOCK - 1) / BLOCK, cut;
    (void)state;
    fill(code, sizeof code, 1);
    fill(other, sizeof other, 77);
    fill(replacement, sizeof replacement, 200);

    for (cut = 0; cut <= blocks; cut++) {
        struct rcx *b = brick_new();
        u8 sel[2] = { 0x91, 1 }, log[3] = { 0x52, 5, 0 }, logv[3] = { 0x62, 0x00, 0x03 };
        u8 before[RCX_REPLY_MAX], after[RCX_REPLY_MAX], arena_other[sizeof other];
        u16 other_start, log_count;

        /* Slot 1 holds a task; a datalog holds one point; slot 0 is being downloaded. */
        brick_cmd(b, sel, 2, NULL);
        assert_int_equal(brick_download(b, 1, 4, other, sizeof other), 0);
        sel[1] = 0;
        brick_cmd(b, sel, 2, NULL);
        brick_cmd(b, log, 3, NULL);
        b->global[3] = 1234;
        brick_cmd(b, logv, 3, NULL);
        log_count = b->log_count;

        partial(b, 2, code, sizeof code, cut);
        assert_true(answers(b));

        /* The cut download's code never runs, whole or not, until its last block came. */
        brick_start(b, 2);
        if (cut < blocks)
            assert_int_equal(b->task[2].state, RCX_TASK_IDLE);

        /* The host comes back and downloads something else: the unfinished task is abandoned. */
        snapshot(b, before);
        assert_int_equal(brick_download(b, 1, 5, replacement, sizeof replacement), 0);
        snapshot(b, after);
        assert_true(answers(b));

        other_start = b->obj_start[rcx_obj_task(1, 4)];
        memcpy(arena_other, b->arena + other_start, sizeof other);
        assert_int_equal(mem_obj_size(b, rcx_obj_task(1, 4)), sizeof other);
        assert_memory_equal(arena_other, other, sizeof other);
        assert_int_equal(b->log_count, log_count);
        assert_int_equal(b->arena[b->obj_start[RCX_OBJS] + 3], 0x03); /* point 1: variable 3 (kind 0 << 5 | 3) */
        assert_int_equal(b->arena[b->obj_start[RCX_OBJS] + 4], (u8)1234);

        if (cut == blocks) {
            assert_int_equal(mem_obj_size(b, rcx_obj_task(0, 2)), sizeof code); /* whole */
            assert_memory_equal(mem_obj_code(b, rcx_obj_task(0, 2)), code, sizeof code);
        } else {
            assert_int_equal(mem_obj_size(b, rcx_obj_task(0, 2)), 0);           /* empty */
        }
        assert_int_equal(mem_obj_size(b, rcx_obj_task(0, 5)), sizeof replacement);
        brick_start(b, 5);
        assert_int_equal(b->task[5].state, RCX_TASK_RUNNING);
        brick_free(b);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = { cmocka_unit_test(interrupted_at_every_block) };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
