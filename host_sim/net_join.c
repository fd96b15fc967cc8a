/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Joining an IR hub (--tcp-join HOST:PORT): brickEmu's ir-server, or another rcxsim --tcp. The room is one client:
 * what the room's bricks (and script) send goes to the hub as it comes off the air, and what the hub sends goes on
 * the air from one port (not back to the hub), except the hub's echo of our own bytes, recognised in order, also
 * when garbled as an rcxsim hub garbles a collided byte.
 *
 * What comes from the hub goes on the air at once (ROOM_AT_ONCE), not at 2400 baud. ir-server relays a chunk as it
 * gets it, and echoes it to its sender at once; NQC 4, on a hub, waits 300 ms for a download block's reply from the
 * moment it sent the block (host-tools.md §1). A brick taking a 200-byte firmware block (409 bytes on the air) in at
 * the line rate would answer 1.9 s later: every block would time out and be sent again. Taken in as it arrives, the
 * reply follows within about 50 ms (the packet is complete, the ROM or the firmware answers 5-6 ms later, at 2400
 * baud). The ROM and the firmware's receiver take bytes one at a time whatever the rate (rom.c, src/ir.c). An rcxsim
 * hub has already paced the bytes on its own air, so taking them at once adds no second line time; what the room's
 * bricks send still goes out at 2400 baud, and so reaches the hub paced as a brick would send it.
 *
 * A hub that goes away (ir-server ends when its last client leaves) is joined again: a first try after 1 s, then
 * after 2, 4, 8, 16 and every 30 s, one line on the standard error each time; the bricks run on alone meanwhile.
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
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

#define NET_CONNECT_S 5
#define REJOIN_FIRST_S 1.0
#define REJOIN_MAX_S 30.0
#define ECHO_MAX 4096
#define ECHO_AGE_S 2.0             /* a hub that does not echo: forget what we sent after this */

struct join {
    struct room_link link;         /* first */
    struct room_port port;
    struct room *room;
    int fd;                        /* -1: no hub */
    int connecting;                /* fd is a connection under way (joining again) */
    double next_try, wait_s, connect_end; /* wall clock: the next try, the wait after it, a try's deadline */
    struct sockaddr_storage addr;  /* the hub's address, as the first join found it */
    socklen_t addrlen;
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

static void join_hear(struct room_port *p, unsigned char byte, int error)
{
    struct join *j = OWNER(p, struct join, port);
    unsigned char b = error ? (unsigned char)(byte ^ 0x5A) : byte;
    if (j->fd < 0 || j->connecting)
        return;                     /* no hub: the bytes stay in the room */
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

/* No hub now (`why`): the next try after the current wait, which then doubles up to REJOIN_MAX_S. */
static void hub_gone(struct join *j, const char *why, double now)
{
    if (j->fd >= 0)
        close(j->fd);
    j->fd = -1;
    j->connecting = 0;
    j->echo_count = 0;
    fprintf(stderr, "rcxsim: --tcp-join %s: %s; joining again in %.0f s\n", j->name, why, j->wait_s);
    j->next_try = now + j->wait_s;
    j->wait_s = j->wait_s * 2 > REJOIN_MAX_S ? REJOIN_MAX_S : j->wait_s * 2;
}

/* A try to join again, without holding the simulation up: the connection is checked at each poll. */
static void rejoin(struct join *j, double now)
{
    int one = 1, e = 0;
    socklen_t len = sizeof e;
    struct pollfd p;

    if (j->fd < 0) {
        if (now < j->next_try)
            return;
        j->fd = socket(j->addr.ss_family, SOCK_STREAM | SOCK_CLOEXEC, 0);
        if (j->fd < 0) {
            hub_gone(j, strerror(errno), now);
            return;
        }
        net_nonblocking(j->fd);
        if (connect(j->fd, (struct sockaddr *)&j->addr, j->addrlen) != 0 && errno != EINPROGRESS) {
            char why[300];
            snprintf(why, sizeof why, "no hub (%s)", strerror(errno));
            hub_gone(j, why, now);
            return;
        }
        j->connecting = 1;
        j->connect_end = now + NET_CONNECT_S;
    }
    p.fd = j->fd;
    p.events = POLLOUT;
    if (poll(&p, 1, 0) != 1) {
        if (now > j->connect_end)
            hub_gone(j, "no hub (no answer)", now);
        return;
    }
    if (getsockopt(j->fd, SOL_SOCKET, SO_ERROR, &e, &len) || e) {
        char why[300];
        snprintf(why, sizeof why, "no hub (%s)", strerror(e ? e : errno));
        hub_gone(j, why, now);
        return;
    }
    setsockopt(j->fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    j->connecting = 0;
    j->wait_s = REJOIN_FIRST_S;
    fprintf(stderr, "rcxsim: --tcp-join %s: joined the IR hub again\n", j->name);
}

static void join_poll(struct room_link *l)
{
    struct join *j = (struct join *)l;
    unsigned char buf[512], air[512];
    double now = wall();
    ssize_t n, i;
    unsigned k = 0;

    if (j->fd < 0 || j->connecting) {
        rejoin(j, now);
        return;
    }
    n = recv(j->fd, buf, sizeof buf, 0);
    if (n == 0 || (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) {
        hub_gone(j, "the hub closed the connection", now);
        return;
    }
    for (i = 0; i < n; i++)
        if (!our_echo(j, buf[i], now))
            air[k++] = buf[i];
    room_send(j->room, &j->port, air, k, ROOM_AT_ONCE);
}

static int join_fds(struct room_link *l, struct pollfd *fds, int max)
{
    struct join *j = (struct join *)l;
    return room_fd(fds, max, j->connecting ? -1 : j->fd);
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
    net_nonblocking(fd);
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

    if (net_split(spec, "127.0.0.1", host, sizeof host, port, sizeof port) || atol(port) == 0) {
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
    for (ai = list; ai; ai = ai->ai_next)
        if ((fd = connect_to(ai)) >= 0)
            break;
    if (fd < 0) {
        snprintf(err, errlen, "%s", strerror(errno));
        freeaddrinfo(list);
        return -1;
    }
    setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    j = calloc(1, sizeof *j);
    if (!j)
        abort();
    memcpy(&j->addr, ai->ai_addr, ai->ai_addrlen);
    j->addrlen = ai->ai_addrlen;
    freeaddrinfo(list);
    j->room = r;
    j->fd = fd;
    j->wait_s = REJOIN_FIRST_S;
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
    fprintf(stderr, "rcxsim: joined the IR hub at %s (tcp)\n", spec);
    return 0;
}
