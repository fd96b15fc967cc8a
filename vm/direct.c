/*
 * Direct commands: one command in, its reply out (spec pp. 12-97, reply lengths as nqc expects them,
 * host-tools.md §1). Framing, echo and the toggle bit belong to the IR layer; this is only the machine's answer.
 */
#include "rcx_string.h"
#include "rcx.h"

static const u8 unlock_key[5] = { 1, 3, 5, 7, 11 };
/* ROM 3.1 and firmware 3.28 ("3.2.8") so that host tools treat the brick as firm0328 (reference-firmware.md). */
static const u8 versions[8] = { 0x00, 0x03, 0x00, 0x01, 0x00, 0x03, 0x02, 0x08 };

/* The commands answered here, in the order of the D_* cases of vm_direct(): a dense switch is a jump table. */
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

/* Before a task's or subroutine's code goes: the task is stopped, or the tasks inside the subroutine are (a task
 * leaves a subroutine's code for good when it is stopped). */
static void stop_users(struct rcx *b, u8 is_task, u8 sub)
{
    u8 n;

    if (is_task) {
        sched_stop_task(b, sub);
        return;
    }
    for (n = 0; n < RCX_TASKS; n++) {
        struct rcx_task *t = &b->task[n];
        if (t->state != RCX_TASK_IDLE && t->sub != RCX_NO_SUB && (t->sub == sub || (t->has_ret && t->ret_sub == sub)))
            sched_stop_task(b, n);
    }
}

/* Deleting never touches code that is still being downloaded: the download stays active (reference-firmware.md). */
static void delete_obj(struct rcx *b, u8 obj)
{
    if (!(b->dl.active && b->dl.obj == obj))
        mem_delete(b, obj);
}

static u8 begin_download(struct rcx *b, u8 is_task, u8 n, u16 size)
{
    u8 obj;
    u16 room;

    if (b->dl.active) {            /* any new download, even a refused one, abandons the unfinished one: */
        b->dl.active = 0;          /* that slot ends up empty */
        mem_delete(b, b->dl.obj);
    }
    if (n >= (is_task ? RCX_TASKS : RCX_SUBS))
        return DL_BAD_NUMBER;
    obj = rcx_obj_sub(b->prog, n);
    if (is_task)
        obj = (u8)(obj + RCX_SUBS); /* rcx_obj_task() */
    room = mem_free(b);
    if (size > room && (u16)(size - room) > mem_obj_size(b, obj))
        return DL_NO_MEMORY;       /* refused: the old code stays as it was */
    stop_users(b, is_task, n);
    mem_resize(b, obj, 0);
    mem_resize(b, obj, size);      /* cannot fail: checked above */
    b->dl.active = 1;
    b->dl.obj = obj;
    b->dl.expect = 1;
    b->dl.last = 0xFFFF;
    b->dl.filled = 0;
    return DL_OK;
}

/* 0x45: seq(2) len(2) data(len) checksum(1), already checked to be complete. Blocks are numbered 1, ..., n, 0. */
static u8 continue_download(struct rcx *b, const u8 *cmd)
{
    u16 seq = RCX_LE16(cmd + 1), count = RCX_LE16(cmd + 3), i;
    u8 sum = 0;

    if (!b->dl.active)
        return DL_NOT_ACTIVE;
    for (i = 0; i < count; i++)
        sum = (u8)(sum + cmd[5 + i]);
    if (sum != cmd[5 + count])
        return DL_BLOCK_ERROR;
    if (seq) {
        if (seq == b->dl.last)
            return DL_OK;          /* a repeated block is acknowledged again, not written twice */
        if (seq != b->dl.expect)
            return DL_BLOCK_ERROR; /* out of order */
    }
    if (count > mem_obj_size(b, b->dl.obj) - b->dl.filled)
        return DL_BLOCK_ERROR;     /* more code than BeginOfTask/Sub announced */
    memcpy(b->arena + b->obj_start[b->dl.obj] + b->dl.filled, cmd + 5, count);
    b->dl.filled = (u16)(b->dl.filled + count);
    b->dl.last = seq;
    b->dl.expect++;
    if (seq == 0) {                /* the last block: the code may run from now on */
        b->dl.active = 0;
#if RCX_SWAN
        swan_download_done(b); /* the object's final size, and its slot's kind (vm/swan.c) */
#else
        mem_resize(b, b->dl.obj, b->dl.filled);
#endif
    }
    return DL_OK;
}

/*
 * addr is at least 0x8000 and addr + count does not pass 0xFFFF (vm_direct checks), so a byte below the arena is at
 * most 0x7FFF below it: its offset wraps to 0x8001 or more, past the arena like the bytes above it.
 */
RCX_STATIC_ASSERT(arena_offsets_wrap_past_it, RCX_ARENA_SIZE <= 0x8001u);
static u8 upload_ram(const struct rcx *b, u16 addr, u8 count, u8 *out)
{
    u16 off = (u16)(addr - b->arena_addr);
    u8 i;

    for (i = 0; i < count; i++, off++)
        out[i] = off < RCX_ARENA_SIZE ? b->arena[off] : 0;
    return count;
}

