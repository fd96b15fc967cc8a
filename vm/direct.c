/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Direct commands: one command in, its reply out (spec pp. 12-97, reply lengths as nqc expects them,
 * host-tools.md §1). Framing, echo and the toggle bit belong to the IR layer; this is only the machine's answer.
 */
#include "rcx_string.h"
#include "rcx.h"

static const u8 unlock_key[5] = { 1, 3, 5, 7, 11 };
/* ROM 3.1 and firmware 3.28 ("3.2.8") so that host tools treat the brick as firm0328 (reference-firmware.md). */
static const u8 versions[8] = { 0x00, 0x03, 0x00, 0x01, 0x00, 0x03, 0x02, 0x08 };

/* The commands only the host sends (RCX_DIRECT alone), as vm_direct() numbers them: direct_ops[D_x] is D_x's opcode,
 * and the dense switch on the number is a jump table. */
enum {
    D_MEMMAP, D_BATTERY, D_DELETE_ALL_TASKS, D_DELETE_TASK, D_DELETE_ALL_SUBS, D_DELETE_SUB, D_POLL, D_UPLOAD_RAM,
    D_UPLOAD_DATALOG, D_UNLOCK_BRICK, D_BEGIN_TASK, D_BEGIN_SUB, D_CONTINUE_DL, D_BOOT_MODE, D_BEGIN_FIRMWARE,
    D_UNLOCK_FIRMWARE, D_REMOTE
};
static const u8 direct_ops[] = {
    RCX_OP_MEMMAP, RCX_OP_BATTERY, RCX_OP_DELETE_ALL_TASKS, RCX_OP_DELETE_TASK, RCX_OP_DELETE_ALL_SUBS,
    RCX_OP_DELETE_SUB, RCX_OP_POLL, RCX_OP_UPLOAD_RAM, RCX_OP_UPLOAD_DATALOG, RCX_OP_UNLOCK_BRICK, RCX_OP_BEGIN_TASK,
    RCX_OP_BEGIN_SUB, RCX_OP_CONTINUE_DL, RCX_OP_BOOT_MODE, RCX_OP_BEGIN_FIRMWARE, RCX_OP_UNLOCK_FIRMWARE,
    RCX_OP_REMOTE
};

enum { DL_OK = 0, DL_NO_MEMORY = 1, DL_BAD_NUMBER = 2, DL_BLOCK_ERROR = 3, DL_NOT_ACTIVE = 6 };

/*
 * Tasks and subroutines are named here by their place among the selected slot's code objects (rcx.h): subroutine n
 * is n, task n is RCX_SUBS + n, and rcx_obj_sub(b->prog, id) its code object either way.
 *
 * Before a task's or subroutine's code goes (mem_delete, vm/progmem.c): the task is stopped, or the tasks inside the
 * subroutine are (a task leaves a subroutine's code for good when it is stopped).
 */
static void release(struct rcx *b, u8 id)
{
    u8 n;

    /* The task itself (id - RCX_SUBS wraps past every task for a subroutine), or every task inside the subroutine
     * (a task's sub and ret_sub are subroutines or RCX_NO_SUB, never a task's id). A task in its own body
     * (RCX_NO_SUB, no return address) never matches a subroutine, and stopping an idle task changes nothing. */
    for (n = 0; n < RCX_TASKS; n++) {
        const struct rcx_task *t = &b->task[n];

        if (n == (u8)(id - RCX_SUBS) || t->sub == id || (t->has_ret && t->ret_sub == id))
            sched_stop_task(b, n);
    }
}

