/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Tasks and program slots: start, stop, select (spec pp. 31-33, 16).
 * Priorities do not enter here: firm0328 gives every running task one byte code per pass whatever its priority,
 * and uses priority only for access control (reference-firmware.md, "Tasks and timing").
 */
#include "rcx.h"

RCX_STATIC_ASSERT(locals_16, RCX_LOCALS == 1 << 4);

void sched_start_task(struct rcx *b, u8 n)
{
    struct rcx_task *t;

    if (n >= RCX_TASKS || !mem_obj_runnable(b, rcx_obj_task(b->prog, n)))
        return; /* an empty (or half-downloaded) task slot is not started */
    t = sched_stop_task(b, n); /* a running task is restarted from the top */
    t->sub = RCX_NO_SUB;
    t->pc = 0;
    t->has_ret = 0;
    t->loop_depth = 0;
#if RCX_SWAN
    t->stack = 0;
#endif
    /* Variables 32-47: the task's locals in an RCX 2.0 program, the globals themselves in a Swan one (source 0
     * addresses globals there: swan-target.md 4). */
    t->local_base = RCX_SWAN && b->swan[b->prog] ? 0 : (u8)(n << 4); /* 16 n */
    t->ev.events = 0;
    sched_set_state(b, t, RCX_TASK_RUNNING);
}

struct rcx_task *sched_stop(struct rcx *b, struct rcx_task *t)
{
    if (t->state != RCX_TASK_IDLE) {
        sched_set_state(b, t, RCX_TASK_IDLE);
        events_task_ended(b, t);
    }
    return t;
}

struct rcx_task *sched_stop_task(struct rcx *b, u8 n)
{
    u8 size = sizeof(struct rcx_task); /* two byte variables: one mulxu, not a shift loop */

    return n < RCX_TASKS ? sched_stop(b, (struct rcx_task *)(void *)((u8 *)b->task + (u16)(n * size))) : NULL;
}

/* One place keeps runmask in step with the states (a shift by a variable count is a loop on the H8/300: written
 * once). */
RCX_STATIC_ASSERT(runmask_bits, RCX_TASKS <= 16);
void sched_set_state(struct rcx *b, struct rcx_task *t, u8 state)
{
    const struct rcx_task *u;
    u16 bit = 1, mask;

#ifdef __H8300__
    if (sizeof(struct rcx_task) == 32) { /* (Swan's image; 30 bytes without its fields) */
        /* The bit set or cleared in place: bset and bclr take the bit number from a register's low three bits.
         * Task n is bit n & 7 of runmask's low byte (n < 8: the second byte, big-endian) or of its high byte. */
        u8 n, *m = (u8 *)&b->runmask;

        t->state = state;
        n = (u8)((u16)((u16)((const u8 *)t - (const u8 *)b->task) << 3) >> 8); /* the offset / 32 */
        if (n < 8)
            m++;
        if (state == RCX_TASK_RUNNING)
            __asm__ __volatile__("bset\t%X1,@%T0" : : "r"(m), "r"(n) : "memory");
        else
            __asm__ __volatile__("bclr\t%X1,@%T0" : : "r"(m), "r"(n) : "memory");
        return;
    }
#endif
    for (u = b->task; u != t; u++)
        bit <<= 1;
    t->state = state;
    mask = (u16)(b->runmask & ~bit);
    if (state == RCX_TASK_RUNNING)
        mask |= bit;
    b->runmask = mask;
}

void sched_stop_all(struct rcx *b)
{
    u8 n;
    for (n = 0; n < RCX_TASKS; n++)
        sched_stop_task(b, n);
}

void sched_select_program(struct rcx *b, u8 prog, u8 from_program)
{
    if (prog >= RCX_PROGRAMS)
        return; /* acknowledged, changes nothing (reference-firmware.md) */
    sched_stop_all(b);
    b->prog = prog;
    /* From a program (or source 8 written by one) the new slot's task 0 starts: chaining, spec p. 33. */
    if (from_program)
        sched_start_task(b, 0);
}
