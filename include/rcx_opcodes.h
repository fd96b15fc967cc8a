/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Accessors over the one instruction table in rcx_opcodes.def.
 *
 * Operand kinds used in the layout column (bytes consumed in brackets):
 *   b [1] plain number         v [1] variable number        x [1] sensor mode | slope
 *   w [2] 16-bit number        s [2] source, 8-bit value     S [3] source, 16-bit value
 *   d [2] destination source (bits 0-5) and index             m [1] motor list (bits 0-2)
 *   M [1] motors + on/off/float (bits 6-7)                     D [1] motors + direction (bits 6-7)
 *   j [1] jump: bits 0-6 distance, bit 7 backwards             J [2] jump: 15-bit distance, bit 7 of byte 0 backwards
 *   f [1] forward jump, unsigned                               F [2] forward jump, unsigned 16-bit
 *   L [2] jump, signed 16-bit                                  c [5] relation|source 1, source 2, value 1 (16), value 2 (8)
 *   k [*] download block: data bytes then checksum (length from the preceding w)
 * Every distance counts from the first byte of its own field (spec p. 11).
 */
#ifndef RCX_OPCODES_H
#define RCX_OPCODES_H

#include "rcx_types.h"
#include "rcx_limits.h"

#define RCX_DIRECT 0x01
#define RCX_PROGRAM 0x02
#define RCX_VARLEN 0xFF
#define RCX_REPLY_VAR 0xFF

#define RCX_TOGGLE 0x08 /* bit 3 of an opcode byte marks a new IR command; never part of the byte code */

enum rcx_op {
#define RCX_OP(code, id, name, lasm, params, avail, reply, layout) RCX_OP_##id = code,
#include "rcx_opcodes.def"
#undef RCX_OP
    RCX_OP_NONE = 0xFF
};

/* The table has 128 rows: the toggle bit folded out of the opcode byte. */
#define rcx_op_index(op) ((u8)((((op) >> 1) & 0x78) | ((op) & 0x07)))

/*
 * Per-opcode properties packed into one byte each (the firmware keeps only these 128 bytes):
 * bits 0-2 operand bytes (ContinueDL's nominal 5: its packet carries its own length), bits 3-4 availability,
 * bits 5-7 reply class (see rcx_op_reply). A row of 0 is an opcode the RCX 2.0 does not have.
 */
extern const u8 rcx_opflags[128];
#define RCX_OPFLAGS_PACK(params, avail, reply)                                                          \
    ((u8)(((params) == RCX_VARLEN ? 5 : (params)) | (avail) << 3 |                                     \
          ((reply) == 0 ? 0 : (reply) == 1 ? 1 : (reply) == 2 ? 2 : (reply) == 3 ? 3 : (reply) == 9 ? 4 \
           : (reply) == 26 ? 5 : (reply) == 189 ? 6 : 7) << 5))
#define rcx_op_avail(op) ((u8)((rcx_opflags[rcx_op_index(op)] >> 3) & 3))

/* Reply length including the reply opcode: 0 none, RCX_REPLY_VAR computed from the operands (host only). */
u8 rcx_op_reply(u8 op);

/* Operand bytes implied by the low three bits of any opcode, known or not (6 and 7 mean 0 and 1). */
#define rcx_op_nominal_params(op) ((u8)(((op) & 7) >= 6 ? ((op) & 7) - 6 : ((op) & 7)))

/* Operand bytes an instruction occupies in program code (unknown opcodes: the nominal count). */
u8 rcx_op_params(u8 op);

/*
 * Swan's program opcodes (the RCX_SWAN_OP rows of rcx_opcodes.def). The firmware keeps one 2-byte row per line of the
 * table: the opcode, its operand bytes and what runs it (enum rcx_swan_kind, vm/swan.c).
 */
enum rcx_swan_op {
#define RCX_SWAN_OP(code, n, id, lasm, params, kind, layout) RCX_SW_##id = code,
#define RCX_OP(code, id, name, lasm, params, avail, reply, layout)
#include "rcx_opcodes.def"
#undef RCX_OP
#undef RCX_SWAN_OP
    RCX_SW_NONE = 0x100
};
/* ops_arith()'s operations (vm/ops.c): the high nibble of SetVar..OrVar (0x14-0x94), then Swan's */
#define ARITH_SET 1
#define ARITH_SUM 2
#define ARITH_SUB 3
#define ARITH_DIV 4
#define ARITH_MUL 5
#define ARITH_SGN 6
#define ARITH_ABS 7
#define ARITH_AND 8
#define ARITH_OR 9
#define ARITH_COMP 10
#define ARITH_MOD 11
#define ARITH_XOR 12
#define ARITH_SHL 13
#define ARITH_SHR 14
#define ARITH_NEG 15
#define ARITH_BSET 16
#define ARITH_BCLR 17
enum rcx_swan_kind {
    SW_WAIT_MS, SW_CLEAR_ALL, SW_PUSH, SW_POP,
    SW_MSG_BYTE, SW_MSG_WORD, SW_SEND_PARAM, SW_SET_PARAM, /* message and parameter: m k8, m k16, T v8 T v16 */
    SW_K8, SW_WORD, SW_SRC8, /* global[g] op= k8 / word / S(T, v8); op by the low three bits, 0x2B-0x2D: = */
    SW_SOURCE                /* S(d) op= S(s); op by the low three bits, or SW_SOURCE + ARITH_*: that one */
};
struct rcx_swan_row {
    u8 code;        /* of a family of eight: its first */
    u8 info;        /* bits 0-2 operand bytes, bits 3-7 the kind */
};
#define rcx_swan_params(r) ((u8)((r)->info & 7))
#define rcx_swan_kind(r) ((u8)((r)->info >> 3))
/* The row of a Swan opcode, all eight bits of it; NULL for any other byte. */
#if RCX_SWAN
const struct rcx_swan_row *rcx_swan_find(u8 op);
#else
#define rcx_swan_find(op) ((void)(op), (const struct rcx_swan_row *)0)
#endif
/* Operand bytes of the instruction at the start of program code: Swan's, or as rcx_op_params(). */
u8 rcx_prog_params(u8 op);

/* Name tables with every column of the table, for the host disassembler and tests (not in the firmware). */
struct rcx_opname {
    u8 code;
    const char *id;
    const char *name;
    const char *lasm;
    const char *layout;
    u8 params;  /* as in the table: RCX_VARLEN for ContinueDL */
    u8 avail;
    u8 reply;
};
struct rcx_swanname {
    u8 code, count, params, kind;
    const char *id;
    const char *lasm;   /* %s: the family's operation, rcx_swan_ops[code & 7] */
    const char *layout;
};
extern const struct rcx_swanname rcx_swannames[];
extern const unsigned rcx_swanname_count;
extern const char *const rcx_swan_ops[8];
/* The row naming a Swan opcode (of a family: its head), NULL for any other byte. */
const struct rcx_swanname *rcx_swanname_find(u8 op);
extern const struct rcx_opname rcx_opnames[];
extern const unsigned rcx_opname_count;
const struct rcx_opname *rcx_opname_find(u8 op);

#endif