u8 vm_direct(struct rcx *b, const u8 *cmd, u8 len, u8 *reply)
{
    u8 op = (u8)(cmd[0] & ~RCX_TOGGLE);
    u8 flags = rcx_opflags[rcx_op_index(op)];
    u8 n = 0, i, c;

#if RCX_SWAN
    if (op == RCX_SW_MSG_WORD && len >= 4)
        remote_param_received(b, cmd); /* a Swan message's parameter, ahead of it (vm/remote.h): no reply */
#endif
    if (!(flags & (RCX_DIRECT << 3)))
        return 0;                  /* unknown or program-only: not answered */
    if (op != RCX_OP_CONTINUE_DL && len < 1 + rcx_op_params(op))
        return 0;                  /* truncated */
    reply[0] = (u8)~cmd[0];
    for (c = 0; c < sizeof direct_ops && direct_ops[c] != op; c++)
        ;

    switch (c) {
    case D_MEMMAP:
        n = mem_memmap(b, reply + 1);
        break;
    case D_DELETE_ALL_TASKS:
    case D_DELETE_TASK:
    case D_DELETE_ALL_SUBS:
    case D_DELETE_SUB: {
        /* Tasks are stopped, and tasks inside a subroutine, before their code goes. */
        u8 tasks = c <= D_DELETE_TASK;
        u8 limit = tasks ? RCX_TASKS : RCX_SUBS, obj;

        i = 0;
        if (op & 7) {              /* one of them: nothing when out of range */
            i = cmd[1];
            if (i < limit)
                limit = (u8)(i + 1);
        }
        for (; i < limit; i++) {
            stop_users(b, tasks, i);
            obj = rcx_obj_sub(b->prog, i);
            if (tasks)
                obj = (u8)(obj + RCX_SUBS); /* rcx_obj_task() */
            delete_obj(b, obj);
        }
        break;
    }
    case D_BATTERY:
    case D_POLL: {
        u16 v = c == D_POLL ? (u16)source_poll(b, cmd) : b->battery_mv;
        reply[1] = (u8)v;
        reply[2] = (u8)(v >> 8);
        n = 2;
        break;
    }
    case D_UPLOAD_RAM: {
        u16 addr = RCX_LE16(cmd + 1);
        /* Only the start address is checked; out of range or over 150 bytes: no reply at all. */
        if (addr < 0x8000u || addr >= 0xFD80u || cmd[3] > 150)
            return 0;
        n = upload_ram(b, addr, cmd[3], reply + 1);
        break;
    }
    case D_UPLOAD_DATALOG: {
        s16 bytes = datalog_upload(b, RCX_LE16(cmd + 1), RCX_LE16(cmd + 3), reply + 1);
        if (bytes < 0)
            return 0;
        n = (u8)bytes;
        break;
    }
    case D_UNLOCK_BRICK:
    case D_BOOT_MODE:
        if (memcmp(cmd + 1, unlock_key, sizeof unlock_key) == 0) {
            if (c == D_BOOT_MODE) {
                b->boot_mode = 1;  /* the runtime answers, then hands the brick to the ROM */
            } else {
                memcpy(reply + 1, versions, sizeof versions);
                n = sizeof versions;
            }
        }                          /* a wrong key gets a bare acknowledgement */
        break;
    case D_BEGIN_TASK:
    case D_BEGIN_SUB:
        reply[1] = begin_download(b, c == D_BEGIN_TASK, cmd[2], RCX_LE16(cmd + 4));
        n = 1;
        break;
    case D_CONTINUE_DL:
        /* A block shorter than its header announces is a truncated packet: no reply, like any other. */
        if (len < 6 || RCX_LE16(cmd + 3) > (u16)(len - 6))
            return 0;
        reply[1] = continue_download(b, cmd);
        n = 1;
        break;
    case D_BEGIN_FIRMWARE:
    case D_UNLOCK_FIRMWARE:
        return 0;                  /* only the ROM's download mode answers these */
    case D_REMOTE:
        remote_command(b, RCX_LE16(cmd + 1));
        return 0;
    default:
        /* A program started from the host (nqc -run) begins as one started with Run does (reference-firmware.md). */
        if (op == RCX_OP_START_TASK && !cmd[1])
            outputs_program_start(b);
        ops_exec(b, NULL, cmd);
        /* Reply class 0: no reply (InternMessage, SendUARTData); 1: the opcode alone; 2: a status byte, which only
         * SetDatalog makes 1, when memory is short (reference-firmware.md). */
        c = (u8)(flags >> 5);
        if (!c)
            return 0;
        reply[1] = op == RCX_OP_SET_DATALOG && !b->log_size;
        n = (u8)(c - 1);
        break;
    }
    return (u8)(1 + n);
}
