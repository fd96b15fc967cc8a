/* Placeholder: the display engine is owed (engine_pending counts its uses). */
#include "rcx.h"

void display_view(struct rcx *b, u8 view) { b->display.view = view; b->engine_pending++; }
void display_user(struct rcx *b, u8 precision, u8 src, u16 index)
{
    (void)precision; (void)src; (void)index; b->engine_pending++;
}
void display_tick(struct rcx *b) { (void)b; }
