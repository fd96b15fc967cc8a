/* Placeholder: remote control and IR transmission are owed (engine_pending counts their uses). */
#include "rcx.h"

void remote_command(struct rcx *b, u16 bits) { (void)bits; b->engine_pending++; }
void remote_send_message(struct rcx *b, u8 message) { (void)message; b->engine_pending++; }
void remote_send_uart(struct rcx *b, u8 start, u8 size) { (void)start; (void)size; b->engine_pending++; }
