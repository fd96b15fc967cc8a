/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Every direct command through the IR layer, byte-exact: reply opcode = complement of the opcode byte as received,
 * reply lengths as nqc expects them (host-tools.md §1), values from the spec (pp. 12-97) and reference-firmware.md
 * (wrong keys, UploadRam limits, commands only the ROM answers); and every download status code (0 OK, 1 no
 * memory, 2 bad number, 3 block checksum or order, 6 not active) as a host sees it over the link.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <string.h>
#include <cmocka.h>
#include "brick.h"
#include "ir_rig.h"

struct direct_case {
    u8 cmd[7];
    u8 len;
    u8 reply[10]; /* expected payload; reply_len 0 = no reply at all */
    u8 reply_len;
};

static const struct direct_case direct_cases[] = {
    { { 0x10 }, 1, { 0xEF }, 1 },
    { { 0x30 }, 1, { 0xCF, 0x28, 0x23 }, 3 },                  /* 9000 mV at power-on */
    { { 0x40 }, 1, { 0xBF }, 1 },
    { { 0x50 }, 1, { 0xAF }, 1 },
    { { 0x60 }, 1, { 0x9F }, 1 },
    { { 0x70 }, 1, { 0x8F }, 1 },
    { { 0x80 }, 1, { 0x7F }, 1 },
    { { 0x90 }, 1, { 0x6F }, 1 },
    { { 0xD0 }, 1, { 0x2F }, 1 },
    { { 0xE0 }, 1, { 0x1F }, 1 },
    { { 0x06 }, 1, { 0xF9 }, 1 },
    { { 0x21, 0x81 }, 2, { 0xDE }, 1 },
    { { 0x31, 0x01 }, 2, { 0xCE }, 1 },
    { { 0x51, 0x02 }, 2, { 0xAE }, 1 },
    { { 0x61, 0x00 }, 2, { 0x9E }, 1 },
    { { 0x71, 0x00 }, 2, { 0x8E }, 1 },
    { { 0x81, 0x00 }, 2, { 0x7E }, 1 },
    { { 0x91, 0x00 }, 2, { 0x6E }, 1 },
    { { 0xA1, 0x00 }, 2, { 0x5E }, 1 },
    { { 0xB1, 0x05 }, 2, { 0x4E }, 1 },
    { { 0xC1, 0x00 }, 2, { 0x3E }, 1 },
    { { 0xD1, 0x00 }, 2, { 0x2E }, 1 },
    { { 0xE1, 0x81 }, 2, { 0x1E }, 1 },
    { { 0x67, 0x81 }, 2, { 0x98 }, 1 },
    { { 0x77, 0x81 }, 2, { 0x88 }, 1 },
    { { 0x97, 0x00 }, 2, { 0x68 }, 1 },
    { { 0xA7, 0x00 }, 2, { 0x58 }, 1 },
    { { 0xB7, 0x00 }, 2, { 0x48 }, 1 },
    { { 0xF7, 0x05 }, 2, { 0 }, 0 },                           /* InternMessage: no reply */
    { { 0x02, 0x00, 0x0A }, 3, { 0xFD }, 1 },
    { { 0x12, 0x02, 0x34 }, 3, { 0xED, 0x34, 0x00 }, 3 },
    { { 0x22, 0x01, 0x02 }, 3, { 0xDD }, 1 },
    { { 0x32, 0x00, 0x01 }, 3, { 0xCD }, 1 },
    { { 0x42, 0x00, 0x20 }, 3, { 0xBD }, 1 },
    { { 0x52, 0x00, 0x00 }, 3, { 0xAD, 0x00 }, 2 },             /* status: made (reference-firmware.md) */
    { { 0x52, 0x00, 0xFF }, 3, { 0xAD, 0x01 }, 2 },             /* status: not enough memory */
    { { 0x62, 0x02, 0x05 }, 3, { 0x9D, 0x00 }, 2 },
    { { 0xC2, 0x00, 0x00 }, 3, { 0 }, 0 },                     /* SendUARTData: no reply */
    { { 0xD2, 0x00, 0x00 }, 3, { 0 }, 0 },                     /* RemoteCommand: no reply */
    { { 0x03, 0x02, 0x00, 0x00 }, 4, { 0xFC }, 1 },
    { { 0x13, 0x01, 0x02, 0x03 }, 4, { 0xEC }, 1 },
    { { 0x23, 0xB8, 0x01, 0x0A }, 4, { 0xDC }, 1 },
    { { 0x33, 0x02, 0x01, 0x00 }, 4, { 0xCC }, 1 },
    { { 0x63, 0x00, 0x90, 0x04 }, 4, { 0x9C, 0, 0, 0, 0 }, 5 }, /* 4 bytes of empty program memory */
    { { 0x63, 0x00, 0x7F, 0x04 }, 4, { 0 }, 0 },               /* below 0x8000: no reply */
    { { 0x63, 0x00, 0x90, 0x97 }, 4, { 0 }, 0 },               /* 151 bytes: no reply */
    { { 0x93, 0x01, 0x00, 0x00 }, 4, { 0x6C }, 1 },
    { { 0xA3, 0x01, 0x02, 0x03 }, 4, { 0x5C }, 1 },
    { { 0x04, 0x01, 0x0A, 0x14, 0x1E }, 5, { 0xFB }, 1 },
    { { 0x14, 0x00, 0x02, 0x05, 0x00 }, 5, { 0xEB }, 1 },
    { { 0x24, 0x00, 0x02, 0x05, 0x00 }, 5, { 0xDB }, 1 },
    { { 0x34, 0x00, 0x02, 0x05, 0x00 }, 5, { 0xCB }, 1 },
    { { 0x44, 0x00, 0x02, 0x05, 0x00 }, 5, { 0xBB }, 1 },
    { { 0x54, 0x00, 0x02, 0x05, 0x00 }, 5, { 0xAB }, 1 },
    { { 0x64, 0x00, 0x02, 0x05, 0x00 }, 5, { 0x9B }, 1 },
    { { 0x74, 0x00, 0x02, 0x05, 0x00 }, 5, { 0x8B }, 1 },
    { { 0x84, 0x00, 0x02, 0x05, 0x00 }, 5, { 0x7B }, 1 },
    { { 0x94, 0x00, 0x02, 0x05, 0x00 }, 5, { 0x6B }, 1 },
    { { 0xA4, 0x00, 0x00, 0x01, 0x00 }, 5, { 0x5B, 0xFF, 0x01, 0x00 }, 4 }, /* entry 0 of no log */
    { { 0x05, 0x00, 0x00, 0x02, 0x07, 0x00 }, 6, { 0xFA }, 1 },
    { { 0x15, 1, 3, 5, 7, 11 }, 6, { 0xEA, 0x00, 0x03, 0x00, 0x01, 0x00, 0x03, 0x02, 0x08 }, 9 },
    { { 0x15, 1, 3, 5, 7, 12 }, 6, { 0xEA }, 1 },              /* wrong key: bare acknowledgement */
    { { 0x25, 0x00, 0x00, 0x00, 0x10, 0x00 }, 6, { 0xDA, 0x00 }, 2 },
    { { 0x35, 0x00, 0x00, 0x00, 0x10, 0x00 }, 6, { 0xCA, 0x00 }, 2 },
    { { 0x45, 0x01, 0x00, 0x00, 0x00, 0x00 }, 6, { 0xBA, 0x06 }, 2 }, /* no download active */
    { { 0x65, 1, 3, 5, 7, 12 }, 6, { 0x9A }, 1 },              /* wrong key: acknowledged, stays */
    { { 0x75, 0x00, 0x80, 0x00, 0x00, 0x00 }, 6, { 0 }, 0 },   /* the ROM's, not the firmware's */
    { { 0xA5, 0x4C, 0x45, 0x47, 0x4F, 0xAE }, 6, { 0 }, 0 },
    { { 0xE5, 0x00, 0x02, 0x00, 0x00, 0x00 }, 6, { 0x1A }, 1 },
    { { 0x17, 0x00 }, 2, { 0 }, 0 },                           /* program-only byte codes */
    { { 0x27, 0x81 }, 2, { 0 }, 0 },
    { { 0x43, 0x02, 0x0A, 0x00 }, 4, { 0 }, 0 },
    { { 0x01, 0x00 }, 2, { 0 }, 0 },                           /* no such opcode */
};

