/* Power-on state and the passage of time. */
#include "rcx_string.h"
#include "rcx.h"

void vm_init(struct rcx *b, u16 arena_addr)
{
    u8 i;

    memset(b, 0, sizeof *b);
    b->arena_addr = arena_addr;
    b->random = 0xACE1;
    b->battery_mv = 9000;
    b->power_down_min = 15;
    for (i = 0; i < RCX_EVENTS; i++) {
        b->event[i].type = RCX_EVENT_NONE;
        b->event[i].state = RCX_EVENT_STATE_UNDEFINED;
        b->event[i].duration = 15; /* 150 ms, the click default of spec p. 71 */
    }
    /* Turning the RCX on: all motors forward, float, full power (spec p. 98); globally on, normal, max 7. */
    for (i = 0; i < RCX_MOTORS; i++) {
        b->out.motor[i] = RCX_MOTOR_FWD | 7;
        b->out.global[i] = RCX_MOTOR_ON | RCX_MOTOR_FWD | 7;
    }
}

static void wake_waiting(struct rcx *b)
{
    u8 n;
    for (n = 0; n < RCX_TASKS; n++) {
        struct rcx_task *t = &b->task[n];
        if (t->state == RCX_TASK_WAITING && (s16)(u16)(b->ticks10 - t->wake) >= 0) {
            t->state = RCX_TASK_RUNNING;
            b->runmask |= (u16)(1u << n);
        }
    }
}

void vm_tick(struct rcx *b)
{
    u8 i;

    if (++b->watch_ms >= 60000u) {
        b->watch_ms = 0;
        if (++b->watch >= 24 * 60)
            b->watch = 0;
    }
    if (++b->ms < 10)
        return;
    b->ms = 0;
    b->ticks10++;
    wake_waiting(b);
    if (++b->step10 < 10)
        return;
    b->step10 = 0;
    for (i = 0; i < RCX_TIMERS; i++)
        b->timer[i] = (u16)((b->timer[i] + 1) & 0x7FFF); /* 0-32767, then 0 again (spec p. 6) */
}
