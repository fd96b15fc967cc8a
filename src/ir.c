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
#include "rcx_string.h"
#include "runtime.h"
#include "hal.h"

RCX_STATIC_ASSERT(packet_length_fits_a_byte, IR_RX_MAX <= 255);

enum {
    IR_RX_IDLE = 0,  /* looking for a header or an opcode */
    IR_RX_OPCODE,    /* a header ended (its 00): the next byte is the opcode, even FF (F7 toggled) */
    IR_RX_VALUE,     /* next byte is a value */
    IR_RX_COMPLEMENT,/* next byte must be the complement of rx_value */
    IR_RX_READY,     /* a good packet waits for ir_poll(); this and the next ignore what arrives */
    IR_RX_DRAIN      /* oversized: ignore everything until IR_QUIET_MS of silence */
};

static const u8 preamble[3] = { 0x55, 0xFF, 0x00 };

void ir_init(struct rcx_brick *k)
{
    memset(&k->ir, 0, sizeof k->ir);
    k->ir.range = 0xFF; /* applied at the first ir_poll() */
}

static u8 sending(struct rcx_brick *k)
{
    return (u8)(k->ir.tx_pos < k->ir.tx_total || hal_ir_busy(&k->vm));
}

u8 ir_idle(struct rcx_brick *k)
{
    return (u8)(!sending(k) && !k->ir.echo);
}

/* A value byte whose complement checked out. */
static void accept(struct rcx_ir *ir, u8 v)
{
    if (ir->rx_len == ir->rx_need) { /* the checksum */
        ir->rx_state = v == ir->rx_sum ? IR_RX_READY : IR_RX_IDLE;
        return;
    }
    ir->rx[ir->rx_len++] = v;
    ir->rx_sum = (u8)(ir->rx_sum + v);
    ir->rx_state = IR_RX_VALUE;
    if (ir->rx_len == 1) {
        ir->rx_need = (u8)(1 + rcx_op_nominal_params(v));
    } else if (ir->rx_len == 5 && (ir->rx[0] & (u8)~RCX_TOGGLE) == RCX_OP_CONTINUE_DL) {
        if (ir->rx[4] || ir->rx[3] > IR_BLOCK_MAX)
            ir->rx_state = IR_RX_DRAIN;
        ir->rx_need = (u8)(6 + ir->rx[3]); /* + data + block checksum */
    }
}

void ir_byte(struct rcx_brick *k, u8 byte, u8 error)
{
    struct rcx_ir *ir = &k->ir;
    u8 st;

    if (ir->echo || sending(k)) { /* our own transmission coming back */
        if (ir->echo)
            ir->echo--;
        return;
    }
    ir->quiet = 0;
    st = ir->rx_state;
    if (st >= IR_RX_READY) /* READY: hosts wait for the answer; DRAIN: the rest of an oversized block */
        return;
    if (error) {
        ir->rx_state = IR_RX_IDLE;
        return;
    }
    if (st == IR_RX_COMPLEMENT) {
        if ((u8)(byte ^ ir->rx_value) == 0xFF) {
            accept(ir, ir->rx_value);
            return;
        }
        st = IR_RX_IDLE; /* not a complement: this byte may begin the next packet */
    }
    if (st == IR_RX_IDLE) {
        if (byte == 0x55 || byte == 0xFF) {
            ir->rx_state = IR_RX_IDLE;
            return;
        }
        if (byte == 0x00) {
            ir->rx_state = IR_RX_OPCODE;
            return;
        }
        st = IR_RX_OPCODE;
    }
    if (st == IR_RX_OPCODE) {
        ir->rx_len = 0;
        ir->rx_sum = 0;
        ir->rx_need = 1;
    }
    ir->rx_value = byte;
    ir->rx_state = IR_RX_COMPLEMENT;
}

void ir_tick(struct rcx_brick *k)
{
    struct rcx_ir *ir = &k->ir;

    if (ir->quiet != 0xFF)
        ir->quiet++;
    if (ir->quiet >= IR_QUIET_MS && ir->rx_state != IR_RX_READY)
        ir->rx_state = IR_RX_IDLE;
    /* An echo byte lost (or garbled into nothing) must not deafen the receiver for good. */
    if (ir->echo && !sending(k)) {
        if (++ir->echo_quiet >= IR_ECHO_MS)
            ir->echo = 0;
    } else {
        ir->echo_quiet = 0;
    }
}

