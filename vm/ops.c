/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Byte codes that programs and direct commands share (availability "Direct/Program" in the spec), plus the
 * program-only ones that do not jump (vm/interp.c runs those). Operands were length-checked by the caller; every
 * index and value is range-checked here, and an out-of-range operand makes the instruction do nothing.
 */
#include "rcx.h"
#include "sources.h"
#include "access.h"

/* Variable arithmetic, spec pp. 75-83, in 16 bits as firm0328 computes it (reference-firmware.md). `kind` is the
 * high nibble of SetVar..OrVar (0x14-0x94), which alone tells them apart (a dense switch), or one of Swan's. */
RCX_STATIC_ASSERT(arith_nibbles, ARITH_SET == RCX_OP_SET_VAR >> 4 && ARITH_SUM == RCX_OP_SUM_VAR >> 4
                                 && ARITH_SUB == RCX_OP_SUB_VAR >> 4 && ARITH_DIV == RCX_OP_DIV_VAR >> 4
                                 && ARITH_MUL == RCX_OP_MUL_VAR >> 4 && ARITH_SGN == RCX_OP_SGN_VAR >> 4
                                 && ARITH_ABS == RCX_OP_ABS_VAR >> 4 && ARITH_AND == RCX_OP_AND_VAR >> 4
                                 && ARITH_OR == RCX_OP_OR_VAR >> 4);
#define IS_MOD(kind) (RCX_SWAN && (kind) == ARITH_MOD)
#if !RCX_SWAN
static
#endif
s16 ops_arith(s16 a, s16 v, u8 kind)
{
#if RCX_SWAN
    u8 n;
    s16 m = 0;                                   /* the variable, while a is a bit's mask */
#endif

    switch (kind) {                              /* (the long cases first: the others reach the end by a short
                                                  * branch; the order measured) */
#if RCX_SWAN
    /* Swan's (swan-target.md 4) */
    default:                                     /* ARITH_BSET, ARITH_BCLR: the mask 1 << v (bit 0-15; else 0) */
        m = a;
        a = 1;
        goto shift;
    case ARITH_SHR:
        v = (s16)(u16)(0u - (u16)v);             /* a right shift is a left one by -v */
        /* fall through */
    case ARITH_SHL:                              /* one bit at a time: 16 or more leaves 0, or the sign going right */
    shift:
        for (n = 16; v && n; n--)                /* |v| steps, 16 at most */
            if (v < 0) {
                a = (s16)(a >> 1);
                v++;
            } else {
                a = (s16)(u16)((u16)a << 1);
                v--;
            }
        if (kind < ARITH_BSET)
            return a;
        return (s16)(kind == ARITH_BSET ? m | a : m & ~a);
    case ARITH_MOD:
#endif
    case ARITH_DIV:
        if (v == 0)
            return a;                            /* division by zero leaves the variable */
        if (v == -1) {                           /* -32768 / -1 = -32768 and -32768 % -1 = 0, without the trap */
            if (IS_MOD(kind))
                return 0;
            v = a;
            goto negate;
        }
        return (s16)(IS_MOD(kind) ? a % v : a / v); /* C99 truncates toward zero, as firm0328; % has the sign
                                                           * of the dividend */
    case ARITH_MUL: return (s16)(u16)((unsigned)(u16)a * (unsigned)(u16)v);
    case ARITH_SET: return v;
#if RCX_SWAN
    case ARITH_NEG:
#endif
    negate:
        a = 0;                                   /* -v = 0 - v */
        /* fall through */
    case ARITH_SUB: return (s16)(u16)((u16)a - (u16)v);
    case ARITH_SUM: return (s16)(u16)((u16)a + (u16)v);
    case ARITH_SGN: return (s16)(v > 0 ? 1 : v < 0 ? -1 : 0);
#if RCX_SWAN
    case ARITH_OR:   return (s16)(a | v);
#endif
    case ARITH_AND: return (s16)(a & v);
    case ARITH_ABS:
        if (v < 0) {
            v = (s16)(u16)(0u - (u16)v);
            if (v < 0)
                v = 32767;                       /* abs(-32768) */
        }
        return v;
#if RCX_SWAN
    case ARITH_COMP: return (s16)~v;
    case ARITH_XOR:  return (s16)(a ^ v);
#else
    default:         return (s16)(a | v);        /* RCX_OP_OR_VAR */
#endif
    }
}

