/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Direct commands: byte-exact replies and effects, derived from LEGO's "RCX 2.0 Firmware Command Overview"
 * (spec, pp. 12-97), reference-firmware.md (firm0328 as observed) and host-tools.md (reply lengths nqc expects).
 *
 * Reply opcode: the firmware answers with the complement of the opcode byte as sent. The spec prints every
 * command and reply "with the transmission toggle bit set to zero" (p. 11), so its listed reply is ~op with
 * bit 3 cleared: 0x10 is answered EF, 0x18 (toggle set) E7 as printed on p. 12.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "brick.h"

#define SEND(b, r, ...) \
    brick_cmd((b), (const u8[]){ __VA_ARGS__ }, sizeof((const u8[]){ __VA_ARGS__ }), (r))

static const u8 loop_inc0[] = { 0x24, 0x00, 0x02, 0x01, 0x00, 0x27, 0x86 }; /* L: sumv var[0],1 ; jmp L */
static const u8 loop_inc1[] = { 0x24, 0x01, 0x02, 0x01, 0x00, 0x27, 0x86 }; /* L: sumv var[1],1 ; jmp L */
static const u8 spin[] = { 0x27, 0x81 };                                    /* jmp 0 (spec p. 11) */
static const u8 call_sub0[] = { 0x17, 0x00, 0x27, 0x81 };                   /* calls 0 ; jmp 0 */
static const u8 call_sub3[] = { 0x17, 0x03, 0x27, 0x81 };                   /* calls 3 ; jmp 0 */

static void assert_unchanged(const struct rcx *b, struct rcx *s)
{
    assert_memory_equal(b, s, sizeof *b);
    brick_free_copy(s);
}

static int running(const struct rcx *b, u8 n)
{
    return b->task[n].state != RCX_TASK_IDLE;
}

static int any_running(const struct rcx *b)
{
    u8 n;
    for (n = 0; n < RCX_TASKS; n++)
        if (running(b, n))
            return 1;
    return 0;
}

static s16 poll(struct rcx *b, u8 src, u8 idx)
{
    u8 r[RCX_REPLY_MAX];
    assert_int_equal(SEND(b, r, 0x12, src, idx), 3);
    return (s16)(u16)(r[1] | r[2] << 8);
}

/* Free program memory as hosts compute it: memory map word 93 - word 92 (reference-firmware.md). */
static unsigned mem_free_map(struct rcx *b)
{
    u8 r[RCX_REPLY_MAX];
    assert_int_equal(SEND(b, r, 0x20), 189);
    return (unsigned)((r[187] << 8 | r[188]) - (r[185] << 8 | r[186]));
}

static u16 map_word(struct rcx *b, unsigned i)
{
    u8 r[RCX_REPLY_MAX];
    assert_int_equal(SEND(b, r, 0x20), 189);
    return (u16)(r[1 + 2 * i] << 8 | r[2 + 2 * i]);
}

/* ---- the table of every direct-available command (spec availability "Direct" or "Direct/Program") ---- */

struct dcmd {
    u8 cmd[6];
    u8 len;       /* opcode + the spec's parameter bytes */
    u8 spec;      /* reply opcode printed in the spec (toggle bit zero); 0 = no reply */
    u8 reply_len; /* host-tools.md §1 */
};

