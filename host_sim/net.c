/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The TCP IR link as the hub (--tcp) and as a brick's tower (--tcp-tower); joining another hub is net_join.c. The
 * stream carries the bytes of the air as they are, with no framing, as brickEmu's ir-server relays them: what one
 * client writes, every client reads, the writer included (its own echo, as a serial tower hears itself; NQC 4's TCP
 * link finds its reply after it by the reply's header).
 *
 * As the hub, each client is a port of the room that hears what bricks and clients send, itself included, and
 * whose bytes go on the air at 2400 baud in simulated time, to every brick, tower and client. A brick's tower is
 * the same listener whose clients face that brick, as a --tty tower does: their bytes reach that brick only (and
 * come back to the sender), they hear everything but other towers' bytes. Unlike ir-server, which
 * interleaves whatever arrives, bytes that overlap on the air collide, as they would between bricks: a client
 * gets a collided byte garbled. A client that sends more than the air can carry (NET_BACKLOG bytes waiting) is
 * disconnected and its waiting bytes dropped, so a flood or garbage stops there; a client that goes away keeps
 * the bytes it sent, which go on the air (nqc -msg writes and closes at once).
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>
#include "net.h"

#define NET_MAX_CLIENTS 32
#define NET_BACKLOG 2200           /* bytes waiting for the air: a whole 1 KB ROM download block, twice the lot */

struct client {
    struct room_port port;         /* first: the port is the client */
    int fd;                        /* -1: gone; the port stays until its bytes are on the air */
    int dead;                      /* a write failed: close at the next poll */
};

struct hub {
    struct room_link link;         /* first */
    struct room *room;
    struct room_port *facing;      /* a brick's tower: the brick its clients face; NULL for the hub */
    const char *option;            /* for messages: --tcp or --tcp-tower */
    int fd;
    struct client *client[NET_MAX_CLIENTS];
};

void net_nonblocking(int fd)
{
    fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
}

/* "[ADDR:]PORT", "HOST[:PORT]" or "[IPV6]:PORT" into host and port; "" is the default of both. */
int net_split(const char *spec, const char *host_default, char *host, size_t hostlen, char *port, size_t portlen)
{
    const char *colon = strrchr(spec, ':'), *h = spec;
    size_t hl;

    if (spec[0] && strspn(spec, "0123456789") == strlen(spec)) {
        colon = spec - 1;           /* a port alone */
        h = host_default;
        hl = strlen(host_default);
    } else if (spec[0] == '[') {
        const char *close = strchr(spec, ']');
        if (!close || (close[1] && close[1] != ':'))
            return -1;
        h = spec + 1;
        hl = (size_t)(close - h);
        colon = close[1] ? close + 1 : NULL;
    } else if (!colon || strchr(spec, ':') != colon) {
        colon = NULL;               /* no port, or an IPv6 address without brackets: all host */
        hl = strlen(spec);
        if (!hl) {
            h = host_default;
            hl = strlen(host_default);
        }
    } else {
        hl = (size_t)(colon - spec);
    }
    if (hl == 0 || hl >= hostlen)
        return -1;
    memcpy(host, h, hl);
    host[hl] = 0;
    snprintf(port, portlen, "%s", colon ? colon + 1 : NET_DEFAULT_PORT);
    if (!port[0] || strspn(port, "0123456789") != strlen(port) || strlen(port) > 5 || atol(port) > 65535)
        return -1;
    return 0;
}

/* ---- the hub ---- */

static void client_hear(struct room_port *p, unsigned char byte, int error)
{
    struct client *c = (struct client *)p;
    unsigned char b = error ? (unsigned char)(byte ^ 0x5A) : byte;
    if (c->fd < 0 || c->dead)
        return;
    if (send(c->fd, &b, 1, MSG_NOSIGNAL) < 0 && errno != EAGAIN && errno != EWOULDBLOCK)
        c->dead = 1;                /* gone; a client that does not read loses bytes, as an overrun would */
}

static void client_end(struct hub *h, int i, int drop)
{
    struct client *c = h->client[i];
    if (c->fd >= 0)
        close(c->fd);
    c->fd = -1;
    if (drop)
        room_silence(&c->port);
}

static void hub_accept(struct hub *h)
{
    for (;;) {
        int fd = accept(h->fd, NULL, NULL), i, one = 1;
        struct client *c;
        if (fd < 0)
            return;
        for (i = 0; i < NET_MAX_CLIENTS && h->client[i]; i++)
            ;
        c = i < NET_MAX_CLIENTS ? calloc(1, sizeof *c) : NULL;
        if (!c || room_join(h->room, &c->port) != 0) {
            fprintf(stderr, "rcxsim: %s: a client more than %d refused\n", h->option, NET_MAX_CLIENTS);
            free(c);
            close(fd);
            continue;
        }
        net_nonblocking(fd);
        setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one); /* a byte goes out as it comes off the air */
        c->fd = fd;
        c->port.hear = client_hear;
        c->port.hears_self = 1;
        c->port.facing = h->facing;
        h->client[i] = c;
    }
}