/* Byte `pos` of the framed packet. */
static u8 framed(const struct rcx_ir *ir, u16 pos)
{
    u8 v;
    if (ir->tx_pack & IR_PACK_PREAMBLE) {
        if (pos < 3)
            return preamble[pos];
        pos -= 3;
    }
    if (ir->tx_pack & IR_PACK_COMPLEMENT) {
        v = (pos >> 1) < ir->tx_src_len ? ir->tx_src[pos >> 1] : ir->tx_sum;
        return (u8)(pos & 1 ? ~v : v);
    }
    return pos < ir->tx_src_len ? ir->tx_src[pos] : ir->tx_sum;
}

static void tx_start(struct rcx_ir *ir, const u8 *src, u8 len, u8 pack, u8 mode)
{
    u8 i, sum = 0;
    for (i = 0; i < len; i++)
        sum = (u8)(sum + src[i]);
    ir->tx_src = src;
    ir->tx_src_len = len;
    ir->tx_pack = pack;
    ir->tx_mode = mode;
    ir->tx_sum = sum;
    ir->tx_pos = 0;
    ir->tx_total = (u16)((pack & IR_PACK_PREAMBLE ? 3 : 0) +
                         (pack & IR_PACK_COMPLEMENT ? 2 * len + 2 : len + (pack & IR_PACK_CHECKSUM ? 1 : 0)));
}

/* Hand the next piece of the packet to the driver once it has sent the previous one. */
static void tx_continue(struct rcx_brick *k)
{
    struct rcx_ir *ir = &k->ir;
    u8 n = 0;

    if (ir->tx_pos >= ir->tx_total || hal_ir_busy(&k->vm))
        return;
    while (n < IR_CHUNK && ir->tx_pos < ir->tx_total)
        ir->chunk[n++] = framed(ir, ir->tx_pos++);
    ir->echo = (u16)(ir->echo + n);
    hal_ir_send(&k->vm, ir->chunk, n, ir->tx_mode);
}

static void execute(struct rcx_brick *k)
{
    struct rcx_ir *ir = &k->ir;
    u8 op = ir->rx[0];

    ir->rx_state = IR_RX_IDLE;
    k->vm.idle_reset = 1; /* every command received restarts the power-down timer (spec p. 35) */
    if (!ir->have_last || op != ir->last_op) {
        ir->reply_len = vm_direct(&k->vm, ir->rx, ir->rx_len, ir->reply);
        ir->last_op = op;
        ir->have_last = 1;
        /* PBAliveOrNot "re-initialises the toggle bit" (spec p. 12): any packet after it is new anyway, since its
         * opcode differs, and a repeated ping is answered the same whether executed or not. */
    }
    if (ir->reply_len)
        tx_start(ir, ir->reply, ir->reply_len, IR_PACK_STANDARD, 0);
}

void ir_poll(struct rcx_brick *k)
{
    struct rcx_ir *ir = &k->ir;
    struct rcx_remote *r = &k->vm.remote;

    if (ir->range != k->vm.tx_range) {
        ir->range = k->vm.tx_range;
        hal_ir_range(&k->vm, ir->range);
    }
    if (ir->tx_pos < ir->tx_total) {
        tx_continue(k);
        return;
    }
    if (ir->rx_state == IR_RX_READY) {
        execute(k);
    } else if (r->tx_len && ir->rx_state == IR_RX_IDLE && ir->quiet >= IR_SENSE_MS && ir_idle(k)) {
        /* Only into a silent room: a brick or host that is talking would be drowned, and so would we. The request
         * is framed into the chunk at once (at most 37 bytes), so the machine may replace it from now on. */
        if (r->tx_msg) {
            if (r->tx[0] == ir->last_msg)
                r->tx[0] ^= RCX_TOGGLE; /* a receiver must not take our new message for a repeat */
            ir->last_msg = r->tx[0];
        }
        tx_start(ir, r->tx, r->tx_len, r->tx_pack, r->tx_mode);
        r->tx_len = 0;
    } else {
        return;
    }
    tx_continue(k);
}
