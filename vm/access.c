/* Placeholder: access control is owed (engine_pending counts its uses); access is always granted for now. */
#include "rcx.h"

void access_enter(struct rcx *b, struct rcx_task *t, u8 resources, u16 target)
{
    (void)t; (void)resources; (void)target; b->engine_pending++;
}
void access_exit(struct rcx *b, struct rcx_task *t) { (void)t; b->engine_pending++; }
