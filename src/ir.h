/* The IR packet layer (host-tools.md §1, rcx-hardware.md §4): framing, toggle bit, replies. */
#ifndef RCX_IR_H
#define RCX_IR_H

#include "rcx_types.h"

struct rcx_brick;

struct rcx_ir {
    u8 placeholder; /* receiver state, last opcode and reply for repeats: defined by the IR issue */
};

void ir_init(struct rcx_brick *k);
void ir_byte(struct rcx_brick *k, u8 byte, u8 error);
void ir_tick(struct rcx_brick *k);
void ir_poll(struct rcx_brick *k); /* execute a complete packet, send replies and the machine's requests */

#endif