/*
 * OnOffFloat, ConnectDisconnect, SetFwdSetRwdRewDir, SetNormSetInvAltDir: motor list in bits 0-2 (A, B, C), a
 * two-bit verb in bits 6-7. Each verb clears some bits of the register, then flips some: state 0 float, 1 off
 * (brake), 2 on; direction 0 backwards, 1 flip, 2 forwards; verb 3 changes nothing. Switching on drops the brake
 * bit: an output that is on reads 0x8F, not 0xCF, after Off then On (reference-firmware.md).
 */
#define STATE_BITS (RCX_MOTOR_ON | RCX_MOTOR_BRAKE)
static const u16 verbs[8] = {
    OUTPUTS_CHANGE(STATE_BITS, 0), OUTPUTS_CHANGE(STATE_BITS, RCX_MOTOR_BRAKE),
    OUTPUTS_CHANGE(STATE_BITS, RCX_MOTOR_ON), 0,
    OUTPUTS_CHANGE(RCX_MOTOR_FWD, 0), OUTPUTS_CHANGE(0, RCX_MOTOR_FWD),
    OUTPUTS_CHANGE(RCX_MOTOR_FWD, RCX_MOTOR_FWD), 0,
};
/* The opcodes tell the four apart: 0x21 state, 0x67 global state, 0xE1 direction, 0x77 global direction. */
#define IS_DIRECTION(op) ((op) & 0x90)
#define IS_GLOBAL(op) ((op) & 0x04)
RCX_STATIC_ASSERT(motor_ops, !IS_DIRECTION(RCX_OP_ON_OFF_FLOAT) && !IS_GLOBAL(RCX_OP_ON_OFF_FLOAT) &&
                             !IS_DIRECTION(RCX_OP_CONNECT_DISCONNECT) && IS_GLOBAL(RCX_OP_CONNECT_DISCONNECT) &&
                             IS_DIRECTION(RCX_OP_SET_DIRECTION) && !IS_GLOBAL(RCX_OP_SET_DIRECTION) &&
                             IS_DIRECTION(RCX_OP_SET_GLOBAL_DIR) && IS_GLOBAL(RCX_OP_SET_GLOBAL_DIR) &&
                             !(OUTPUTS_GLOBAL & 0x07));

/* SetPower, SetMaxPower (0xA3: global): 0-7. Their low three bits (3) tell them from the four above (1 or 7). */
RCX_STATIC_ASSERT(power_ops, (RCX_OP_SET_POWER & 7) == 3 && (RCX_OP_SET_MAX_POWER & 7) == 3
                             && !(RCX_OP_SET_POWER & 0x80) && (RCX_OP_SET_MAX_POWER & 0x80)
                             && (RCX_OP_ON_OFF_FLOAT & 7) != 3 && (RCX_OP_CONNECT_DISCONNECT & 7) != 3
                             && (RCX_OP_SET_DIRECTION & 7) != 3 && (RCX_OP_SET_GLOBAL_DIR & 7) != 3);

/* The six byte codes on a list of motors (bits 0-2 of the byte after the opcode): one call of outputs_update(). */
static void set_motors(struct rcx *b, struct rcx_task *t, const u8 *ins)
{
    u8 low = (u8)(ins[0] & 7), global, verb;
    u16 change;
    s16 power;

    if (low == 3) {                    /* SetPower, SetMaxPower */
        power = ops_source8(b, t, ins + 1); /* the source one byte on */
        if ((u16)power > 7)
            return;
        change = OUTPUTS_CHANGE(RCX_MOTOR_POWER, power);
        global = (u8)(ins[0] & 0x80);
    } else {
        verb = (u8)(ins[1] >> 6);
        if (IS_DIRECTION(ins[0]))
            verb += 4;
        change = verbs[verb];
        global = (u8)IS_GLOBAL(ins[0]);
    }
    outputs_update(b, (u8)((ins[1] & 0x07) | (global ? OUTPUTS_GLOBAL : 0)), change);
}

s16 ops_source(struct rcx *b, const struct rcx_task *t, const u8 *ins)
{
    return source_get(b, t, ins[1], RCX_LE16(ins + 2));
}

s16 ops_source8(struct rcx *b, const struct rcx_task *t, const u8 *ins)
{
    return source_get(b, t, ins[1], ins[2]);
}

void ops_var(struct rcx *b, struct rcx_task *t, const u8 *ins)
{
    s16 value = ops_source(b, t, ins + 1); /* the source one byte on */
    s16 *var = var_ref(b, t, ins[1]);
    if (var)
        *var = ops_arith(*var, value, (u8)(ins[0] >> 4)); /* the toggle bit is bit 3 */
}

/*
 * One small handler per byte code, found through a table rather than a switch: on the H8/300 a large switch
 * turns nearly every branch into a 6-byte long-branch sequence, and the handlers cost less than those.
 * Operands are read only by the handler that knows the instruction has them.
 */
