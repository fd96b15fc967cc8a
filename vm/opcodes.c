/* Decoder tables generated from include/rcx_opcodes.def: the only place byte-code properties are stated. */
#include "rcx_opcodes.h"

const struct rcx_opinfo rcx_opinfo[128] = {
#define RCX_OP(code, id, name, lasm, params, avail, reply, layout) \
    [rcx_op_index(code)] = { code, params, avail, reply },
#include "rcx_opcodes.def"
#undef RCX_OP
};

u8 rcx_op_params(u8 op)
{
    const struct rcx_opinfo *info = &rcx_opinfo[rcx_op_index(op)];
    /* Unknown opcodes and the self-sized download block are skipped by their nominal length (spec p. 5). */
    if (info->avail == 0 || info->params == RCX_VARLEN)
        return rcx_op_nominal_params(op);
    return info->params;
}
