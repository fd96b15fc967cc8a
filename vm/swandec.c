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
static const struct rcx_swan_row swan_rows[] = {
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
#endif
