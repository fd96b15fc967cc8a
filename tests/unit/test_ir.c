/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The IR packet layer (src/ir.c) driven byte by byte, the way the UART driver feeds it, with the recording HAL
 * behind it. Expected bytes come from host-tools.md §1 (framing, reply lengths), reference-firmware.md (headers,
 * repeat rule, UploadRam limits, download status codes) and the spec's reply opcodes (pp. 12-97, toggle bit 0).
 *
 * The rig (tests/e2e/ir_rig.h) plays the part of the room: every byte the brick hands to hal_ir_send() comes back
 * to its receiver as the echo, as it does on the brick (rcx-hardware.md §3.8). Every direct command's framed reply
 * and the download status codes are in tests/e2e/test_ir_replies.c.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "brick.h"
#include "fake_hal.h"
#include "runtime.h"

#include "ir_rig.h"

/* ---- framing and headers ---- */

static void ping_is_answered_byte_exact(void **state)
{
    struct rig *r = rig_new();
    static const u8 ping[] = { 0x55, 0xFF, 0x00, 0x10, 0xEF, 0x10, 0xEF };
    static const u8 pong[] = { 0x55, 0xFF, 0x00, 0xEF, 0x10, 0xEF, 0x10 };
    (void)state;
    feed(r, ping, sizeof ping);
    pump(r);
    assert_int_equal(r->out_len, sizeof pong);
    assert_memory_equal(r->out, pong, sizeof pong);
    assert_int_equal(r->h->ir_mode, 0); /* 2400 baud, 38 kHz, 50 % */
    rig_free(r);
}

static void every_header_form_is_accepted(void **state)
{
    static const u8 *const forms[] = {
        (const u8 *)"\xFF\x00\x12\xED\x02\xFD\x07\xF8\x1B\xE4",                 /* FF 00 */
        (const u8 *)"\x00\x12\xED\x02\xFD\x07\xF8\x1B\xE4",                     /* 00 */
        (const u8 *)"\x12\xED\x02\xFD\x07\xF8\x1B\xE4",                         /* none */
        (const u8 *)"\x3C\x99\x55\xFF\x00\x12\xED\x02\xFD\x07\xF8\x1B\xE4",     /* garbage first */
        (const u8 *)"\x55\xFF\x00\x55\xFF\x00\x12\xED\x02\xFD\x07\xF8\x1B\xE4", /* header twice */
    };
    static const unsigned lens[] = { 10, 9, 8, 13, 14 };
    unsigned i;
    (void)state;
    for (i = 0; i < 5; i++) {
        struct rig *r = rig_new();
        feed(r, forms[i], lens[i]);
        pump(r);
        REPLY(r, 0xED, 0x07, 0x00); /* poll of constant 7 */
        rig_free(r);
    }
}

static void bad_complement_or_checksum_is_dropped(void **state)
{
    u8 pkt[32];
    unsigned n, at;
    (void)state;
    /* Corrupt every complement and the checksum of SetVar var[3] = 5 in turn: never executed, never answered. */
    for (at = 4; at < 16; at += 2) {
        struct rig *r = rig_new();
        n = frame((const u8[]){ 0x14, 0x03, 0x02, 0x05, 0x00 }, 5, pkt);
        assert_int_equal(n, 15);
        if (at == 14)
            pkt[13] ^= 0x01, pkt[14] ^= 0x01; /* checksum wrong but consistently complemented */
        else
            pkt[at] ^= 0x40;
        r->out_len = 0;
        feed(r, pkt, n);
        pump(r);
        assert_int_equal(r->out_len, 0);
        assert_int_equal(poll_var(r, 3), 0);  /* the next good packet is answered, even right behind it */
        rig_free(r);
    }
}

static void receive_errors_drop_the_packet(void **state)
{
    struct rig *r = rig_new();
    u8 pkt[32];
    unsigned n = frame((const u8[]){ 0x14, 0x03, 0x02, 0x05, 0x00 }, 5, pkt), i;
    (void)state;
    for (i = 0; i < n; i++)
        rt_ir_byte(r->k, pkt[i], i == 7); /* a parity error on one byte */
    pump(r);
    assert_int_equal(r->out_len, 0);
    assert_int_equal(poll_var(r, 3), 0);
    rig_free(r);
}

