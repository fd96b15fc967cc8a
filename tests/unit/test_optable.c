/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The instruction table (include/rcx_opcodes.def) checked row by row against the specification:
 *   - every opcode of the spec's table of contents (pp. 2-3) has exactly one row, and there are no others;
 *   - availability as printed on each command's page (pp. 12-97);
 *   - operand count = the NNN rule of spec p. 5 (low three bits, 6 and 7 meaning 0 and 1), except SCheckDo (6),
 *     LCheckDo (7) (their layouts, pp. 93-94) and ContinueDL (self-sized, p. 90);
 *   - reply length as nqc requires it (host-tools.md §1).
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>
#include "brick.h"

#define D RCX_DIRECT
#define P RCX_PROGRAM
#define DP (RCX_DIRECT | RCX_PROGRAM)

/* Opcode and availability, transcribed from the spec's command pages (toggle bit clear, spec p. 11). */
static const struct { u8 code, avail; } spec_ops[] = {
    { 0x10, DP }, { 0x20, D }, { 0x30, D }, { 0x40, D }, { 0x50, DP }, { 0x60, DP }, { 0x70, D },
    { 0x80, DP }, { 0x90, DP }, { 0xA0, P }, { 0xB0, P }, { 0xD0, DP }, { 0xE0, DP }, { 0x06, DP },
    { 0xF6, P },  { 0x21, DP }, { 0x31, DP }, { 0x51, DP }, { 0x61, D }, { 0x71, DP }, { 0x81, DP },
    { 0x91, DP }, { 0xA1, DP }, { 0xB1, DP }, { 0xC1, D }, { 0xD1, DP }, { 0xE1, DP }, { 0x17, P },
    { 0x27, P },  { 0x37, P },  { 0x67, DP }, { 0x77, DP }, { 0x97, DP }, { 0xA7, DP }, { 0xB7, DP },
    { 0xD7, P },  { 0xF7, DP }, { 0x02, DP }, { 0x12, D },  { 0x22, DP }, { 0x32, DP }, { 0x42, DP },
    { 0x52, DP }, { 0x62, DP }, { 0x72, P },  { 0x82, P },  { 0x92, P },  { 0xB2, P },  { 0xC2, DP },
    { 0xD2, D },  { 0xF2, P },  { 0x03, DP }, { 0x13, DP }, { 0x23, DP }, { 0x33, DP }, { 0x43, P },
    { 0x63, D },  { 0x73, P },  { 0x93, DP }, { 0xA3, DP }, { 0xF3, P },  { 0x04, DP }, { 0x14, DP },
    { 0x24, DP }, { 0x34, DP }, { 0x44, DP }, { 0x54, DP }, { 0x64, DP }, { 0x74, DP }, { 0x84, DP },
    { 0x94, DP }, { 0xA4, D },  { 0xB4, P },  { 0x05, DP }, { 0x15, D },  { 0x25, D },  { 0x35, D },
    { 0x45, D },  { 0x65, D },  { 0x75, D },  { 0x85, P },  { 0x95, P },  { 0xA5, D },  { 0xB5, P },
    { 0xE5, DP },
};
#define SPEC_OPS (sizeof spec_ops / sizeof spec_ops[0])

static int spec_index(u8 code)
{
    unsigned i;
    for (i = 0; i < SPEC_OPS; i++)
        if (spec_ops[i].code == code)
            return (int)i;
    return -1;
}

/* host-tools.md §1: 25 35 45 75 -> 2; 12 30 -> 3; 15 -> 9; A5 -> 26; 20 -> 189; A4 -> 3*count+1;
 * 52 62 -> 2: firm0328 answers a status byte (reference-firmware.md, "The brick's face"; nqc reads the opcode);
 * F7, D2, C2 send no reply (spec pp. 48, 61, 60); program-only commands are never answered; all others 1.
 * UploadRam 63 answers its opcode plus the requested bytes (spec p. 68): variable like A4. */
static unsigned expected_reply(u8 code, u8 avail)
{
    switch (code) {
    case 0x25: case 0x35: case 0x45: case 0x75: case 0x52: case 0x62: return 2;
    case 0x12: case 0x30: return 3;
    case 0x15: return 9;
    case 0xA5: return 26;
    case 0x20: return 189;
    case 0xA4: case 0x63: return RCX_REPLY_VAR;
    case 0xF7: case 0xD2: case 0xC2: return 0;
    }
    return avail == P ? 0 : 1;
}

static void every_spec_opcode_has_one_row(void **state)
{
    unsigned i, j;
    (void)state;
    assert_int_equal(rcx_opname_count, SPEC_OPS);
    for (i = 0; i < SPEC_OPS; i++) {
        unsigned found = 0;
        for (j = 0; j < rcx_opname_count; j++)
            found += rcx_opnames[j].code == spec_ops[i].code;
        if (found != 1)
            fail_msg("opcode %02X has %u rows", spec_ops[i].code, found);
    }
}

static void rows_have_toggle_bit_clear_and_match_opinfo(void **state)
{
    unsigned j, used = 0;
    (void)state;
    for (j = 0; j < rcx_opname_count; j++) {
        u8 code = rcx_opnames[j].code;
        assert_int_equal(code & RCX_TOGGLE, 0); /* spec p. 11 lists codes with the toggle bit zero */
        assert_int_not_equal(rcx_opflags[rcx_op_index(code)], 0);
        /* the toggle bit folds onto the same row (spec p. 5: XXXX NNN is the byte code) */
        assert_int_equal(rcx_op_index(code | RCX_TOGGLE), rcx_op_index(code));
        assert_ptr_equal(rcx_opname_find((u8)(code | RCX_TOGGLE)), &rcx_opnames[j]);
    }
    for (j = 0; j < 128; j++)
        used += rcx_opflags[j] != 0;
    assert_int_equal(used, SPEC_OPS); /* no rows beyond the spec's */
}

