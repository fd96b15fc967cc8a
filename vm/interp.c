/*
 * The interpreter: one byte code of one task per call, and the round-robin scheduler around it.
 *
 * Control flow lives here (jumps, loops, tests, subroutines, waits, monitoring and access-control regions);
 * everything else is shared with direct commands in ops.c. Code is untrusted: an instruction that runs past the
 * end of its code object, or a jump that lands outside it, stops the task instead of reading foreign memory.
 */
#include "rcx.h"

/* Relations of SCheckDo/LCheckDo (spec p. 93): the jump is taken when the comparison FAILS. */
static u8 holds(u8 rel, s16 a, s16 b)
{
    switch (rel) {
    case 0: return a > b;
    case 1: return a < b;
    case 2: return a == b;
    default: return a != b;
    }
}

static void stop(struct rcx *b, struct rcx_task *t)
{
    sched_stop_task(b, (u8)(t - b->task));
}

/* EndOfSub, explicit or by running off the end of a subroutine (nqc does not append 0xF6). */
static void end_of_sub(struct rcx *b, struct rcx_task *t)
{
    events_sub_returned(b, t);
    if (!t->has_ret) {
        stop(b, t); /* spec p. 26: no return address means something has gone wrong */
        return;
    }
    t->has_ret = 0;
    t->sub = t->ret_sub;
    t->pc = t->ret_pc;
}

/* Sign-magnitude distances: 7 bits (+ 8 more in a second byte), bit 7 of the first byte = backwards. */
static s16 dist_sm8(const u8 *f)
{
    s16 d = (s16)(f[0] & 0x7F);
    return (f[0] & 0x80) ? (s16)-d : d;
}
static s16 dist_sm16(const u8 *f)
{
    s16 d = (s16)((f[0] & 0x7F) | ((u16)f[1] << 7));
    return (f[0] & 0x80) ? (s16)-d : d;
}

#define NO_JUMP 0xFFFFu
#define OUTSIDE 0xFFFEu /* larger than any code object */

/* The position `d` bytes from the distance field at `from`, or OUTSIDE when it falls outside 0..0xFFFD.
 * In 16 bits: 32-bit arithmetic costs the H8/300 several times the code. */
static u16 jump_fwd(u16 from, u16 d)
{
    return d >= (u16)(OUTSIDE - from) ? OUTSIDE : (u16)(from + d);
}
static u16 jump_to(u16 from, s16 d)
{
    if (d < 0) {
        u16 m = (u16)(0u - (u16)d);
        return m > from ? OUTSIDE : (u16)(from - m);
    }
    return jump_fwd(from, (u16)d);
}

/*
 * Execute one byte code of task t. `code`/`size` are its current code object.
 * Returns nothing; the task's state says what happened.
 */
