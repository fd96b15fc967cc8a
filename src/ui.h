/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The brick's own user interface: the On-Off, Run, View and Prgm buttons (spec p. 98 for the motors), the
 * power-down timer (spec p. 35), PBTurnOff, and the low-battery mark.
 */
#ifndef RCX_UI_H
#define RCX_UI_H

#include "rcx_types.h"

struct rcx_brick;

#define UI_MINUTE_MS 60000u
#define UI_BATTERY_LOW_MV 6300u  /* battery mark on below this (brickOS's "low", rcx-hardware.md §3.4) */
#define UI_BATTERY_OK_MV 6700u   /* and off again only above this ("normal"): no flicker at the threshold */

enum { UI_ON = 0, UI_OFF_ASKED, UI_OFF_CLICKING /* the key click plays, then standby */ };

struct rcx_ui {
    u16 idle_ms;     /* milliseconds into the current minute without a command or a button */
    u8 idle_min;     /* whole minutes without one */
    u8 off;          /* UI_OFF_*: switching off (On-Off, PBTurnOff, power-down time), done by ui_poll */
    u8 battery_low;  /* the mark is on */
};

/* Once rt_init() has cleared struct rcx_ui (nothing idle yet, not switching off, no battery mark): the double beep,
 * which firm0328 plays when it starts (its own request, not the ROM's: issue 15, observed on the emulated brick), as
 * when the brick is switched on. A macro: rt_init() is its one user. */
#define ui_init(k) sound_ui(&(k)->vm, 1)
void ui_button(struct rcx_brick *k, u8 button, u8 down);
void ui_tick(struct rcx_brick *k);
void ui_battery(struct rcx_brick *k); /* rcx.battery_mv was measured again: the low-battery mark */
void ui_poll(struct rcx_brick *k); /* act on the machine's power requests (PBTurnOff, switching off), standby on
                                      the brick; the runtime calls it while rcx_ui.off or rcx.turn_off is set */

#endif