static void silence_inside_a_packet_resynchronises(void **state)
{
    struct rig *r = rig_new();
    u8 pkt[32];
    unsigned n = frame((const u8[]){ 0x14, 0x03, 0x02, 0x05, 0x00 }, 5, pkt);
    (void)state;
    /* A pause shorter than the timeout keeps the packet together ... */
    feed(r, pkt, 6);
    ticks(r, IR_QUIET_MS - 1);
    r->out_len = 0;
    feed(r, pkt + 6, n - 6);
    pump(r);
    REPLY(r, 0xEB);
    assert_int_equal(poll_var(r, 3), 5);
    /* ... a longer one drops it, and its tail is not taken for a command. */
    pkt[3] = 0x1C, pkt[4] = 0xE3, pkt[9] = 0x09, pkt[10] = 0xF6, pkt[13] = 0x2A, pkt[14] = 0xD5; /* var[3] = 9 */
    feed(r, pkt, 6);
    ticks(r, IR_QUIET_MS);
    r->out_len = 0;
    feed(r, pkt + 6, n - 6);
    pump(r);
    assert_int_equal(r->out_len, 0);
    ticks(r, IR_QUIET_MS);
    assert_int_equal(poll_var(r, 3), 5);
    rig_free(r);
}

static void truncated_packets_get_no_reply(void **state)
{
    u8 pkt[32];
    unsigned n = frame((const u8[]){ 0x14, 0x03, 0x02, 0x05, 0x00 }, 5, pkt), cut;
    (void)state;
    for (cut = 1; cut < n; cut++) {
        struct rig *r = rig_new();
        r->out_len = 0;
        feed(r, pkt, cut);
        pump(r);
        assert_int_equal(r->out_len, 0);
        ticks(r, IR_QUIET_MS);
        assert_int_equal(poll_var(r, 3), 0);
        assert_int_equal(TX(r, 0x10), 7);
        rig_free(r);
    }
}

/* ---- half duplex ---- */

static void own_echo_and_busy_line_are_ignored(void **state)
{
    struct rig *r = rig_new();
    u8 pkt[32];
    unsigned n = frame((const u8[]){ 0x14, 0x03, 0x02, 0x05, 0x00 }, 5, pkt);
    (void)state;
    /* While the driver is busy sending, what arrives is the brick's own light. */
    r->h->ir_busy = 1;
    feed(r, pkt, n);
    r->h->ir_busy = 0;
    pump(r);
    assert_int_equal(r->out_len, 0);
    /* The echo of a reply is swallowed byte for byte; the packet right behind it is answered. */
    assert_int_equal(TX(r, 0x10), 7);
    assert_int_equal(TX(r, 0x14, 0x03, 0x02, 0x05, 0x00), 7);
    assert_int_equal(poll_var(r, 3), 5);
    rig_free(r);
}

static void a_lost_echo_does_not_deafen_the_receiver(void **state)
{
    struct rig *r = rig_new();
    u8 pkt[16];
    unsigned n = frame((const u8[]){ 0x10 }, 1, pkt);
    (void)state;
    feed(r, pkt, n);
    pump_echo(r, 0);            /* reply sent, echo never heard */
    assert_int_equal(r->out_len, 7);
    assert_false(ir_idle(r->k));
    ticks(r, IR_ECHO_MS);
    assert_true(ir_idle(r->k));
    assert_int_equal(poll_var(r, 0), 0);
    rig_free(r);
}

/* ---- the repeat rule (reference-firmware.md: judged by the opcode byte alone) ---- */

static void a_repeated_opcode_is_answered_not_executed(void **state)
{
    struct rig *r = rig_new();
    u8 bad[32];
    unsigned n;
    (void)state;
    assert_int_equal(TX(r, 0x24, 0x00, 0x02, 0x01, 0x00), 7); /* var[0] += 1 */
    REPLY(r, 0xDB);
    assert_int_equal(TX(r, 0x24, 0x00, 0x02, 0x01, 0x00), 7); /* a retry: same answer, not executed */
    REPLY(r, 0xDB);
    assert_int_equal(TX(r, 0x24, 0x00, 0x02, 0x05, 0x00), 7); /* other operands, same opcode byte */
    REPLY(r, 0xDB);
    assert_int_equal(TX(r, 0x2C, 0x00, 0x02, 0x01, 0x00), 7); /* toggled: new */
    REPLY(r, 0xD3);
    /* A corrupt packet in between does not end the repeat ... */
    n = frame((const u8[]){ 0x12, 0x00, 0x00 }, 3, bad);
    bad[6] ^= 0xFF;
    feed(r, bad, n);
    ticks(r, IR_QUIET_MS);
    assert_int_equal(TX(r, 0x2C, 0x00, 0x02, 0x01, 0x00), 7);
    REPLY(r, 0xD3);
    /* ... any other opcode does. */
    assert_int_equal(poll_var(r, 0), 2);
    assert_int_equal(TX(r, 0x2C, 0x00, 0x02, 0x01, 0x00), 7);
    assert_int_equal(poll_var(r, 0), 3);
    rig_free(r);
}

