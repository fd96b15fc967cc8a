/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The runtime around the byte-code machine: a whole brick as the firmware (or one virtual RCX) runs it.
 *
 * Inputs arrive through the rt_* calls below (from drivers/ on the brick, from host_sim/ on the host), outputs leave
 * through hal.h. Nothing here may be called from an interrupt handler: drivers buffer bytes and count ticks in their
 * interrupts, and the main loop feeds them in.
 */
#ifndef RCX_RUNTIME_H
#define RCX_RUNTIME_H

#include "rcx.h"
#include "ir.h"
#include "ui.h"

struct rcx_brick {
    struct rcx vm;          /* first, so that a hal call's `struct rcx *` is also the brick (rt_brick_of) */
    struct rcx_ir ir;       /* IR packet layer: receiver, toggle handling, replies, outgoing requests */
    struct rcx_ui ui;       /* buttons, program selection, power-down timer, low battery, standby */
};

#define rt_brick_of(b) ((struct rcx_brick *)(void *)(b))

/* Power-on: machine, IR link and user interface in their initial state. Keeps rcx.port: attach the port first. */
void rt_init(struct rcx_brick *k, u16 arena_addr);

/* One millisecond has passed (call once per elapsed ms, from the main loop). Inline: the brick runs it a thousand
 * times a second, and a call of its own would cost more than its body. */
static inline void rt_tick(struct rcx_brick *k)
{
    vm_tick(&k->vm);
    if (ir_tick_due(k))
        ir_tick(k);
    ui_tick(k);
}

/*
 * Quiet milliseconds, for a port that would rather not work through every tick: while no IR exchange, sound or
 * reversing pause is in progress and the power-down timer need not start again, a millisecond that does not end a
 * 10 ms step only counts. rt_quiet() tells how many of the next milliseconds are such (0: the next is not);
 * rt_skip(k, n), n no more than that, does what n calls of rt_tick() would, except that a minute of the watch or of
 * the power-down timer that ends in them is seen at the next rt_tick(). Meanwhile the port either sleeps, when no
 * task runs (rt_run() would have nothing to do, but for a PBTurnOff that a task ended with, carried out up to 9 ms
 * later), or lets the tasks run on, as long as they start nothing that needs the clock (a note, a reversing pause, a
 * transmission: vm_sounding(), vm_pausing(), remote.tx_len), then counts the milliseconds. The inputs must be
 * as quiet: the port stops skipping once a sample or a byte is there to feed. tests/unit/test_quiet_ms.c holds a
 * skipping brick to one that ticks every millisecond.
 */
static inline u8 rt_quiet(const struct rcx_brick *k)
{
    const struct rcx *b = &k->vm;

    /* An IR exchange or a switch-off is in progress only while ir_tick() is due or a sound plays: ir_poll() and
     * ui_poll() do all they can without the clock. */
    if (ir_tick_due(k) || vm_pausing(b) || vm_sounding(b) || b->idle_reset || (RCX_SWAN && (b->waiting & WAIT_MS)))
        return 0;
    return (u8)(9 - b->ms); /* the step's last millisecond is rt_tick()'s */
}

static inline void rt_skip(struct rcx_brick *k, u8 n)
{
    k->vm.ms = (u8)(k->vm.ms + n);
    if (RCX_SWAN)
        k->vm.ms_now = (u16)(k->vm.ms_now + n);
    k->vm.watch_ms = (u16)(k->vm.watch_ms + n);
    k->ui.idle_ms = (u16)(k->ui.idle_ms + n);
}

/* Main-loop work: complete packets are executed and answered, transmit requests sent, then up to `budget` byte
 * codes run. Returns the byte codes executed. While a move of program memory is left (RCX_MOVE_STEP), a step of it
 * instead, counted as 1. */
u16 rt_run(struct rcx_brick *k, u16 budget);

/* A byte received on the IR link; `error` non-zero for a parity/framing/overrun error. */
void rt_ir_byte(struct rcx_brick *k, u8 byte, u8 error);

/* 10-bit A/D samples of the three inputs (raw10[0] of input 1), every 1 ms; then rt_sensors_resting() tells whether
 * another scan equal to it would change nothing. */
#define rt_sensor_scan(k, raw10) sensor_scan(&(k)->vm, raw10)
/* Nonzero: the samples given from now on are late, newer ones wait behind them (the port fell behind); their values
 * and rotation steps are kept, their events told only of the newest (vm/sensors.c). */
static inline void rt_sensors_late(struct rcx_brick *k, u8 late)
{
    k->vm.sensor[0].late = late;
}
/* Nonzero when another scan equal to the last would change nothing, until that may no longer be so (vm/sensors.h,
 * sensors_at_rest): a port may skip such scans. */
#define rt_sensors_resting(k) ((k)->vm.sensors_rest)
/* The battery in millivolts, whenever measured. Inline, as rt_button() below: a call the port may as well make
 * itself. */
static inline void rt_battery(struct rcx_brick *k, u16 millivolts)
{
    k->vm.battery_mv = millivolts;
    ui_battery(k);
}

/* A debounced button edge. */
enum rt_button { RT_BUTTON_ONOFF = 0, RT_BUTTON_RUN, RT_BUTTON_VIEW, RT_BUTTON_PRGM };
static inline void rt_button(struct rcx_brick *k, u8 button, u8 down)
{
    ui_button(k, button, down);
}

#endif