static void step(struct rcx *b, struct rcx_task *t, const u8 *code, u16 size)
{
    u16 pc = t->pc;
    const u8 *ins = code + pc;
    u8 op = (u8)(ins[0] & ~RCX_TOGGLE);
    u8 n = rcx_op_params(op);
    u16 field = (u16)(pc + 1);         /* position of the first operand */
    u16 target = NO_JUMP;              /* a taken jump's destination */
    s16 value;
    s16 *var;

    if ((u16)(size - pc) <= n) {       /* truncated instruction at the end of the code */
        stop(b, t);
        return;
    }
    t->pc = (u16)(field + n);

    switch (op) {
    case RCX_OP_SET_VAR:               /* the commonest byte codes go straight to their handler */
    case RCX_OP_SUM_VAR:
    case RCX_OP_SUB_VAR:
    case RCX_OP_MUL_VAR:
    case RCX_OP_DIV_VAR:
    case RCX_OP_SGN_VAR:
    case RCX_OP_ABS_VAR:
    case RCX_OP_AND_VAR:
    case RCX_OP_OR_VAR:
        ops_var(b, t, ins);
        break;
    case RCX_OP_SJUMP:
        target = jump_to(field, dist_sm8(ins + 1));
        break;
    case RCX_OP_LJUMP:
        target = jump_to(field, dist_sm16(ins + 1));
        break;
    case RCX_OP_SDEC_JUMP_LTZ:
    case RCX_OP_LDEC_JUMP_LTZ:
        if ((var = var_ref(b, t, ins[1])) == NULL)
            break;
        *var = (s16)(u16)((u16)*var - 1u);
        if (*var < 0)
            target = jump_to((u16)(field + 1), op == RCX_OP_SDEC_JUMP_LTZ ? dist_sm8(ins + 2) : dist_sm16(ins + 2));
        break;
    case RCX_OP_SCHECK_DO:
    case RCX_OP_LCHECK_DO:
        value = source_get(b, t, ins[2] & 0x3F, ins[5]);
        if (!holds((u8)(ins[1] >> 6), source_get(b, t, ins[1] & 0x3F, RCX_LE16(ins + 3)), value)) {
            if (op == RCX_OP_SCHECK_DO)
                target = jump_fwd((u16)(field + 5), ins[6]);                /* forward only */
            else
                target = jump_to((u16)(field + 5), (s16)RCX_LE16(ins + 6)); /* signed 16-bit */
        }
        break;
    case RCX_OP_SET_LOOP:
        /* A fifth level is ignored; counts outside 1-255 become 0 and exit at the first check (spec p. 57). */
        if (t->loop_depth < RCX_LOOP_LEVELS) {
            value = source_get(b, t, ins[1], ins[2]);
            t->loop[t->loop_depth++] = (u8)((value >= 1 && value <= 255) ? value : 0);
        }
        break;
    case RCX_OP_SCHECK_LOOP:
    case RCX_OP_LCHECK_LOOP:
        if (t->loop_depth == 0)
            break;                     /* no active loop level: ignored */
        if (t->loop[t->loop_depth - 1] == 0) {
            t->loop_depth--;
            /* Forward only: an unsigned distance, 8 or 16 bits. */
            target = jump_fwd(field, op == RCX_OP_SCHECK_LOOP ? ins[1] : RCX_LE16(ins + 1));
        } else {
            t->loop[t->loop_depth - 1]--;
        }
        break;
    case RCX_OP_GOSUB:
        if (ins[1] >= RCX_SUBS || !mem_obj_runnable(b, rcx_obj_sub(b->prog, ins[1])))
            break;                     /* calling an empty subroutine does nothing */
        /* One return address per task: a Gosub inside a subroutine overwrites it (spec p. 39). */
        t->has_ret = 1;
        t->ret_sub = t->sub;
        t->ret_pc = t->pc;
        t->sub = ins[1];
        t->pc = 0;
        break;
    case RCX_OP_END_OF_SUB:
        if (t->sub == RCX_NO_SUB)
            stop(b, t);                /* EndOfSub in a task body: no return address */
        else
            end_of_sub(b, t);
        break;
    case RCX_OP_WAIT:
        value = source_get(b, t, ins[1], RCX_LE16(ins + 2));
        if (value <= 0)
            break;                     /* negative: ignored (spec p. 67); zero: no wait */
        /* Waits run on the 10 ms grid: Wait(1) resumes at the next 10 ms step. */
        t->wake = (u16)(b->ticks10 + (u16)value);
        t->state = RCX_TASK_WAITING;
        b->runmask &= (u16)~(1u << (t - b->task));
        break;
    case RCX_OP_SENTER_EVENT:
    case RCX_OP_LENTER_EVENT: {
        u16 to = jump_to((u16)(field + 3), op == RCX_OP_SENTER_EVENT ? dist_sm8(ins + 4) : dist_sm16(ins + 4));
        if (to <= size)
            events_monitor_enter(b, t, (u16)source_get(b, t, ins[1], RCX_LE16(ins + 2)), (u16)to);
        else
            stop(b, t);
        break;
    }
    case RCX_OP_ENTER_ACCESS: {
        u16 to = jump_to((u16)(field + 1), dist_sm16(ins + 2));
        if (to <= size)
            access_enter(b, t, ins[1], (u16)to);
        else
            stop(b, t);
        break;
    }
    case RCX_OP_EXIT_EVENT:
        events_monitor_exit(b, t);
        break;
    case RCX_OP_EXIT_ACCESS:
        access_exit(b, t);
        break;
    default:
        if (rcx_op_avail(op) & RCX_PROGRAM)
            ops_exec(b, t, ins);
        /* Unknown and direct-only byte codes are skipped by their length (spec p. 5). */
        break;
    }

    if (target == NO_JUMP)
        return;
    if (target <= size)
        t->pc = target;
    else
        stop(b, t);                    /* a jump outside the code object */
}

/* Run task n for one byte code; reaching the end of the code ends the task or returns from the subroutine. */
static void run_one(struct rcx *b, u8 n)
{
    struct rcx_task *t = &b->task[n];
    u8 obj = t->sub == RCX_NO_SUB ? rcx_obj_task(b->prog, n) : rcx_obj_sub(b->prog, t->sub);
    u16 size = mem_obj_size(b, obj);

    if (t->pc >= size) {
        if (t->sub == RCX_NO_SUB)
            stop(b, t);
        else
            end_of_sub(b, t);
        return;
    }
    step(b, t, mem_obj_code(b, obj), size);
}

u16 vm_run(struct rcx *b, u16 budget)
{
    u16 done = 0;
    u8 n = b->rr;

    while (done < budget && b->runmask) {
        u16 m = (u16)(b->runmask >> n);
        if (!m) {                      /* wrap around: the next pass starts at task 0 */
            n = 0;
            m = b->runmask;
        }
        while (!(m & 1)) {
            m >>= 1;
            n++;
        }
        run_one(b, n);
        done++;
        if (++n >= RCX_TASKS)
            n = 0;
    }
    b->rr = n;
    return done;
}
