/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The user interface of the brick (ui.h). Buttons act on their press, never on their release. Every press and
 * every command received (the IR layer sets vm.idle_reset, spec p. 35; so do PBAliveOrNot and PBPowerDownTime)
 * restarts the power-down timer.
 */
#include "runtime.h"
#include "hal.h"

/* View steps from whatever is shown (a program's own view included, which drops out) to the watch, then through
 * inputs 1-3 and outputs A-C and back to the watch, as firm0328 does (reference-firmware.md). */
static void next_view(struct rcx *b)
{
    u8 v = (u8)(b->display.view + 1);

    b->display.view = v > DISPLAY_OUTPUT_C ? DISPLAY_WATCH : v;
}

void ui_button(struct rcx_brick *k, u8 button, u8 down)
{
    struct rcx *b = &k->vm;

    if (!down)
        return;
    b->idle_reset = 1;
    if (button == RT_BUTTON_ONOFF) {
        k->ui.off = UI_OFF_ASKED;
        return;
    }
    if (button > RT_BUTTON_PRGM)
        return;
    if (button == RT_BUTTON_VIEW) {
        next_view(b);
    } else if (button == RT_BUTTON_RUN && !program_running(b)) { /* spec p. 98: "start 0" or "stop" */
        outputs_program_start(b);
        sched_start_task(b, 0);
    } else {
        if (button == RT_BUTTON_RUN) {
            sched_stop_all(b);
        } else { /* spec p. 98 "prgm N"; selecting stops a running program */
            u8 prog = (u8)(b->prog + 1);

            sched_select_program(b, prog < RCX_PROGRAMS ? prog : 0, 0);
        }
        outputs_program_stop(b);
    }
    sound_ui(b, 0); /* key click */
}

/* Every millisecond: the fields addressed from k each time, which costs less than a pointer set up for them, and the
 * milliseconds stored once. */
void ui_tick(struct rcx_brick *k)
{
    u16 ms = 0;

    if (k->vm.idle_reset) {
        k->vm.idle_reset = 0;
        k->ui.idle_min = 0;
    } else {
        ms = (u16)(k->ui.idle_ms + 1);
        if (ms >= UI_MINUTE_MS) {
            ms -= UI_MINUTE_MS; /* not 0: rt_skip() may have counted past the minute */
            if (k->vm.power_down_min && ++k->ui.idle_min >= k->vm.power_down_min)
                k->ui.off = UI_OFF_ASKED;
        }
    }
    k->ui.idle_ms = ms;
}

/* A new battery reading (every 64 ms on the brick). */
void ui_battery(struct rcx_brick *k)
{
    struct rcx *b = &k->vm;
    u8 low = k->ui.battery_low;

    if (low ? b->battery_mv > UI_BATTERY_OK_MV : b->battery_mv < UI_BATTERY_LOW_MV) {
        k->ui.battery_low = (u8)(low ^ 1);
        /* The mark flips with it: nothing else switches it (display_mark() would, at a cost in .high). */
        b->display.marks[DISPLAY_MARK_BATTERY >> 3] ^= (u8)(1u << (DISPLAY_MARK_BATTERY & 7));
    }
}

/*
 * Off (spec p. 98: all motors float) until On-Off is pressed again. Programs, variables and the datalog stay as they
 * are; the running program does not survive, and the watch starts again from 00:00 (reference-firmware.md). The
 * motors are left forward, braked, full power: what firm0328 reports after switching off. Switching off plays the
 * key click, and standby waits until it has been heard; switching on plays the double beep.
 */
void ui_poll(struct rcx_brick *k)
{
    struct rcx *b = &k->vm;
    u8 off;

    if (b->turn_off) {
        b->turn_off = 0; /* the machine only sets it when a power-down time is set */
        k->ui.off = UI_OFF_ASKED;
    }
    off = k->ui.off;
    /* A PBTurnOff from the host is acknowledged first: the reply and its echo have to be through. */
    if (!off || ir_busy(k))
        return;
    if (off == UI_OFF_ASKED) {
        k->ui.off = UI_OFF_CLICKING;
        sound_clear(b);
        sound_ui(b, 0);
    } else if (b->sound.count) {
        return;
    }
    /* Stopped at once, and again right before standby: a command may have started a task during the click. */
    sched_stop_all(b);
    outputs_init(b);
    if (off == UI_OFF_ASKED)
        return;
    k->ui.off = 0;
    hal_power_off(b); /* returns when switched on again */
    b->watch_ms = 0;
    b->watch = 0;
    sound_ui(b, 1);
    b->idle_reset = 1;
}
