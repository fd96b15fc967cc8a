/*
 * Byte codes that programs and direct commands share (availability "Direct/Program" in the spec), plus the two
 * program-only ones that do not steer control flow. Operands were length-checked by the caller; every index and
 * value is range-checked here, and an out-of-range operand makes the instruction do nothing.
 */
#include "rcx.h"
#include "sources.h"

/* Variable arithmetic, spec pp. 75-83, in 16 bits as firm0328 computes it (reference-firmware.md). */
static s16 arith(u8 op, s16 a, s16 v)
{
    switch (op) {
    case RCX_OP_SET_VAR: return v;
    case RCX_OP_SUM_VAR: return (s16)(u16)((u16)a + (u16)v);
    case RCX_OP_SUB_VAR: return (s16)(u16)((u16)a - (u16)v);
    case RCX_OP_MUL_VAR: return (s16)(u16)((unsigned)(u16)a * (unsigned)(u16)v);
    case RCX_OP_DIV_VAR:
        if (v == 0)
            return a;                            /* division by zero leaves the variable */
        if (v == -1)
            return (s16)(u16)(0u - (u16)a);      /* -32768 / -1 = -32768, without the overflow trap */
        return (s16)(a / v);                     /* C99 truncates toward zero, as firm0328 */
    case RCX_OP_SGN_VAR: return (s16)(v > 0 ? 1 : v < 0 ? -1 : 0);
    case RCX_OP_ABS_VAR: return v == -32768 ? 32767 : (s16)(v < 0 ? -v : v);
    case RCX_OP_AND_VAR: return (s16)(a & v);
    default:             return (s16)(a | v);    /* RCX_OP_OR_VAR */
    }
}

/* Motor list in bits 0-2 (A, B, C), a two-bit verb in bits 6-7. */
static void set_motors(struct rcx *b, u8 *reg, u8 arg, u8 direction)
{
    u8 i, verb = (u8)(arg >> 6);

    for (i = 0; i < RCX_MOTORS; i++) {
        if (!(arg & (1u << i)))
            continue;
        if (direction) {   /* 0 backwards, 1 flip, 2 forwards */
            if (verb == 0)
                reg[i] &= (u8)~RCX_MOTOR_FWD;
            else if (verb == 1)
                reg[i] ^= RCX_MOTOR_FWD;
            else if (verb == 2)
                reg[i] |= RCX_MOTOR_FWD;
        } else {           /* state: 0 float, 1 off (brake), 2 on */
            if (verb == 0)
                reg[i] &= (u8)~(RCX_MOTOR_ON | RCX_MOTOR_BRAKE);
            else if (verb == 1)
                reg[i] = (u8)((reg[i] & ~RCX_MOTOR_ON) | RCX_MOTOR_BRAKE);
            else if (verb == 2)
                reg[i] |= RCX_MOTOR_ON;
        }
    }
    outputs_changed(b);
}

static void set_power(struct rcx *b, u8 *reg, u8 motors, s16 power)
{
    u8 i;
    if (power < 0 || power > 7)
        return;
    for (i = 0; i < RCX_MOTORS; i++)
        if (motors & (1u << i))
            reg[i] = (u8)((reg[i] & ~RCX_MOTOR_POWER) | power);
    outputs_changed(b);
}

static u8 event_type_valid(u8 type)
{
    /* 0-3 and 7-12 detect, 14 mailbox, 16 clears (spec p. 70). */
    return type <= 3 || (type >= 7 && type <= 12) || type == 14 || type == 16;
}

void ops_var(struct rcx *b, struct rcx_task *t, const u8 *ins)
{
    s16 value = source_get(b, t, ins[2], RCX_LE16(ins + 3));
    s16 *var = var_ref(b, t, ins[1]);
    if (var)
        *var = arith((u8)(ins[0] & ~RCX_TOGGLE), *var, value);
}

