/* Placeholder until the IR issue: bytes are ignored. */
#include "runtime.h"

void ir_init(struct rcx_brick *k) { (void)k; }
void ir_byte(struct rcx_brick *k, u8 byte, u8 error) { (void)k; (void)byte; (void)error; }
void ir_tick(struct rcx_brick *k) { (void)k; }
void ir_poll(struct rcx_brick *k) { (void)k; }
