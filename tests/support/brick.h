/* SPDX-License-Identifier: MPL-2.0 */
/* Test harness: a brick driven only through the machine's public interface. */
#ifndef TEST_BRICK_H
#define TEST_BRICK_H

#include "rcx.h"
#include "sources.h"

/* Arena address used by host tests; any value from 0x8000 keeps UploadRam and the memory map realistic. */
#define TEST_ARENA_ADDR 0x9000u

/* A freshly powered-on brick (heap-allocated: the struct holds the whole program memory), with a recording
 * hal.h behind it (fake_hal.h, fake_hal_of(b)). */
struct rcx *brick_new(void);
void brick_free(struct rcx *b);

/* Send one direct command; returns the reply length (0 = no reply), reply copied into `reply` if non-NULL. */
unsigned brick_cmd(struct rcx *b, const u8 *cmd, unsigned len, u8 *reply);

/* Download code into task or subroutine n of the selected slot through 0x25/0x35 and 0x45 blocks of 20 bytes,
 * exactly as nqc does. Returns the first non-zero status seen, 0 on success. */
int brick_download(struct rcx *b, int is_task, u8 n, const u8 *code, unsigned len);

/* Advance simulated time by `ms` milliseconds, executing up to `per_ms` byte codes per millisecond. */
void brick_run_ms(struct rcx *b, unsigned ms, unsigned per_ms);

/* Run until no task is running or waiting, at most `max_ms`; returns the milliseconds used, or -1 on timeout. */
long brick_run_until_idle(struct rcx *b, unsigned max_ms, unsigned per_ms);

/* A byte-for-byte copy of the whole machine, to compare with later (brick_free_copy releases it). */
struct rcx *brick_copy(const struct rcx *b);
void brick_free_copy(struct rcx *copy);

/* Start task n of the selected slot, as `nqc -run` does for task 0. */
void brick_start(struct rcx *b, u8 n);

/* ENTER EV and ENTER AC made by task t's byte codes, LEnterEventCheck of a constant MON and EnterAccessControl, whose
 * label is the pc `lbl` (access_enter() gets it from the interpreter and does not read the distance). */
static inline void brick_enter_ev(struct rcx *b, struct rcx_task *t, u16 mon, u16 lbl)
{
    const u8 ins[6] = { RCX_OP_LENTER_EVENT, RCX_SRC_CONST, (u8)mon, (u8)(mon >> 8), 0, 0 };
    access_enter(b, t, ins, lbl);
}
static inline void brick_enter_ac(struct rcx *b, struct rcx_task *t, u8 res, u16 lbl)
{
    const u8 ins[4] = { RCX_OP_ENTER_ACCESS, res, 0, 0 };
    access_enter(b, t, ins, lbl);
}

#endif