static void repeats_of_unanswered_commands_stay_silent(void **state)
{
    struct rig *r = rig_new();
    (void)state;
    assert_int_equal(TX(r, 0xD2, 0x00, 0x08), 0);  /* RemoteCommand: A forward */
    assert_int_equal(TX(r, 0xD2, 0x00, 0x00), 0);  /* same opcode byte: a repeat, A keeps running */
    assert_int_equal(r->k->vm.remote.held, 0x0800);
    /* An unanswered command ends the repeat of an answered one. */
    assert_int_equal(TX(r, 0x24, 0x01, 0x02, 0x01, 0x00), 7);
    assert_int_equal(TX(r, 0xF7, 0x01), 0);
    assert_int_equal(TX(r, 0x24, 0x01, 0x02, 0x01, 0x00), 7);
    assert_int_equal(poll_var(r, 1), 2);
    rig_free(r);
}

/* reference-firmware.md: two messages in a row are both taken (nqc -msg 42, then nqc -msg 200: each run sends F7),
 * whether or not anything came in between, and a message ends the repeat of the command before it. */
static void messages_are_never_repeats(void **state)
{
    struct rig *r = rig_new();
    (void)state;
    assert_int_equal(TX(r, 0xF7, 42), 0);
    assert_int_equal(r->k->vm.message, 42);
    assert_int_equal(TX(r, 0xF7, 200), 0);
    assert_int_equal(r->k->vm.message, 200);
    assert_int_equal(TX(r, 0xFF, 7), 0);
    assert_int_equal(r->k->vm.message, 7);
    assert_int_equal(TX(r, 0xFF, 9), 0);
    assert_int_equal(r->k->vm.message, 9);
    assert_int_equal(TX(r, 0xF7, 9), 0);      /* even the same message again */
    assert_int_equal(r->k->vm.message, 9);
    rig_free(r);
}

/* Issue 9: the reply starts no sooner than 5 ms after the command's last byte, and well before firm0328's 17 ms. */
static void the_reply_waits_5_ms_after_the_last_byte(void **state)
{
    static const u8 ping[] = { 0x55, 0xFF, 0x00, 0x10, 0xEF, 0x10, 0xEF };
    struct rig *r = rig_new();
    unsigned ms;
    (void)state;
    feed(r, ping, sizeof ping);
    /* The first tick may come at any moment after the last byte: after n ticks, n - 1 ms have surely passed. */
    for (ms = 0; ms <= 5; ms++) {
        rt_run(r->k, 0);
        assert_int_equal(r->h->ir_len, 0);
        rt_tick(r->k);
    }
    rt_run(r->k, 0);                          /* 6 ticks: at least 5 ms */
    assert_int_equal(r->h->ir_len, 7);
    /* Noise while the answer waits does not hold it back. */
    r->h->ir_len = 0;
    ticks(r, IR_ECHO_MS + 1);                 /* the echo never came: the receiver listens again */
    feed(r, (const u8[]){ 0x55, 0xFF, 0x00, 0x18, 0xE7, 0x18, 0xE7 }, 7);
    for (ms = 0; ms < IR_REPLY_MS; ms++) {
        rt_ir_byte(r->k, 0x3C, 0);
        rt_tick(r->k);
    }
    rt_run(r->k, 0);
    assert_int_equal(r->h->ir_len, 7);
    assert_int_equal(r->h->ir[3], 0xE7);
    rig_free(r);
}

