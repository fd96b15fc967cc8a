/* Names and operand layouts of the byte codes, for the host disassembler and tests; not part of the firmware. */
#include "rcx_opcodes.h"

const struct rcx_opname rcx_opnames[] = {
#define RCX_OP(code, id, name, lasm, params, avail, reply, layout) \
    { code, #id, name, lasm, layout, params, avail, reply },
#include "rcx_opcodes.def"
#undef RCX_OP
};

const unsigned rcx_opname_count = sizeof rcx_opnames / sizeof rcx_opnames[0];

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
