/* Placeholder until the firmware issue: buttons are ignored. */
#include "runtime.h"

void ui_init(struct rcx_brick *k) { (void)k; }
void ui_button(struct rcx_brick *k, u8 button, u8 down) { (void)k; (void)button; (void)down; }
void ui_tick(struct rcx_brick *k) { (void)k; }
void ui_poll(struct rcx_brick *k) { (void)k; }
