/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The RCX ROM's download mode, as the host tools see it (rcx-hardware.md §2.1-2.4, §4.3; host-tools.md §2).
 *
 * It answers 10 (alive), 15 (versions: ROM 3.1, no firmware), 65 (acknowledged), 75 (begin download: entry and the
 * 16-bit sum of 8000-CBFF; memory cleared, blocks expected from 1), 45 (blocks appended in order; a block with the
 * number of the previous one is written again at the same place; the last may be numbered 0) and A5 "LEGO®"
 * (unlock: the sum of 8000-CBFF must match and the knock string must lie inside it). Then the firmware starts:
 * on the virtual RCX that is always the host-compiled OpenRCX runtime, whatever bytes came down.
 * Everything else is ignored, as the ROM ignores it.
 */
#include <string.h>
#include "sim.h"

enum { ROM_IDLE, ROM_VALUE, ROM_COMPLEMENT, ROM_READY, ROM_DRAIN };
enum { ST_OK = 0, ST_BLOCK = 3, ST_FIRMWARE = 4, ST_INACTIVE = 6 };

#define CHECKED_END 0x4C00u         /* 8000-CBFF: summed and searched for the knock string */
#define ROM_VARS 0x6E5Eu            /* EE5E: the ROM's own variables; an image must stop below */

static const char knock[] = "Do you byte, when I knock?";
static const char unlocked[] = "Just a bit off the block!";
static const unsigned char lego[5] = { 'L', 'E', 'G', 'O', 0xAE };
static const unsigned char key[5] = { 1, 3, 5, 7, 11 };

void rom_reset(struct sim_brick *b)
{
    struct sim_rom *r = &b->rom;
    memset(r, 0, sizeof *r);
}

static void send_reply(struct sim_brick *b, const unsigned char *payload, unsigned n)
{
    unsigned char out[3 + 2 * 32 + 2];
    unsigned i, len = 0, sum = 0;
    out[len++] = 0x55;
    out[len++] = 0xFF;
    out[len++] = 0x00;
    for (i = 0; i < n; i++) {
        out[len++] = payload[i];
        out[len++] = (unsigned char)~payload[i];
        sum += payload[i];
    }
    out[len++] = (unsigned char)sum;
    out[len++] = (unsigned char)~sum;
    room_send(&b->sim->room, &b->port, out, len, 0);
    b->rom.echo = len;
    {
        char hex[2 * sizeof out + 1];
        for (i = 0; i < len; i++)
            sprintf(hex + 2 * i, "%02x", out[i]);
        trace_line(b, "\"ir\":\"%s\"", hex);
    }
}

static unsigned image_sum(const struct sim_rom *r)
{
    unsigned i, sum = 0;
    for (i = 0; i < CHECKED_END; i++)
        sum += r->mem[i];
    return sum & 0xFFFFu;
}

static int has_knock(const struct sim_rom *r)
{
    unsigned i, n = sizeof knock - 1;
    for (i = 0; i + n <= CHECKED_END; i++)
        if (memcmp(r->mem + i, knock, n) == 0)
            return 1;
    return 0;
}

static unsigned char block(struct sim_brick *b)
{
    struct sim_rom *r = &b->rom;
    unsigned seq = r->rx[1] | r->rx[2] << 8, len = r->rx[3] | r->rx[4] << 8, at, i;
    unsigned char sum = 0;

    if (!r->active)
        return ST_INACTIVE;
    for (i = 0; i < len; i++)
        sum = (unsigned char)(sum + r->rx[5 + i]);
    if (sum != r->rx[5 + len])
        return ST_BLOCK;
    if (seq != 0 && seq == r->last_block)
        at = r->last_ptr;           /* sent again: written again at the same place */
    else if (seq == 0 || seq == r->expect)
        at = r->ptr;
    else
        return ST_BLOCK;            /* out of order */
    if (at + len > ROM_VARS) {
        /* On a brick this would overwrite the ROM's variables at EE5E and crash the download; refuse it. */
        trace_line(b, "\"rom\":\"block past 0xEE5D refused\"");
        return ST_BLOCK;
    }
    memcpy(r->mem + at, r->rx + 5, len);
    r->last_ptr = at;
    r->ptr = at + len;
    if (r->ptr > r->image_end)
        r->image_end = r->ptr;
    r->last_block = seq;
    r->expect = seq + 1;
    if (seq == 0) {
        r->active = 0;
        trace_line(b, "\"rom\":\"download complete\",\"bytes\":%u", r->image_end);
        if (image_sum(r) != r->checksum)
            return ST_FIRMWARE;
    }
    return ST_OK;
}

