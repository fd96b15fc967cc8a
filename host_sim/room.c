/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The simulated IR room.
 *
 * Every transmitter sends its bytes back to back at its line rate (2400 baud 8O1 = 11 bits, or 4800 baud 8N1, or
 * one a microsecond for a joined hub's bytes, ROOM_AT_ONCE); a byte reaches its receivers when its last bit has
 * gone out. Who hears whom:
 *   a port facing another (a tower) -> the port it faces and itself (the echo nqc waits for, host-tools.md §1);
 *   any other port (a brick, the script, a network client) -> every port that hears, itself only if it hears its
 *                                      own bytes (a brick does: rcx-hardware.md §3.8).
 * So towers face their own brick only, and a host talking to brick 0 is not answered by brick 1 as well. Bytes that
 * overlap in time on the air collide: receivers get them with an error (and towers a garbled byte). Receivers
 * listen at 2400 baud; a 4800-baud byte reaches them garbled too.
 */
#include <string.h>
#include "room.h"
#include "hal.h"

static sim_us byte_time(unsigned mode)
{
    if (mode & ROOM_AT_ONCE)
        return 1;
    return mode & HAL_IR_4800 ? 2084 : 4583; /* 10 bits at 4800, 11 bits at 2400 */
}

int room_join(struct room *r, struct room_port *p)
{
    if (r->nports == ROOM_MAX_PORTS)
        return -1;
    r->port[r->nports++] = p;
    return 0;
}

void room_leave(struct room *r, struct room_port *p)
{
    int i;
    for (i = 0; i < r->nports; i++)
        if (r->port[i] == p) {
            memmove(&r->port[i], &r->port[i + 1], (size_t)(r->nports - i - 1) * sizeof r->port[0]);
            r->nports--;
            return;
        }
}

int room_busy(const struct room_port *p)
{
    return p->tx.count != 0;
}

void room_silence(struct room_port *p)
{
    p->tx.count = 0;
}

void room_send(struct room *r, struct room_port *p, const unsigned char *data, unsigned len, unsigned mode)
{
    struct room_tx *tx = &p->tx;
    unsigned i;
    for (i = 0; i < len && tx->count < ROOM_TX_QUEUE; i++) {
        tx->queue[(tx->head + tx->count) % ROOM_TX_QUEUE] = (unsigned short)(data[i] | (mode & 0xFu) << 8);
        if (tx->count++ == 0) {
            tx->start = r->now;
            tx->end = r->now + byte_time(mode);
            tx->collided = 0;
        }
    }
}

static int hears(const struct room_port *to, const struct room_port *from)
{
    if (!to->hear)
        return 0;
    if (to == from)
        return to->hears_self;
    return !from->facing || from->facing == to;
}

static void deliver(struct room *r, struct room_port *from)
{
    struct room_tx *tx = &from->tx;
    unsigned entry = tx->queue[tx->head];
    unsigned char byte = (unsigned char)entry;
    int error, i;

    for (i = 0; i < r->nports; i++) {
        struct room_tx *o = &r->port[i]->tx;
        if (o != tx && o->count && o->start < tx->end && o->end > tx->start)
            tx->collided = o->collided = 1;
    }
    error = tx->collided || (entry >> 8 & HAL_IR_4800);
    for (i = 0; i < r->nports; i++)
        if (hears(r->port[i], from))
            r->port[i]->hear(r->port[i], byte, error);
    /* Only now is the byte off the air: a sender that asks hal_ir_busy() while hearing its echo is still busy. */
    tx->head = (tx->head + 1) % ROOM_TX_QUEUE;
    if (--tx->count) {
        tx->start = tx->end;
        tx->end = tx->start + byte_time(tx->queue[tx->head] >> 8);
        tx->collided = 0;
    }
}

void room_advance(struct room *r, sim_us until)
{
    for (;;) {
        int i, best = -1;
        for (i = 0; i < r->nports; i++) {
            const struct room_tx *tx = &r->port[i]->tx;
            if (tx->count && tx->end <= until && (best < 0 || tx->end < r->port[best]->tx.end))
                best = i;
        }
        if (best < 0)
            return;
        deliver(r, r->port[best]);
    }
}

void room_attach(struct room *r, struct room_link *l)
{
    struct room_link **end = &r->links;
    while (*end)
        end = &(*end)->next;
    l->next = NULL;
    *end = l;
}

void room_poll(struct room *r)
{
    struct room_link *l;
    for (l = r->links; l; l = l->next)
        l->poll(l);
}

int room_fds(struct room *r, struct pollfd *fds, int max)
{
    struct room_link *l;
    int n = 0;
    for (l = r->links; l && n < max; l = l->next)
        n += l->fds(l, fds + n, max - n);
    return n;
}

int room_fd(struct pollfd *fds, int max, int fd)
{
    if (max < 1 || fd < 0)
        return 0;
    fds->fd = fd;
    fds->events = POLLIN;
    return 1;
}

void room_close(struct room *r)
{
    while (r->links) {
        struct room_link *l = r->links;
        r->links = l->next;
        l->close(l);
    }
}
