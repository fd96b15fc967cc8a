/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Swan's program opcodes (rcx_opcodes.def, swan-target.md 2), with OpenRCX's rules where Swan is silent (4). One
 * decoder for the arithmetic: every form (global op= k8 / word / source, source op= source) becomes a destination (a
 * global, or a source operand) and a value, the operation comes from the family's low three bits or the row, and
 * ops_arith() computes it as it does RCX 2.0's SetVar..OrVar. Written for size: this is firmware code.
 */
#include "rcx_string.h"
#include "rcx.h"
#include "sources.h"

#if RCX_SWAN

/* + - * / & | ~ %: a family's operation, from its low three bits */
static const u8 arith_of[8] = {
    ARITH_SUM, ARITH_SUB, ARITH_MUL, ARITH_DIV, ARITH_AND, ARITH_OR, ARITH_COMP, ARITH_MOD,
};

/* ClearAll's flags: 0x01 timers (both kinds), 0x02 inputs, 0x04 variables, 0x08 task stacks, 0x10 events,
 * 0x40 datalog; 0x20 breakpoints: OpenRCX has none */
static void clear_all(struct rcx *b, u8 f)
{
    struct rcx_task *t;
    u8 i;

    if (f & 0x01)
        for (i = 0; i < RCX_TIMERS; i++) {
            b->timer[i] = 0;
            b->ms_base[i] = b->ms_now;
        }
    if (f & 0x02)
        for (i = 0; i < RCX_SENSORS; i++)
            sensor_clear(b, i);
    if (f & 0x04)
        memset(b->global, 0, sizeof b->global);
    if (f & 0x08)
        for (t = b->task; t < b->task + RCX_TASKS; t++)
            t->stack = 0;
    if (f & 0x10)
        events_clear_all(b);
    if (f & 0x40)
        b->log_size = b->log_count = 0;
}

/* Push (0xE3) and pop (0x01 n) change the stack's depth; overflow and underflow are bad input: the task stops. */
static void stack(struct rcx *b, struct rcx_task *t, const u8 *ins, u8 kind)
{
    s16 depth = (s16)(t->stack + (kind == SW_PUSH ? 1 : -(s16)ins[1]));

    if ((u16)depth > RCX_SWAN_STACK)
        sched_stop(b, t);
    else
        t->stack = (u8)depth;
}

/* Messages with a parameter: A2 m k8, B3 m k16, C3/C4 T v8 T v16 (send, set) */
static void message(struct rcx *b, struct rcx_task *t, const u8 *ins, u8 kind)
{
    s16 m, v;                          /* (the message: its low byte) */

    if (kind >= SW_SEND_PARAM) {
        m = ops_source8(b, t, ins);
        v = ops_source(b, t, ins + 2);
        if (kind == SW_SEND_PARAM) {
            remote_send_message_param(b, (u8)m, v);
            return;
        }
    } else {
        m = ins[1];
        v = ins[2];
        if (kind != SW_MSG_BYTE)
            v = (s16)RCX_LE16(ins + 2);
    }
    b->msg_param = v;                  /* first, so that the events the message raises find it */
    ops_set_message(b, (u8)m);
}

void swan_exec(struct rcx *b, struct rcx_task *t, const u8 *ins, const struct rcx_swan_row *r)
{
    u8 kind = rcx_swan_kind(r), f;
    s16 v, *g;

    if (kind >= SW_SOURCE) {           /* op Td d16 Ts s16: the operation is the row's, or the family's */
        v = ops_source(b, t, ins + 3);
        f = (u8)(kind - SW_SOURCE);
        if (!f)
            f = arith_of[ins[0] & 7];
        source_set(b, t, ins[1], RCX_LE16(ins + 2), ops_arith(ops_source(b, t, ins), v, f));
        return;
    }
    if (kind >= SW_K8) {               /* op g k8 / op g H L / op g T v8 */
        v = ins[2];                    /* byte constants are unsigned */
        if (kind == SW_WORD)           /* high byte first */
            v = (s16)(u16)((u16)ins[2] << 8 | ins[3]);
        if (kind == SW_SRC8)
            v = ops_source8(b, t, ins + 1);
        g = &b->global[ins[1]];
        *g = ops_arith(*g, v, ins[0] & 0x40 ? arith_of[ins[0] & 7] : ARITH_SET); /* 0x2B-0x2D: = */
        return;
    }
    if (kind >= SW_MSG_BYTE)
        message(b, t, ins, kind);
    else if (kind == SW_CLEAR_ALL)
        clear_all(b, ins[1]);
    else if (kind >= SW_PUSH)
        stack(b, t, ins, kind);
    else
        ops_wait(b, t, ins);           /* SW_WAIT_MS */
}

#endif