static const struct dcmd table[] = {
    { { 0x10 }, 1, 0xE7, 1 },                            /* p. 12 PBAliveOrNot */
    { { 0x20 }, 1, 0xD7, 189 },                          /* p. 13 MemMap */
    { { 0x30 }, 1, 0xC7, 3 },                            /* p. 14 PBBattery */
    { { 0x40 }, 1, 0xB7, 1 },                            /* p. 15 DeleteAllTasks */
    { { 0x50 }, 1, 0xA7, 1 },                            /* p. 16 StopAllTasks */
    { { 0x60 }, 1, 0x97, 1 },                            /* p. 17 PBTurnOff */
    { { 0x70 }, 1, 0x87, 1 },                            /* p. 18 DeleteAllSubs */
    { { 0x80 }, 1, 0x77, 1 },                            /* p. 19 ClearSound */
    { { 0x90 }, 1, 0x67, 1 },                            /* p. 20 ClearPBMessage */
    { { 0xD0 }, 1, 0x27, 1 },                            /* p. 23 MuteSound */
    { { 0xE0 }, 1, 0x17, 1 },                            /* p. 24 UnmuteSound */
    { { 0x06 }, 1, 0xF1, 1 },                            /* p. 25 ClearAllEvents */
    { { 0x21, 0x87 }, 2, 0xD6, 1 },                      /* p. 27 OnOffFloat */
    { { 0x31, 0x01 }, 2, 0xC6, 1 },                      /* p. 28 PbTXPower */
    { { 0x51, 0x01 }, 2, 0xA6, 1 },                      /* p. 29 PlaySystemSound */
    { { 0x61, 0x03 }, 2, 0x96, 1 },                      /* p. 30 DeleteTask */
    { { 0x71, 0x00 }, 2, 0x86, 1 },                      /* p. 31 StartTask */
    { { 0x81, 0x00 }, 2, 0x76, 1 },                      /* p. 32 StopTask */
    { { 0x91, 0x01 }, 2, 0x66, 1 },                      /* p. 33 SelectProgram */
    { { 0xA1, 0x00 }, 2, 0x56, 1 },                      /* p. 34 ClearTimer */
    { { 0xB1, 0x05 }, 2, 0x46, 1 },                      /* p. 35 PBPowerDownTime */
    { { 0xC1, 0x00 }, 2, 0x36, 1 },                      /* p. 36 DeleteSub */
    { { 0xD1, 0x00 }, 2, 0x26, 1 },                      /* p. 37 ClearSensorValue */
    { { 0xE1, 0x87 }, 2, 0x16, 1 },                      /* p. 38 SetFwdSetRwdRewDir */
    { { 0x67, 0x87 }, 2, 0x90, 1 },                      /* p. 42 ConnectDisconnect */
    { { 0x77, 0x87 }, 2, 0x80, 1 },                      /* p. 43 SetNormSetInvAltDir */
    { { 0x97, 0x00 }, 2, 0x60, 1 },                      /* p. 44 IncCounter */
    { { 0xA7, 0x00 }, 2, 0x50, 1 },                      /* p. 45 DecCounter */
    { { 0xB7, 0x00 }, 2, 0x40, 1 },                      /* p. 46 ClearCounter */
    { { 0xF7, 0x05 }, 2, 0, 0 },                         /* p. 48 InternMessage: no reply */
    { { 0x02, 0x00, 0x0A }, 3, 0xF5, 1 },                /* p. 49 PlayToneVar */
    { { 0x12, 0x02, 0x07 }, 3, 0xE5, 3 },                /* p. 50 Poll */
    { { 0x22, 0x0C, 0x1E }, 3, 0xD5, 1 },                /* p. 51 SetWatch */
    { { 0x32, 0x00, 0x01 }, 3, 0xC5, 1 },                /* p. 52 SetSensorType */
    { { 0x42, 0x00, 0x20 }, 3, 0xB5, 1 },                /* p. 53 SetSensorMode (reply illegible in the OCR: ~0x42) */
    { { 0x52, 0x05, 0x00 }, 3, 0xA5, 2 },                /* p. 54 SetDataLog, and a status (reference-firmware.md) */
    { { 0x62, 0x00, 0x00 }, 3, 0x95, 2 },                /* p. 55 DataLogNext, and a status (reference-firmware.md) */
    { { 0xC2, 0x00, 0x02 }, 3, 0, 0 },                   /* p. 60 SendUARTData: no reply */
    { { 0xD2, 0x00, 0x00 }, 3, 0, 0 },                   /* p. 61 RemoteCommand: no reply */
    { { 0x03, 0x02, 0x00, 0x00 }, 4, 0xF4, 1 },          /* p. 63 DirectEvent */
    { { 0x13, 0x07, 0x02, 0x07 }, 4, 0xE4, 1 },          /* p. 64 SetPower */
    { { 0x23, 0xB8, 0x01, 0x0A }, 4, 0xD4, 1 },          /* p. 65 PlayTone */
    { { 0x33, 0x02, 0x00, 0x00 }, 4, 0xC4, 1 },          /* p. 66 SelectDisplay */
    { { 0x63, 0x00, 0x80, 0x04 }, 4, 0x94, 5 },          /* p. 68 UploadRam, 4 bytes */
    { { 0x93, 0x00, 0x00, 0x0A }, 4, 0x64, 1 },          /* p. 70 SetEvent */
    { { 0xA3, 0x07, 0x02, 0x07 }, 4, 0x54, 1 },          /* p. 72 SetMaxPower */
    { { 0x04, 0x00, 0x10, 0x20, 0x05 }, 5, 0xF3, 1 },    /* p. 74 CalibrateEvent */
    { { 0x14, 0x00, 0x02, 0x01, 0x00 }, 5, 0xE3, 1 },    /* p. 75 SetVar */
    { { 0x24, 0x00, 0x02, 0x01, 0x00 }, 5, 0xD3, 1 },    /* p. 76 SumVar */
    { { 0x34, 0x00, 0x02, 0x01, 0x00 }, 5, 0xC3, 1 },    /* p. 77 SubVar */
    { { 0x44, 0x00, 0x02, 0x01, 0x00 }, 5, 0xB3, 1 },    /* p. 78 DivVar */
    { { 0x54, 0x00, 0x02, 0x01, 0x00 }, 5, 0xA3, 1 },    /* p. 79 MulVar */
    { { 0x64, 0x00, 0x02, 0x01, 0x00 }, 5, 0x93, 1 },    /* p. 80 SgnVar */
    { { 0x74, 0x00, 0x02, 0x01, 0x00 }, 5, 0x83, 1 },    /* p. 81 AbsVar */
    { { 0x84, 0x00, 0x02, 0x01, 0x00 }, 5, 0x73, 1 },    /* p. 82 AndVar */
    { { 0x94, 0x00, 0x02, 0x01, 0x00 }, 5, 0x63, 1 },    /* p. 83 OrVar */
    { { 0xA4, 0x00, 0x00, 0x01, 0x00 }, 5, 0x53, 4 },    /* p. 84 Upload, 1 entry: 3 * 1 + 1 */
    { { 0x05, 0x00, 0x00, 0x02, 0x01, 0x00 }, 6, 0xF2, 1 }, /* p. 86 SetSourceValue */
    { { 0x15, 1, 3, 5, 7, 11 }, 6, 0xE2, 9 },            /* p. 87 UnlockPBrick */
    { { 0x25, 0, 0, 0, 4, 0 }, 6, 0xD2, 2 },             /* p. 88 BeginOfTask */
    { { 0x35, 0, 0, 0, 4, 0 }, 6, 0xC2, 2 },             /* p. 89 BeginOfSub */
    { { 0x45, 0, 0, 0, 0, 0 }, 6, 0xB2, 2 },             /* p. 90 ContinueDL (status 6: not active) */
    { { 0x65, 1, 3, 5, 7, 11 }, 6, 0x92, 1 },            /* p. 91 GoIntoBootMode */
    { { 0xE5, 0, 0, 0x02, 0, 0 }, 6, 0x12, 1 },          /* p. 97 ViewSourceValue */
};
#define TABLE_N (sizeof table / sizeof table[0])

