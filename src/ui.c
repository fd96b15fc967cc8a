/*
 * The user interface of the brick (ui.h). Buttons act on their press, never on their release. Every press and
 * every command received (the IR layer sets vm.idle_reset, spec p. 35; so do PBAliveOrNot and PBPowerDownTime)
 * restarts the power-down timer.
 */
#include "rcx_string.h"
#include "runtime.h"
#include "hal.h"

RCX_STATIC_ASSERT(watch_is_0, DISPLAY_WATCH == 0);

/* Nothing idle yet, not switching off, View coming back to the watch, no battery mark. */
void ui_init(struct rcx_brick *k)
{
    memset(&k->ui, 0, sizeof k->ui);
}

/* View steps through inputs 1-3 and outputs A-C, then back to the view it started from (the watch, or a
 * program's own choice), so that looking around does not lose the display a program asked for. */
static void next_view(struct rcx_brick *k)
{
    u8 v = k->vm.display.view;

    if (v == DISPLAY_OUTPUT_C) {
        v = k->ui.home_view;
    } else if (v >= DISPLAY_INPUT_1 && v < DISPLAY_OUTPUT_C) {
        v++;
    } else {
        k->ui.home_view = v;
        v = DISPLAY_INPUT_1;
    }
    display_view(&k->vm, v);
}

void ui_button(struct rcx_brick *k, u8 button, u8 down)
{
    struct rcx *b = &k->vm;

    if (!down)
        return;
    b->idle_reset = 1;
    if (button == RT_BUTTON_ONOFF) {
        k->ui.off = 1;
        return;
    }
    if (button > RT_BUTTON_PRGM)
        return;
    if (button == RT_BUTTON_VIEW) {
        next_view(k);
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

void ui_tick(struct rcx_brick *k)
{
    struct rcx *b = &k->vm;
    struct rcx_ui *ui = &k->ui;

    if (b->idle_reset) {
        b->idle_reset = 0;
        ui->idle_ms = 0;
        ui->idle_min = 0;
    } else if (++ui->idle_ms >= UI_MINUTE_MS) {
        ui->idle_ms = 0;
        if (b->power_down_min && ++ui->idle_min >= b->power_down_min)
            ui->off = 1;
    }
    if (b->turn_off) {
        b->turn_off = 0; /* the machine only sets it when a power-down time is set */
        ui->off = 1;
    }
    if (ui->battery_low ? b->battery_mv > UI_BATTERY_OK_MV : b->battery_mv < UI_BATTERY_LOW_MV) {
        ui->battery_low ^= 1;
        display_mark(b, DISPLAY_MARK_BATTERY, ui->battery_low);
    }
}

/*
 * Off (spec p. 98: all motors float) until On-Off is pressed again. Programs, variables, datalog and watch stay as
 * they are; the running program does not survive. The motors are left forward, float, full power, which is also
 * the state p. 98 asks for when the brick comes on again.
 */
void ui_poll(struct rcx_brick *k)
{
    struct rcx *b = &k->vm;

    /* A PBTurnOff from the host is acknowledged first: the reply and its echo have to be through. */
    if (!k->ui.off || !ir_idle(k))
        return;
    k->ui.off = 0;
    sched_stop_all(b);
    sound_clear(b);
    outputs_init(b);
    outputs_changed(b);
    hal_power_off(b); /* returns when switched on again */
    b->idle_reset = 1;
}
