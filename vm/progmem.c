/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Program memory: one arena holding the code of every task and subroutine of all five slots, then the datalog.
 * Objects are packed in a fixed order (slot 0 subs 0-7, tasks 0-9, slot 1 ...), so an absent object has size 0
 * and an address anyway, and resizing one object slides everything after it. Tasks hold their pc relative to
 * their code object, which is why code may move under a running program.
 */
#include "rcx_string.h"
#include "rcx.h"

#define LOG_BYTES(b) ((u16)((b)->log_size * 3u))
#define CODE_END(b) ((b)->obj_start[RCX_OBJS])

u16 mem_free(const struct rcx *b)
{
    return (u16)(RCX_ARENA_SIZE - CODE_END(b) - LOG_BYTES(b));
}

u16 mem_obj_size(const struct rcx *b, u8 obj)
{
    return (u16)(b->obj_start[obj + 1] - b->obj_start[obj]);
}

u8 mem_obj_runnable(const struct rcx *b, u8 obj)
{
    /* Code still being downloaded must not run (reference-firmware.md, "Downloads"). */
    if (b->dl.active && b->dl.obj == obj)
        return 0;
    return mem_obj_size(b, obj) != 0;
}

/*
 * What follows the objects moves by the difference: at once, or, with RCX_MOVE_STEP (the brick), a pass of the main
 * loop at a time (mem_step), so that a command on a full memory never holds the IR link and the buttons for long
 * (issue 21, docs/timing.md). The offsets are the new ones at once; the bytes still to move are rcx.move's. A command
 * makes one resize but for two cases (mem_delete meeting the download in progress, a download abandoned by the next
 * BeginOfTask/Sub), whose second resize's move, worked out on the offsets the first left, is made after the first's
 * (no command runs while a move is left: rt_run).
 */
u8 mem_resize(struct rcx *b, u8 obj, u8 n, u16 size)
{
    u16 *start, *last, first, tail, end, old, delta;
    u8 *at;
#if RCX_MOVE_STEP
    struct rcx_move *m = b->move;

    while (m[1].len)               /* (never so: two moves are all a command leaves) */
        mem_step(b);
#endif
    start = &b->obj_start[obj];
    last = start + n;
    first = *start;
    tail = *last;
    end = (u16)(CODE_END(b) + LOG_BYTES(b)); /* of the datalog */
    old = (u16)(tail - first);
    delta = (u16)(size - old);     /* growth, or shrinkage as a 16-bit negative */
    if (size > (u16)(RCX_ARENA_SIZE - end + old))
        return 0;                  /* growth needs the room */
    if (!delta)                    /* the same size (the last block of a download as announced, a range already */
        return 1;                  /* empty): nothing to move, nor any offset to change */
    end = (u16)(end - tail);       /* bytes after the objects, up to the datalog's end */
    at = b->arena + tail;
#if RCX_MOVE_STEP
    if (m->len)
        m++;                       /* after the first */
    m->from = at;
    m->to = at + delta;
    m->len = end;
#else
    /* What follows the objects moves by delta either way, as a signed number now that a growth is known to be less
     * than the arena (a shrinkage moves it down). The bytes gained keep what was there, as on the brick, until the
     * blocks of a download overwrite them. */
    memmove(at + (s16)delta, at, end);
#endif
    while (++start < last)
        *start = first;
    for (; start <= &b->obj_start[RCX_OBJS]; start++)
        *start = (u16)(*start + delta);
    return 1;
}

/* The selected slot's subroutines or tasks id to id + count - 1 (numbered as vm/direct.c does), whose tasks are
 * stopped, go at once (one move of the memory), but for the code still being downloaded: the download stays active
 * (reference-firmware.md). */
void mem_delete(struct rcx *b, u8 id, u8 count)
{
    u8 obj = rcx_obj_sub(b->prog, id), k = (u8)(b->dl.obj - obj);

    if (b->dl.active && k < count) { /* the objects after it go, then those before */
        mem_resize(b, (u8)(b->dl.obj + 1), (u8)(count - k - 1), 0);
        count = k;
    }
    mem_resize(b, obj, count, 0);
}

#if RCX_MOVE_STEP
/* RCX_MOVE_STEP bytes of the move left (downwards from its start, upwards from its end, so that nothing is overwritten
 * before it is moved): the first, then the second (mem_resize sets it only while the first is left); 0 when there was
 * none. The bytes an object gains keep what was there until its blocks come. */
u8 mem_step(struct rcx *b)
{
    struct rcx_move *m = b->move;
    u16 n, left;
    u8 *to, *from;

    if (!m->len)
        m++;                       /* the first made (or none), the second's turn */
    n = m->len;
    to = m->to;
    from = m->from;
    if (!n)
        return 0;
    if (n > RCX_MOVE_STEP)
        n = RCX_MOVE_STEP;
    m->len = left = (u16)(m->len - n);
    if (to < from) {               /* downwards: the first bytes, and the move goes on after them */
        m->to = to + n;
        m->from = from + n;
    } else {                       /* upwards: the last */
        to += left;
        from += left;
    }
    memmove(to, from, n);
    return 1;
}
#endif

static u8 *put_word(u8 *p, u16 w)
{
    p[0] = (u8)(w >> 8); /* the memory map is the one big-endian reply (spec p. 13) */
    p[1] = (u8)w;
    return p + 2;
}

u8 mem_memmap(const struct rcx *b, u8 *out)
{
    u16 base = b->arena_addr, log;
    const u16 *start = b->obj_start;
    u8 *other = out + RCX_PROGRAMS * RCX_SUBS * 2, left = RCX_SLOT_OBJS;

    /* The subroutines of every slot, then the tasks: the objects in arena order, a slot's 8 subroutines to the first
     * part of the map and its 10 tasks to the second; `other` is where the part not being written goes on. */
    do {
        u16 w = (u16)(base + *start++);
        out[0] = (u8)(w >> 8); /* the memory map is the one big-endian reply (spec p. 13) */
        out[1] = (u8)w;
        out += 2;
        if (--left == RCX_TASKS || left == 0) { /* from the subroutines to the tasks, or back at the next slot */
            u8 *p = other;
            other = out;
            out = p;
            if (left == 0)
                left = RCX_SLOT_OBJS;
        }
    } while (start < &b->obj_start[RCX_OBJS]);
    log = (u16)(base + *start);
    out = put_word(other, log);        /* (the end of the tasks' part) */
    out = put_word(out, (u16)(log + b->log_count * 3u));
    out = put_word(out, (u16)(log + LOG_BYTES(b)));
    /* firm0328 hosts compute free memory as word 93 - word 92, so 93 is the end of the arena, not its last byte. */
    put_word(out, (u16)(base + RCX_ARENA_SIZE));
    return (RCX_OBJS + 4) * 2;
}
