/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The IR packet layer: 55 FF 00, byte/complement pairs, checksum/complement (host-tools.md §1).
 *
 * The receiver is tolerant the way firm0328 is (reference-firmware.md): 55 and FF before the opcode are skipped and
 * a 00 ends the header, so "55 FF 00", "FF 00", "00" and none are all accepted, while FF right after a header is
 * the opcode F7 with its toggle bit. Garbage is skipped because a byte that is not followed by its complement
 * starts the search again. A packet with a bad complement or checksum is dropped without a reply. The packet's
 * length comes from the opcode's low three bits (spec p. 5), for 0x45 from its own length field; a block longer
 * than the buffer is drained until the line falls silent (the host retries later).
 */
#include "runtime.h"
#include "hal.h"

RCX_STATIC_ASSERT(packet_length_fits_a_byte, IR_RX_MAX <= 255);
RCX_STATIC_ASSERT(chunk_fits_rx, IR_CHUNK <= IR_RX_MAX);
RCX_STATIC_ASSERT(block_reply_fits, IR_RX_MAX + 2 <= IR_BUF_SIZE); /* a 0x45 block's reply after the block */

static const u8 preamble[3] = { 0x55, 0xFF, 0x00 };

u8 ir_busy(struct rcx_brick *k)
{
    if (k->ir.echo || k->ir.tx_left)
        return 1;
    return hal_ir_busy(&k->vm);
}

/* A value byte whose complement checked out. Out of line, so that ir_byte() stays within the reach of the H8's short
 * branches. */
static __attribute__((noinline)) void accept(struct rcx_ir *ir, u8 v)
{
    u8 n = ir->rx_len;

    if (!n) {                      /* the opcode: how many bytes follow it */
        u8 p = (u8)(v & 7);        /* rcx_op_nominal_params(), in byte arithmetic */
        if (p >= 6)
            p = (u8)(p - 6);
        ir->rx_need = (u8)(p + 1);
    } else if (n == ir->rx_need) { /* the checksum */
        ir->rx_state = v == ir->rx_sum ? IR_RX_READY : IR_RX_IDLE;
        return;
    }
    if (n >= ir->reply_at) /* over the last reply: it is gone */
        ir->last_op = RCX_OP_MESSAGE;
    ir->rx[n++] = v;
    ir->rx_len = n;
    ir->rx_sum = (u8)(ir->rx_sum + v);
    ir->rx_state = IR_RX_VALUE;
    if (n == 5 && (u8)(ir->rx[0] | RCX_TOGGLE) == (RCX_OP_CONTINUE_DL | RCX_TOGGLE)) {
        if (ir->rx[4] || ir->rx[3] > IR_BLOCK_MAX)
            ir->rx_state = IR_RX_DRAIN;
        ir->rx_need = (u8)(6 + ir->rx[3]); /* + data + block checksum */
    }
}

/* rt_ir_byte() (src/runtime.h) is the receiver itself: one call less for every byte. */
void rt_ir_byte(struct rcx_brick *k, u8 byte, u8 error)
{
    struct rcx_ir *ir = &k->ir;
    u8 st;

    if (ir_busy(k)) { /* our own transmission coming back */
        if (ir->echo)
            ir->echo--;
        return;
    }
    st = ir->rx_state;
    if (st == IR_RX_READY) /* hosts wait for the answer: noise now must not hold the reply back */
        return;
    ir->quiet = 0;
    if (st == IR_RX_DRAIN) /* the rest of an oversized block */
        return;
    if (error) {
        ir->rx_state = IR_RX_IDLE;
        return;
    }
    if (st == IR_RX_COMPLEMENT && (u8)(byte ^ ir->rx_value) == 0xFF) {
        accept(ir, ir->rx_value);
        return;
    }
    /* Looking for a packet, or a byte that is not the complement (it may begin the next packet): a header byte, or
     * the opcode. */
    if (st < IR_RX_OPCODE) {       /* IDLE, COMPLEMENT */
        if (byte == 0x55 || byte == 0xFF) {
            ir->rx_state = IR_RX_IDLE;
            return;
        }
        if (byte == 0x00) {
            ir->rx_state = IR_RX_OPCODE;
            return;
        }
    }
    if (st != IR_RX_VALUE) {       /* a new packet: its opcode */
        ir->rx_len = 0;
        ir->rx_sum = 0;
    }
    ir->rx_value = byte;
    ir->rx_state = IR_RX_COMPLEMENT;
}

void ir_tick(struct rcx_brick *k)
{
    struct rcx_ir *ir = &k->ir;
    u8 quiet = ir->quiet, eq = 0; /* eq: echo_quiet's new value */

    if (quiet != 0xFF)
        ir->quiet = ++quiet;
    if (quiet >= IR_QUIET_MS && ir->rx_state != IR_RX_READY)
        ir->rx_state = IR_RX_IDLE;
    /* An echo byte lost (or garbled into nothing) must not deafen the receiver for good. */
    if (ir->echo && !ir->tx_left && !hal_ir_busy(&k->vm)) { /* nothing being sent */
        eq = (u8)(ir->echo_quiet + 1);
        if (eq >= IR_ECHO_MS)
            ir->echo = 0;
    }
    ir->echo_quiet = eq;
}