static void every_direct_reply_is_framed_byte_exact(void **state)
{
    unsigned i;
    (void)state;
    for (i = 0; i < sizeof direct_cases / sizeof direct_cases[0]; i++) {
        const struct direct_case *c = &direct_cases[i];
        struct rig *r = rig_new();
        transact(r, c->cmd, c->len);
        if (c->reply_len == 0) {
            if (r->out_len)
                fail_msg("command %02x answered", c->cmd[0]);
        } else {
            expect_reply(r, c->reply, c->reply_len);
        }
        assert_int_equal(r->h->rom_entries, 0);
        rig_free(r);
    }
}

static void download_status_codes(void **state)
{
    static const u8 code[] = { 0x14, 0x04, 0x02, 0x2A, 0x00, 0x14, 0x05, 0x02, 0x07, 0x00 }; /* v4=42; v5=7 */
    struct rig *r = rig_new();
    u8 pkt[IR_RX_MAX + 8];
    unsigned n, free_bytes;
    (void)state;
    assert_int_equal(TX(r, 0x25, 0, 10, 0, 4, 0), 9);                 /* task 10 */
    assert_int_equal(r->out[5], 2);
    assert_int_equal(TX(r, 0x35, 0, 8, 0, 4, 0), 9);                  /* subroutine 8 */
    assert_int_equal(r->out[5], 2);
    assert_int_equal(TX(r, 0x20), 383);                               /* free = word 93 - word 92 */
    free_bytes = (unsigned)((r->out[3 + 2 * 187] << 8 | r->out[3 + 2 * 188]) -
                            (r->out[3 + 2 * 185] << 8 | r->out[3 + 2 * 186]));
    assert_int_equal(TX(r, 0x2D, 0, 0, 0, (u8)(free_bytes + 1), (u8)((free_bytes + 1) >> 8)), 9);
    assert_int_equal(r->out[5], 1);                                   /* one byte more than free */
    n = block(pkt, 1, code, 5, 0);
    assert_int_equal(status_of(r, pkt, n, 0), 6);                     /* nothing being downloaded */
    assert_int_equal(TX(r, 0x25, 0, 0, 0, sizeof code, 0), 9);
    assert_int_equal(r->out[5], 0);
    n = block(pkt, 1, code, 5, 1);
    assert_int_equal(status_of(r, pkt, n, 0), 3);                     /* block checksum */
    n = block(pkt, 2, code, 5, 0);
    assert_int_equal(status_of(r, pkt, n, 8), 3);                     /* out of order */
    n = block(pkt, 1, code, 5, 0);
    assert_int_equal(status_of(r, pkt, n, 0), 0);
    assert_int_equal(status_of(r, pkt, n, 8), 0);                     /* the same block again: acknowledged */
    n = block(pkt, 0, code + 5, 5, 0);
    assert_int_equal(status_of(r, pkt, n, 0), 0);                     /* the last, numbered 0 */
    assert_int_equal(status_of(r, pkt, n, 8), 6);                     /* download over */
    assert_int_equal(TX(r, 0x71, 0), 7);
    rt_run(r->k, 100);
    assert_int_equal(poll_var(r, 4), 42);
    assert_int_equal(poll_var(r, 5), 7);                              /* written once, in order */
    rig_free(r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_direct_reply_is_framed_byte_exact),
        cmocka_unit_test(download_status_codes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
