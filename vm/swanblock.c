/* SPDX-License-Identifier: MPL-2.0 */
/*
 * A download's blocks, written and looked at for Swan code as they come (vm/direct.c's ContinueDL).
 *
 * A Swan program is one whose code has a Swan opcode, or a test (SCheckDo/LCheckDo) of source 43 or 44: NQC's Swan
 * code reaches every variable it compiles through those (swan-target.md 4). Each block's instructions are looked at
 * as it comes (the last block's all, a truncated one too), walked from the object's start instruction by instruction,
 * until the first Swan code: the end of a download then has no walk of its slot to make, which on a full slot held
 * the main loop 75 ms (issue 21 item 3, docs/timing.md).
 *
 * On the brick swan_block() is drivers/h8300/swanblock.S: gcc 3.4's code for the C below took some 2 500 states an
 * instruction (a linear search of Swan's 27 rows, rcx_swan_find()), 31 ms for a block of 200 one-byte byte codes,
 * where the assembler tests one bit of a 32-byte map of Swan's opcodes, in fewer bytes. The C here is its reference
 * (tests/drivers/test_h8swan.c compares the two).
 */
#include "rcx_string.h"
#include "rcx.h"
#include "sources.h"

#if RCX_SWAN
#ifdef __H8300__
#include <stddef.h>
#include "swanblock.h"
RCX_STATIC_ASSERT(sb_fields, offsetof(struct rcx, obj_start) == 0 && offsetof(struct rcx, dl.active) == SB_DL_ACTIVE
                             && offsetof(struct rcx, dl.obj) == SB_DL_OBJ && offsetof(struct rcx, dl.last) == SB_DL_LAST
                             && offsetof(struct rcx, dl.filled) == SB_DL_FILLED
                             && offsetof(struct rcx, swan) == SB_SWAN && offsetof(struct rcx, dl_scan) == SB_DL_SCAN
                             && offsetof(struct rcx, dl_swan) == SB_DL_SWAN && offsetof(struct rcx, arena) == SB_ARENA
                             && RCX_SLOT_OBJS == SB_SLOT_OBJS);
#else
RCX_STATIC_ASSERT(checks, (RCX_OP_SCHECK_DO & 0xE7) == 0x85 && (RCX_OP_LCHECK_DO & 0xE7) == 0x85);
#define SWAN_SOURCE(s) ((u8)(((s) & 0x3F) - RCX_SRC_GLOBAL) <= 1) /* 43 or 44 */

/* The block of `count` bytes at `src` is written first; the last block ends the download. */
void swan_block(struct rcx *b, const u8 *src, u16 count)
{
    u8 *code = b->arena + b->obj_start[b->dl.obj], *end = code + b->dl.filled, *whole = end, op;
    const u8 *p = code + b->dl_scan;
    const u16 *at;

    memcpy(end - count, src, count);
    if (count == b->dl.filled) {       /* the first block */
        p = code;
        b->dl_swan = 0;
    }
    if (b->dl.last)                    /* more blocks to come: an instruction (8 bytes at most) that starts in the */
        whole -= 7;                    /* last 7 may have the rest of its bytes in the next */
    if (!b->dl_swan) {                 /* (Swan code found: nothing more to look for until the next download) */
        for (; p < whole; p += 1 + rcx_op_params(op)) {
            op = *p;                   /* toggle bit folded */
            if (rcx_swan_find(op)
                || ((u8)(op & 0xE7) == 0x85 && p + 2 < end && (SWAN_SOURCE(p[1]) || SWAN_SOURCE(p[2])))) {
                b->dl_swan = 1;
                break;
            }
        }
        b->dl_scan = (u16)(p - code);
    }
    if (b->dl.last)
        return;
    /* The last block: the code may run from now on, its final size, then its slot's kind. The slot's other objects
     * are not walked again: a slot that was a Swan program stays one as long as it has other code (a program's
     * objects are downloaded into an emptied slot, nqc -d, host-tools.md, and each one's kind is known as it comes). */
    b->dl.active = 0;
    mem_resize(b, b->dl.obj, 1, b->dl.filled);
    op = (u8)(b->dl.obj / RCX_SLOT_OBJS); /* the slot */
    at = &b->obj_start[(u8)(op * RCX_SLOT_OBJS)]; /* its first object */
    b->swan[op] = b->dl_swan || (b->swan[op] && (u16)(at[RCX_SLOT_OBJS] - at[0]) != b->dl.filled);
}
#endif /* __H8300__ */
#endif /* RCX_SWAN */
