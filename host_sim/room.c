/*
 * The simulated IR room and the serial towers.
 *
 * Every transmitter sends its bytes back to back at its line rate (2400 baud 8O1 = 11 bits, or 4800 baud 8N1);
 * a byte reaches its receivers when its last bit has gone out. Who hears whom:
 *   a brick      -> every brick (itself included: the echo, rcx-hardware.md §3.8) and every tower;
 *   a tower      -> its own brick and itself (the echo nqc waits for, host-tools.md §1);
 *   the script   -> every brick and every tower.
 * Towers face their own brick only, so a host talking to brick 0 is not answered by brick 1 as well. Bytes that
 * overlap in time on the air collide: receivers get them with an error (and towers a garbled byte). Receivers
 * listen at 2400 baud; a 4800-baud byte reaches them garbled too.
 */
#define _GNU_SOURCE /* posix_openpt, ptsname, cfmakeraw */
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>
#include "sim.h"
#include "hal.h"

static sim_us byte_time(unsigned mode)
{
    return mode & HAL_IR_4800 ? 2084 : 4583; /* 10 bits at 4800, 11 bits at 2400 */
}

int room_busy(const struct sim_tx *tx)
{
    return tx->count != 0;
}

void room_send(struct sim *s, struct sim_tx *tx, const unsigned char *data, unsigned len, unsigned mode)
{
    unsigned i;
    for (i = 0; i < len && tx->count < SIM_TX_QUEUE; i++) {
        tx->queue[(tx->head + tx->count) % SIM_TX_QUEUE] = (unsigned short)(data[i] | (mode & 7u) << 8);
        if (tx->count++ == 0) {
            tx->start = s->now;
            tx->end = s->now + byte_time(mode);
            tx->collided = 0;
        }
    }
}

static void hear(struct sim_brick *b, unsigned char byte, int error)
{
    if (b->mode != SIM_STANDBY)
        b->ir_in++;
    if (b->mode == SIM_FIRMWARE)
        rt_ir_byte(&b->k, byte, (u8)error);
    else if (b->mode == SIM_ROM)
        rom_byte(b, byte, error);
    /* in standby the receiver is off */
}

static void tower_hear(struct sim_tower *t, unsigned char byte, int error)
{
    unsigned char c = error ? (unsigned char)(byte ^ 0x5A) : byte;
    ssize_t n = write(t->master, &c, 1);
    (void)n; /* a full buffer loses the byte, as an overrun would */
}

/* All transmitters, in a fixed order. */
static int transmitters(struct sim *s, struct sim_tx **list)
{
    int i, n = 0;
    for (i = 0; i < s->nbricks; i++)
        list[n++] = &s->brick[i]->tx;
    for (i = 0; i < s->ntowers; i++)
        list[n++] = &s->tower[i].tx;
    list[n++] = &s->script_tx;
    return n;
}

static void deliver(struct sim *s, struct sim_tx **list, int n, int from)
{
    struct sim_tx *tx = list[from];
    unsigned entry = tx->queue[tx->head];
    unsigned char byte = (unsigned char)entry;
    int error, i;

    for (i = 0; i < n; i++) {
        struct sim_tx *o = list[i];
        if (i != from && o->count && o->start < tx->end && o->end > tx->start)
            tx->collided = o->collided = 1;
    }
    error = tx->collided || (entry >> 8 & HAL_IR_4800);
    if (from < s->nbricks || tx == &s->script_tx) {
        for (i = 0; i < s->nbricks; i++)
            hear(s->brick[i], byte, error);
        for (i = 0; i < s->ntowers; i++)
            tower_hear(&s->tower[i], byte, error);
    } else {
        struct sim_tower *t = &s->tower[from - s->nbricks];
        if (t->link)
            tower_hear(t, byte, error);
        for (i = 0; i < s->nbricks; i++)
            if (s->brick[i]->tower == t)
                hear(s->brick[i], byte, error);
    }
    /* Only now is the byte off the air: a sender that asks hal_ir_busy() while hearing its echo is still busy. */
    tx->head = (tx->head + 1) % SIM_TX_QUEUE;
    if (--tx->count) {
        tx->start = tx->end;
        tx->end = tx->start + byte_time(tx->queue[tx->head] >> 8);
        tx->collided = 0;
    }
}

void room_advance(struct sim *s, sim_us until)
{
    struct sim_tx *list[2 * SIM_MAX_BRICKS + 1];
    int n = transmitters(s, list);

    for (;;) {
        int i, best = -1;
        for (i = 0; i < n; i++)
            if (list[i]->count && list[i]->end <= until && (best < 0 || list[i]->end < list[best]->end))
                best = i;
        if (best < 0)
            return;
        deliver(s, list, n, best);
    }
}

int tower_open(struct sim *s, struct sim_tower *t, const char *link, struct sim_brick *b)
{
    struct termios tio;
    struct stat st;
    const char *name;

    (void)s;
    memset(t, 0, sizeof *t);
    t->master = posix_openpt(O_RDWR | O_NOCTTY);
    if (t->master < 0 || grantpt(t->master) || unlockpt(t->master) || !(name = ptsname(t->master)))
        return -1;
    t->slave = open(name, O_RDWR | O_NOCTTY);
    if (t->slave < 0)
        return -1;
    /* Raw until the host tool sets its own line: no echo or line editing by the pty itself. */
    if (tcgetattr(t->slave, &tio) == 0) {
        cfmakeraw(&tio);
        tcsetattr(t->slave, TCSANOW, &tio);
    }
    fcntl(t->master, F_SETFL, fcntl(t->master, F_GETFL) | O_NONBLOCK);
    /* Replace a stale symlink from an earlier run, never a real file. */
    if (lstat(link, &st) == 0 && S_ISLNK(st.st_mode))
        unlink(link);
    if (symlink(name, link) != 0)
        return -1;
    t->link = strdup(link);
    b->tower = t;
    return 0;
}

void tower_poll(struct sim *s)
{
    int i;
    for (i = 0; i < s->ntowers; i++) {
        unsigned char buf[1024];
        ssize_t n;
        while ((n = read(s->tower[i].master, buf, sizeof buf)) > 0)
            room_send(s, &s->tower[i].tx, buf, (unsigned)n, 0);
    }
}

void tower_close(struct sim_tower *t)
{
    if (t->link) {
        unlink(t->link);
        free(t->link);
        t->link = NULL;
    }
    if (t->slave >= 0)
        close(t->slave);
    if (t->master >= 0)
        close(t->master);
}
