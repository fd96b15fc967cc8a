/*
 * The TCP IR link (--tcp, --tcp-join). The stream carries the bytes of the air as they are, with no framing, as
 * brickEmu's ir-server relays them: what one client writes, every client reads, the writer included (its own echo,
 * as a serial tower hears itself; NQC 4's TCP link finds its reply after it by the reply's header).
 *
 * As the hub, each client is a port of the room that hears what bricks and clients send, itself included (a tower
 * faces its own brick only, network clients as well as the others), and whose bytes go on the air at 2400 baud in
 * simulated time, to every brick, tower and client. Unlike ir-server, which
 * interleaves whatever arrives, bytes that overlap on the air collide, as they would between bricks: a client
 * gets a collided byte garbled. A client that sends more than the air can carry (NET_BACKLOG bytes waiting) is
 * disconnected and its waiting bytes dropped, so a flood or garbage stops there; a client that goes away keeps
 * the bytes it sent, which go on the air (nqc -msg writes and closes at once).
 *
 * Joining a hub, the room is one client: what the room's bricks (and script) send goes to the hub, and what the hub
 * sends goes on the air from one port (not back to the hub), except the hub's echo of our own bytes, recognised in
 * order, also when garbled as this hub garbles a collided byte.
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
#include <time.h>
#include <unistd.h>
#include "net.h"

#define NET_MAX_CLIENTS 32
#define NET_BACKLOG 2200           /* bytes waiting for the air: a whole 1 KB ROM download block, twice the lot */
#define NET_CONNECT_S 5
#define ECHO_MAX 4096
#define ECHO_AGE_S 2.0             /* a hub that does not echo: forget what we sent after this */

struct client {
    struct room_port port;         /* first: the port is the client */
    int fd;                        /* -1: gone; the port stays until its bytes are on the air */
    int dead;                      /* a write failed: close at the next poll */
};

struct hub {
    struct room_link link;         /* first */
    struct room *room;
    int fd;
    struct client *client[NET_MAX_CLIENTS];
};

struct join {
    struct room_link link;         /* first */
    struct room_port port;
    struct room *room;
    int fd;
    char name[300];
    unsigned char echo[ECHO_MAX];  /* bytes sent to the hub whose echo has not come back, oldest first */
    double echo_at[ECHO_MAX];
    unsigned echo_head, echo_count;
};

#define OWNER(ptr, type, member) ((type *)(void *)((char *)(ptr) - offsetof(type, member)))

static double wall(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec / 1e9;
}

static void nonblocking(int fd)
{
    fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
}

/* "[ADDR:]PORT", "HOST[:PORT]" or "[IPV6]:PORT" into host and port; "" is the default of both. */
static int split(const char *spec, const char *host_default, char *host, size_t hostlen, char *port, size_t portlen)
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
            fprintf(stderr, "rcxsim: --tcp: a client more than %d refused\n", NET_MAX_CLIENTS);
            free(c);
            close(fd);
            continue;
        }
        nonblocking(fd);
        setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one); /* a byte goes out as it comes off the air */
        c->fd = fd;
        c->port.hear = client_hear;
        c->port.hears_self = 1;
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
                fprintf(stderr, "rcxsim: --tcp: a client sent more than the IR line carries, disconnected\n");
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

