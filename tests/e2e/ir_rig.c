/* SPDX-License-Identifier: MPL-2.0 */
/* The IR test bench (ir_rig.h). */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "brick.h"
#include "ir_rig.h"


struct rig *rig_new(void)
{
    struct rig *r = calloc(1, sizeof *r);
    assert_non_null(r);
    r->k = calloc(1, sizeof *r->k);
    r->h = calloc(1, sizeof *r->h);
    assert_non_null(r->k);
    assert_non_null(r->h);
    r->k->vm.port = r->h;          /* rt_init keeps the port */
    rt_init(r->k, TEST_ARENA_ADDR);
    assert_ptr_equal(fake_hal_of(&r->k->vm), r->h);
    return r;
}

void rig_free(struct rig *r)
{
    free(r->h);
    free(r->k);
    free(r);
}

void feed(struct rig *r, const u8 *bytes, unsigned n)
{
    unsigned i;
    for (i = 0; i < n; i++)
        rt_ir_byte(r->k, bytes[i], 0);
}

void ticks(struct rig *r, unsigned ms)
{
    while (ms--)
        rt_tick(r->k);
}

/* Let the main loop run: what it transmits is collected and, unless `deaf`, heard back as the echo. The brick
 * answers a command only IR_REPLY_MS after its last byte, so that much time passes first. */
void pump_echo(struct rig *r, int echo)
{
    unsigned round;
    ticks(r, IR_REPLY_MS);
    for (round = 0; round < 32; round++) {
        unsigned before = r->h->ir_len;
        rt_run(r->k, 0);
        if (r->h->ir_len == before && round > 0)
            break;
        assert_true(r->out_len + (r->h->ir_len - before) <= sizeof r->out);
        memcpy(r->out + r->out_len, r->h->ir + before, r->h->ir_len - before);
        r->out_len += r->h->ir_len - before;
        if (echo)
            feed(r, r->h->ir + before, r->h->ir_len - before);
        r->h->ir_len = 0;
    }
}

/* Standard framing as host-tools.md §1 gives it. */
unsigned frame(const u8 *payload, unsigned n, u8 *out)
{
    unsigned i, len = 0;
    u8 sum = 0;
    out[len++] = 0x55;
    out[len++] = 0xFF;
    out[len++] = 0x00;
    for (i = 0; i < n; i++) {
        out[len++] = payload[i];
        out[len++] = (u8)~payload[i];
        sum = (u8)(sum + payload[i]);
    }
    out[len++] = sum;
    out[len++] = (u8)~sum;
    return len;
}

/* Send one standard packet; returns the number of bytes transmitted in reply (collected in r->out). */
unsigned transact(struct rig *r, const u8 *payload, unsigned n)
{
    u8 pkt[2 * 300];
    r->out_len = 0;
    feed(r, pkt, frame(payload, n, pkt));
    pump(r);
    return r->out_len;
}

/* The reply in r->out must be exactly the framed `payload`. */
void expect_reply(struct rig *r, const u8 *payload, unsigned n)
{
    u8 want[2 * 300];
    unsigned len = frame(payload, n, want);
    assert_int_equal(r->out_len, len);
    assert_memory_equal(r->out, want, len);
}

s16 poll_var(struct rig *r, u8 n)
{
    r->poll_toggle ^= RCX_TOGGLE;
    assert_int_equal(TX(r, (u8)(0x12 | r->poll_toggle), 0x00, n), 11);
    return (s16)(u16)(r->out[5] | r->out[7] << 8);
}

unsigned block(u8 *out, u16 seq, const u8 *data, u16 len, int bad_sum)
{
    u16 i;
    u8 sum = 0;
    out[0] = 0x45;
    out[1] = (u8)seq;
    out[2] = (u8)(seq >> 8);
    out[3] = (u8)len;
    out[4] = (u8)(len >> 8);
    for (i = 0; i < len; i++) {
        out[5 + i] = data[i];
        sum = (u8)(sum + data[i]);
    }
    out[5 + len] = (u8)(sum + (bad_sum ? 1 : 0));
    return 6u + len;
}

u8 status_of(struct rig *r, u8 *pkt, unsigned n, u8 toggle)
{
    pkt[0] ^= toggle;
    assert_int_equal(transact(r, pkt, n), 9);
    assert_int_equal(r->out[3], (u8)~pkt[0]);
    return r->out[5];
}

