/* SPDX-License-Identifier: MPL-2.0 */
/*
 * RemoteCommand 0xD2 (spec p. 61 table, p. 98 motor scheme) and the transmit requests of SendPBMessage 0xB2
 * (p. 59) and SendUARTData 0xC2 (p. 60, source 33 layout p. 9), at the machine's level (the IR layer's handling
 * of repeats and the bytes on the wire are tests/unit/test_ir.c).
 *
 * The calls into the outputs engine are intercepted (linked with --wrap, see tests/e2e/CMakeLists.txt) so that the
 * masks handed over are checked here whatever that engine does with them; they are passed on to it unchanged.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <string.h>
#include <cmocka.h>
#include "brick.h"
#include "fake_hal.h"

#define SEND(b, ...) brick_cmd((b), (const u8[]){ __VA_ARGS__ }, sizeof((const u8[]){ __VA_ARGS__ }), NULL)
#define REMOTE(b, bits) SEND((b), 0xD2, (u8)(bits), (u8)((bits) >> 8))

static struct {
    unsigned remote_calls, stop_calls;
    u8 fwd, rev;
} seen;

void __real_outputs_remote(struct rcx *b, u8 fwd_mask, u8 rev_mask);
void __real_outputs_program_stop(struct rcx *b);

void __wrap_outputs_remote(struct rcx *b, u8 fwd_mask, u8 rev_mask)
{
    seen.remote_calls++;
    seen.fwd = fwd_mask;
    seen.rev = rev_mask;
    __real_outputs_remote(b, fwd_mask, rev_mask);
}

void __wrap_outputs_program_stop(struct rcx *b)
{
    seen.stop_calls++;
    __real_outputs_program_stop(b);
}

static struct rcx *fresh(void)
{
    memset(&seen, 0, sizeof seen);
    return brick_new();
}

static int any_running(const struct rcx *b)
{
    return b->runmask != 0 || b->task[0].state != RCX_TASK_IDLE;
}

static void messages_one_to_three(void **state)
{
    static const u16 bits[3] = { 0x0100, 0x0200, 0x0400 };
    unsigned i;
    (void)state;
    for (i = 0; i < 3; i++) {
        struct rcx *b = fresh();
        assert_int_equal(REMOTE(b, bits[i]), 0);           /* no reply */
        assert_int_equal(b->message, i + 1);
        assert_int_equal(seen.remote_calls, 0);             /* a one-shot button leaves the motors alone */
        brick_free(b);
    }
}

static void one_shot_buttons_act_on_the_press_only(void **state)
{
    struct rcx *b = fresh();
    (void)state;
    REMOTE(b, 0x0200);
    assert_int_equal(b->message, 2);
    SEND(b, 0x90);                     /* message cleared */
    REMOTE(b, 0x0200);                 /* still held: nothing */
    assert_int_equal(b->message, 0);
    REMOTE(b, 0x0600);                 /* message 3 pressed while 2 is held */
    assert_int_equal(b->message, 3);
    REMOTE(b, 0);                      /* remote 0 clears the buffers (spec p. 61) */
    REMOTE(b, 0x0200);
    assert_int_equal(b->message, 2);
    brick_free(b);
}

static void program_buttons_select_and_start(void **state)
{
    u8 n;
    struct rcx *b = fresh();
    (void)state;
    for (n = 0; n < 5; n++) {          /* slot n: task 0 sets var[0] = n + 1 */
        u8 code[] = { 0x14, 0x00, 0x02, (u8)(n + 1), 0x00 };
        SEND(b, n & 1 ? 0x99 : 0x91, n);
        assert_int_equal(brick_download(b, 1, 0, code, sizeof code), 0);
    }
    SEND(b, 0x91, 0);
    for (n = 0; n < 5; n++) {
        unsigned stops = seen.stop_calls;
        REMOTE(b, 0x0002u << n);
        assert_int_equal(b->prog, n);
        assert_true(any_running(b));   /* "prgm N, start 0" */
        assert_int_equal(seen.stop_calls, stops + 1); /* motors brake (spec p. 98) */
        brick_run_until_idle(b, 100, 10);
        assert_int_equal(b->global[0], n + 1);
        REMOTE(b, 0x0002u << n);       /* held: not started again */
        assert_false(any_running(b));
        REMOTE(b, 0);
    }
    brick_free(b);
}

static void stop_button_stops_program_and_motors(void **state)
{
    static const u8 spin[] = { 0x27, 0x81 };
    struct rcx *b = fresh();
    (void)state;
    assert_int_equal(brick_download(b, 1, 3, spin, sizeof spin), 0);
    brick_start(b, 3);
    brick_run_ms(b, 5, 5);
    assert_int_not_equal(b->task[3].state, RCX_TASK_IDLE);
    REMOTE(b, 0x0040);
    assert_int_equal(b->task[3].state, RCX_TASK_IDLE);
    assert_int_equal(seen.stop_calls, 1);
    brick_free(b);
}

