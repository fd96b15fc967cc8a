/* SPDX-License-Identifier: MPL-2.0 */
/* Names and operand layouts of the byte codes, for the host disassembler and tests; not part of the firmware. */
#include "rcx_opcodes.h"

const struct rcx_opname rcx_opnames[] = {
#define RCX_OP(code, id, name, lasm, params, avail, reply, layout) \
    { code, #id, name, lasm, layout, params, avail, reply },
#include "rcx_opcodes.def"
#undef RCX_OP
};

const unsigned rcx_opname_count = sizeof rcx_opnames / sizeof rcx_opnames[0];

const struct rcx_swanname rcx_swannames[] = {
#define RCX_SWAN_OP(code, n, id, lasm, params, kind, layout) { code, n, params, kind, #id, lasm, layout },
#define RCX_OP(code, id, name, lasm, params, avail, reply, layout)
#include "rcx_opcodes.def"
#undef RCX_OP
#undef RCX_SWAN_OP
};
const unsigned rcx_swanname_count = sizeof rcx_swannames / sizeof rcx_swannames[0];
const char *const rcx_swan_ops[8] = { "sum", "sub", "mul", "div", "and", "or", "not", "mod" };

const struct rcx_swanname *rcx_swanname_find(u8 op)
{
    unsigned i;
    for (i = 0; i < rcx_swanname_count; i++)
        if ((rcx_swannames[i].count == 8 ? (u8)(op & 0xF8) : op) == rcx_swannames[i].code)
            return &rcx_swannames[i];
    return NULL;
}

/* The firmware needs no reply lengths (vm_direct knows its replies); tests and host tools decode them here. */
static const u8 reply_lengths[8] = { 0, 1, 2, 3, 9, 26, 189, RCX_REPLY_VAR };

u8 rcx_op_reply(u8 op)
{
    return reply_lengths[rcx_opflags[rcx_op_index(op)] >> 5];
}

const struct rcx_opname *rcx_opname_find(u8 op)
{
    unsigned i;
    op &= (u8)~RCX_TOGGLE;
    for (i = 0; i < rcx_opname_count; i++)
        if (rcx_opnames[i].code == op)
            return &rcx_opnames[i];
    return NULL;
}

u8 rcx_prog_params(u8 op)
{
    const struct rcx_swan_row *r = rcx_swan_find(op);
    return r ? rcx_swan_params(r) : rcx_op_params(op);
}
