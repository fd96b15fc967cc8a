/* SPDX-License-Identifier: MPL-2.0 */
/* Decoder tables generated from include/rcx_opcodes.def: the only place byte-code properties are stated. */
#include "rcx_opcodes.h"

const u8 rcx_opflags[128] = {
#define RCX_OP(code, id, name, lasm, params, avail, reply, layout) \
    [rcx_op_index(code)] = RCX_OPFLAGS_PACK(params, avail, reply),
#include "rcx_opcodes.def"
#undef RCX_OP
};

#ifndef __H8300__ /* the brick's one walk of program code inlines it (drivers/h8300/swanblock.S) */
u8 rcx_op_params(u8 op)
{
    u8 f = rcx_opflags[rcx_op_index(op)], n = (u8)(op & 7);

    if (f)
        return (u8)(f & 7);
    if (n >= 6)
        n -= 6;                        /* unknown opcodes: their nominal length (rcx_op_nominal_params(), spec p. 5) */
    return n;
}
#endif
