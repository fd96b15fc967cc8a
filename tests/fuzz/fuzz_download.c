/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Fuzzer 3 of issue 6: random interleavings of download, delete, select, start/stop and other direct commands with
 * wrong sizes, numbers, checksums and orders, on a populated brick.
 *
 * Input: a sequence of operations, each a selector byte followed by its operands (see the switch).
 * Checked after each operation: every reply has the length nqc expects for its opcode; objects never targeted by a
 * download or delete are byte-identical; a download answered 0 on its last block holds exactly the data of the
 * blocks that were accepted; the datalog is untouched; the memory map agrees with the arena.
 */
#include <stdint.h>
#include <string.h>
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

struct dl_model {
    int active;
    u8 obj;
    u8 got[512];    /* data of the accepted blocks, in order */
    u16 len;
    u16 last;       /* number of the last accepted block */
};

static const u8 *take(const uint8_t *data, size_t size, size_t *pos, unsigned n)
{
    static const u8 zeros[32];
    const u8 *p = *pos + n <= size ? data + *pos : zeros;
    *pos += n;
    return p;
}

static void expect_reply(unsigned got, unsigned want)
{
    if (got != want)
        fuzz_fail("reply length differs from what nqc expects");
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    struct rcx *b = fuzz_populate();
    struct fuzz_snapshot snap;
    struct dl_model dl;
    u8 touched[RCX_OBJS], cmd[32 + 6], r[RCX_REPLY_MAX];
    size_t pos = 0;
    unsigned i;

    fuzz_snapshot(b, &snap);
    memset(touched, 0, sizeof touched);
    memset(&dl, 0, sizeof dl);

    while (pos < size) {
        u8 op = data[pos++] % 10;
        const u8 *a = take(data, size, &pos, 3);
        switch (op) {
        case 0:
        case 1: { /* BeginOfTask / BeginOfSub, number 0-15, size 0-511 */
            int is_task = op == 0;
            u8 n = a[0] & 0x0F;
            u16 len = (u16)(a[1] | (a[2] & 1) << 8);
            u8 obj = is_task ? rcx_obj_task(b->prog, n % RCX_TASKS) : rcx_obj_sub(b->prog, n % RCX_SUBS);
            cmd[0] = is_task ? 0x25 : 0x35;
            cmd[1] = 0;
            cmd[2] = n;
            cmd[3] = 0;
            cmd[4] = (u8)len;
            cmd[5] = (u8)(len >> 8);
            expect_reply(brick_cmd(b, cmd, 6, r), 2);
            if (dl.active)
                dl.active = 0; /* abandoned: its object may now be empty */
            if (r[1] == 0) {
                touched[obj] = 1;
                dl.active = 1;
                dl.obj = obj;
                dl.len = 0;
                dl.last = 0xFFFF;
            } else if (r[1] != 1 && r[1] != 2) {
                fuzz_fail("BeginOfTask/Sub status other than 0, 1, 2");
            }
            break;
        }
        case 2: { /* ContinueDL: block number 0-3, 0-31 data bytes, checksum right or wrong */
            u16 seq = a[0] & 3;
            u8 n = a[1] & 0x1F, sum = 0;
            const u8 *d = take(data, size, &pos, n);
            cmd[0] = 0x45 | (a[2] & 0x08);
            cmd[1] = (u8)seq;
            cmd[2] = 0;
            cmd[3] = n;
            cmd[4] = 0;
            for (i = 0; i < n; i++)
                sum = (u8)(sum + (cmd[5 + i] = d[i]));
            cmd[5 + n] = (u8)(sum + (a[2] & 0x80 ? 1 : 0));
            expect_reply(brick_cmd(b, cmd, 6u + n, r), 2);
            if (r[1] != 0 && r[1] != 3 && r[1] != 6)
                fuzz_fail("ContinueDL status other than 0, 3, 6");
            if (r[1] == 0) {
                if (!dl.active)
                    fuzz_fail("block accepted with no download active");
                if (seq == 0 || seq != dl.last) { /* a repeat of the last block is acknowledged, not stored */
                    memcpy(dl.got + dl.len, cmd + 5, n);
                    dl.len = (u16)(dl.len + n);
                    dl.last = seq;
                }
                if (seq == 0) {
                    if (mem_obj_size(b, dl.obj) != dl.len ||
                        memcmp(mem_obj_code(b, dl.obj), dl.got, dl.len) != 0)
                        fuzz_fail("downloaded code differs from the accepted blocks");
                    dl.active = 0;
                }
            }
            break;
        }
        case 3: /* DeleteTask */
        case 4: /* DeleteSub */
            cmd[0] = op == 3 ? 0x61 : 0xC1;
            cmd[1] = a[0] & 0x0F;
            if (cmd[1] < (op == 3 ? RCX_TASKS : RCX_SUBS))
                touched[op == 3 ? rcx_obj_task(b->prog, cmd[1]) : rcx_obj_sub(b->prog, cmd[1])] = 1;
            expect_reply(brick_cmd(b, cmd, 2, r), 1);
            break;
        case 5: /* DeleteAllTasks or DeleteAllSubs */
            cmd[0] = a[0] & 1 ? 0x40 : 0x70;
            for (i = 0; i < (a[0] & 1 ? RCX_TASKS : RCX_SUBS); i++)
                touched[a[0] & 1 ? rcx_obj_task(b->prog, i) : rcx_obj_sub(b->prog, i)] = 1;
            expect_reply(brick_cmd(b, cmd, 1, r), 1);
            break;
        case 6: /* SelectProgram 0-7 (5-7 acknowledged, ignored) */
            cmd[0] = 0x91;
            cmd[1] = a[0] & 7;
            expect_reply(brick_cmd(b, cmd, 2, r), 1);
            break;
        case 7: /* StartTask / StopTask / StopAllTasks, then a few milliseconds */
            cmd[0] = a[0] & 1 ? 0x71 : (a[0] & 2 ? 0x81 : 0x50);
            cmd[1] = a[1] & 0x0F;
            /* Only the populated code is started: code this input wrote could log (fuzz_interp runs such code). */
            if (cmd[0] == 0x71 && cmd[1] < RCX_TASKS && touched[rcx_obj_task(b->prog, cmd[1])])
                cmd[0] = 0x81;
            expect_reply(brick_cmd(b, cmd, cmd[0] == 0x50 ? 1 : 2, r), 1);
            brick_run_ms(b, a[2] & 7, 4);
            break;
        case 8: /* Ping, poll, memory map, battery, UploadRam */
            cmd[0] = a[0] & 1 ? 0x12 : 0x63;
            cmd[1] = a[1];
            cmd[2] = a[2];
            cmd[3] = a[0];
            if (cmd[0] == 0x12) {
                expect_reply(brick_cmd(b, cmd, 3, r), 3);
            } else {
                unsigned got = brick_cmd(b, cmd, 4, r);
                u16 addr = (u16)(cmd[1] | cmd[2] << 8);
                expect_reply(got, (addr < 0x8000u || addr >= 0xFD80u || cmd[3] > 150) ? 0 : 1u + cmd[3]);
            }
            break;
        default: /* Upload datalog entries */
            cmd[0] = 0xA4;
            cmd[1] = a[0] & 0x0F;
            cmd[2] = 0;
            cmd[3] = a[1] & 0x0F;
            cmd[4] = 0;
            i = brick_cmd(b, cmd, 5, r);
            if (i != 0 && i != 1u + 3u * cmd[3])
                fuzz_fail("datalog upload reply length");
            break;
        }
        fuzz_check_untouched(b, &snap, touched);
        fuzz_check_log(b, &snap);
    }
    fuzz_check_machine(b);
    brick_free(b);
    return 0;
}