static void the_memory_map_goes_out_in_pieces(void **state)
{
    struct rig *r = rig_new();
    u8 want[RCX_REPLY_MAX], pkt[2 * RCX_REPLY_MAX + 8];
    unsigned n, handed = 0, rounds = 0;
    (void)state;
    /* What the machine answers, framed: 3 + 2 x 189 + 2 bytes, more than one hal_ir_send() can take. */
    assert_int_equal(vm_direct(&r->k->vm, (const u8[]){ 0x20 }, 1, want), 189);
    assert_int_equal(want[0], 0xDF);
    n = frame((const u8[]){ 0x20 }, 1, pkt);
    feed(r, pkt, n);
    ticks(r, IR_REPLY_MS);
    r->out_len = 0;
    /* While the driver is busy nothing more is handed over. */
    while (handed < 383 && rounds++ < 100) {
        unsigned before = r->h->ir_len;
        r->h->ir_busy = 1;
        rt_run(r->k, 0);
        if (handed)
            assert_int_equal(r->h->ir_len, before);
        r->h->ir_busy = 0;
        rt_run(r->k, 0);
        assert_true(r->h->ir_len - before <= IR_CHUNK);
        memcpy(r->out + r->out_len, r->h->ir + before, r->h->ir_len - before);
        r->out_len += r->h->ir_len - before;
        feed(r, r->h->ir + before, r->h->ir_len - before);
        handed = r->out_len;
        r->h->ir_len = 0;
    }
    expect_reply(r, want, 189);
    assert_int_equal(TX(r, 0x10), 7);
    rig_free(r);
}

/* The last reply shares its buffer with the receiver (src/ir.h): a packet that reaches into it, even one dropped
 * for a bad checksum, must not have its bytes sent as the answer to a repeat. */
static void a_repeat_after_a_long_packet_gets_a_true_reply(void **state)
{
    static u8 data[IR_BLOCK_MAX];
    struct rig *r = rig_new();
    u8 want[RCX_REPLY_MAX], pkt[2 * (IR_RX_MAX + 8)], raw[IR_RX_MAX + 8];
    unsigned n, i;
    (void)state;
    assert_int_equal(vm_direct(&r->k->vm, (const u8[]){ 0x20 }, 1, want), 189);
    for (i = 0; i < sizeof data; i++)
        data[i] = (u8)(0x80 + i);
    assert_int_equal(TX(r, 0x20), 3 + 2 * 189 + 2);
    expect_reply(r, want, 189);
    assert_int_equal(TX(r, 0x20), 3 + 2 * 189 + 2); /* a repeat: the reply kept */
    expect_reply(r, want, 189);
    n = frame(raw, block(raw, 1, data, IR_BLOCK_MAX, 0), pkt);
    pkt[n - 1] ^= 0x01;                              /* the checksum's complement spoilt: dropped */
    r->out_len = 0;
    feed(r, pkt, n);
    pump(r);
    assert_int_equal(r->out_len, 0);
    ticks(r, IR_QUIET_MS);
    assert_int_equal(TX(r, 0x20), 3 + 2 * 189 + 2); /* the same opcode byte again */
    expect_reply(r, want, 189);
    rig_free(r);
}

static void oversized_blocks_are_drained_and_forgotten(void **state)
{
    static u8 data[IR_BLOCK_MAX + 1];
    struct rig *r = rig_new();
    u8 pkt[2 * (IR_RX_MAX + 8)], raw[IR_RX_MAX + 8];
    unsigned n;
    (void)state;
    memset(data, 0x10, sizeof data); /* on the wire 10 EF 10 EF ...: pings, if it were parsed as packets */
    assert_int_equal(TX(r, 0x25, 0, 0, 0, 0xD2, 0), 9);                /* a 210-byte task */
    assert_int_equal(r->out[5], 0);
    n = block(raw, 1, data, IR_BLOCK_MAX + 1, 0);
    r->out_len = 0;
    feed(r, pkt, frame(raw, n, pkt));
    pump(r);
    assert_int_equal(r->out_len, 0);
    ticks(r, IR_QUIET_MS);
    n = block(raw, 1, data, IR_BLOCK_MAX, 0);                           /* the largest block fits */
    assert_int_equal(status_of(r, raw, n, 8), 0);
    rig_free(r);
}

static void garbage_never_hangs_the_receiver(void **state)
{
    struct rig *r = rig_new();
    u32 x = 12345;
    unsigned i;
    (void)state;
    for (i = 0; i < 200000; i++) {
        x = x * 1103515245u + 12345u;
        rt_ir_byte(r->k, (u8)(x >> 16), (x >> 30) == 3 && (i & 7) == 0);
        if ((i & 63) == 0) {
            r->h->ir_len = 0;
            rt_run(r->k, 10);
            rt_tick(r->k);
        }
    }
    r->h->ir_len = 0;
    ticks(r, IR_QUIET_MS + IR_ECHO_MS);
    pump(r);
    ticks(r, IR_QUIET_MS + IR_ECHO_MS);
    assert_int_equal(TX(r, 0x10), 7);
    REPLY(r, 0xEF);
    rig_free(r);
}