static void check_entry(const struct dcmd *d, u8 toggle)
{
    struct rcx *b = brick_new();
    u8 cmd[6], r[RCX_REPLY_MAX];
    unsigned n;

    memcpy(cmd, d->cmd, sizeof cmd);
    cmd[0] |= toggle;
    n = brick_cmd(b, cmd, d->len, r);
    if (n != d->reply_len)
        fail_msg("opcode %02X: reply length %u, expected %u", cmd[0], n, d->reply_len);
    if (n) {
        assert_int_equal(r[0], (u8)~cmd[0]);          /* complement of the byte as sent */
        assert_int_equal(r[0] & 0xF7, d->spec);       /* the spec's printed reply, toggle bit zero */
    }
    brick_free(b);
}

/* Every direct command, toggle bit clear and set: the reply length nqc expects and the complemented opcode.
 * This also covers "every Direct/Program command gives a 1-byte reply except InternMessage/SendUARTData". */
static void every_direct_command_replies_as_specified(void **state)
{
    unsigned i;
    (void)state;
    for (i = 0; i < TABLE_N; i++) {
        check_entry(&table[i], 0x00);
        check_entry(&table[i], 0x08);
    }
}

static void ping_reply(void **state)
{
    struct rcx *b = brick_new();
    u8 r[RCX_REPLY_MAX];
    (void)state;
    assert_int_equal(SEND(b, r, 0x10), 1);
    assert_int_equal(r[0], 0xEF);
    assert_int_equal(SEND(b, r, 0x18), 1);
    assert_int_equal(r[0], 0xE7); /* p. 12 */
    brick_free(b);
}

static void toggled_command_is_executed(void **state)
{
    struct rcx *b = brick_new();
    u8 r[RCX_REPLY_MAX];
    (void)state;
    assert_int_equal(SEND(b, r, 0x1C, 0x04, 0x02, 0x39, 0x05), 1); /* SetVar with the toggle bit */
    assert_int_equal(r[0], 0xE3);
    assert_int_equal(poll(b, 0, 4), 0x0539);
    brick_free(b);
}

static void battery_reply(void **state)
{
    struct rcx *b = brick_new();
    u8 r[RCX_REPLY_MAX];
    (void)state;
    b->battery_mv = 7321; /* 0x1C99 */
    assert_int_equal(SEND(b, r, 0x30), 3);
    assert_int_equal(r[0], 0xCF);
    assert_int_equal(r[1], 0x99); /* p. 14: value LO, HI */
    assert_int_equal(r[2], 0x1C);
    brick_free(b);
}

static void unlock_version(void **state)
{
    static const u8 expect[9] = { 0xE2, 0x00, 0x03, 0x00, 0x01, 0x00, 0x03, 0x02, 0x08 };
    struct rcx *b = brick_new();
    u8 r[RCX_REPLY_MAX];
    (void)state;
    assert_int_equal(SEND(b, r, 0x1D, 1, 3, 5, 7, 11), 9);
    assert_memory_equal(r, expect, 9);                    /* reference-firmware.md: ROM 3.1, firmware 3.2.8 */
    assert_int_equal(SEND(b, r, 0x15, 1, 3, 5, 7, 11), 9);
    assert_int_equal(r[0], 0xEA);
    assert_memory_equal(r + 1, expect + 1, 8);
    /* Wrong key: a bare acknowledgement (reference-firmware.md). */
    assert_int_equal(SEND(b, r, 0x15, 1, 3, 5, 7, 12), 1);
    assert_int_equal(r[0], 0xEA);
    assert_int_equal(SEND(b, r, 0x1D, 0, 0, 0, 0, 0), 1);
    assert_int_equal(r[0], 0xE2);
    brick_free(b);
}

