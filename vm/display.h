/* The LCD (spec pp. 51, 66, 97; source 14; rcx-hardware.md §3.6): views composed into the 9-byte segment image. */
#ifndef RCX_DISPLAY_H
#define RCX_DISPLAY_H

#include "rcx_types.h"

struct rcx;

struct rcx_display {
    u8 view;   /* 0 watch, 1-3 inputs, 4-6 outputs, 7 user selection */
};

void display_view(struct rcx *b, u8 view);                          /* SelectDisplay, View button, SetWatch */
void display_user(struct rcx *b, u8 precision, u8 src, u16 index);  /* ViewSourceValue */
void display_tick(struct rcx *b);                                   /* every 1 ms */

#endif
