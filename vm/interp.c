/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The interpreter: byte codes of the running tasks in round-robin order, one per task and pass of the scheduler.
 *
 * The byte codes that jump or end the code live here (jumps, loop checks, tests, entering monitoring and
 * access-control regions, the end of a subroutine); every other one runs in ops.c, with the direct commands. Code is
 * untrusted: an instruction that runs past the end of its code object, or a jump that lands outside it, stops the
 * task instead of reading foreign memory.
 */
#include "rcx.h"
#include "sources.h"

/* Relations of SCheckDo/LCheckDo (spec p. 93): bit 0 (a < b), 1 (a == b) or 2 (a > b) of each row holds.
 * The jump is taken when the comparison FAILS. */
static const u8 relation[4] = { 4, 1, 2, 5 };

/* EndOfSub, explicit or by running off the end of the code (nqc does not append 0xF6): a subroutine returns, a task
 * ends; so does a subroutine without a return address (spec p. 26: something has gone wrong). */
static void end_of_code(struct rcx *b, struct rcx_task *t)
{
    if (t->sub != RCX_NO_SUB) {
        events_sub_returned(b, t);
        if (t->has_ret) {
            t->has_ret = 0;
            t->sub = t->ret_sub;
            t->pc = t->ret_pc;
            return;
        }
    }
    sched_stop(b, t);
}

/*
 * The program-only byte codes run_slow() handles itself, found by a search (a switch on the sparse opcodes would
 * cost the H8/300 a tree of long branches), the commonest first. All but the last carry a distance, in pairs of a
 * short (even index) and a long form; dist_at gives its field's offset per pair. Each distance counts from the first
 * byte of its own field (spec p. 11):
 *   0-1   forward unsigned 8 bits, or signed 16 bits
 *   2-3   forward, unsigned 8 or 16 bits
 *   4-11  sign-magnitude: 7 bits (+ 8 more in a second byte), bit 7 of the first byte = backwards
 */
#define OUTSIDE 0xFFFFu /* negative as an s16, unlike any offset in a code object: the one test for "outside" */
RCX_STATIC_ASSERT(offsets_positive, RCX_ARENA_SIZE < 0x8000u);
#define NOT_AN_OP 0x08 /* has the toggle bit: no opcode reaches the search with it */
static const u8 control[] = {
    RCX_OP_SCHECK_DO, RCX_OP_LCHECK_DO,
    RCX_OP_SCHECK_LOOP, RCX_OP_LCHECK_LOOP,
    RCX_OP_SJUMP, RCX_OP_LJUMP,
    RCX_OP_SDEC_JUMP_LTZ, RCX_OP_LDEC_JUMP_LTZ,
    RCX_OP_SENTER_EVENT, RCX_OP_LENTER_EVENT,
    NOT_AN_OP, RCX_OP_ENTER_ACCESS,
    RCX_OP_END_OF_SUB,
};
static const u8 dist_at[6] = { 6, 1, 1, 2, 4, 2 };
enum { C_CHECK_DO = 0, C_CHECK_LOOP = 2, C_JUMP = 4, C_DEC = 6, C_ENTER = 8, C_ACCESS = 11, C_END_OF_SUB };

/* Where the code task n executes starts: its code object's entry in b->obj_start (the next entry is its end). */
#define OBJECT_OF(b, t, n) \
    (&(b)->obj_start[(u8)((b)->prog * RCX_SLOT_OBJS + ((t)->sub == RCX_NO_SUB ? (n) + RCX_SUBS : (t)->sub))])

/*
 * Execute the byte code at the pc of task t, whose code object is at OBJECT_OF(), or end its code: the task ends, or
 * returns from its subroutine. An instruction that runs past the end of the code, or a jump that lands outside it,
 * stops the task.
 */