static const u8 readable[] = { 0, 1, 2, 3, 4, 8, 9, 10, 11, 12, 13, 14, 15, 17, 21, 23,
                                25, 26, 27, 28, 29, 30, 31, 33, 34, 35, 36 };

static void poll_values_and_locals(void **state)
{
    struct rcx *b = brick_new();
    u8 r[RCX_REPLY_MAX];
    u8 v;
    (void)state;
    SEND(b, NULL, 0x14, 0x03, 0x02, 0xFE, 0xFF);          /* var[3] = -2 */
    assert_int_equal(SEND(b, r, 0x12, 0x00, 0x03), 3);
    assert_int_equal(r[0], 0xED);
    assert_int_equal(r[1], 0xFE);                         /* LO, HI (p. 50) */
    assert_int_equal(r[2], 0xFF);
    assert_int_equal(poll(b, 2, 200), 200);               /* constant */
    /* Task locals cannot be polled (p. 50); firm0328 answers 0x8000 (reference-firmware.md). */
    for (v = 32; v < 48; v++) {
        assert_int_equal(SEND(b, r, 0x12, 0x00, v), 3);
        assert_int_equal(r[1], 0x00);
        assert_int_equal(r[2], 0x80);
    }
    /* What does not exist answers 0x8000 too (reference-firmware.md, "The brick's face"): 12 00 FF (no such
     * variable), 12 FF 00 (no such source), and by the same rule an index a source does not have. */
    assert_int_equal((u16)poll(b, 0, 0xFF), 0x8000);
    assert_int_equal((u16)poll(b, 0, 48), 0x8000);
    assert_int_equal((u16)poll(b, 0xFF, 0), 0x8000);
    assert_int_equal((u16)poll(b, 45, 0), 0x8000);        /* one past the last source (37-44: issue 16) */
    assert_int_equal((u16)poll(b, 5, 0), 0x8000);         /* sources 5-7 are not in the table of pp. 6-10 */
    assert_int_equal((u16)poll(b, 9, 3), 0x8000);         /* input 4 */
    assert_int_equal((u16)poll(b, 3, 3), 0x8000);         /* output D */
    assert_int_equal(poll(b, 9, 2), 0);                   /* input 3 exists and reads 0 */
    /* Every readable source of pp. 6-10 answers ~op, LO, HI. */
    for (v = 0; v < sizeof readable; v++) {
        assert_int_equal(SEND(b, r, 0x1A, readable[v], 0), 3);
        assert_int_equal(r[0], 0xE5);
    }
    b->battery_mv = 0x2345;
    assert_int_equal(SEND(b, r, 0x12, 34, 0), 3);
    assert_int_equal(r[1], 0x45);
    assert_int_equal(r[2], 0x23);
    assert_int_equal(SEND(b, r, 0x12, 35, 0), 3);
    assert_int_equal(r[1], 0x48);                         /* 328 = 0x0148 */
    assert_int_equal(r[2], 0x01);
    brick_free(b);
}

static void poll_local_of_running_task(void **state)
{
    /* setv var[40], 1234 ; jmp self */
    static const u8 code[] = { 0x14, 0x28, 0x02, 0xD2, 0x04, 0x27, 0x81 };
    struct rcx *b = brick_new();
    (void)state;
    assert_int_equal(brick_download(b, 1, 0, code, sizeof code), 0);
    brick_start(b, 0);
    brick_run_ms(b, 5, 10);
    assert_true(running(b, 0));
    assert_int_equal((u16)poll(b, 0, 40), 0x8000);
    brick_free(b);
}

