/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Fuzzer 2 of issue 6: arbitrary task and subroutine code downloaded into slot 2 of a populated brick and run for a
 * bounded time with changing sensor input and events armed.
 *
 * Input: byte 0 = milliseconds to run (1-128), byte 1 = byte codes per millisecond (1-16), byte 2 = sensor seed,
 * then chunks: header (bit 7: subroutine, bits 0-3: number), length, code bytes. Code is decoded on all eight bits,
 * so Swan's opcodes (issue 16) are in reach; the corpus has Swan programs compiled by nqc -TSwan and one with every
 * Swan opcode on sources 43-62.
 * Checked after each input: no crash (sanitizers), code of every other object byte-identical, the datalog intact
 * unless the code itself may have logged, the memory map consistent with the arena, task states consistent.
 */
#include <stdint.h>
#include <string.h>
#include "fuzz_common.h"

#define SLOT 2

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static int may_touch_log(const u8 *code, unsigned len)
{
    unsigned i;
    for (i = 0; i < len; i++)
        if ((code[i] & 0xF7) == 0x52 || (code[i] & 0xF7) == 0x62 || code[i] == 0xC7 || code[i] == 24)
            return 1; /* SetDataLog or DataLogNext; Swan's ClearAll or system setting 24 (38: a new datalog) */
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    struct rcx *b;
    struct fuzz_snapshot snap;
    u8 touched[RCX_OBJS], started = 0, log_free = 1;
    unsigned ms, per_ms, i, pos = 3;
    u16 rng;
    u8 sel[2] = { 0x91, SLOT };
    u8 ev[4] = { 0x93, 0, 0, 0 };

    if (size < 3)
        return 0;
    ms = 1u + (data[0] & 0x7F);
    per_ms = 1u + (data[1] & 0x0F);
    rng = (u16)(data[2] * 257u + 1u);

    b = fuzz_populate();
    brick_cmd(b, sel, 2, NULL);
    for (i = 0; i < 4; i++) { /* some events armed, so the event engine has work */
        ev[1] = (u8)i;
        ev[2] = (u8)(i % 3);
        ev[3] = (u8)(i == 3 ? 10 : i);
        brick_cmd(b, ev, 4, NULL);
    }
    fuzz_snapshot(b, &snap);
    memset(touched, 0, sizeof touched);

    while (pos + 2 <= size) {
        u8 head = data[pos], len = data[pos + 1];
        int is_sub = head & 0x80;
        u8 n = (u8)(is_sub ? (head & 0x0F) % RCX_SUBS : (head & 0x0F) % RCX_TASKS);
        u8 obj = is_sub ? rcx_obj_sub(SLOT, n) : rcx_obj_task(SLOT, n);
        pos += 2;
        if (len > size - pos)
            len = (u8)(size - pos);
        if (brick_download(b, !is_sub, n, data + pos, len) == 0) {
            touched[obj] = 1;
            if (!is_sub)
                started |= (u8)(1u << (n & 7));
            if (may_touch_log(data + pos, len))
                log_free = 0;
        }
        pos += len;
    }
    fuzz_check_untouched(b, &snap, touched);
    for (i = 0; i < 8; i++)
        if (started & (1u << i))
            brick_start(b, (u8)i);

    while (ms--) {
        for (i = 0; i < RCX_SENSORS; i++) {
            rng ^= (u16)(rng << 7);
            rng ^= (u16)(rng >> 9);
            rng ^= (u16)(rng << 8);
            sensor_sample(b, (u8)i, rng & 0x3FF);
        }
        vm_run(b, (u16)per_ms);
        vm_tick(b);
    }

    fuzz_check_untouched(b, &snap, touched);
    if (log_free)
        fuzz_check_log(b, &snap);
    fuzz_check_machine(b);
    brick_free(b);
    return 0;
}
