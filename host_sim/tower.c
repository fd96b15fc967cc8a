/* SPDX-License-Identifier: MPL-2.0 */
/*
 * A serial IR tower on a pseudo-terminal (--tty): a port of the room facing one brick, and a link that brings in
 * what the host tool writes. The tower sends at the speed the host set on its side of the line: 4800 baud for
 * firmdl3's fast mode and nqc -firmfast, whose bytes a receiver listening at 2400 baud hears garbled, as on a brick
 * whose ROM cannot switch speed. That is said once on rcxsim's output, since the tools only report a failure.
 */
#define _GNU_SOURCE /* posix_openpt, ptsname, cfmakeraw */
#include <errno.h>
#include <fcntl.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>
#include "tower.h"
#include "hal.h"

struct tower {
    struct room_link link;         /* first: the link is the tower */
    struct room_port port;
    struct room *room;
    int master, slave;             /* we keep the slave open so the master never sees a hang-up */
    char *path;                    /* the symlink the user named */
    int told_fast;                 /* the 4800-baud note was printed */
};

static void tower_hear(struct room_port *p, unsigned char byte, int error)
{
    struct tower *t = (struct tower *)(void *)((char *)p - offsetof(struct tower, port));
    unsigned char c = error ? (unsigned char)(byte ^ 0x5A) : byte;
    ssize_t n = write(t->master, &c, 1);
    (void)n; /* a full buffer loses the byte, as an overrun would */
}

/* The line speed the host tool set, as a transmit mode. */
static unsigned line_mode(struct tower *t)
{
    struct termios tio;
    if (tcgetattr(t->slave, &tio) != 0 || cfgetospeed(&tio) != B4800)
        return 0;
    if (!t->told_fast) {
        t->told_fast = 1;
        fprintf(stderr, "rcxsim: --tty %s: the host switched to 4800 baud (firmdl3's fast mode, nqc -firmfast): fast "
                        "mode is not available, the virtual RCX stays at 2400; use firmdl3 --slow or nqc -firmware\n",
                t->path);
    }
    return HAL_IR_4800;
}

static void tower_poll(struct room_link *l)
{
    struct tower *t = (struct tower *)l;
    unsigned char buf[1024];
    ssize_t n;
    while ((n = read(t->master, buf, sizeof buf)) > 0)
        room_send(t->room, &t->port, buf, (unsigned)n, line_mode(t));
}

static int tower_fds(struct room_link *l, struct pollfd *fds, int max)
{
    return room_fd(fds, max, ((struct tower *)l)->master);
}

static void tower_close(struct room_link *l)
{
    struct tower *t = (struct tower *)l;
    if (t->path) {
        unlink(t->path);
        free(t->path);
    }
    if (t->slave >= 0)
        close(t->slave);
    if (t->master >= 0)
        close(t->master);
    free(t);
}

int tower_open(struct room *r, const char *path, struct room_port *brick)
{
    struct tower *t = calloc(1, sizeof *t);
    struct termios tio;
    struct stat st;
    const char *name;
    int err;

    if (!t)
        abort();
    t->room = r;
    t->slave = -1;
    t->link.poll = tower_poll;
    t->link.fds = tower_fds;
    t->link.close = tower_close;
    t->port.hear = tower_hear;
    t->port.facing = brick;
    t->port.hears_self = 1;
    t->master = posix_openpt(O_RDWR | O_NOCTTY);
    if (t->master < 0 || grantpt(t->master) || unlockpt(t->master) || !(name = ptsname(t->master)))
        goto fail;
    t->slave = open(name, O_RDWR | O_NOCTTY);
    if (t->slave < 0)
        goto fail;
    /* Raw until the host tool sets its own line: no echo or line editing by the pty itself. */
    if (tcgetattr(t->slave, &tio) == 0) {
        cfmakeraw(&tio);
        tcsetattr(t->slave, TCSANOW, &tio);
    }
    fcntl(t->master, F_SETFL, fcntl(t->master, F_GETFL) | O_NONBLOCK);
    /* Replace a stale symlink from an earlier run, never a real file. */
    if (lstat(path, &st) == 0 && S_ISLNK(st.st_mode))
        unlink(path);
    if (symlink(name, path) != 0)
        goto fail;
    t->path = strdup(path);
    if (room_join(r, &t->port) != 0) {
        errno = EMFILE;
        goto fail;
    }
    room_attach(r, &t->link);
    return 0;
fail:
    err = errno;
    tower_close(&t->link);
    errno = err;
    return -1;
}