int net_hub_open(struct room *r, const char *spec, char *err, size_t errlen)
{
    char host[256], port[8], shown[300];
    struct addrinfo hints, *ai;
    struct sockaddr_storage bound;
    socklen_t boundlen = sizeof bound;
    struct hub *h;
    int fd, one = 1, e;

    if (split(spec, "127.0.0.1", host, sizeof host, port, sizeof port)) {
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
    nonblocking(fd);
    h = calloc(1, sizeof *h);
    if (!h)
        abort();
    h->room = r;
    h->fd = fd;
    h->link.poll = hub_poll;
    h->link.fds = hub_fds;
    h->link.close = hub_close;
    room_attach(r, &h->link);
    snprintf(shown, sizeof shown, strchr(host, ':') ? "[%s]" : "%s", host);
    fprintf(stderr, "rcxsim: IR hub at %s:%u (tcp)\n", shown,
            ntohs(bound.ss_family == AF_INET6 ? ((struct sockaddr_in6 *)&bound)->sin6_port
                                              : ((struct sockaddr_in *)&bound)->sin_port));
    return 0;
}

/* ---- joining a hub ---- */

static void join_hear(struct room_port *p, unsigned char byte, int error)
{
    struct join *j = OWNER(p, struct join, port);
    unsigned char b = error ? (unsigned char)(byte ^ 0x5A) : byte;
    if (j->fd < 0)
        return;
    if (send(j->fd, &b, 1, MSG_NOSIGNAL) != 1)
        return;                     /* a hub that does not read loses bytes; one that went away shows at the poll */
    if (j->echo_count == ECHO_MAX) {
        j->echo_head = (j->echo_head + 1) % ECHO_MAX;
        j->echo_count--;
    }
    j->echo[(j->echo_head + j->echo_count) % ECHO_MAX] = b;
    j->echo_at[(j->echo_head + j->echo_count) % ECHO_MAX] = wall();
    j->echo_count++;
}

/* The hub's echo of our own next byte, as sent or garbled: dropped. */
static int our_echo(struct join *j, unsigned char byte, double now)
{
    while (j->echo_count && now - j->echo_at[j->echo_head] > ECHO_AGE_S) {
        j->echo_head = (j->echo_head + 1) % ECHO_MAX;
        j->echo_count--;
    }
    if (!j->echo_count || (byte != j->echo[j->echo_head] && (byte ^ 0x5A) != j->echo[j->echo_head]))
        return 0;
    j->echo_head = (j->echo_head + 1) % ECHO_MAX;
    j->echo_count--;
    return 1;
}

static void join_poll(struct room_link *l)
{
    struct join *j = (struct join *)l;
    unsigned char buf[512], air[512];
    double now = wall();
    ssize_t n, i;
    unsigned k = 0;

    if (j->fd < 0)
        return;
    n = recv(j->fd, buf, sizeof buf, 0);
    if (n == 0 || (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) {
        fprintf(stderr, "rcxsim: --tcp-join %s: the hub closed the connection\n", j->name);
        close(j->fd);
        j->fd = -1;
        return;
    }
    for (i = 0; i < n; i++)
        if (!our_echo(j, buf[i], now))
            air[k++] = buf[i];
    room_send(j->room, &j->port, air, k, 0);
}

static int join_fds(struct room_link *l, struct pollfd *fds, int max)
{
    return room_fd(fds, max, ((struct join *)l)->fd);
}

static void join_close(struct room_link *l)
{
    struct join *j = (struct join *)l;
    room_leave(j->room, &j->port);
    if (j->fd >= 0)
        close(j->fd);
    free(j);
}

/* A connection to one of the addresses, within NET_CONNECT_S seconds; -1 with errno. */
static int connect_to(const struct addrinfo *ai)
{
    int fd = socket(ai->ai_family, ai->ai_socktype | SOCK_CLOEXEC, ai->ai_protocol), e = 0;
    socklen_t len = sizeof e;
    struct pollfd p;

    if (fd < 0)
        return -1;
    nonblocking(fd);
    if (connect(fd, ai->ai_addr, ai->ai_addrlen) == 0)
        return fd;
    if (errno != EINPROGRESS)
        goto fail;
    p.fd = fd;
    p.events = POLLOUT;
    if (poll(&p, 1, NET_CONNECT_S * 1000) != 1) {
        errno = ETIMEDOUT;
        goto fail;
    }
    if (getsockopt(fd, SOL_SOCKET, SO_ERROR, &e, &len) || e) {
        errno = e ? e : errno;
        goto fail;
    }
    return fd;
fail:
    e = errno;
    close(fd);
    errno = e;
    return -1;
}

int net_join(struct room *r, const char *spec, char *err, size_t errlen)
{
    char host[256], port[8];
    struct addrinfo hints, *list, *ai;
    struct join *j;
    int fd = -1, e, one = 1;

    if (split(spec, "127.0.0.1", host, sizeof host, port, sizeof port) || atol(port) == 0) {
        snprintf(err, errlen, "expected HOST:PORT with PORT 1-65535");
        return -1;
    }
    memset(&hints, 0, sizeof hints);
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    hints.ai_flags = AI_NUMERICSERV;
    if ((e = getaddrinfo(host, port, &hints, &list)) != 0) {
        snprintf(err, errlen, "%s: %s", host, gai_strerror(e));
        return -1;
    }
    errno = ECONNREFUSED;
    for (ai = list; ai && fd < 0; ai = ai->ai_next)
        fd = connect_to(ai);
    if (fd < 0) {
        snprintf(err, errlen, "%s", strerror(errno));
        freeaddrinfo(list);
        return -1;
    }
    freeaddrinfo(list);
    setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    j = calloc(1, sizeof *j);
    if (!j)
        abort();
    j->room = r;
    j->fd = fd;
    snprintf(j->name, sizeof j->name, "%s", spec);
    j->port.hear = join_hear;
    if (room_join(r, &j->port) != 0) {
        close(fd);
        free(j);
        snprintf(err, errlen, "the IR room is full");
        return -1;
    }
    j->link.poll = join_poll;
    j->link.fds = join_fds;
    j->link.close = join_close;
    room_attach(r, &j->link);
    return 0;
}
