/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Fuzzer 1 of issue 6: arbitrary byte streams into the IR receive path of a whole brick (packet layer, toggle
 * handling, direct commands, downloads), with the brick's own echo fed back as a serial tower hears it.
 *
 * Input: the bytes as they arrive; a byte 0xF0-0xFF that follows a 0x55 0xAA marker is not sent but lets
 * (byte & 0x0F) x 5 ms of silence pass (so timeouts and resynchronisation get exercised).
 * Checked: every packet the brick transmits is well formed (header, complements, checksum) with the reply length
 * nqc expects for the command it answers; while the selected slot stays 0, slots 1-4 are byte-identical; the datalog
 * is untouched unless a datalog command byte appeared; the memory map stays consistent with the arena.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "fuzz_common.h"
#include "fake_hal.h"
#include "runtime.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* Expected reply length (opcode included) for the command whose reply opcode is r, or 0 when any length of the
 * variable-length replies is acceptable and checked by `variable_ok`. */
static int reply_ok(u8 r, unsigned len)
{
    u8 op = (u8)~r, fixed = rcx_op_reply(op);
    op &= (u8)~RCX_TOGGLE;
    if (op == RCX_OP_UPLOAD_RAM)
        return len >= 1 && len <= 151;
    if (op == RCX_OP_UPLOAD_DATALOG)
        return len >= 1 && (len - 1) % 3 == 0;
    if (op == RCX_OP_UNLOCK_BRICK)
        return len == 9 || len == 1;   /* a wrong key gets a bare acknowledgement */
    return fixed != 0 && fixed != RCX_REPLY_VAR && len == fixed;
}

/*
 * Whether tx[i..to) is a sequence of standard reply packets: 55 FF 00, byte/complement pairs, then the checksum
 * pair. Data may contain anything, so every end where the checksum and the length fit is tried.
 */
static int parses(const u8 *tx, unsigned i, unsigned to)
{
    u8 sum = 0, first = 0;
    unsigned n = 0;

    if (i == to)
        return 1;
    if (i + 3 > to || tx[i] != 0x55 || tx[i + 1] != 0xFF || tx[i + 2] != 0x00)
        return 0;
    for (i += 3; i + 2 <= to && (tx[i] ^ tx[i + 1]) == 0xFF; i += 2) {
        if (n > 0 && tx[i] == sum && reply_ok(first, n) && parses(tx, i + 2, to))
            return 1;
        if (n == 0)
            first = tx[i];
        sum = (u8)(sum + tx[i]);
        if (++n > RCX_REPLY_MAX)
            return 0;
    }
    return 0;
}

static void check_replies(const u8 *tx, unsigned from, unsigned to)
{
    if (!parses(tx, from, to))
        fuzz_fail("the brick sent something that is not a well-formed reply of the expected length");
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    struct rcx_brick *k = calloc(1, sizeof *k);
    struct fake_hal *h = calloc(1, sizeof *h);
    struct fuzz_snapshot snap;
    unsigned i, sent = 0, checked = 0;
    int slot_changed = 0, log_free = 1;
    u8 touched[RCX_OBJS];

    if (!k || !h)
        abort();
    k->vm.port = h;
    rt_init(k, TEST_ARENA_ADDR);
    fuzz_fill(&k->vm);
    fuzz_snapshot(&k->vm, &snap);
    memset(touched, 0, sizeof touched);
    for (i = 0; i < RCX_OBJS; i++)
        touched[i] = i < RCX_SLOT_OBJS; /* slot 0 is the one commands may change */

    for (i = 0; i < size; i++) {
        u8 c = data[i];
        if ((c & 0xF7) == 0x52 || (c & 0xF7) == 0x62)
            log_free = 0;
        if (i >= 2 && data[i - 2] == 0x55 && data[i - 1] == 0xAA && c >= 0xF0) {
            unsigned ms = (c & 0x0Fu) * 5u;
            while (ms--) {
                rt_tick(k);
                rt_run(k, 4);
            }
        } else {
            rt_ir_byte(k, c, 0);
            rt_run(k, 4);
        }
        /* The tower hears the brick's own transmission: feed it back, then check what was sent. */
        while (sent < h->ir_len) {
            rt_ir_byte(k, h->ir[sent++], 0);
            rt_run(k, 4);
        }
        if (h->ir_len > FAKE_IR_LOG / 2 && sent == h->ir_len && ir_idle(k)) {
            check_replies(h->ir, checked, h->ir_len);
            h->ir_len = 0;
            sent = checked = 0;
        }
        if (k->vm.prog != 0)
            slot_changed = 1;
    }
    for (i = 0; i < 40; i++) { /* let anything pending go out */
        rt_tick(k);
        rt_run(k, 4);
        while (sent < h->ir_len) {
            rt_ir_byte(k, h->ir[sent++], 0);
            rt_run(k, 4);
        }
    }
    check_replies(h->ir, checked, h->ir_len);
    if (!slot_changed)
        fuzz_check_untouched(&k->vm, &snap, touched);
    if (log_free)
        fuzz_check_log(&k->vm, &snap);
    fuzz_check_machine(&k->vm);
    free(h);
    free(k);
    return 0;
}
