/* Decoder tables generated from include/rcx_opcodes.def: the only place byte-code properties are stated. */
#include "rcx_opcodes.h"

const u8 rcx_opflags[128] = {
#define RCX_OP(code, id, name, lasm, params, avail, reply, layout) \
    [rcx_op_index(code)] = RCX_OPFLAGS_PACK(params, avail, reply),
#include "rcx_opcodes.def"
#undef RCX_OP
};

static const u8 reply_lengths[8] = { 0, 1, 2, 3, 9, 26, 189, RCX_REPLY_VAR };

u8 rcx_op_reply(u8 op)
{
    return reply_lengths[rcx_opflags[rcx_op_index(op)] >> 5];
}

u8 rcx_op_params(u8 op)
{
    u8 f = rcx_opflags[rcx_op_index(op)];
    /* Unknown opcodes are skipped by their nominal length (spec p. 5). */
    return f ? (u8)(f & 7) : rcx_op_nominal_params(op);
}