static void upload_ram(void **state)
{
    u8 code[30], r[RCX_REPLY_MAX];
    struct rcx *b = brick_new();
    u16 addr;
    unsigned i;
    (void)state;
    for (i = 0; i < sizeof code; i++)
        code[i] = (u8)(0xA0 + i);
    assert_int_equal(brick_download(b, 1, 3, code, sizeof code), 0);
    addr = map_word(b, 40 + 3); /* word 40 + task number: task 3 of program 0 */
    assert_int_equal(SEND(b, r, 0x63, (u8)addr, (u8)(addr >> 8), 30), 31);
    assert_int_equal(r[0], 0x9C);
    assert_memory_equal(r + 1, code, sizeof code);
    assert_int_equal(SEND(b, r, 0x6B, (u8)(addr + 5), (u8)((addr + 5) >> 8), 3), 4);
    assert_int_equal(r[0], 0x94);
    assert_memory_equal(r + 1, code + 5, 3);
    /* Across the arena's ends: what lies outside it reads as 0. */
    assert_int_equal(addr, TEST_ARENA_ADDR); /* the only code there is */
    addr = (u16)(TEST_ARENA_ADDR - 10);
    assert_int_equal(SEND(b, r, 0x63, (u8)addr, (u8)(addr >> 8), 30), 31);
    for (i = 1; i <= 10; i++)
        assert_int_equal(r[i], 0);
    assert_memory_equal(r + 11, code, 20);
    b->arena[sizeof b->arena - 1] = 0x55;
    addr = (u16)(TEST_ARENA_ADDR + sizeof b->arena - 3);
    assert_int_equal(SEND(b, r, 0x63, (u8)addr, (u8)(addr >> 8), 6), 7);
    assert_int_equal(r[3], 0x55);
    assert_int_equal(r[4] | r[5] | r[6], 0);

    /* Limits (p. 68, reference-firmware.md): 0-150 bytes from 0x8000 up; only the start address is checked. */
    assert_int_equal(SEND(b, r, 0x63, 0x00, 0x80, 0), 1);
    assert_int_equal(SEND(b, r, 0x63, 0x00, 0x80, 150), 151);
    assert_int_equal(SEND(b, r, 0x63, 0x7F, 0xFD, 150), 151);
    assert_int_equal(SEND(b, r, 0x63, 0x00, 0x80, 151), 0);
    assert_int_equal(SEND(b, r, 0x63, 0x00, 0x80, 255), 0);
    assert_int_equal(SEND(b, r, 0x63, 0xFF, 0x7F, 1), 0);
    assert_int_equal(SEND(b, r, 0x63, 0xFF, 0x7F, 0), 0);
    assert_int_equal(SEND(b, r, 0x63, 0x00, 0x00, 4), 0);
    assert_int_equal(SEND(b, r, 0x63, 0x80, 0xFD, 0), 0);
    assert_int_equal(SEND(b, r, 0x63, 0x80, 0xFD, 1), 0);
    assert_int_equal(SEND(b, r, 0x63, 0xFF, 0xFF, 1), 0);
    brick_free(b);
}

static void no_reply_commands(void **state)
{
    struct rcx *b = brick_new();
    u8 r[RCX_REPLY_MAX];
    (void)state;
    assert_int_equal(SEND(b, r, 0xF7, 0x2A), 0);         /* p. 48 */
    assert_int_equal(poll(b, 15, 0), 0x2A);               /* ... but the message is set */
    assert_int_equal(SEND(b, r, 0xFF, 0x07), 0);
    assert_int_equal(poll(b, 15, 0), 0x07);
    assert_int_equal(SEND(b, r, 0xD2, 0x00, 0x00), 0);   /* p. 61 */
    assert_int_equal(SEND(b, r, 0xDA, 0x02, 0x00), 0);
    assert_int_equal(SEND(b, r, 0xC2, 0x00, 0x04), 0);   /* p. 60 */
    assert_int_equal(SEND(b, r, 0xCA, 0x00, 0x04), 0);
    brick_free(b);
}

/* The spec's opcodes (table of contents, pp. 2-3). */
static const u8 program_only[] = { 0xA0, 0xB0, 0xF6, 0x17, 0x27, 0x37, 0xD7, 0x72, 0x82, 0x92,
                                   0xB2, 0xF2, 0x43, 0x73, 0xF3, 0xB4, 0x85, 0x95, 0xB5 };

static int is_spec_opcode(u8 op)
{
    unsigned i;
    op &= 0xF7;
    for (i = 0; i < TABLE_N; i++)
        if ((table[i].cmd[0] & 0xF7) == op)
            return 1;
    for (i = 0; i < sizeof program_only; i++)
        if (program_only[i] == op)
            return 1;
    return op == 0x75 || op == 0xA5; /* ROM-mode firmware download */
}

/* A brick with something to disturb: code in slot 0 (sub 0, tasks 0 and 1), task 0 running inside sub 0. */
static struct rcx *busy_brick(void)
{
    struct rcx *b = brick_new();
    assert_int_equal(brick_download(b, 0, 0, loop_inc1, sizeof loop_inc1), 0);
    assert_int_equal(brick_download(b, 1, 0, call_sub0, sizeof call_sub0), 0);
    assert_int_equal(brick_download(b, 1, 1, loop_inc0, sizeof loop_inc0), 0);
    SEND(b, NULL, 0x52, 0x04, 0x00);
    brick_start(b, 0);
    brick_start(b, 1);
    brick_run_ms(b, 3, 5);
    SEND(b, NULL, 0x14, 0x05, 0x02, 0x03, 0x00); /* var[5] = 3 */
    return b;
}

static void program_only_opcodes_ignored(void **state)
{
    unsigned i, t;
    (void)state;
    for (i = 0; i < sizeof program_only; i++) {
        for (t = 0; t < 2; t++) {
            struct rcx *b = busy_brick();
            u8 cmd[8] = { (u8)(program_only[i] | (t ? 0x08 : 0)), 0x00, 0x05, 0x02, 0x00, 0x81, 0x00, 0x00 };
            struct rcx *s = brick_copy(b);
            if (brick_cmd(b, cmd, sizeof cmd, NULL) != 0)
                fail_msg("program-only opcode %02X answered", cmd[0]);
            assert_unchanged(b, s);
            brick_free(b);
        }
    }
}