/* 0x25, 0x35: opcode, 0, number, 0, size(2). */
static u8 begin_download(struct rcx *b, const u8 *cmd)
{
    u8 id = cmd[2], n = RCX_SUBS;

    if (!(cmd[0] & 0x10)) {        /* BeginOfTask 0x25, not BeginOfSub 0x35 */
        n = RCX_TASKS;
        id = (u8)(id + RCX_SUBS);
    }
    if (cmd[2] >= n)
        id = 0xFF;
    if (b->dl.active) {            /* any new download, even a refused one, abandons the unfinished one: */
        b->dl.active = 0;          /* that slot ends up empty */
        mem_resize(b, b->dl.obj, 1, 0);
    }
    if (id == 0xFF)
        return DL_BAD_NUMBER;
    b->dl.obj = rcx_obj_sub(b->prog, id); /* only read while dl.active */
    /* mem_resize() refuses exactly what does not fit, and then changes nothing: the old code stays as it was. Once
     * it fits, the old code goes (its tasks stopped): its bytes are overwritten by the blocks (one resize, one move of
     * the memory). */
    if (!mem_resize(b, b->dl.obj, 1, RCX_LE16(cmd + 4)))
        return DL_NO_MEMORY;
    release(b, id);
    b->dl.active = 1;
    b->dl.expect = 1;
    b->dl.last = 0xFFFF;
    b->dl.filled = 0;
    return DL_OK;
}

/* 0x45: seq(2) len(2) data(len) checksum(1), already checked to be complete. Blocks are numbered 1, ..., n, 0. */
static u8 continue_download(struct rcx *b, const u8 *cmd)
{
    u16 seq = RCX_LE16(cmd + 1), count = RCX_LE16(cmd + 3), *start, at;
    const u8 *p = cmd + 5, *end = p + count;
    u8 sum = 0;

    if (!b->dl.active)
        return DL_NOT_ACTIVE;
    while (p != end)
        sum = (u8)(sum + *p++);
    if (sum != *end)
        return DL_BLOCK_ERROR;
    if (seq) {
        if (seq == b->dl.last)
            return DL_OK;          /* a repeated block is acknowledged again, not written twice */
        if (seq != b->dl.expect)
            return DL_BLOCK_ERROR; /* out of order */
    }
    start = &b->obj_start[b->dl.obj];
    at = (u16)(start[0] + b->dl.filled);
    if (count > (u16)(start[1] - at))
        return DL_BLOCK_ERROR;     /* more code than BeginOfTask/Sub announced */
    b->dl.filled = (u16)(b->dl.filled + count);
    b->dl.last = seq;
    b->dl.expect = (u16)(seq + 1); /* (after the last block, 0, nothing more is expected) */
#if RCX_SWAN
    swan_block(b, end - count, count); /* written, looked at for Swan code; the last ends the download (swanblock.c) */
#else
    memcpy(b->arena + at, end - count, count);
    if (!b->dl.last) {             /* the last block: the code may run from now on */
        b->dl.active = 0;
        mem_resize(b, b->dl.obj, 1, b->dl.filled);
    }
#endif
    return DL_OK;
}

/*
 * addr is at least 0x8000 and addr + count does not pass 0xFFFF (vm_direct checks), so a byte below the arena is at
 * most 0x7FFF below it: its offset wraps to 0x8001 or more, past the arena like the bytes above it.
 */
RCX_STATIC_ASSERT(single_deletes_odd, (D_DELETE_TASK & 1) && (D_DELETE_SUB & 1) && !(D_DELETE_ALL_TASKS & 1)
                                      && !(D_DELETE_ALL_SUBS & 1));
RCX_STATIC_ASSERT(arena_offsets_wrap_past_it, RCX_ARENA_SIZE <= 0x8001u);
static u8 upload_ram(const struct rcx *b, u16 addr, u8 count, u8 *out)
{
    u16 off = (u16)(addr - b->arena_addr);
    u8 i;

    for (i = 0; i < count; i++, off++)
        out[i] = off < RCX_ARENA_SIZE ? b->arena[off] : 0;
    return count;
}