typedef void op_fn(struct rcx *b, struct rcx_task *t, const u8 *ins);

#define OP(name) static void name(struct rcx *b, struct rcx_task *t, const u8 *ins)
#define UNUSED_T (void)t
#define UNUSED_INS (void)ins

OP(op_ping) { UNUSED_T; UNUSED_INS; b->idle_reset = 1; }
OP(op_stop_all) { UNUSED_T; UNUSED_INS; sched_stop_all(b); }
OP(op_turn_off)
{
    UNUSED_T; UNUSED_INS;
    if (b->power_down_min) /* ignored when the power-down time is 0 (reference-firmware.md) */
        b->turn_off = 1;
}
static RCX_HIGH_CODE void op_clear_sound(struct rcx *b, struct rcx_task *t, const u8 *ins) /* (room at F000) */
{
    UNUSED_T;
    UNUSED_INS;
    sound_clear(b);
}
void ops_set_message(struct rcx *b, u8 m)
{
    b->message = m;
    events_message_changed(b); /* ClearPBMessage too: firm0328 raises a mailbox event for it */
}
OP(op_clear_message) { UNUSED_T; UNUSED_INS; ops_set_message(b, 0); }
OP(op_message)
{
    u8 m = ins[1];
#if RCX_SWAN
    if (!t) /* received: a plain message has parameter 0 (swan-target.md 4), one after a B3 that one's */
        b->msg_param = remote_message_received(b, m);
#else
    UNUSED_T;
#endif
    ops_set_message(b, m);
}
RCX_STATIC_ASSERT(mute_ops, !(RCX_OP_MUTE & 0x20) && (RCX_OP_UNMUTE & 0x20)); /* bit 5 tells them apart */
OP(op_mute) { UNUSED_T; sound_mute(b, (u8)(ins[0] & 0x20 ? 0 : 1)); }
static RCX_HIGH_CODE void op_clear_events(struct rcx *b, struct rcx_task *t, const u8 *ins) /* (room at F000) */
{
    UNUSED_T;
    UNUSED_INS;
    events_clear_all(b);
}
OP(op_tx_power)
{
    UNUSED_T;
    if (ins[1] <= 1)
        b->tx_range = ins[1];
}
OP(op_system_sound)
{
    UNUSED_T;
    if (ins[1] <= 5)
        sound_system(b, ins[1]);
}
OP(op_tone) { UNUSED_T; sound_tone(b, RCX_LE16(ins + 1), ins[3]); }
OP(op_tone_var)
{
    s16 *var = var_ref(b, t, ins[1]);
    if (var)
        sound_tone(b, (u16)*var, ins[2]);
}
OP(op_start) { UNUSED_T; sched_start_task(b, ins[1]); }
OP(op_stop) { UNUSED_T; sched_stop_task(b, ins[1]); }
OP(op_select) { sched_select_program(b, ins[1], t != NULL); }
OP(op_clear_timer)
{
    UNUSED_T;
    if (ins[1] < RCX_TIMERS)
        b->timer[ins[1]] = 0;
}
OP(op_power_down)
{
    UNUSED_T;
    b->power_down_min = ins[1];
    b->idle_reset = 1;
}
OP(op_clear_sensor) { UNUSED_T; sensor_clear(b, ins[1]); }
OP(op_counter)
{
    u8 n = ins[1], op = (u8)(ins[0] & ~RCX_TOGGLE);
    s16 *c;
    UNUSED_T;
    if (n >= RCX_COUNTERS)
        return;
    c = &b->global[n];
    if (op == RCX_OP_CLEAR_COUNTER)
        *c = 0;
    else
        *c = (s16)(u16)((u16)*c + (op == RCX_OP_INC_COUNTER ? 1u : 0xFFFFu));
    events_counter_changed(b, n);
}
OP(op_watch)
{
    UNUSED_T;
    if (ins[1] < 24 && ins[2] < 60) {
        b->watch = (u16)(ins[1] * 60u + ins[2]);
        b->watch_ms = 0;
        if (b->display.view != DISPLAY_USER)
            display_view(b, 0); /* the watch is selected (spec p. 51), but a program's own view stays, as firm0328
                                 * keeps it (issue 15, observed on the emulated brick) */
    }
}
OP(op_sensor_type) { UNUSED_T; sensor_set_type(b, ins[1], ins[2]); }
OP(op_sensor_mode) { UNUSED_T; sensor_set_mode(b, ins[1], ins[2]); }
OP(op_datalog) { UNUSED_T; datalog_set(b, RCX_LE16(ins + 1)); }
OP(op_log) { datalog_add(b, t, ins[1], ins[2]); }
OP(op_uart)
{
    u8 start = ins[1], size = ins[2];
    UNUSED_T;
    if (size <= 16 && start <= (u8)(16 - size)) /* start + size <= 16 (spec p. 60), in bytes */
        remote_send_uart(b, start, size);
}
OP(op_event) { events_raise(b, (u16)ops_source(b, t, ins)); }
OP(op_view)
{
    s16 value = ops_source(b, t, ins);
    if (value >= 0 && value <= 7)
        display_view(b, (u8)value);
}
OP(op_user_view)
{
    UNUSED_T;
    if (ins[2] <= 3)
        display_user(b, ins[2], ins[3], RCX_LE16(ins + 4));
}
/* The event engine checks event numbers, sources and types itself (spec p. 70). */
static RCX_HIGH_CODE void op_set_event(struct rcx *b, struct rcx_task *t, const u8 *ins) /* (room at F000) */
{
    UNUSED_T;
    events_set(b, ins[1], ins[2], ins[3]);
}
static RCX_HIGH_CODE void op_calibrate(struct rcx *b, struct rcx_task *t, const u8 *ins) /* (the last room at F000) */
{
    UNUSED_T;
    events_calibrate(b, ins); /* which reads the operands in nqc's order (vm/events.c) */
}
OP(op_set_source)
{
    /* Source numbers use bits 0-5 of their byte (spec p. 86). */
    s16 value = source_get(b, t, (u8)(ins[3] & 0x3F), RCX_LE16(ins + 4));

    source_set(b, t, (u8)(ins[1] & 0x3F), ins[2], value);
}
/* SetPriority and SendPBMessage are program-only (vm_direct() runs none): t is a task. */
OP(op_priority) { (void)b; t->priority = ins[1]; }
/* Wait, and Swan's WaitMS (vm/swan.c): a task that waits costs nothing until vm_tick() wakes it. Waits run on the
 * 10 ms grid: Wait(1) resumes at the next 10 ms step; WaitMS on the millisecond. */