/* Byte `pos` of the framed packet, counted as if it had the preamble (tx_start). */
static u8 framed(const struct rcx_brick *k, u16 pos)
{
    u8 flip = 0, v;

    if (pos < 3)
        return preamble[pos];
    pos -= 3;
    if (k->ir.tx_pack & IR_PACK_COMPLEMENT) {
        if (pos & 1)
            flip = 0xFF;           /* the complement, after its byte */
        pos >>= 1;
    }
    v = pos < k->ir.tx_src_len ? k->ir.tx_src[pos] : k->ir.tx_sum;
    return (u8)(v ^ flip);
}

/* Start sending the `len` (not 0) bytes at tx_src, framed as tx_pack says. Out of line, so that ir_poll() keeps its
 * registers. */
static __attribute__((noinline)) void tx_start(struct rcx_brick *k, u8 len)
{
    const u8 *p;
    u8 sum, pack = k->ir.tx_pack;
    u16 left = len, pos = 3;

    k->ir.tx_src_len = len;
    if (pack & IR_PACK_COMPLEMENT)
        left = (u16)(2 * left + 2);
    else if (pack & IR_PACK_CHECKSUM)
        left++;
    /* Positions are counted from the preamble's first byte, which a packet without it starts after. */
    if (pack & IR_PACK_PREAMBLE) {
        pos = 0;
        left += 3;
    }
    k->ir.tx_pos = pos;
    k->ir.tx_left = left;
    p = k->ir.tx_src;
    sum = 0;
    do                             /* len is not 0 */
        sum = (u8)(sum + *p++);
    while (--len);
    k->ir.tx_sum = sum;
}

static void execute(struct rcx_brick *k)
{
    u8 op = k->ir.rx[0];

    k->ir.rx_state = IR_RX_IDLE;
    k->vm.idle_reset = 1; /* every command received restarts the power-down timer (spec p. 35) */
    /* Messages are never repeats (reference-firmware.md): every brick and host sends each one as F7. */
    if (op != k->ir.last_op || (u8)(op | RCX_TOGGLE) == (RCX_OP_MESSAGE | RCX_TOGGLE)) {
        u8 at = k->ir.rx_len > IR_CHUNK ? k->ir.rx_len : IR_CHUNK;
        k->ir.reply_at = at;
        k->ir.reply_len = vm_direct(&k->vm, k->ir.rx, k->ir.rx_len, k->ir.rx + at);
        k->ir.last_op = op;
        /* PBAliveOrNot "re-initialises the toggle bit" (spec p. 12): any packet after it is new anyway, since its
         * opcode differs, and a repeated ping is answered the same whether executed or not. */
    }
}

void ir_poll(struct rcx_brick *k)
{
    u8 n, len, pack, mode;
    const u8 *src;
    u16 pos;

    if (k->ir.range != k->vm.tx_range) {
        k->ir.range = k->vm.tx_range;
        hal_ir_range(&k->vm, k->ir.range);
    }
    if (!k->ir.tx_left) {
        /* Nothing being sent: the reply to a command, or what the machine asks to transmit. */
        if (k->ir.rx_state == IR_RX_READY && k->ir.quiet >= IR_REPLY_MS) {
            execute(k);
            src = k->ir.rx + k->ir.reply_at;
            len = k->ir.reply_len;
            pack = IR_PACK_STANDARD;
            mode = 0;
        } else if ((k->vm.remote.tx_len || (RCX_SWAN && k->vm.remote.follow)) && k->ir.rx_state == IR_RX_IDLE &&
                   k->ir.quiet >= IR_SENSE_MS && !ir_busy(k)) {
#if RCX_SWAN
            if (!k->vm.remote.tx_len)
                remote_sent(&k->vm); /* the message after its parameter, now that the room is quiet (vm/remote.h) */
#endif
            /* Only into a silent room: a brick or host that is talking would be drowned, and so would we. The
             * request is framed into the chunk at once (at most 37 bytes), so the machine may replace it from now
             * on. */
            src = k->vm.remote.tx;
            len = k->vm.remote.tx_len;
            pack = k->vm.remote.tx_pack;
            mode = k->vm.remote.tx_mode;
            k->vm.remote.tx_len = 0;
        } else {
            goto send;
        }
        k->ir.tx_src = src;
        k->ir.tx_pack = pack;
        k->ir.tx_mode = mode;
        display_ir_activity(&k->vm); /* lit by every command received, as by the brick's own transmissions */
        if (len)
            tx_start(k, len);
    }
send:
    /* Hand the next piece of the packet to the driver once it has sent the previous one. */
    if (!k->ir.tx_left || hal_ir_busy(&k->vm))
        return;
    n = 0;
    pos = k->ir.tx_pos;
    do
        k->ir.rx[n++] = framed(k, pos++);
    while (--k->ir.tx_left && n < IR_CHUNK);
    k->ir.tx_pos = pos;
    k->ir.echo = (u16)(k->ir.echo + n);
    hal_ir_send(&k->vm, k->ir.rx, n, k->ir.tx_mode);
}
