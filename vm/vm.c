/* SPDX-License-Identifier: MPL-2.0 */
/* Power-on state and the passage of time. */
#include "rcx_string.h"
#include "rcx.h"

void vm_init(struct rcx *b, u16 arena_addr)
{
    void *port = b->port;

    memset(b, 0, sizeof *b);
    b->port = port;
    b->arena_addr = arena_addr;
    b->random = 0xACE1;
    b->battery_mv = 9000;
    b->power_down_min = 15;
    events_init(b);
    outputs_init(b); /* turning the RCX on (spec p. 98) */
}

static void wake_waiting(struct rcx *b)
{
    struct rcx_task *t = b->task;
    u8 still = 0;

    do { /* (a pointer: an index would cost a multiplication by the task's size, a shift loop) */
        if (t->state == RCX_TASK_WAITING) {
#if RCX_SWAN
            if ((s16)(u16)(wait_clock(b, t) - t->wake) >= 0) {
                sched_set_state(b, t, RCX_TASK_RUNNING);
            } else {
                still |= (u8)(t->wait_ms + 1); /* WAIT_MS or WAIT_10MS */
            }
#else
            if ((s16)(u16)(b->ticks10 - t->wake) >= 0) {
                sched_set_state(b, t, RCX_TASK_RUNNING);
            } else {
                still = 1;
            }
#endif
        }
    } while (++t != b->task + RCX_TASKS);
    b->waiting = still;
}

void vm_tick(struct rcx *b)
{
    u8 wake = 0;

    /* Engines with nothing in progress are not called: each would only find that out. No reversing pause; no note
     * and none queued (a sound is only ever started with a note's length, so none is sounding either). */
    if (vm_pausing(b))
        outputs_tick(b);
    if (vm_sounding(b))
        sound_tick(b);
    if (++b->watch_ms >= 60000u) {
        b->watch_ms -= 60000u; /* not 0: rt_skip() (src/runtime.h) may have counted past the minute */
        if (++b->watch >= 24 * 60)
            b->watch = 0;
    }
#if RCX_SWAN
    b->ms_now++;
    wake = (u8)(b->waiting & WAIT_MS);
#endif
    if (++b->ms >= 10) {
        b->ms = 0;
        b->ticks10++;
        wake = b->waiting;
    }
    if (wake)                          /* once, after both clocks have moved on */
        wake_waiting(b);
    if (b->ms)
        return;
    if (++b->step10 >= 10) {
        u16 *tm = b->timer;
        u8 n = RCX_TIMERS;

        b->step10 = 0;
        do { /* 0-32767, then 0 again (spec p. 6) */
            *tm = (u16)((*tm + 1) & 0x7FFF);
            tm++;
        } while (--n);
    }
    /* A 10 ms step ended: once the timers have moved on, the events that watch them, and every other step the
     * display (DISPLAY_REFRESH_MS). */
    if (b->ticks10 & 1)
        display_tick(b);
    events_tick(b);
}