static void unknown_opcodes_ignored(void **state)
{
    unsigned op;
    struct rcx *b = busy_brick();
    (void)state;
    for (op = 0; op < 256; op++) {
        u8 cmd[8] = { (u8)op, 0x00, 0x05, 0x02, 0x01, 0x00, 0x00, 0x00 };
        struct rcx *s;
        if (is_spec_opcode((u8)op) || (op & ~RCX_TOGGLE) == RCX_SW_MSG_WORD)
            continue; /* B3: a Swan message's parameter, kept for the message after it (test_swan.c) */
        s = brick_copy(b);
        if (brick_cmd(b, cmd, sizeof cmd, NULL) != 0)
            fail_msg("unknown opcode %02X answered", op);
        assert_unchanged(b, s);
    }
    brick_free(b);
}

static void truncated_commands_ignored(void **state)
{
    unsigned i, len;
    (void)state;
    for (i = 0; i < TABLE_N; i++) {
        if (table[i].cmd[0] == 0x45)
            continue; /* variable length: see truncated_download_block */
        for (len = 1; len < table[i].len; len++) {
            struct rcx *b = busy_brick();
            struct rcx *s = brick_copy(b);
            if (brick_cmd(b, table[i].cmd, len, NULL) != 0)
                fail_msg("opcode %02X truncated to %u bytes answered", table[i].cmd[0], len);
            assert_unchanged(b, s);
            brick_free(b);
        }
    }
}

/* A 0x45 too short to hold its own header, or its announced data and checksum (p. 90), is truncated. */
static void truncated_download_block(void **state)
{
    static const u8 full[] = { 0x45, 0x00, 0x00, 0x04, 0x00, 0x27, 0x81, 0x27, 0x81, 0x50 };
    struct rcx *b = brick_new();
    unsigned len, answered = 0;
    u8 r[RCX_REPLY_MAX];
    (void)state;
    assert_int_equal(SEND(b, r, 0x25, 0, 0, 0, 4, 0), 2);
    assert_int_equal(r[1], 0);
    for (len = 1; len < sizeof full; len++) {
        struct rcx *s = brick_copy(b);
        if (brick_cmd(b, full, len, r) != 0) {
            print_error("0x45 truncated to %u bytes answered (status %u)\n", len, r[1]);
            answered++;
        }
        assert_unchanged(b, s);
    }
    assert_int_equal(brick_cmd(b, full, sizeof full, r), 2); /* the download is still on */
    assert_int_equal(r[1], 0);
    assert_int_equal(answered, 0);
    brick_free(b);
}

static void select_program_direct(void **state)
{
    struct rcx *b = brick_new();
    u8 r[RCX_REPLY_MAX];
    (void)state;
    SEND(b, NULL, 0x91, 0x02);
    assert_int_equal(brick_download(b, 1, 0, loop_inc0, sizeof loop_inc0), 0);
    SEND(b, NULL, 0x91, 0x00);
    assert_int_equal(brick_download(b, 1, 0, spin, sizeof spin), 0);
    brick_start(b, 0);
    assert_true(running(b, 0));
    /* p. 33: stop all tasks of the current program, select; task 0 is started only from a program. */
    assert_int_equal(SEND(b, r, 0x91, 0x02), 1);
    assert_int_equal(r[0], 0x6E);
    assert_int_equal(poll(b, 8, 0), 2);
    assert_false(running(b, 0));
    brick_run_ms(b, 20, 5);
    assert_int_equal(poll(b, 0, 0), 0);
    /* Now slot 2's task 0 runs; SelectProgram 5 is acknowledged and changes nothing (reference-firmware.md). */
    brick_start(b, 0);
    assert_true(running(b, 0));
    assert_int_equal(SEND(b, r, 0x99, 0x05), 1);
    assert_int_equal(r[0], 0x66);
    assert_int_equal(poll(b, 8, 0), 2);
    assert_true(running(b, 0));
    assert_int_equal(SEND(b, r, 0x91, 0xFF), 1);
    assert_int_equal(poll(b, 8, 0), 2);
    assert_true(running(b, 0));
    brick_free(b);
}