/* ---- the IR mark ---- */

#define IR_MARK_LIT(r) (((r)->h->lcd[6] >> 2) & 1) /* the IR mark's lower arc, segment 6.2 (rcx-hardware.md §3.6) */

/* Milliseconds the IR mark stays lit from now, at most `max`; 0 when it is dark after the first refresh. */
static unsigned ir_mark_ms(struct rig *r, unsigned max)
{
    unsigned ms;
    ticks(r, DISPLAY_REFRESH_MS); /* lit by the next refresh */
    for (ms = DISPLAY_REFRESH_MS; ms < max && IR_MARK_LIT(r); ms++)
        ticks(r, 1);
    return IR_MARK_LIT(r) ? ms : ms == DISPLAY_REFRESH_MS ? 0 : ms;
}

/* firm0328 lights the IR mark for a moment (0.25-0.8 s) around every IR exchange (reference-firmware.md, "The
 * brick's face"): a command and its reply, a message with no reply, and the brick's own transmissions. */
static void the_ir_mark_lights_around_every_exchange(void **state)
{
    struct rig *r = rig_new();
    u8 code[] = { 0xB2, 0x02, 0x07 }; /* SendPBMessage 7 */
    unsigned ms;
    (void)state;
    ticks(r, 1000);
    assert_false(IR_MARK_LIT(r));
    TX(r, 0x10);
    REPLY(r, 0xEF);
    ms = ir_mark_ms(r, 2000);
    assert_true(ms >= 250 && ms <= 800);
    TX(r, 0xF7, 0x05);              /* an IR message: no reply, still an exchange */
    ms = ir_mark_ms(r, 2000);
    assert_true(ms >= 250 && ms <= 800);
    r->k->vm.prog = 0;
    assert_int_equal(brick_download(&r->k->vm, 1, 0, code, sizeof code), 0);
    assert_int_equal(brick_cmd(&r->k->vm, (const u8[]){ 0x71, 0 }, 2, NULL), 1); /* started without IR */
    rt_run(r->k, 1);
    ticks(r, 100);                  /* sent into a silent room ... */
    assert_false(IR_MARK_LIT(r));
    r->out_len = 0;
    pump(r);
    REPLY(r, 0xF7, 0x07);
    ms = ir_mark_ms(r, 2000);       /* ... and the mark lit as it went out */
    assert_true(ms >= 250 && ms <= 800);
    rig_free(r);
}

/* ---- what the machine asks to transmit ---- */

static void a_program_message_always_goes_out_as_f7(void **state)
{
    struct rig *r = rig_new();
    u8 code[] = { 0xB2, 0x02, 0x07, 0xB2, 0x02, 0x09 }; /* SendPBMessage 7, then 9 */
    (void)state;
    r->k->vm.prog = 0;
    assert_int_equal(brick_download(&r->k->vm, 1, 0, code, sizeof code), 0);
    assert_int_equal(TX(r, 0x71, 0), 7);
    rt_run(r->k, 1);               /* first message requested */
    ticks(r, IR_SENSE_MS);         /* sent into a silent room only */
    r->out_len = 0;
    pump(r);
    REPLY(r, 0xF7, 0x07);
    rt_run(r->k, 1);
    r->out_len = 0;
    pump(r);
    REPLY(r, 0xF7, 0x09);          /* as every brick sends it: receivers never take a message for a repeat */
    rig_free(r);
}