RCX_STATIC_ASSERT(wait_flags, WAIT_10MS == 1 && WAIT_MS == 2 && RCX_SW_WAIT_MS == (RCX_OP_WAIT | 4)
                              && !(RCX_OP_WAIT & 4));
void ops_wait(struct rcx *b, struct rcx_task *t, const u8 *ins)
{
    s16 value = ops_source(b, t, ins);
#if RCX_SWAN
    u8 ms = (u8)((ins[0] >> 2) & 1); /* WaitMS 0x47, Wait 0x43 */
#endif

    if (value <= 0)
        return;                        /* negative: ignored (spec p. 67); zero: no wait */
#if RCX_SWAN
    t->wait_ms = ms;
    t->wake = (u16)(wait_clock(b, t) + (u16)value);
    b->waiting |= (u8)(ms + 1);        /* WAIT_MS or WAIT_10MS */
#else
    t->wake = (u16)(b->ticks10 + (u16)value);
    b->waiting = WAIT_10MS;
#endif
    sched_set_state(b, t, RCX_TASK_WAITING);
}
OP(op_set_loop)
{
    u8 depth = t->loop_depth;
    u16 value;
    /* A fifth level is ignored; counts outside 1-255 become 0 and exit at the first check (spec p. 57). */
    if (depth < RCX_LOOP_LEVELS) {
        value = (u16)ops_source8(b, t, ins);
        t->loop[depth] = (u8)(value <= 255 ? value : 0); /* (a negative count too) */
        t->loop_depth = (u8)(depth + 1);
    }
}
OP(op_gosub)
{
    u8 sub = ins[1];

    if (sub >= RCX_SUBS || !mem_obj_runnable(b, rcx_obj_sub(b->prog, sub)))
        return;                        /* calling an empty subroutine does nothing */
    /* One return address per task: a Gosub inside a subroutine overwrites it (spec p. 39). */
    t->has_ret = 1;
    t->ret_sub = t->sub;
    t->ret_pc = t->pc;
    t->sub = sub;
    t->pc = 0;
}
/* ExitEventCheck (0xB0), ExitAccessControl (0xA0): bit 4 tells them apart */
RCX_STATIC_ASSERT(exit_ops, (RCX_OP_EXIT_EVENT & 0x10) && !(RCX_OP_EXIT_ACCESS & 0x10));
OP(op_exit) { access_input(b, t, ins[0] & 0x10 ? ACCESS_IN_EXIT_EV : ACCESS_IN_EXIT_AC); }
OP(op_send_message) { remote_send_message(b, (u8)ops_source8(b, t, ins)); }