u8 vm_direct(struct rcx *b, const u8 *cmd, u8 len, u8 *out)
{
    u8 op = (u8)(cmd[0] & ~RCX_TOGGLE);
    u8 flags = rcx_opflags[rcx_op_index(op)];
    u8 c;

#if RCX_SWAN
    if (op == RCX_SW_MSG_WORD && len >= 4)
        remote_param_received(b, cmd); /* a Swan message's parameter, ahead of it (vm/remote.h): no reply */
#endif
    if (!(flags & (RCX_DIRECT << 3)))
        return 0;                  /* unknown or program-only: not answered */
    if (len <= (flags & 7))
        return 0;                  /* truncated (ContinueDL's 5: its header) */
    *out++ = (u8)~cmd[0];          /* the reply's opcode; out is then the rest of the reply */
    for (c = 0; c < sizeof direct_ops && direct_ops[c] != op; c++)
        ;

    /* Each case returns the reply's length, its opcode included (0: no reply). Their order is the one that leaves
     * the fewest branches too far for the H8's short ones (measured). */
    switch (c) {
    default: /* a command programs have too (RCX_DIRECT | RCX_PROGRAM) */
        /* A program started from the host (nqc -run) begins as one started with Run does (reference-firmware.md). */
        if (op == RCX_OP_START_TASK && !cmd[1])
            outputs_program_start(b);
        ops_exec(b, NULL, cmd);
        /* Reply class 0: no reply (InternMessage, SendUARTData); 1: the opcode alone; 2: a status byte, which only
         * SetDatalog makes 1, when memory is short (reference-firmware.md). The byte is written whatever the class:
         * the reply's length decides whether it goes out. */
        out[0] = op == RCX_OP_SET_DATALOG && !b->log_size;
        return (u8)(flags >> 5);
    case D_DELETE_ALL_TASKS:
    case D_DELETE_TASK:
    case D_DELETE_ALL_SUBS:
    case D_DELETE_SUB: {
        u8 id = 0, n = RCX_SUBS;    /* all the subroutines, or all the tasks */

        if (c <= D_DELETE_TASK) {
            id = RCX_SUBS;
            n = RCX_TASKS;
        }
        if (c & 1) {               /* one of them: D_DELETE_TASK, D_DELETE_SUB */
            if (cmd[1] >= n)
                return 1;          /* out of range: nothing */
            id = (u8)(id + cmd[1]);
            n = 1;
        }
        c = n;
        do
            release(b, (u8)(id + --n));
        while (n);
        mem_delete(b, id, c);      /* all at once: one move of the memory (vm/progmem.c) */
        return 1;
    }
    case D_UNLOCK_BRICK:
    case D_BOOT_MODE:
        if (memcmp(cmd + 1, unlock_key, sizeof unlock_key))
            return 1;              /* a wrong key gets a bare acknowledgement */
        if (op == RCX_OP_BOOT_MODE) {
            b->boot_mode = 1;      /* the runtime answers, then hands the brick to the ROM */
            return 1;
        }
        memcpy(out, versions, sizeof versions);
        return 1 + sizeof versions;
    case D_BEGIN_TASK:
    case D_BEGIN_SUB:
        out[0] = begin_download(b, cmd);
        return 2;
    case D_CONTINUE_DL:
        /* A block shorter than its header announces is a truncated packet: no reply, like any other. */
        if (RCX_LE16(cmd + 3) > (u16)(len - 6))
            return 0;
        out[0] = continue_download(b, cmd);
        return 2;
    case D_UPLOAD_DATALOG: {
        s16 bytes = datalog_upload(b, RCX_LE16(cmd + 1), RCX_LE16(cmd + 3), out);
        return bytes < 0 ? 0 : (u8)(1 + bytes);
    }
    case D_UPLOAD_RAM: {
        u16 addr = RCX_LE16(cmd + 1);
        /* Only the start address is checked; out of range or over 150 bytes: no reply at all. */
        if (addr < 0x8000u || addr >= 0xFD80u || cmd[3] > 150)
            return 0;
        return (u8)(1 + upload_ram(b, addr, cmd[3], out));
    }
    case D_MEMMAP:
        return (u8)(1 + mem_memmap(b, out));
    case D_BEGIN_FIRMWARE:
    case D_UNLOCK_FIRMWARE:
        return 0;                  /* only the ROM's download mode answers these */
    case D_REMOTE:
        remote_command(b, RCX_LE16(cmd + 1));
        return 0;
    case D_BATTERY:
    case D_POLL: {
        u16 v = c == D_POLL ? (u16)source_poll(b, cmd) : b->battery_mv;
        out[0] = (u8)v;
        out[1] = (u8)(v >> 8);
        return 3;
    }
    }
}
