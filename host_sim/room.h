/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The simulated IR room: the one place every way into the virtual RCX's infrared plugs in.
 *
 * A port is a transmitter and a receiver in the room: a brick's IR LED and receiver, a serial tower on a
 * pseudo-terminal, the script's `ir` lines, a client of the TCP hub, the link to another hub. A link is something
 * outside the simulation that feeds ports (a pseudo-terminal, a listening socket, a connection): the main loop asks
 * the room to poll the links now and then, and to wait on their descriptors while it paces itself. The room knows
 * neither bricks nor links by type: it only moves bytes between ports and calls what they registered.
 */
#ifndef RCX_ROOM_H
#define RCX_ROOM_H

#include <poll.h>

typedef unsigned long long sim_us; /* simulated time, microseconds */

#define ROOM_TX_QUEUE 4096         /* bytes waiting at one transmitter */
/* A room_send() mode beside HAL_IR_*: the bytes come from a network that paced them itself, or not at all (a joined
 * hub), and go on the air as fast as they came, one a microsecond, instead of at the line rate (net.c says why). */
#define ROOM_AT_ONCE 0x08
#define ROOM_MAX_PORTS 64

/* A transmitter: bytes leave back to back at the line rate. */
struct room_tx {
    unsigned short queue[ROOM_TX_QUEUE]; /* byte | (HAL_IR_* | ROOM_AT_ONCE) mode << 8 */
    unsigned head, count;
    sim_us start, end;             /* the byte on the air (count > 0) */
    int collided;                  /* another transmitter overlapped it */
};

struct room_port {
    struct room_tx tx;
    /* A byte off the air; `error` when it collided or was sent at 4800 baud. NULL: the port only transmits. It may
     * send (room_send), but not join, leave or silence ports. */
    void (*hear)(struct room_port *p, unsigned char byte, int error);
    struct room_port *facing;      /* set: its bytes reach only that port and itself (a tower facing its brick) */
    int hears_self;                /* its own bytes come back to it (an echo) */
};

struct room_link {
    void (*poll)(struct room_link *l);  /* bring in what arrived: bytes onto the air, ports joining or leaving */
    int (*fds)(struct room_link *l, struct pollfd *fds, int max); /* what a pacing loop may wait on; how many */
    void (*close)(struct room_link *l);
    struct room_link *next;
};

struct room {
    sim_us now;
    int nports;
    struct room_port *port[ROOM_MAX_PORTS]; /* in the order they joined: ties on the air go to the earlier */
    struct room_link *links;
};

int room_join(struct room *r, struct room_port *p); /* -1: the room is full */
void room_leave(struct room *r, struct room_port *p);
void room_send(struct room *r, struct room_port *p, const unsigned char *data, unsigned len, unsigned mode);
int room_busy(const struct room_port *p);
void room_silence(struct room_port *p);       /* drops what it had not yet sent */
void room_advance(struct room *r, sim_us until); /* delivers every byte whose last bit is out by `until` */

void room_attach(struct room *r, struct room_link *l);
void room_poll(struct room *r);
int room_fds(struct room *r, struct pollfd *fds, int max);
/* For a link's fds(): waiting on `fd` for input, if there is room (max > 0) and it is open (>= 0); how many: 1 or 0. */
int room_fd(struct pollfd *fds, int max, int fd);
void room_close(struct room *r);              /* closes every link */

#endif