#ifdef __H8300__
void run_slow(struct rcx *b, struct rcx_task *t, const u16 *at); /* called by drivers/h8300/runfast.S */
#else
static
#endif
__attribute__((noinline)) void run_slow(struct rcx *b, struct rcx_task *t, const u16 *at)
{
    u16 pc = t->pc, size = (u16)(at[1] - at[0]), to; /* to: a distance's destination, OUTSIDE if beyond the code */
    const u8 *ins;
#if RCX_SWAN
    const struct rcx_swan_row *sw;
#endif
    u8 op, i, jump = 0, len, flags;
    s16 value;
    s16 *var;

    if (pc >= size)                    /* the end of the code: as EndOfSub */
        goto end;
    ins = b->arena + at[0] + pc;
#if RCX_SWAN
    if ((sw = rcx_swan_find(ins[0])) != NULL) { /* all eight bits: a Swan opcode (vm/swan.c) */
        len = rcx_swan_params(sw);
        if ((u16)(pc + len) >= size)
            goto stop;
        t->pc = (u16)(pc + 1 + len);
        swan_exec(b, t, ins, sw);
        return;
    }
#endif
    op = ins[0];                       /* (the toggle bit changes neither the row nor the length) */
    flags = rcx_opflags[rcx_op_index(op)];
    len = (u8)((flags ? flags : op) & 7); /* as rcx_op_params(): unknown opcodes the nominal count */
    if (!flags && len >= 6)
        len = (u8)(len - 6);
    if ((u16)(pc + len) >= size)
        goto stop;                     /* truncated instruction at the end of the code */
    t->pc = (u16)(pc + 1 + len);
    flags &= RCX_PROGRAM << 3 | RCX_DIRECT << 3; /* availability (bits 3-4), compared as a number */
    if (flags < (RCX_PROGRAM << 3))
        return;                        /* unknown and direct-only byte codes are skipped by their length (spec p. 5) */
    if (flags != (RCX_PROGRAM << 3)) { /* shared with direct commands: none of the ones below */
        ops_exec(b, t, ins);
        return;
    }
    op = (u8)(ins[0] & ~RCX_TOGGLE);   /* read again: fewer values kept up to here */
    for (i = 0; i < sizeof control && control[i] != op; i++)
        ;
    /* The cases by ranges of i (a switch costs a 26-byte jump table); first the two without a distance. */
    if (i >= C_END_OF_SUB) {
        if (i != C_END_OF_SUB) {       /* not found: run by ops.c */
            ops_exec(b, t, ins);
            return;
        }
end:
        end_of_code(b, t);
        return;
    }
    {   /* The distance as a 16-bit two's complement added to its field's offset: a code object is shorter than
         * 0x8000 bytes, so a backward one past the start wraps to above its end, as does a forward one past the end
         * (none reaches 0x10000). Only CheckLoop's unsigned 16 bits could wrap around into the code: capped. */
        u8 field = dist_at[i >> 1];
        const u8 *p = ins + field;
        u16 d = p[0];
        if (i & 1)
            d |= (u16)p[1] << 8;
        if (i >= C_JUMP) {             /* sign-magnitude (bit 7 of the first byte); the short form has nothing above */
            u16 m = (u16)((d & 0x7F) | ((d >> 1) & 0x7F80));
            d = d & 0x80 ? (u16)(0u - m) : m;
        } else if (i == C_CHECK_LOOP + 1 && (d & 0x8000)) {
            d = 0x8000u;
        }
        to = (u16)(pc + field + d);    /* from the offset the distance counts from */
        if (to > size)
            to = OUTSIDE;
    }

    if (i >= C_ENTER) {                /* C_ENTER, C_ENTER + 1, C_ACCESS (NOT_AN_OP is never found) */
        if ((s16)to < 0)
            goto stop;
        access_enter(b, t, ins, to);
        return;
    }
    if (i < C_CHECK_LOOP) {
        s16 a;
        u8 holds, rel;
        value = source_get(b, t, ins[2] & 0x3F, ins[5]);
        a = source_get(b, t, ins[1] & 0x3F, RCX_LE16(ins + 3));
        holds = a < value ? 1 : a == value ? 2 : 4;
        rel = ins[1];                  /* the relation in bits 6-7: rotated into 0-1 (two rotates, not six shifts) */
        jump = !(relation[(u8)((u8)(rel << 2) | (u8)(rel >> 6)) & 3] & holds);
    } else if (i < C_JUMP) {           /* CheckLoop */
        if ((len = t->loop_depth) == 0)
            return;                    /* no active loop level: ignored */
        if (t->loop[len - 1] == 0) {
            t->loop_depth = (u8)(len - 1);
            jump = 1;
        } else {
            t->loop[len - 1]--;
        }
    } else if (i < C_DEC) {
        jump = 1;
    } else if ((var = var_ref(b, t, ins[1])) != NULL) { /* DecVarJumpLTZero */
        *var = (s16)(u16)((u16)*var - 1u);
        jump = *var < 0;
    }

    if (!jump)
        return;
    if ((s16)to >= 0) {
        t->pc = to;
        return;
    }                                  /* a jump outside the code object */
stop:
    sched_stop(b, t);
}

