/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Shared by the fuzzers: a brick populated with known code in every slot and a datalog, and the invariants
 * checked after every input. A violated invariant aborts with a message, which libFuzzer reports as a crash.
 */
#ifndef FUZZ_COMMON_H
#define FUZZ_COMMON_H

#include <stddef.h>
#include "brick.h"

#define FUZZ_LOG_ENTRIES 12  /* datalog made by fuzz_populate, with FUZZ_LOGGED points in it */
#define FUZZ_LOGGED 5

struct fuzz_snapshot {
    u8 code[RCX_OBJS][64];   /* first bytes of every code object (populated objects are shorter) */
    u16 size[RCX_OBJS];
    u8 log[3 * (FUZZ_LOG_ENTRIES + 1)];
    u16 log_count, log_size;
};

/* A fresh brick with a task or sub of known bytes in most objects of every slot, and a datalog. */
struct rcx *fuzz_populate(void);

/* The same contents put into an existing, freshly initialised machine. */
void fuzz_fill(struct rcx *b);

void fuzz_snapshot(const struct rcx *b, struct fuzz_snapshot *s);

/* Abort unless every object not marked in `touched` is byte-identical to the snapshot. */
void fuzz_check_untouched(const struct rcx *b, const struct fuzz_snapshot *s, const u8 *touched);

/* Abort unless the datalog is exactly as in the snapshot. */
void fuzz_check_log(const struct rcx *b, const struct fuzz_snapshot *s);

/* Abort unless the memory map reply agrees with the arena and the task states are consistent. */
void fuzz_check_machine(struct rcx *b);

void fuzz_fail(const char *what);

#endif
