/* SPDX-License-Identifier: MPL-2.0 */
#include <stdlib.h>
#include <string.h>
#include "brick.h"
#include "fake_hal.h"

struct rcx *brick_new(void)
{
    struct rcx *b = calloc(1, sizeof *b);
    struct fake_hal *h = calloc(1, sizeof *h);
    if (!b || !h)
        abort();
    b->port = h; /* vm_init keeps it: the outputs are set up through it */
    vm_init(b, TEST_ARENA_ADDR);
    return b;
}

void brick_free(struct rcx *b)
{
    free(b->port);
    free(b);
}

unsigned brick_cmd(struct rcx *b, const u8 *cmd, unsigned len, u8 *reply)
{
    u8 buf[RCX_REPLY_MAX];
    unsigned n = vm_direct(b, cmd, (u8)len, buf);
    if (reply)
        memcpy(reply, buf, n);
    return n;
}

int brick_download(struct rcx *b, int is_task, u8 n, const u8 *code, unsigned len)
{
    u8 begin[6] = { is_task ? 0x25 : 0x35, 0, n, 0, (u8)len, (u8)(len >> 8) };
    u8 reply[RCX_REPLY_MAX];
    unsigned off = 0;
    u16 seq = 1;

    if (brick_cmd(b, begin, sizeof begin, reply) != 2)
        return -1;
    if (reply[1])
        return reply[1];
    do {
        u8 block[6 + 20];
        unsigned chunk = len - off > 20 ? 20 : len - off, i;
        u8 sum = 0;
        u16 number = off + chunk >= len ? 0 : seq;
        block[0] = 0x45;
        block[1] = (u8)number;
        block[2] = (u8)(number >> 8);
        block[3] = (u8)chunk;
        block[4] = 0;
        for (i = 0; i < chunk; i++) {
            block[5 + i] = code[off + i];
            sum = (u8)(sum + code[off + i]);
        }
        block[5 + chunk] = sum;
        if (brick_cmd(b, block, 6 + chunk, reply) != 2)
            return -1;
        if (reply[1])
            return reply[1];
        off += chunk;
        seq++;
    } while (off < len);
    return 0;
}

void brick_run_ms(struct rcx *b, unsigned ms, unsigned per_ms)
{
    while (ms--) {
        vm_run(b, (u16)per_ms);
        vm_tick(b);
    }
}

static int busy(const struct rcx *b)
{
    unsigned n;
    for (n = 0; n < RCX_TASKS; n++)
        if (b->task[n].state != RCX_TASK_IDLE)
            return 1;
    return 0;
}

long brick_run_until_idle(struct rcx *b, unsigned max_ms, unsigned per_ms)
{
    unsigned ms;
    for (ms = 0; ms < max_ms; ms++) {
        if (!busy(b))
            return (long)ms;
        vm_run(b, (u16)per_ms);
        vm_tick(b);
    }
    return busy(b) ? -1 : (long)ms;
}

struct rcx *brick_copy(const struct rcx *b)
{
    struct rcx *s = malloc(sizeof *s);
    if (!s)
        abort();
    memcpy(s, b, sizeof *s);
    return s;
}

void brick_free_copy(struct rcx *copy)
{
    free(copy);
}

void brick_start(struct rcx *b, u8 n)
{
    u8 cmd[2] = { 0x71, n };
    brick_cmd(b, cmd, 2, NULL);
}
