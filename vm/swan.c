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

/* + - * / & | ~ %: a family's low three bits; then SW_SET ... SW_NEG */
static const u8 arith_of[8 + SW_NEG - SW_SET + 1] = {
    RCX_OP_SUM_VAR >> 4, RCX_OP_SUB_VAR >> 4, RCX_OP_MUL_VAR >> 4, RCX_OP_DIV_VAR >> 4, RCX_OP_AND_VAR >> 4,
    RCX_OP_OR_VAR >> 4, ARITH_COMP, ARITH_MOD,
    ARITH_SET, RCX_OP_ABS_VAR >> 4, RCX_OP_SGN_VAR >> 4, ARITH_BSET, ARITH_BCLR, ARITH_XOR, ARITH_SHL, ARITH_SHR,
    ARITH_NEG,
};

u8 swan_exec(struct rcx *b, struct rcx_task *t, const u8 *ins, const struct rcx_swan_row *r)
{
    u8 op = ins[0], kind = r->kind, f = arith_of[op & 7], i;
    s16 v;

    if (kind == SW_GLOBAL) {           /* op g k8 / op g H L / op g T v8 */
        s16 *g = &b->global[ins[1]];
        v = ins[2];                    /* byte constants are unsigned */
        if (r->params & 1)             /* four bytes: a word high byte first, or a source */
            v = (op & 0x80) || op == RCX_SW_SET_G ? ops_source8(b, t, ins + 1) : (s16)(u16)((u16)ins[2] << 8 | ins[3]);
        if (!(op & 0x40))
            f = ARITH_SET;             /* 0x2B-0x2D */
        *g = ops_arith(f, *g, v);
        return 0;
    }
    if (kind <= SW_NEG) {              /* op Td d16 Ts s16 */
        v = ops_source(b, t, ins + 3);
        if (kind != SW_SOURCE)
            f = arith_of[8 + kind - SW_SET];
        ops_store(b, t, ins, ops_arith(f, ops_source(b, t, ins), v));
        return 0;
    }
    if (kind == SW_CLEAR_ALL) {
        f = ins[1];
        for (i = 0; i < RCX_TASKS; i++) {
            if (f & 0x01 && i < RCX_TIMERS) { /* timers, both kinds */
                b->timer[i] = 0;
                b->ms_base[i] = b->ms_now;
            }
            if (f & 0x02 && i < RCX_SENSORS)
                sensor_clear(b, i);
            if (f & 0x08)
                b->task[i].stack = 0;
        }
        if (f & 0x04)
            memset(b->global, 0, sizeof b->global);
        if (f & 0x10)
            events_clear_all(b);
        if (f & 0x40)
            b->log_size = b->log_count = 0; /* no datalog; 0x20 breakpoints: OpenRCX has none */
        return 0;
    }
    if (kind <= SW_POP) {              /* the stack's depth; overflow and underflow are bad input: the task stops */
        v = (s16)(t->stack + (kind == SW_PUSH ? 1 : -(s16)ins[1]));
        if ((u16)v > RCX_SWAN_STACK)
            return 1;
        t->stack = (u8)v;
        return 0;
    }
    /* Messages with a parameter: A2 m k8, B3 m k16, C3/C4 T v8 T v16 */
    i = ins[1];
    v = kind == SW_MSG_BYTE ? (s16)ins[2] : (s16)RCX_LE16(ins + 2);
    if (kind >= SW_SEND_PARAM) {
        i = (u8)ops_source8(b, t, ins);
        v = ops_source(b, t, ins + 2);
        if (kind == SW_SEND_PARAM) {
            remote_send_message_param(b, i, v);
            return 0;
        }
    }
    b->msg_param = v;                  /* first, so that the events the message raises find it */
    ops_set_message(b, i);
    return 0;
}

/*
 * The last block of a download came: the object's final size, then its slot's kind. A Swan program is one whose
 * code (any of its objects) has a Swan opcode, or a test (SCheckDo/LCheckDo) of source 43 or 44: NQC's Swan code
 * reaches every variable it compiles through those (swan-target.md 4).
 */
RCX_STATIC_ASSERT(checks, (RCX_OP_SCHECK_DO & 0xE7) == 0x85 && (RCX_OP_LCHECK_DO & 0xE7) == 0x85);
#define SWAN_SOURCE(s) ((u8)(((s) & 0x3F) - RCX_SRC_GLOBAL) <= 1) /* 43 or 44 */
void swan_download_done(struct rcx *b)
{
    u8 obj = b->dl.obj, slot = 0, n = RCX_SLOT_OBJS, op;
    const u8 *p, *end;

    mem_resize(b, obj, b->dl.filled);
    while (obj >= RCX_SLOT_OBJS) {     /* obj / 18 without a division */
        obj = (u8)(obj - RCX_SLOT_OBJS);
        slot++;
    }
    b->swan[slot] = 0;
    obj = (u8)(b->dl.obj - obj);       /* the slot's first object */
    do {
        p = b->arena + b->obj_start[obj];
        end = b->arena + b->obj_start[++obj];
        while (p < end) {
            op = *p;
            /* a Swan opcode, or SCheckDo/LCheckDo (toggle bit or not) with source 43 or 44 */
            if (rcx_swan_find(op) || ((op & 0xE7) == 0x85 && end - p > 2 && (SWAN_SOURCE(p[1]) || SWAN_SOURCE(p[2])))) {
                b->swan[slot] = 1;
                return;
            }
            p += 1 + rcx_op_params((u8)(op & ~RCX_TOGGLE));
        }
    } while (--n);
}
#endif
