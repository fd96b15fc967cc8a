/* SPDX-License-Identifier: MPL-2.0 */
/* The decoder's table of Swan's opcodes, generated from include/rcx_opcodes.def (its RCX_SWAN_OP rows). A file of its
 * own: a build without Swan's programs leaves it out whole. */
#include "rcx_opcodes.h"

#if RCX_SWAN
/* Two bytes a row: the families of eight first (their count n is the token 8), then the single opcodes (1). */
#define ROW(code, params, kind) { code, (u8)((params) | (kind) << 3) },
#define ROW_IF_8_8(code, params, kind) ROW(code, params, kind)
#define ROW_IF_8_1(code, params, kind)
#define ROW_IF_1_8(code, params, kind)
#define ROW_IF_1_1(code, params, kind) ROW(code, params, kind)
#ifdef __H8300__
#define swan_rows rcx_swan_rows        /* read by drivers/h8300/swanblock.S */
extern const struct rcx_swan_row rcx_swan_rows[];
#else
static
#endif
const struct rcx_swan_row swan_rows[] = {
#define RCX_OP(code, id, name, lasm, params, avail, reply, layout)
#define RCX_SWAN_OP(code, n, id, lasm, params, kind, layout) ROW_IF_8_##n(code, params, kind)
#include "rcx_opcodes.def"
#undef RCX_SWAN_OP
#define RCX_SWAN_OP(code, n, id, lasm, params, kind, layout) ROW_IF_1_##n(code, params, kind)
#include "rcx_opcodes.def"
#undef RCX_SWAN_OP
#undef RCX_OP
};
enum {
    FAMILIES = 0
#define RCX_OP(code, id, name, lasm, params, avail, reply, layout)
#define RCX_SWAN_OP(code, n, id, lasm, params, kind, layout) + ((n) == 8)
#include "rcx_opcodes.def"
#undef RCX_SWAN_OP
#undef RCX_OP
};

#ifdef __H8300__
/* On the brick rcx_swan_find() is drivers/h8300/swanblock.S: a byte that is none of Swan's opcodes (every byte code
 * run_slow() runs, vm/interp.c) is told so by one bit of a map in some 90 states, not by the 2 500 of this search. */
#include "swanblock.h"
RCX_STATIC_ASSERT(families, FAMILIES == SB_SWAN_FAMILIES && sizeof(struct rcx_swan_row) == 2);
#else
const struct rcx_swan_row *rcx_swan_find(u8 op)
{
    const struct rcx_swan_row *r = swan_rows;
    u8 m;

    do {
        m = op;
        if (r < swan_rows + FAMILIES)
            m &= 0xF8;
        if (m == r->code)
            return r;
    } while (++r != swan_rows + sizeof swan_rows / sizeof swan_rows[0]);
    return NULL;
}
#endif /* __H8300__ */
#endif