static void execute(struct sim_brick *b)
{
    struct sim_rom *r = &b->rom;
    unsigned char op = r->rx[0], *reply = r->reply;
    unsigned n = 1;

    r->state = ROM_IDLE;
    if (r->have_last && op == r->last_op) {     /* a retry: the same answer again */
        if (r->reply_len)
            send_reply(b, r->reply, r->reply_len);
        return;
    }
    r->have_last = 1;
    r->last_op = op;
    reply[0] = (unsigned char)~op;
    switch (op & 0xF7) {
    case 0x10:
        break;
    case 0x15:
        if (memcmp(r->rx + 1, key, 5) == 0) {
            static const unsigned char versions[8] = { 0, 3, 0, 1, 0, 0, 0, 0 };
            memcpy(reply + 1, versions, 8);
            n = 9;
        }
        break;
    case 0x65:
        break;
    case 0x75:
        memset(r->mem, 0, sizeof r->mem);
        r->entry = r->rx[1] | r->rx[2] << 8;
        r->checksum = r->rx[3] | r->rx[4] << 8;
        r->active = r->loaded = 1;
        r->ptr = r->last_ptr = r->image_end = 0;
        r->expect = 1;
        r->last_block = 0xFFFFFFFFu;
        reply[1] = ST_OK;
        n = 2;
        break;
    case 0x45:
        reply[1] = block(b);
        n = 2;
        break;
    case 0xA5:
        if (memcmp(r->rx + 1, lego, 5) != 0) {
            n = 0;
        } else if (!r->loaded || image_sum(r) != r->checksum || !has_knock(r)) {
            trace_line(b, "\"rom\":\"unlock refused\",\"checksum\":%s,\"knock\":%s",
                       r->loaded && image_sum(r) == r->checksum ? "true" : "false", has_knock(r) ? "true" : "false");
            n = 0;                  /* the ROM buzzes and stays */
        } else {
            memcpy(reply + 1, unlocked, sizeof unlocked - 1);
            n = 1 + sizeof unlocked - 1;
            r->start_pending = 1;
        }
        break;
    default:
        n = 0;                      /* not the ROM's business */
    }
    r->reply_len = (unsigned char)n;
    if (n)
        send_reply(b, reply, n);
}

static void accept(struct sim_rom *r, unsigned char v)
{
    if (r->rx_len == r->rx_need) {
        r->state = v == r->rx_sum ? ROM_READY : ROM_IDLE;
        return;
    }
    r->rx[r->rx_len++] = v;
    r->rx_sum = (unsigned char)(r->rx_sum + v);
    r->state = ROM_VALUE;
    if (r->rx_len == 1) {
        r->rx_need = 1 + ((v & 7u) >= 6 ? (v & 7u) - 6 : (v & 7u));
    } else if (r->rx_len == 5 && (r->rx[0] & 0xF7) == 0x45) {
        r->rx_need = 6 + (r->rx[3] | r->rx[4] << 8);
        if (r->rx_need > ROM_RX_MAX)
            r->state = ROM_DRAIN;
    }
}

void rom_byte(struct sim_brick *b, unsigned char byte, int error)
{
    struct sim_rom *r = &b->rom;

    if (r->echo || room_busy(&b->port)) { /* the ROM discards what it hears while it sends */
        if (r->echo)
            r->echo--;
        return;
    }
    r->quiet = 0;
    if (r->state >= ROM_READY)
        return;
    if (error) {
        r->state = ROM_IDLE;
        return;
    }
    if (r->state == ROM_COMPLEMENT) {
        if ((unsigned char)(byte ^ r->rx_value) == 0xFF) {
            accept(r, r->rx_value);
            return;
        }
        r->state = ROM_IDLE;
    }
    if (r->state == ROM_IDLE) {
        if (byte == 0x55 || byte == 0xFF || byte == 0x00)
            return;
        r->rx_len = r->rx_sum = 0;
        r->rx_need = 1;
    }
    r->rx_value = byte;
    r->state = ROM_COMPLEMENT;
}

/* Once a millisecond: the 30 ms resynchronisation, a complete packet, the hand-over to the firmware. */
int rom_tick(struct sim_brick *b)
{
    struct sim_rom *r = &b->rom;

    if (r->state != ROM_IDLE && r->state != ROM_READY && ++r->quiet >= 30)
        r->state = ROM_IDLE;
    if (!room_busy(&b->port))
        r->echo = 0;
    if (r->state == ROM_READY && !room_busy(&b->port))
        execute(b);
    if (r->start_pending && !room_busy(&b->port)) {
        if (r->image_end < 1024)
            fprintf(stderr, "rcxsim: brick %d: a %u-byte image is no firmware (firmdl3's fast-download helper? use "
                            "firmdl3 --slow); the virtual RCX runs OpenRCX anyway\n", b->index, r->image_end);
        trace_line(b, "\"rom\":\"firmware started\",\"bytes\":%u,\"entry\":\"%04x\"", r->image_end, r->entry);
        return 1;
    }
    return 0;
}