static void availability_matches_spec_pages(void **state)
{
    unsigned j;
    (void)state;
    for (j = 0; j < rcx_opname_count; j++) {
        u8 code = rcx_opnames[j].code;
        int s = spec_index(code);
        assert_true(s >= 0);
        if (rcx_op_avail(code) != spec_ops[s].avail || rcx_opnames[j].avail != spec_ops[s].avail)
            fail_msg("%s (%02X): availability %u/%u, spec says %u", rcx_opnames[j].name, code,
                     rcx_op_avail(code), rcx_opnames[j].avail, spec_ops[s].avail);
    }
}

static void operand_count_follows_nnn_rule(void **state)
{
    unsigned j;
    (void)state;
    for (j = 0; j < rcx_opname_count; j++) {
        u8 code = rcx_opnames[j].code;
        u8 params = rcx_opnames[j].params;
        unsigned nominal = (code & 7) >= 6 ? (code & 7) - 6u : (code & 7u); /* spec p. 5 and footnote 1 */
        unsigned expect = code == 0x85 ? 6u      /* src1|rel, src2, value1 (2), value2 (1), distance (1), p. 93 */
                        : code == 0x95 ? 7u      /* the same with a 2-byte distance, p. 94 */
                        : code == 0x45 ? RCX_VARLEN /* header + data + checksum, p. 90 */
                        : nominal;
        if (params != expect)
            fail_msg("%s (%02X): %u operand bytes, expected %u", rcx_opnames[j].name, code, params, expect);
        /* The decoder skips ContinueDL (never valid in a program) by its nominal length. */
        assert_int_equal(rcx_op_params(code), code == 0x45 ? nominal : expect);
        assert_int_equal(rcx_op_nominal_params(code), nominal);
    }
}

static void nominal_rule_for_unknown_opcodes(void **state)
{
    unsigned op;
    (void)state;
    /* An unknown opcode is skipped by its low three bits (spec p. 5): 0-5 bytes, and 6, 7 mean 0, 1. */
    for (op = 0; op < 256; op++) {
        static const u8 len[8] = { 0, 1, 2, 3, 4, 5, 0, 1 };
        assert_int_equal(rcx_op_nominal_params((u8)op), len[op & 7]);
        if (spec_index((u8)(op & ~RCX_TOGGLE)) < 0)
            assert_int_equal(rcx_op_params((u8)op), len[op & 7]);
    }
    /* The two exceptions as seen by the decoder. */
    assert_int_equal(rcx_op_params(0x85), 6);
    assert_int_equal(rcx_op_params(0x8D), 6);
    assert_int_equal(rcx_op_params(0x95), 7);
}

static void reply_lengths_match_host_tools(void **state)
{
    unsigned j;
    (void)state;
    for (j = 0; j < rcx_opname_count; j++) {
        u8 code = rcx_opnames[j].code;
        unsigned expect = expected_reply(code, spec_ops[spec_index(code)].avail);
        if (rcx_op_reply(code) != expect || rcx_opnames[j].reply != expect)
            fail_msg("%s (%02X): reply %u/%u, expected %u", rcx_opnames[j].name, code, rcx_op_reply(code),
                     rcx_opnames[j].reply, expect);
    }
}

/* Spot checks through vm_direct: the machine answers with the lengths the table states. */
static void direct_replies_have_table_lengths(void **state)
{
    static const struct { u8 cmd[6]; u8 len; u8 reply; } cases[] = {
        { { 0x10 }, 1, 1 },                         /* ping */
        { { 0x30 }, 1, 3 },                         /* battery */
        { { 0x12, 0x02, 0x05 }, 3, 3 },             /* poll constant 5 */
        { { 0x20 }, 1, 189 },                       /* memory map */
        { { 0x15, 1, 3, 5, 7, 11 }, 6, 9 },         /* version */
        { { 0x14, 0x00, 0x02, 0x05, 0x00 }, 5, 1 }, /* setv */
        { { 0xF7, 0x05 }, 2, 0 },                   /* message: no reply (p. 48) */
        { { 0x17, 0x00 }, 2, 0 },                   /* Gosub is program-only */
        { { 0x27, 0x81 }, 2, 0 },                   /* SJump is program-only */
        { { 0x43, 0x02, 0x01, 0x00 }, 4, 0 },       /* Wait is program-only */
        { { 0x45, 0x01, 0x00, 0x00, 0x00, 0x00 }, 6, 2 }, /* ContinueDL, none active: status 6 */
        { { 0x25, 0, 0, 0, 4, 0 }, 6, 2 },          /* BeginOfTask */
    };
    struct rcx *b = brick_new();
    u8 reply[RCX_REPLY_MAX];
    unsigned i;
    (void)state;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        unsigned n = brick_cmd(b, cases[i].cmd, cases[i].len, reply);
        if (n != cases[i].reply)
            fail_msg("command %02X: reply length %u, expected %u", cases[i].cmd[0], n, cases[i].reply);
        if (n)
            assert_int_equal(reply[0], (u8)~cases[i].cmd[0]);
    }
    brick_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_spec_opcode_has_one_row),
        cmocka_unit_test(rows_have_toggle_bit_clear_and_match_opinfo),
        cmocka_unit_test(availability_matches_spec_pages),
        cmocka_unit_test(operand_count_follows_nnn_rule),
        cmocka_unit_test(nominal_rule_for_unknown_opcodes),
        cmocka_unit_test(reply_lengths_match_host_tools),
        cmocka_unit_test(direct_replies_have_table_lengths),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