static void start_stop_task(void **state)
{
    /* setv var[1], 0 ; L: sumv var[1], 1 ; jmp L */
    static const u8 code[] = { 0x14, 0x01, 0x02, 0x00, 0x00, 0x24, 0x01, 0x02, 0x01, 0x00, 0x27, 0x86 };
    struct rcx *b = brick_new();
    s16 v;
    (void)state;
    assert_int_equal(brick_download(b, 1, 4, code, sizeof code), 0);
    assert_int_equal(SEND(b, NULL, 0x71, 0x04), 1);
    assert_true(running(b, 4));
    brick_run_ms(b, 10, 5);
    v = poll(b, 0, 1);
    assert_true(v > 0);
    /* p. 31: (re)starts — a running task starts again from its first byte code. */
    assert_int_equal(SEND(b, NULL, 0x71, 0x04), 1);
    vm_run(b, 1);
    assert_int_equal(poll(b, 0, 1), 0);
    brick_run_ms(b, 10, 5);
    assert_int_equal(SEND(b, NULL, 0x81, 0x04), 1);       /* p. 32 */
    assert_false(running(b, 4));
    v = poll(b, 0, 1);
    brick_run_ms(b, 10, 5);
    assert_int_equal(poll(b, 0, 1), v);
    /* Empty slot or bad number: acknowledged, nothing starts (p. 31: "if the task slot is non-empty"). */
    assert_int_equal(SEND(b, NULL, 0x71, 0x05), 1);
    assert_int_equal(SEND(b, NULL, 0x71, 0x0A), 1);
    assert_int_equal(SEND(b, NULL, 0x81, 0x0A), 1);
    assert_false(any_running(b));
    brick_free(b);
}

static void delete_task_and_all_tasks(void **state)
{
    struct rcx *b = brick_new();
    unsigned f0;
    (void)state;
    SEND(b, NULL, 0x91, 0x01);
    assert_int_equal(brick_download(b, 1, 0, spin, sizeof spin), 0);
    SEND(b, NULL, 0x91, 0x00);
    f0 = mem_free_map(b);
    assert_int_equal(brick_download(b, 1, 0, loop_inc0, sizeof loop_inc0), 0);
    assert_int_equal(brick_download(b, 1, 1, loop_inc1, sizeof loop_inc1), 0);
    assert_int_equal(brick_download(b, 0, 0, spin, sizeof spin), 0);
    brick_start(b, 0);
    brick_start(b, 1);
    /* DeleteTask (p. 30): the task is stopped and its memory given back; the other one runs on. */
    assert_int_equal(SEND(b, NULL, 0x61, 0x01), 1);
    assert_false(running(b, 1));
    assert_true(running(b, 0));
    assert_int_equal(mem_free_map(b), f0 - sizeof loop_inc0 - sizeof spin);
    brick_start(b, 1);
    assert_false(running(b, 1));
    assert_int_equal(SEND(b, NULL, 0x61, 0x0A), 1);      /* no such task: acknowledged */
    /* DeleteAllTasks (p. 15): every task of the selected program; its subroutines stay. */
    assert_int_equal(SEND(b, NULL, 0x40), 1);
    assert_false(running(b, 0));
    assert_int_equal(mem_free_map(b), f0 - sizeof spin);
    brick_start(b, 0);
    assert_false(running(b, 0));
    /* Program 1's task 0 is untouched. */
    SEND(b, NULL, 0x91, 0x01);
    brick_start(b, 0);
    assert_true(running(b, 0));
    brick_free(b);
}

static void delete_sub_stops_tasks_inside(void **state)
{
    struct rcx *b = brick_new();
    unsigned f0;
    (void)state;
    assert_int_equal(brick_download(b, 0, 0, spin, sizeof spin), 0);
    assert_int_equal(brick_download(b, 0, 3, spin, sizeof spin), 0);
    assert_int_equal(brick_download(b, 1, 0, call_sub0, sizeof call_sub0), 0);
    assert_int_equal(brick_download(b, 1, 1, loop_inc0, sizeof loop_inc0), 0); /* calls nothing */
    assert_int_equal(brick_download(b, 1, 2, call_sub3, sizeof call_sub3), 0);
    f0 = mem_free_map(b);
    brick_start(b, 0);
    brick_start(b, 1);
    brick_start(b, 2);
    brick_run_ms(b, 5, 10);
    /* DeleteSub (p. 36): the task executing sub 0 is stopped, a task that never calls it runs on. */
    assert_int_equal(SEND(b, NULL, 0xC1, 0x00), 1);
    assert_false(running(b, 0));
    assert_true(running(b, 1));
    assert_true(running(b, 2));
    assert_int_equal(mem_free_map(b), f0 + sizeof spin);
    /* DeleteAllSubs (p. 18): tasks inside subroutines are stopped. */
    assert_int_equal(SEND(b, NULL, 0x70), 1);
    assert_false(running(b, 2));
    assert_true(running(b, 1));
    assert_int_equal(mem_free_map(b), f0 + 2 * sizeof spin);
    brick_free(b);
}

/* DeleteTask 10 and DeleteSub 8 name nothing (tasks 0-9, subroutines 0-7, spec pp. 30, 36): acknowledged, and the code
 * objects right after the slot's last task and last subroutine (the next slot's subroutine 0, this slot's task 0)
 * stay, running or not, as does everything else. */