static void hub_poll(struct room_link *l)
{
    struct hub *h = (struct hub *)l;
    int i;

    hub_accept(h);
    for (i = 0; i < NET_MAX_CLIENTS; i++) {
        struct client *c = h->client[i];
        unsigned char buf[512];
        ssize_t n;
        if (!c)
            continue;
        if (c->fd >= 0 && !c->dead) {
            n = recv(c->fd, buf, sizeof buf, 0);
            if (n > 0 && c->port.tx.count + (unsigned)n > NET_BACKLOG) {
                fprintf(stderr, "rcxsim: %s: a client sent more than the IR line carries, disconnected\n", h->option);
                client_end(h, i, 1);
            } else if (n > 0) {
                room_send(h->room, &c->port, buf, (unsigned)n, 0);
            } else if (n == 0 || (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) {
                client_end(h, i, 0);
            }
        } else if (c->dead) {
            client_end(h, i, 0);
        }
        if (c->fd < 0 && !room_busy(&c->port)) {
            room_leave(h->room, &c->port);
            free(c);
            h->client[i] = NULL;
        }
    }
}

static int hub_fds(struct room_link *l, struct pollfd *fds, int max)
{
    struct hub *h = (struct hub *)l;
    int i, n = room_fd(fds, max, h->fd);
    for (i = 0; i < NET_MAX_CLIENTS; i++)
        if (h->client[i])
            n += room_fd(fds + n, max - n, h->client[i]->fd);
    return n;
}

static void hub_close(struct room_link *l)
{
    struct hub *h = (struct hub *)l;
    int i;
    for (i = 0; i < NET_MAX_CLIENTS; i++)
        if (h->client[i]) {
            client_end(h, i, 1);
            room_leave(h->room, &h->client[i]->port);
            free(h->client[i]);
        }
    close(h->fd);
    free(h);
}

int net_hub_open(struct room *r, const char *spec, struct room_port *facing, const char *what, char *err,
                 size_t errlen)
{
    char host[256], port[8], shown[300];
    struct addrinfo hints, *ai;
    struct sockaddr_storage bound;
    socklen_t boundlen = sizeof bound;
    struct hub *h;
    int fd, one = 1, e;

    if (net_split(spec, "127.0.0.1", host, sizeof host, port, sizeof port)) {
        snprintf(err, errlen, "expected [ADDR:]PORT with PORT 0-65535");
        return -1;
    }
    memset(&hints, 0, sizeof hints);
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    hints.ai_flags = AI_PASSIVE | AI_NUMERICSERV;
    if ((e = getaddrinfo(host, port, &hints, &ai)) != 0) {
        snprintf(err, errlen, "%s: %s", host, gai_strerror(e));
        return -1;
    }
    fd = socket(ai->ai_family, ai->ai_socktype | SOCK_CLOEXEC, ai->ai_protocol);
    /* SO_REUSEADDR only lets a restarted hub past the old one's closing connections; a port in use stays in use. */
    if (fd < 0 || setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one) || bind(fd, ai->ai_addr, ai->ai_addrlen) ||
        listen(fd, NET_MAX_CLIENTS) || getsockname(fd, (struct sockaddr *)&bound, &boundlen)) {
        snprintf(err, errlen, "%s", strerror(errno));
        if (fd >= 0)
            close(fd);
        freeaddrinfo(ai);
        return -1;
    }
    freeaddrinfo(ai);
    net_nonblocking(fd);
    h = calloc(1, sizeof *h);
    if (!h)
        abort();
    h->room = r;
    h->facing = facing;
    h->option = facing ? "--tcp-tower" : "--tcp";
    h->fd = fd;
    h->link.poll = hub_poll;
    h->link.fds = hub_fds;
    h->link.close = hub_close;
    room_attach(r, &h->link);
    snprintf(shown, sizeof shown, strchr(host, ':') ? "[%s]" : "%s", host);
    fprintf(stderr, "rcxsim: %s at %s:%u (tcp)\n", what, shown,
            ntohs(bound.ss_family == AF_INET6 ? ((struct sockaddr_in6 *)&bound)->sin6_port
                                              : ((struct sockaddr_in *)&bound)->sin_port));
    return 0;
}