static void motor_buttons_are_held(void **state)
{
    static const struct { u16 bits; u8 fwd, rev; } rows[] = {
        { 0x0800, 1, 0 }, { 0x1000, 2, 0 }, { 0x2000, 4, 0 },
        { 0x4000, 0, 1 }, { 0x8000, 0, 2 }, { 0x0001, 0, 4 },
        { 0x3801, 7, 4 }, { 0xC000, 0, 3 },
    };
    unsigned i;
    (void)state;
    for (i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        struct rcx *b = fresh();
        REMOTE(b, rows[i].bits);
        assert_int_equal(seen.remote_calls, 1);
        assert_int_equal(seen.fwd, rows[i].fwd);
        assert_int_equal(seen.rev, rows[i].rev);
        REMOTE(b, rows[i].bits | 0x0100); /* a one-shot added while held: motors untouched */
        assert_int_equal(seen.remote_calls, 1);
        REMOTE(b, 0);                      /* released */
        assert_int_equal(seen.remote_calls, 2);
        assert_int_equal(seen.fwd, 0);
        assert_int_equal(seen.rev, 0);
        brick_free(b);
    }
}

static void sound_button_beeps_unless_muted(void **state)
{
    struct rcx *b = fresh();
    struct fake_hal *h = fake_hal_of(b);
    (void)state;
    REMOTE(b, 0x0080);
    brick_run_ms(b, 500, 1);
    assert_true(h->sound_calls > 0);
    assert_int_equal(h->sound_log[0], 996); /* beep-beep, system sound 1 (rcx-hardware.md §3.7) */
    brick_free(b);

    b = fresh();
    h = fake_hal_of(b);
    SEND(b, 0xD0);                          /* MuteSound: the command interpreter's sounds are ignored */
    REMOTE(b, 0x0080);
    brick_run_ms(b, 500, 1);
    assert_int_equal(h->sound_calls, 0);
    brick_free(b);
}

static void uart_requests_copy_the_buffer_and_setup(void **state)
{
    struct rcx *b = fresh();
    (void)state;
    SEND(b, 0x05, 33, 1, 2, 0x11, 0);
    SEND(b, 0x0D, 33, 2, 2, 0x22, 0);
    SEND(b, 0x05, 33, 3, 2, 0x33, 0);
    SEND(b, 0x0D, 33, 16, 2, 0x05, 0);      /* PackConf: preamble + checksum */
    SEND(b, 0x05, 33, 17, 2, 0x03, 0);      /* UartConf: 4800 baud, 76 kHz */
    assert_int_equal(SEND(b, 0xC2, 1, 3), 0);
    assert_int_equal(b->remote.tx_len, 3);
    assert_memory_equal(b->remote.tx, ((const u8[]){ 0x11, 0x22, 0x33 }), 3);
    assert_int_equal(b->remote.tx_pack, 0x05);
    assert_int_equal(b->remote.tx_mode, 0x03);
    SEND(b, 0x0D, 33, 2, 2, 0x99, 0);       /* the request keeps what the buffer held when it was made */
    assert_int_equal(b->remote.tx[1], 0x22);
    brick_free(b);
}

static void uart_requests_past_the_buffer_are_refused(void **state)
{
    struct rcx *b = fresh();
    (void)state;
    SEND(b, 0xC2, 12, 5);                   /* start + size > 16 (spec p. 60) */
    assert_int_equal(b->remote.tx_len, 0);
    SEND(b, 0xCA, 0, 0);                    /* nothing to send */
    assert_int_equal(b->remote.tx_len, 0);
    SEND(b, 0xC2, 0, 16);                   /* the whole buffer is allowed */
    assert_int_equal(b->remote.tx_len, 16);
    brick_free(b);
}

static void send_message_takes_the_low_byte_of_its_source(void **state)
{
    static const u8 code[] = { 0x14, 0x05, 0x02, 0x34, 0x12, 0xB2, 0x00, 0x05 }; /* v5 = 0x1234; msg v5 */
    struct rcx *b = fresh();
    (void)state;
    assert_int_equal(brick_download(b, 1, 0, code, sizeof code), 0);
    brick_start(b, 0);
    brick_run_until_idle(b, 100, 10);
    assert_int_equal(b->remote.tx_len, 2);
    assert_int_equal(b->remote.tx[0], 0xF7);
    assert_int_equal(b->remote.tx[1], 0x34);
    assert_int_equal(b->remote.tx_pack, 0x07);
    assert_int_equal(b->remote.tx_mode, 0);
    assert_int_equal(b->message, 0);        /* sending is not receiving */
    brick_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(messages_one_to_three),
        cmocka_unit_test(one_shot_buttons_act_on_the_press_only),
        cmocka_unit_test(program_buttons_select_and_start),
        cmocka_unit_test(stop_button_stops_program_and_motors),
        cmocka_unit_test(motor_buttons_are_held),
        cmocka_unit_test(sound_button_beeps_unless_muted),
        cmocka_unit_test(uart_requests_copy_the_buffer_and_setup),
        cmocka_unit_test(uart_requests_past_the_buffer_are_refused),
        cmocka_unit_test(send_message_takes_the_low_byte_of_its_source),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