/* Opcodes and their handlers, in two parallel arrays (3 bytes a row on the brick). */
static const u8 op_codes[] = {
    RCX_OP_WAIT,
    RCX_OP_PING, RCX_OP_STOP_ALL_TASKS, RCX_OP_TURN_OFF, RCX_OP_CLEAR_SOUND, RCX_OP_CLEAR_MESSAGE, RCX_OP_MUTE,
    RCX_OP_UNMUTE, RCX_OP_CLEAR_ALL_EVENTS, RCX_OP_ON_OFF_FLOAT, RCX_OP_CONNECT_DISCONNECT, RCX_OP_SET_DIRECTION,
    RCX_OP_SET_GLOBAL_DIR, RCX_OP_SET_POWER, RCX_OP_SET_MAX_POWER, RCX_OP_TX_POWER, RCX_OP_PLAY_SYSTEM_SOUND,
    RCX_OP_PLAY_TONE, RCX_OP_PLAY_TONE_VAR, RCX_OP_START_TASK, RCX_OP_STOP_TASK, RCX_OP_SELECT_PROGRAM,
    RCX_OP_CLEAR_TIMER, RCX_OP_POWER_DOWN_TIME, RCX_OP_CLEAR_SENSOR, RCX_OP_INC_COUNTER, RCX_OP_DEC_COUNTER,
    RCX_OP_CLEAR_COUNTER, RCX_OP_MESSAGE, RCX_OP_SET_WATCH, RCX_OP_SET_SENSOR_TYPE, RCX_OP_SET_SENSOR_MODE,
    RCX_OP_SET_DATALOG, RCX_OP_DATALOG_NEXT, RCX_OP_SEND_UART, RCX_OP_DIRECT_EVENT, RCX_OP_SELECT_DISPLAY,
    RCX_OP_VIEW_SOURCE, RCX_OP_SET_EVENT, RCX_OP_CALIBRATE_EVENT, RCX_OP_SET_SOURCE, RCX_OP_SET_PRIORITY,
    RCX_OP_SEND_MESSAGE, RCX_OP_SET_LOOP, RCX_OP_GOSUB, RCX_OP_EXIT_EVENT, RCX_OP_EXIT_ACCESS,
};
static op_fn *const op_fns[] = {
    ops_wait,
    op_ping, op_stop_all, op_turn_off, op_clear_sound, op_clear_message, op_mute,
    op_mute, op_clear_events, set_motors, set_motors, set_motors,
    set_motors, set_motors, set_motors, op_tx_power, op_system_sound,
    op_tone, op_tone_var, op_start, op_stop, op_select,
    op_clear_timer, op_power_down, op_clear_sensor, op_counter, op_counter,
    op_counter, op_message, op_watch, op_sensor_type, op_sensor_mode,
    op_datalog, op_log, op_uart, op_event, op_view,
    op_user_view, op_set_event, op_calibrate, op_set_source, op_priority,
    op_send_message, op_set_loop, op_gosub, op_exit, op_exit,
};
RCX_STATIC_ASSERT(op_rows_match, sizeof op_codes == sizeof op_fns / sizeof op_fns[0]);

/* SetVar..OrVar are 0x14-0x94, the opcodes from 0x10 to 0x9F with a low nibble of 4: found by that, not in the
 * table. */
RCX_STATIC_ASSERT(var_ops, RCX_OP_SET_VAR == 0x14 && RCX_OP_OR_VAR == 0x94 && (RCX_OP_SUM_VAR & 0x0F) == 4
                           && (RCX_OP_SUB_VAR & 0x0F) == 4 && (RCX_OP_DIV_VAR & 0x0F) == 4
                           && (RCX_OP_MUL_VAR & 0x0F) == 4 && (RCX_OP_SGN_VAR & 0x0F) == 4
                           && (RCX_OP_ABS_VAR & 0x0F) == 4 && (RCX_OP_AND_VAR & 0x0F) == 4);
void ops_exec(struct rcx *b, struct rcx_task *t, const u8 *ins)
{
    u8 op = (u8)(ins[0] & ~RCX_TOGGLE), i, d = (u8)(op - RCX_OP_SET_VAR);
    op_fn *f = ops_var;

    if (d > RCX_OP_OR_VAR - RCX_OP_SET_VAR || (d & 0x0F)) {
        for (i = 0; op_codes[i] != op;)
            if (++i >= sizeof op_codes)
                return;
        f = op_fns[i];
    }
    f(b, t, ins);
}
