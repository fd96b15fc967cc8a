/* The brick's own user interface: On-Off, Run, View and Prgm buttons, power-down timer, low battery, standby. */
#ifndef RCX_UI_H
#define RCX_UI_H

#include "rcx_types.h"

struct rcx_brick;

struct rcx_ui {
    u8 placeholder; /* defined by the firmware issue */
};

void ui_init(struct rcx_brick *k);
void ui_button(struct rcx_brick *k, u8 button, u8 down);
void ui_tick(struct rcx_brick *k);
void ui_poll(struct rcx_brick *k); /* act on the machine's power requests (turn off, boot mode) */

#endif
