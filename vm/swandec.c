/* The decoder's table of Swan's opcodes, generated from include/rcx_opcodes.def (its RCX_SWAN_OP rows). Not in
 * opcodes.c, which runs from the full F000 region on the brick. */
#include "rcx_opcodes.h"

#if RCX_SWAN
static const struct rcx_swan_row swan_rows[] = {
#define RCX_SWAN_OP(code, n, id, lasm, params, kind, layout) { code, (u8)((params) | ((n) == 8 ? RCX_SWAN_FAMILY : 0)), kind },
#define RCX_OP(code, id, name, lasm, params, avail, reply, layout)
#include "rcx_opcodes.def"
#undef RCX_OP
#undef RCX_SWAN_OP
};

const struct rcx_swan_row *rcx_swan_find(u8 op)
{
    const struct rcx_swan_row *r = swan_rows;
    u8 n = sizeof swan_rows / sizeof swan_rows[0];

    do {
        if ((u8)(op & (r->params & RCX_SWAN_FAMILY ? 0xF8 : 0xFF)) == r->code)
            return r;
        r++;
    } while (--n);
    return NULL;
}
#endif
