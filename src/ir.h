/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The IR packet layer (host-tools.md §1, rcx-hardware.md §4, reference-firmware.md "IR command handling"):
 * framing, the repeat rule of the toggle bit, replies, and what the machine asks to transmit.
 *
 * Half duplex: the receiver hears the brick's own transmission, so from the first byte handed to the driver
 * until that many bytes have come back (or a little while after the line fell silent) received bytes are ignored.
 * All buffers live in struct rcx_ir, i.e. in .bss on the brick, never on its 448-byte stack.
 */
#ifndef RCX_IR_H
#define RCX_IR_H

#include "rcx_types.h"
#include "rcx_limits.h"

struct rcx_brick;

#define IR_BLOCK_MAX 200            /* longest 0x45 data block accepted: the 200 of nqc -firmware and firmdl3 */
#define IR_RX_MAX (6 + IR_BLOCK_MAX) /* opcode, block number, length, data, block checksum */
/* The receiver, the transmitter's chunk and the last reply share one buffer (program memory is what a larger one
 * would cost): a reply goes after the command it answers and after the chunk, which the 189 bytes of the longest
 * reply (MemMap) just fill. Only a 0x45 block is longer than the chunk, and its reply has two bytes. */
#define IR_BUF_SIZE (IR_CHUNK + RCX_REPLY_MAX)
#define IR_CHUNK 40                 /* bytes handed to hal_ir_send() at once: a whole 16-byte UART packet fits */
#define IR_QUIET_MS 30              /* silence inside a packet that resynchronises the receiver */
#define IR_ECHO_MS 10               /* after transmitting, about two character times at 2400 baud for the echo */
#define IR_SENSE_MS 10              /* silence before the machine's own transmission may start */
/* A reply starts no sooner than 5 ms after the command's last byte (issue 9: a tower is blind while it sends and
 * needs a moment after its last byte; firm0328 waits about 17 ms). `quiet` counts ticks, and the first may come
 * right after the byte, so 6 ticks are at least 5 ms. */
#define IR_REPLY_MS 6

struct rcx_ir {
    /* Receiver. */
    u8 rx_state;        /* IR_RX_* in ir.c */
    u8 rx_value;        /* value byte waiting for its complement */
    u8 rx_sum;
    u8 quiet;           /* milliseconds since another device's last byte (up to 255; counted while below
                           IR_QUIET_MS at least, see ir_tick_due) */
    u8 rx_len;          /* payload bytes accepted */
    u8 rx_need;         /* payload bytes of this packet, once the opcode (and a 0x45 length) told */
    u8 rx[IR_BUF_SIZE]; /* the packet from rx[0]; the transmitter's chunk from rx[0] too (nothing is received while
                           the brick transmits); the last reply from rx[reply_at] */

    /* Repeat rule: a packet whose opcode byte equals the last one is answered again, not executed; IR messages
     * (F7, FF) never are. Becomes F7 once a packet reaches into the reply, which then can no longer be sent again:
     * so the first packet is always new (reply_at starts at 0, and its first byte reaches it). */
    u8 last_op;
    u8 reply_len;       /* 0: the last command has no reply */
    u8 reply_at;        /* where in rx the last reply is: after its command and after the chunk */

    /* Transmitter: a packet is framed on the fly from tx_src, IR_CHUNK bytes at a time, into rx. */
    const u8 *tx_src;
    u8 tx_src_len;
    u8 tx_pack;         /* IR_PACK_* below */
    u8 tx_mode;         /* HAL_IR_* */
    u8 tx_sum;
    /* The next byte's position in the framed packet, counted from the preamble's first byte even when it has none
     * (tx_pos then starts at 3), and the bytes not handed to the driver yet (nonzero: a packet goes out). */
    u16 tx_pos;
    u16 tx_left;
    u16 echo;           /* own bytes not heard back yet */
    u8 echo_quiet;      /* milliseconds since the transmitter went idle with echo outstanding */
    u8 range;           /* range last given to hal_ir_range() */
};

/* rcx_ir.rx_state (src/ir.c). */
enum {
    IR_RX_IDLE = 0,  /* looking for a header or an opcode */
    IR_RX_COMPLEMENT,/* next byte must be the complement of rx_value (if not, it may begin a packet: below 2, as
                        IDLE) */
    IR_RX_OPCODE,    /* a header ended (its 00): the next byte is the opcode, even FF (F7 toggled) */
    IR_RX_VALUE,     /* next byte is a value */
    IR_RX_READY,     /* a good packet waits for ir_poll(); this and the next ignore what arrives */
    IR_RX_DRAIN      /* oversized: ignore everything until IR_QUIET_MS of silence */
};

/* Framing bits, as PackConf (source 33 byte 16, spec p. 9) names them. */
#define IR_PACK_PREAMBLE 0x01   /* 55 FF 00 */
#define IR_PACK_COMPLEMENT 0x02 /* every byte followed by its complement, checksum included */
#define IR_PACK_CHECKSUM 0x04   /* a checksum byte (always present with IR_PACK_COMPLEMENT) */
#define IR_PACK_STANDARD 0x07

/* Once rt_init() has cleared struct rcx_ir: the range is applied at the first ir_poll() (and the first packet is new
 * without more: last_op). A macro: rt_init() is its one user. */
#define ir_init(k) ((k)->ir.range = 0xFF)
/* Received bytes arrive through rt_ir_byte() (src/runtime.h), which src/ir.c implements. */
void ir_tick(struct rcx_brick *k);
void ir_poll(struct rcx_brick *k); /* execute a complete packet, send replies and the machine's requests */
/* Whether the call can change anything: nearly every millisecond it cannot, and these are cheaper than the calls.
 * At rest (nobody heard for IR_QUIET_MS, no echo outstanding or being timed) the receiver is back to looking for a
 * packet, and counting `quiet` further changes nothing: it is only compared with IR_QUIET_MS and smaller times.
 * With nothing being sent, no packet to answer, no request (nor a message to follow its parameter) and the range as
 * it was, there is nothing to poll for. */
#define ir_tick_due(k) ((k)->ir.quiet < IR_QUIET_MS || (k)->ir.echo || (k)->ir.echo_quiet)
#define ir_poll_due(k) ((k)->ir.tx_left || (k)->ir.rx_state == IR_RX_READY || (k)->vm.remote.tx_len || \
                        (RCX_SWAN && (k)->vm.remote.follow) || (k)->ir.range != (k)->vm.tx_range)
u8 ir_busy(struct rcx_brick *k);   /* nonzero while something is being sent or an echo is outstanding */
#define ir_idle(k) (!ir_busy(k))

#endif