static void delete_past_the_last_changes_nothing(void **state)
{
    struct rcx *b = brick_new(), *s;
    (void)state;
    SEND(b, NULL, 0x91, 0x01);
    assert_int_equal(brick_download(b, 0, 0, spin, sizeof spin), 0); /* program 2's subroutine 0 */
    SEND(b, NULL, 0x91, 0x00);
    assert_int_equal(brick_download(b, 1, 0, spin, sizeof spin), 0);
    assert_int_equal(brick_download(b, 1, 9, loop_inc0, sizeof loop_inc0), 0);
    assert_int_equal(brick_download(b, 0, 7, spin, sizeof spin), 0);
    brick_start(b, 0);
    s = brick_copy(b);
    assert_int_equal(SEND(b, NULL, 0x61, 0x0A), 1);
    assert_int_equal(SEND(b, NULL, 0x69, 0xFF), 1);
    assert_int_equal(SEND(b, NULL, 0xC1, 0x08), 1);
    assert_int_equal(SEND(b, NULL, 0xC9, 0xFF), 1);
    assert_unchanged(b, s);
    brick_free(b);
}

static void power_requests(void **state)
{
    struct rcx *b = brick_new();
    u8 r[RCX_REPLY_MAX];
    (void)state;
    b->idle_reset = 0;
    assert_int_equal(SEND(b, r, 0xB1, 0x0A), 1);         /* p. 35: sets the time and resets the timer */
    assert_int_equal(b->power_down_min, 10);
    assert_int_equal(b->idle_reset, 1);
    b->idle_reset = 0;
    assert_int_equal(SEND(b, r, 0x10), 1);               /* p. 12 / p. 35 */
    assert_int_equal(b->idle_reset, 1);
    assert_int_equal(b->turn_off, 0);
    assert_int_equal(SEND(b, r, 0x60), 1);               /* p. 17 */
    assert_int_equal(r[0], 0x9F);
    assert_int_equal(b->turn_off, 1);

    b = (brick_free(b), brick_new());
    assert_int_equal(SEND(b, r, 0xB1, 0x00), 1);         /* 0 = never time out */
    assert_int_equal(b->power_down_min, 0);
    assert_int_equal(SEND(b, r, 0x60), 1);               /* ignored (reference-firmware.md), still answered */
    assert_int_equal(b->turn_off, 0);
    brick_free(b);
}

static void tx_range(void **state)
{
    struct rcx *b = brick_new();
    u8 r[RCX_REPLY_MAX];
    (void)state;
    assert_int_equal(SEND(b, r, 0x31, 0x01), 1);         /* p. 28: 1 long range */
    assert_int_equal(r[0], 0xCE);
    assert_int_equal(b->tx_range, 1);
    assert_int_equal(SEND(b, r, 0x39, 0x00), 1);         /* 0 short range */
    assert_int_equal(b->tx_range, 0);
    brick_free(b);
}

static void boot_mode(void **state)
{
    struct rcx *b = brick_new();
    u8 r[RCX_REPLY_MAX];
    (void)state;
    assert_int_equal(SEND(b, r, 0x65, 1, 3, 5, 7, 10), 1);
    assert_int_equal(b->boot_mode, 0);                    /* wrong key */
    assert_int_equal(SEND(b, r, 0x65, 1, 3, 5, 7, 11), 1); /* p. 91; firmdl3 needs the 1-byte reply */
    assert_int_equal(r[0], 0x9A);
    assert_int_equal(b->boot_mode, 1);
    brick_free(b);
}

static void rom_only_commands_unanswered(void **state)
{
    struct rcx *b = busy_brick();
    struct rcx *s = brick_copy(b);
    (void)state;
    assert_int_equal(SEND(b, NULL, 0x75, 0x00, 0x80, 0x34, 0x12, 0x00), 0);
    assert_int_equal(SEND(b, NULL, 0xA5, 0x4C, 0x45, 0x47, 0x4F, 0xAE), 0);
    assert_int_equal(SEND(b, NULL, 0x7D, 0x00, 0x80, 0x34, 0x12, 0x00), 0);
    assert_int_equal(SEND(b, NULL, 0xAD, 0x4C, 0x45, 0x47, 0x4F, 0xAE), 0);
    assert_unchanged(b, s);
    brick_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_direct_command_replies_as_specified),
        cmocka_unit_test(ping_reply),
        cmocka_unit_test(toggled_command_is_executed),
        cmocka_unit_test(battery_reply),
        cmocka_unit_test(unlock_version),
        cmocka_unit_test(poll_values_and_locals),
        cmocka_unit_test(poll_local_of_running_task),
        cmocka_unit_test(upload_ram),
        cmocka_unit_test(no_reply_commands),
        cmocka_unit_test(program_only_opcodes_ignored),
        cmocka_unit_test(unknown_opcodes_ignored),
        cmocka_unit_test(truncated_commands_ignored),
        cmocka_unit_test(truncated_download_block),
        cmocka_unit_test(select_program_direct),
        cmocka_unit_test(start_stop_task),
        cmocka_unit_test(delete_task_and_all_tasks),
        cmocka_unit_test(delete_sub_stops_tasks_inside),
        cmocka_unit_test(delete_past_the_last_changes_nothing),
        cmocka_unit_test(power_requests),
        cmocka_unit_test(tx_range),
        cmocka_unit_test(boot_mode),
        cmocka_unit_test(rom_only_commands_unanswered),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