u8 ops_exec(struct rcx *b, struct rcx_task *t, const u8 *ins)
{
    u8 op = (u8)(ins[0] & ~RCX_TOGGLE);
    /* First operand, read only when the instruction has one: a lone opcode may end its buffer. */
    u8 a = rcx_op_nominal_params(op) ? ins[1] : 0;
    s16 value;
    s16 *var;

    switch (op) {
    case RCX_OP_PING:
        b->idle_reset = 1;
        break;
    case RCX_OP_STOP_ALL_TASKS:
        sched_stop_all(b);
        break;
    case RCX_OP_TURN_OFF:
        if (b->power_down_min) /* ignored when the power-down time is 0 (reference-firmware.md) */
            b->turn_off = 1;
        break;
    case RCX_OP_CLEAR_SOUND:
        sound_clear(b);
        break;
    case RCX_OP_CLEAR_MESSAGE:
        b->message = 0;
        events_message_changed(b); /* firm0328 raises a mailbox event here too */
        break;
    case RCX_OP_MUTE:
        sound_mute(b, 1);
        break;
    case RCX_OP_UNMUTE:
        sound_mute(b, 0);
        break;
    case RCX_OP_CLEAR_ALL_EVENTS:
        events_clear_all(b);
        break;
    case RCX_OP_ON_OFF_FLOAT:
        set_motors(b, b->out.motor, a, 0);
        break;
    case RCX_OP_CONNECT_DISCONNECT:
        set_motors(b, b->out.global, a, 0);
        break;
    case RCX_OP_SET_DIRECTION:
        set_motors(b, b->out.motor, a, 1);
        break;
    case RCX_OP_SET_GLOBAL_DIR:
        set_motors(b, b->out.global, a, 1);
        break;
    case RCX_OP_SET_POWER:
        set_power(b, b->out.motor, a, source_get(b, t, ins[2], ins[3]));
        break;
    case RCX_OP_SET_MAX_POWER:
        set_power(b, b->out.global, a, source_get(b, t, ins[2], ins[3]));
        break;
    case RCX_OP_TX_POWER:
        if (a <= 1)
            b->tx_range = a;
        break;
    case RCX_OP_PLAY_SYSTEM_SOUND:
        if (a <= 5)
            sound_system(b, a);
        break;
    case RCX_OP_PLAY_TONE:
        sound_tone(b, RCX_LE16(ins + 1), ins[3]);
        break;
    case RCX_OP_PLAY_TONE_VAR:
        if ((var = var_ref(b, t, a)) != NULL)
            sound_tone(b, (u16)*var, ins[2]);
        break;
    case RCX_OP_START_TASK:
        sched_start_task(b, a);
        break;
    case RCX_OP_STOP_TASK:
        sched_stop_task(b, a);
        break;
    case RCX_OP_SELECT_PROGRAM:
        sched_select_program(b, a, t != NULL);
        break;
    case RCX_OP_CLEAR_TIMER:
        if (a < RCX_TIMERS)
            b->timer[a] = 0;
        break;
    case RCX_OP_POWER_DOWN_TIME:
        b->power_down_min = a;
        b->idle_reset = 1;
        break;
    case RCX_OP_CLEAR_SENSOR:
        sensor_clear(b, a);
        break;
    case RCX_OP_INC_COUNTER:
    case RCX_OP_DEC_COUNTER:
    case RCX_OP_CLEAR_COUNTER:
        if (a < RCX_COUNTERS) {
            if (op == RCX_OP_CLEAR_COUNTER)
                b->global[a] = 0;
            else
                b->global[a] = (s16)(u16)((u16)b->global[a] + (op == RCX_OP_INC_COUNTER ? 1u : 0xFFFFu));
            events_counter_changed(b, a);
        }
        break;
    case RCX_OP_MESSAGE:
        b->message = a;
        events_message_changed(b);
        break;
    case RCX_OP_SET_WATCH:
        if (a < 24 && ins[2] < 60) {
            b->watch = (u16)(a * 60u + ins[2]);
            b->watch_ms = 0;
            display_view(b, 0); /* the watch is selected (spec p. 51) */
        }
        break;
    case RCX_OP_SET_SENSOR_TYPE:
        sensor_set_type(b, a, ins[2]);
        break;
    case RCX_OP_SET_SENSOR_MODE:
        sensor_set_mode(b, a, ins[2]);
        break;
    case RCX_OP_SET_DATALOG:
        datalog_set(b, RCX_LE16(ins + 1));
        break;
    case RCX_OP_DATALOG_NEXT:
        datalog_add(b, t, a, ins[2]);
        break;
    case RCX_OP_SEND_UART:
        if ((u16)a + ins[2] <= 16) /* start + size <= 16 (spec p. 60) */
            remote_send_uart(b, a, ins[2]);
        break;
    case RCX_OP_DIRECT_EVENT:
        events_raise(b, (u16)source_get(b, t, a, RCX_LE16(ins + 2)));
        break;
    case RCX_OP_SELECT_DISPLAY:
        value = source_get(b, t, a, RCX_LE16(ins + 2));
        if (value >= 0 && value <= 7)
            display_view(b, (u8)value);
        break;
    case RCX_OP_VIEW_SOURCE:
        if (ins[2] <= 3)
            display_user(b, ins[2], ins[3], RCX_LE16(ins + 4));
        break;
    case RCX_OP_SET_EVENT:
        if (a < RCX_EVENTS && ins[2] <= 10 && event_type_valid(ins[3]))
            events_set(b, a, ins[2], ins[3]);
        break;
    case RCX_OP_CALIBRATE_EVENT:
        /* Upper factor first, as nqc encodes CalibrateEvent(event, lower, upper, hysteresis): the spec's table
         * (p. 74) lists lower first, but nqc's order is the one programs were written and run with. */
        if (a < RCX_EVENTS)
            events_calibrate(b, a, ins[3], ins[2], ins[4]);
        break;
    case RCX_OP_SET_VAR:
    case RCX_OP_SUM_VAR:
    case RCX_OP_SUB_VAR:
    case RCX_OP_DIV_VAR:
    case RCX_OP_MUL_VAR:
    case RCX_OP_SGN_VAR:
    case RCX_OP_ABS_VAR:
    case RCX_OP_AND_VAR:
    case RCX_OP_OR_VAR:
        ops_var(b, t, ins);
        break;
    case RCX_OP_SET_SOURCE:
        /* Source numbers use bits 0-5 of their byte (spec p. 86). */
        source_set(b, t, (u8)(a & 0x3F), ins[2], source_get(b, t, (u8)(ins[3] & 0x3F), RCX_LE16(ins + 4)));
        break;
    case RCX_OP_SET_PRIORITY:
        if (t)
            t->priority = a;
        break;
    case RCX_OP_SEND_MESSAGE:
        if (t)
            remote_send_message(b, (u8)source_get(b, t, a, ins[2]));
        break;
    default:
        return 0;
    }
    return 1;
}
