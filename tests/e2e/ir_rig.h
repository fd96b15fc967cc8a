/* SPDX-License-Identifier: MPL-2.0 */
/*
 * A brick with its IR receiver and transmitter on a test bench: bytes are fed in as the UART driver would, what the
 * brick transmits is collected and, like on the brick (rcx-hardware.md §3.8), heard back as its own echo.
 * Packets are framed as host-tools.md §1 gives it. Shared by tests/unit/test_ir.c and tests/e2e/test_ir_replies.c.
 */
#ifndef TEST_IR_RIG_H
#define TEST_IR_RIG_H

#include "runtime.h"
#include "fake_hal.h"

struct rig {
    struct rcx_brick *k;
    struct fake_hal *h;
    u8 out[1024];     /* bytes the brick transmitted by the last transaction */
    unsigned out_len;
    u8 poll_toggle;   /* successive polls differ in bit 3, as nqc sends them */
};

struct rig *rig_new(void);
void rig_free(struct rig *r);
void feed(struct rig *r, const u8 *bytes, unsigned n);
void ticks(struct rig *r, unsigned ms);
void pump_echo(struct rig *r, int echo);        /* run the main loop until it has nothing more to send */
unsigned frame(const u8 *payload, unsigned n, u8 *out);
unsigned transact(struct rig *r, const u8 *payload, unsigned n); /* one packet in; bytes sent back (r->out) */
void expect_reply(struct rig *r, const u8 *payload, unsigned n);  /* r->out is exactly the framed payload */
s16 poll_var(struct rig *r, u8 n);
unsigned block(u8 *out, u16 seq, const u8 *data, u16 len, int bad_sum); /* a 45 packet's payload */
u8 status_of(struct rig *r, u8 *pkt, unsigned n, u8 toggle);             /* its download status */

#define pump(r) pump_echo((r), 1)
#define TX(r, ...) transact((r), (const u8[]){ __VA_ARGS__ }, sizeof((const u8[]){ __VA_ARGS__ }))
#define REPLY(r, ...) expect_reply((r), (const u8[]){ __VA_ARGS__ }, sizeof((const u8[]){ __VA_ARGS__ }))

#endif