#ifdef __H8300__
/*
 * On the brick the loop over the running tasks is drivers/h8300/runfast.S: it runs their byte codes of the
 * commonest kinds itself, in turn or a lone task's many in a row (RCX_RUN_CHUNK at most between two looks at yield),
 * any other through run_slow(), and returns the count left once it has run `count`, or nothing runs any more, or
 * yield is set (looked at after each round and each call of run_slow()), leaving b->rr as the loop below does. It
 * does what the loop below does (tests/drivers/test_h8tasks.c compares the two).
 */
#include "runfast.h"
u16 rcx_run_fast(struct rcx *b, u16 count);
RCX_STATIC_ASSERT(rf_prog, offsetof(struct rcx, prog) == RF_PROG && offsetof(struct rcx, rr) == RF_RR);
RCX_STATIC_ASSERT(rf_mask, offsetof(struct rcx, runmask) == RF_RUNMASK && offsetof(struct rcx, yield) == RF_YIELD);
RCX_STATIC_ASSERT(rf_vars, offsetof(struct rcx, global) == RF_GLOBAL && offsetof(struct rcx, task) == RF_TASK);
RCX_STATIC_ASSERT(rf_arena, offsetof(struct rcx, arena) == RF_ARENA && offsetof(struct rcx, obj_start) == 0);
RCX_STATIC_ASSERT(rf_task, sizeof(struct rcx_task) == RF_TASK_SIZE && offsetof(struct rcx_task, sub) == RF_SUB
                           && offsetof(struct rcx_task, pc) == RF_PC
                           && offsetof(struct rcx_task, local_base) == RF_LOCAL_BASE);
RCX_STATIC_ASSERT(rf_limits, RCX_TASKS == RF_TASKS && RCX_SUBS == RF_SUBS && RCX_SLOT_OBJS == RF_SLOT_OBJS
                             && RCX_NO_SUB == RF_NO_SUB && RCX_GLOBALS == RF_GLOBALS && RCX_LOCALS == RF_LOCALS);
RCX_STATIC_ASSERT(rf_codes, RCX_TOGGLE == RF_TOGGLE && RCX_OP_SET_VAR == RF_OP_SET_VAR
                            && RCX_OP_SUM_VAR == RF_OP_SUM_VAR && RCX_OP_SUB_VAR == RF_OP_SUB_VAR
                            && RCX_OP_SJUMP == RF_OP_SJUMP && RCX_SRC_VAR == RF_SRC_VAR
                            && RCX_SRC_CONST == RF_SRC_CONST && RCX_RUN_CHUNK == RF_RUN_CHUNK);

u16 vm_run(struct rcx *b, u16 budget)
{
    if (!budget || !b->runmask || b->yield)
        return 0;
    return (u16)(budget - rcx_run_fast(b, budget));
}
#else
/*
 * Run up to `count` byte codes of task n: the commonest kinds in a loop that calls nothing and keeps the position in
 * a register, any other (or an irregular case of these: a truncated instruction, a jump leaving the code) through
 * run_slow(). More than one only while the task is the only one running: the scheduler would pick it every time.
 * Returns how many of the `count` are left when that stops being so.
 *
 * gcc 3.4 gives the loop's values registers only in this shape: the code object's pointers are the function's own
 * (recomputed after each run_slow(), which may change it), the loop has no calls, and its blocks are in this order
 * (SJump before the dispatch) so that every way back to the dispatch is a short branch on the H8/300.
 */