static void uart_data_follows_packconf_and_uartconf(void **state)
{
    static const struct {
        u8 pack, uart;
        u8 want[16];
        u8 len;
    } cases[] = {
        { 0x00, 0x00, { 0x41, 0x42 }, 2 },
        { 0x01, 0x01, { 0x55, 0xFF, 0x00, 0x41, 0x42 }, 5 },
        { 0x04, 0x02, { 0x41, 0x42, 0x83 }, 3 },
        { 0x05, 0x04, { 0x55, 0xFF, 0x00, 0x41, 0x42, 0x83 }, 6 },
        { 0x02, 0x07, { 0x41, 0xBE, 0x42, 0xBD, 0x83, 0x7C }, 6 },
        { 0x07, 0x00, { 0x55, 0xFF, 0x00, 0x41, 0xBE, 0x42, 0xBD, 0x83, 0x7C }, 9 },
    };
    unsigned i, n;
    u8 pkt[16];
    (void)state;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        struct rig *r = rig_new();
        TX(r, 0x05, 33, 3, 2, 0x41, 0);    /* uart[3] = 'A' */
        TX(r, 0x0D, 33, 4, 2, 0x42, 0);    /* uart[4] = 'B' */
        TX(r, 0x05, 33, 16, 2, cases[i].pack, 0);
        TX(r, 0x0D, 33, 17, 2, cases[i].uart, 0);
        n = frame((const u8[]){ 0xC2, 3, 2 }, 3, pkt);
        feed(r, pkt, n);
        rt_run(r->k, 0);                   /* executed: no reply, a request */
        ticks(r, IR_SENSE_MS - 1);         /* the room was not silent for long enough yet */
        rt_run(r->k, 0);
        assert_int_equal(r->h->ir_len, 0);
        ticks(r, 1);
        r->h->ir_busy = 1;                 /* a busy line holds the request back too */
        rt_run(r->k, 0);
        assert_int_equal(r->h->ir_len, 0);
        r->h->ir_busy = 0;
        r->out_len = 0;
        pump(r);
        assert_int_equal(r->out_len, cases[i].len);
        assert_memory_equal(r->out, cases[i].want, cases[i].len);
        assert_int_equal(r->h->ir_mode, cases[i].uart);
        rig_free(r);
    }
}

/* ---- requests to the rest of the runtime ---- */

static void boot_mode_waits_for_its_acknowledgement(void **state)
{
    struct rig *r = rig_new();
    u8 pkt[32];
    unsigned n = frame((const u8[]){ 0x65, 1, 3, 5, 7, 11 }, 6, pkt);
    (void)state;
    feed(r, pkt, n);
    pump_echo(r, 0);
    REPLY(r, 0x9A);
    assert_int_equal(r->h->rom_entries, 0);      /* the echo has not come back yet */
    feed(r, r->out, r->out_len);
    rt_run(r->k, 0);
    assert_int_equal(r->h->rom_entries, 1);
    rig_free(r);
}

static void range_commands_reach_the_driver(void **state)
{
    struct rig *r = rig_new();
    (void)state;
    assert_int_equal(TX(r, 0x31, 0x01), 7);
    rt_run(r->k, 0);
    assert_int_equal(r->h->ir_far, 1);
    assert_int_equal(TX(r, 0x39, 0x00), 7);
    rt_run(r->k, 0);
    assert_int_equal(r->h->ir_far, 0);
    rig_free(r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(ping_is_answered_byte_exact),
        cmocka_unit_test(every_header_form_is_accepted),
        cmocka_unit_test(bad_complement_or_checksum_is_dropped),
        cmocka_unit_test(receive_errors_drop_the_packet),
        cmocka_unit_test(silence_inside_a_packet_resynchronises),
        cmocka_unit_test(truncated_packets_get_no_reply),
        cmocka_unit_test(own_echo_and_busy_line_are_ignored),
        cmocka_unit_test(a_lost_echo_does_not_deafen_the_receiver),
        cmocka_unit_test(a_repeated_opcode_is_answered_not_executed),
        cmocka_unit_test(repeats_of_unanswered_commands_stay_silent),
        cmocka_unit_test(messages_are_never_repeats),
        cmocka_unit_test(a_repeat_after_a_long_packet_gets_a_true_reply),
        cmocka_unit_test(the_reply_waits_5_ms_after_the_last_byte),
        cmocka_unit_test(the_memory_map_goes_out_in_pieces),
        cmocka_unit_test(oversized_blocks_are_drained_and_forgotten),
        cmocka_unit_test(garbage_never_hangs_the_receiver),
        cmocka_unit_test(the_ir_mark_lights_around_every_exchange),
        cmocka_unit_test(a_program_message_always_goes_out_as_f7),
        cmocka_unit_test(uart_data_follows_packconf_and_uartconf),
        cmocka_unit_test(boot_mode_waits_for_its_acknowledgement),
        cmocka_unit_test(range_commands_reach_the_driver),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
