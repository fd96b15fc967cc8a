/* SPDX-License-Identifier: MPL-2.0 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fuzz_common.h"

void fuzz_fail(const char *what)
{
    fprintf(stderr, "invariant violated: %s\n", what);
    abort();
}

/* Known code for object `obj`: a harmless straight-line program (sumv var[obj % 32], 1 ...), length 5..45. */
static unsigned known_code(u8 obj, u8 *out)
{
    unsigned n = 1 + obj % 9, i;
    for (i = 0; i < n; i++) {
        u8 *p = out + 5 * i;
        p[0] = 0x24;
        p[1] = (u8)(obj % 32);
        p[2] = 0x02;
        p[3] = (u8)(i + 1);
        p[4] = 0x00;
    }
    return 5 * n;
}

struct rcx *fuzz_populate(void)
{
    struct rcx *b = brick_new();
    fuzz_fill(b);
    return b;
}

void fuzz_fill(struct rcx *b)
{
    u8 code[64], cmd[8];
    unsigned prog, n, i;

    for (prog = 0; prog < RCX_PROGRAMS; prog++) {
        cmd[0] = 0x91;
        cmd[1] = (u8)prog;
        brick_cmd(b, cmd, 2, NULL);
        for (n = 0; n < RCX_SUBS; n += 2)
            if (brick_download(b, 0, (u8)n, code, known_code(rcx_obj_sub(prog, n), code)) != 0)
                fuzz_fail("populate sub");
        for (n = 0; n < RCX_TASKS; n += 3)
            if (brick_download(b, 1, (u8)n, code, known_code(rcx_obj_task(prog, n), code)) != 0)
                fuzz_fail("populate task");
    }
    cmd[0] = 0x91;
    cmd[1] = 0;
    brick_cmd(b, cmd, 2, NULL);
    cmd[0] = 0x52; /* SetDataLog */
    cmd[1] = FUZZ_LOG_ENTRIES;
    cmd[2] = 0;
    brick_cmd(b, cmd, 3, NULL);
    for (i = 0; i < FUZZ_LOGGED; i++) {
        u8 log[3] = { 0x62, 0x09, 0x00 }; /* DataLogNext of sensor 1's value */
        b->sensor[0].value = (s16)(1000 * i + 7);
        brick_cmd(b, log, 3, NULL);
    }
    if (b->log_count != FUZZ_LOGGED + 1)
        fuzz_fail("populate datalog");
}

void fuzz_snapshot(const struct rcx *b, struct fuzz_snapshot *s)
{
    unsigned obj;
    memset(s, 0, sizeof *s);
    for (obj = 0; obj < RCX_OBJS; obj++) {
        s->size[obj] = mem_obj_size(b, (u8)obj);
        memcpy(s->code[obj], mem_obj_code(b, (u8)obj), s->size[obj] < 64 ? s->size[obj] : 64);
    }
    s->log_count = b->log_count;
    s->log_size = b->log_size;
    memcpy(s->log, b->arena + b->obj_start[RCX_OBJS], 3u * s->log_count);
}

void fuzz_check_untouched(const struct rcx *b, const struct fuzz_snapshot *s, const u8 *touched)
{
    unsigned obj;
    for (obj = 0; obj < RCX_OBJS; obj++) {
        if (touched && touched[obj])
            continue;
        if (mem_obj_size(b, (u8)obj) != s->size[obj] ||
            memcmp(mem_obj_code(b, (u8)obj), s->code[obj], s->size[obj] < 64 ? s->size[obj] : 64) != 0)
            fuzz_fail("code of an object the input did not target changed");
    }
}

void fuzz_check_log(const struct rcx *b, const struct fuzz_snapshot *s)
{
    if (b->log_count != s->log_count || b->log_size != s->log_size ||
        memcmp(b->arena + b->obj_start[RCX_OBJS], s->log, 3u * s->log_count) != 0)
        fuzz_fail("datalog changed");
}

static u16 word(const u8 *r, unsigned i)
{
    return (u16)(r[1 + 2 * i] << 8 | r[2 + 2 * i]);
}

void fuzz_check_machine(struct rcx *b)
{
    u8 cmd[1] = { 0x20 }, r[RCX_REPLY_MAX];
    unsigned i, prog, n, total = 0;

    if (brick_cmd(b, cmd, 1, r) != 189)
        fuzz_fail("memory map reply length");
    for (prog = 0; prog < RCX_PROGRAMS; prog++) {
        for (n = 0; n < RCX_SUBS; n++)
            if (word(r, prog * RCX_SUBS + n) != (u16)(b->arena_addr + b->obj_start[rcx_obj_sub(prog, n)]))
                fuzz_fail("memory map: sub address");
        for (n = 0; n < RCX_TASKS; n++)
            if (word(r, 40 + prog * RCX_TASKS + n) != (u16)(b->arena_addr + b->obj_start[rcx_obj_task(prog, n)]))
                fuzz_fail("memory map: task address");
    }
    for (i = 0; i < RCX_OBJS; i++) {
        if (b->obj_start[i + 1] < b->obj_start[i])
            fuzz_fail("code objects out of order");
        total += mem_obj_size(b, (u8)i);
    }
    if (total != b->obj_start[RCX_OBJS] || b->obj_start[0] != 0)
        fuzz_fail("code sizes do not add up");
    if (word(r, 90) != (u16)(b->arena_addr + total) || word(r, 91) != (u16)(word(r, 90) + 3u * b->log_count) ||
        word(r, 92) != (u16)(word(r, 90) + 3u * b->log_size) || (u16)(word(r, 93) - word(r, 92)) != mem_free(b) ||
        total + 3u * b->log_size + mem_free(b) != RCX_ARENA_SIZE)
        fuzz_fail("memory map: datalog or free memory");
    if (b->log_count > b->log_size || (b->log_size && b->arena[total] != 0xFF))
        fuzz_fail("datalog header");
    for (n = 0; n < RCX_TASKS; n++) {
        const struct rcx_task *t = &b->task[n];
        u8 obj = t->sub == RCX_NO_SUB ? rcx_obj_task(b->prog, n) : rcx_obj_sub(b->prog, t->sub);
        if (((b->runmask >> n) & 1) != (t->state == RCX_TASK_RUNNING))
            fuzz_fail("run mask disagrees with task state");
        if (t->state == RCX_TASK_IDLE)
            continue;
        if ((t->sub != RCX_NO_SUB && t->sub >= RCX_SUBS) || t->loop_depth > RCX_LOOP_LEVELS)
            fuzz_fail("task state out of range");
        if (t->pc > mem_obj_size(b, obj))
            fuzz_fail("task pc outside its code");
    }
    if (b->runmask >> RCX_TASKS)
        fuzz_fail("run mask names a task that does not exist");
}