static __attribute__((noinline)) u8 run_task(struct rcx *b, u8 n, u8 count)
{
    u16 mask = b->runmask;
    struct rcx_task *t;
    const u16 *at;
    const u8 *code, *end, *ip;
    u8 op, d, v;
    u16 room, value, old;
    s16 *var;

next:
    t = &b->task[n];
    at = OBJECT_OF(b, t, n);
    code = b->arena + at[0];
    end = b->arena + at[1];
    if (t->pc >= (u16)(end - code))
        goto slow;
    ip = code + t->pc;
    /* Invariant: ip < end, so the opcode is inside the code. A byte code the loop runs must leave it so: one that
     * ends the code, or jumps to its very end, is left to run_slow() as much as any irregular one. */
    goto dispatch;

sjump:
    if (--room == 0)                   /* now the bytes from ip + 1 */
        goto leave;
    d = ip[1];                         /* distances count from their field, ip + 1 */
    if (!(d & 0x80)) {
        if (d >= room)
            goto leave;
        ip += 1 + d;
    } else {
        d &= 0x7F;
        if (d > (u16)(ip - code) + 1u)
            goto leave;
        ip = ip + 1 - d;
    }
    if (!--count)
        goto leave;
dispatch:
    op = ip[0];                        /* all eight bits: 0x2C and 0x2F are Swan's, not SumVar and SJump */
    room = (u16)(end - ip);            /* bytes from the opcode to the end of the code, at least 1 */
    if (op == RCX_OP_SJUMP)
        goto sjump;
    if ((op != RCX_OP_SUM_VAR && op != RCX_OP_SET_VAR && op != RCX_OP_SUB_VAR) || room <= 5)
        goto leave;
    value = RCX_LE16(ip + 3);
    if (ip[2] != RCX_SRC_CONST) {      /* else a global variable, or the slow way */
        if (ip[2] != RCX_SRC_VAR || value >= RCX_GLOBALS)
            goto leave;
        value = (u16)b->global[value];
    }
    v = ip[1];
    if (v >= RCX_GLOBALS) {
        if (v >= RCX_VARS)
            goto leave;
        v = (u8)(v + t->local_base);   /* the task's local: swan-target.md 4 */
    }
    var = &b->global[v];
    old = (u16)*var;
    if (op != RCX_OP_SUM_VAR) {
        if (op == RCX_OP_SUB_VAR)
            value = (u16)(0u - value);
        else
            old = 0;
    }
    *var = (s16)(u16)(old + value);
    ip += 5;
    if (--count)
        goto dispatch;

leave:
    t->pc = (u16)(ip - code);
    if (!count)
        return 0;
slow:
    run_slow(b, t, at);
    if (!--count || b->runmask != mask || b->yield)
        return count;
    goto next;
}

/* Bit n of a task mask: a table, since a shift by a variable count is a loop on the H8/300. */
static const u16 bit_of[RCX_TASKS] = { 1, 2, 4, 8, 16, 32, 64, 128, 256, 512 };

u16 vm_run(struct rcx *b, u16 budget)
{
    u16 left = budget, mask;
    u8 n = b->rr, count;

    while (left && (mask = b->runmask) != 0 && !b->yield) {
        count = 1;
        if (!(mask & (u16)(mask - 1u))) {
            /* The only running task runs on: the scheduler would pick it every time (a chunk at once). */
            n = 0;
            count = left > RCX_RUN_CHUNK ? RCX_RUN_CHUNK : (u8)left;
        }
        for (;; n++) {
            if (n >= RCX_TASKS)
                n = 0;                 /* wrap around: the next pass starts at task 0 */
            if (mask & bit_of[n])
                break;
        }
        left = (u16)(left - count + run_task(b, n, count));
        n++;
    }
    b->rr = n;
    return (u16)(budget - left);
}
#endif
