/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Output engine: the effective output handed to hal_motor() (direction after the global invert, power capped by the
 * global maximum, global disconnect as off or float), the six motor states and the 60 ms reversing pause of spec
 * p. 99, and the motor scheme of spec p. 98.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <string.h>
#include <cmocka.h>
#include "brick.h"
#include "fake_hal.h"

enum { FLOAT = HAL_MOTOR_FLOAT, REV = HAL_MOTOR_REV, FWD = HAL_MOTOR_FWD, BRAKE = HAL_MOTOR_BRAKE };

static void cmd2(struct rcx *b, u8 op, u8 arg)
{
    u8 c[2] = { op, arg };
    brick_cmd(b, c, 2, NULL);
}

static void cmd4(struct rcx *b, u8 op, u8 a, u8 c2, u8 c3)
{
    u8 c[4] = { op, a, c2, c3 };
    brick_cmd(b, c, 4, NULL);
}

static u8 status(struct rcx *b, u8 motor)
{
    u8 c[3] = { 0x12, 3, motor }, reply[RCX_REPLY_MAX];
    assert_int_equal(brick_cmd(b, c, 3, reply), 3);
    return reply[1];
}

#define ON(list) cmd2(b, 0x21, (u8)(0x80 | (list)))
#define OFF(list) cmd2(b, 0x21, (u8)(0x40 | (list)))
#define FLT(list) cmd2(b, 0x21, (u8)(0x00 | (list)))
#define DIR_FWD(list) cmd2(b, 0xE1, (u8)(0x80 | (list)))
#define DIR_REV(list) cmd2(b, 0xE1, (u8)(0x00 | (list)))
#define DIR_ALT(list) cmd2(b, 0xE1, (u8)(0x40 | (list)))
#define POWER(list, p) cmd4(b, 0x13, list, 2, p)
#define MAX_POWER(list, p) cmd4(b, 0xA3, list, 2, p)

static void expect_motor(struct rcx *b, u8 port, u8 mode, u8 level)
{
    struct fake_hal *h = fake_hal_of(b);
    if (h->motor_mode[port] != mode || h->motor_level[port] != level)
        fail_msg("motor %c: mode %u level %u, expected mode %u level %u", 'A' + port, h->motor_mode[port],
                 h->motor_level[port], mode, level);
}

static void ticks(struct rcx *b, unsigned ms)
{
    while (ms--)
        vm_tick(b);
}

/* firm0328 reads 0x4F (off = brake, forward, power 7) for every output right after it has started
 * (reference-firmware.md, "Observed"); the hardware is told so once (the port's latch starts at float). */
static void power_on_brakes(void **state)
{
    struct rcx *b = brick_new();
    unsigned i;
    (void)state;
    ticks(b, 100);
    assert_int_equal(fake_hal_of(b)->motor_calls, 3);
    for (i = 0; i < 3; i++) {
        assert_int_equal(status(b, (u8)i), 0x4F);
        expect_motor(b, (u8)i, BRAKE, 7);
    }
    brick_free(b);
}

/* A new brick whose hardware call count starts after the power-on braking (counted in power_on_brakes). */
static struct rcx *brick_counted(void)
{
    struct rcx *b = brick_new();
    fake_hal_of(b)->motor_calls = 0;
    return b;
}

static void effective_output(void **state)
{
    struct rcx *b = brick_counted();
    struct fake_hal *h = fake_hal_of(b);
    (void)state;
    ON(0x01);
    expect_motor(b, 0, FWD, 7);
    assert_int_equal(h->motor_calls, 1);
    POWER(0x01, 3);
    expect_motor(b, 0, FWD, 3);
    MAX_POWER(0x01, 2);            /* the global maximum caps the level */
    expect_motor(b, 0, FWD, 2);
    POWER(0x01, 1);
    expect_motor(b, 0, FWD, 1);
    MAX_POWER(0x01, 7);
    POWER(0x01, 0);                /* level 0 still drives: 1 ms in 8 (rcx-hardware.md §3.2) */
    expect_motor(b, 0, FWD, 0);
    OFF(0x01);
    expect_motor(b, 0, BRAKE, 7);
    FLT(0x01);
    expect_motor(b, 0, FLOAT, 0);

    ON(0x06);
    DIR_REV(0x04);                 /* B forward; C reverses, through the pause */
    expect_motor(b, 1, FWD, 7);
    expect_motor(b, 2, BRAKE, 7);
    ticks(b, 60);
    expect_motor(b, 2, REV, 7);
    cmd2(b, 0x77, 0x06);           /* global direction reverse for B and C: B reverse, C forward */
    ticks(b, 60);
    expect_motor(b, 1, REV, 7);
    expect_motor(b, 2, FWD, 7);
    assert_int_equal(status(b, 1) & 0x08, 0);
    assert_int_equal(status(b, 2) & 0x08, 0x08);

    cmd2(b, 0x67, 0x42);           /* B globally off: brake, though on */
    expect_motor(b, 1, BRAKE, 7);
    cmd2(b, 0x67, 0x02);           /* globally float */
    expect_motor(b, 1, FLOAT, 0);
    cmd2(b, 0x67, 0x82);           /* connected again: its own state (on, reverse) */
    expect_motor(b, 1, REV, 7);
    OFF(0x02);
    cmd2(b, 0x67, 0x02);           /* a braked motor globally floated floats */
    expect_motor(b, 1, FLOAT, 0);
    brick_free(b);
}

static void hardware_told_only_of_changes(void **state)
{
    struct rcx *b = brick_counted();
    struct fake_hal *h = fake_hal_of(b);
    (void)state;
    ON(0x07);
    assert_int_equal(h->motor_calls, 3);
    ON(0x07);
    DIR_FWD(0x07);
    POWER(0x07, 7);
    MAX_POWER(0x07, 7);
    cmd2(b, 0x67, 0x87);           /* connect the connected */
    cmd2(b, 0x77, 0x87);           /* normal direction again */
    ticks(b, 200);
    assert_int_equal(h->motor_calls, 3);
    POWER(0x07, 4);
    assert_int_equal(h->motor_calls, 6);
    MAX_POWER(0x01, 5);            /* 4 is below the cap: no change */
    assert_int_equal(h->motor_calls, 6);
    brick_free(b);
}

/* The six states of spec p. 99 and what each event leads to ('-' in the spec = stays). */
enum { ON_FWD, ON_RWD, FLT_FWD, FLT_RWD, OFF_FWD, OFF_RWD };
static const u8 state_status[6] = { 0x88, 0x80, 0x08, 0x00, 0x48, 0x40 }; /* source 3 bits on, brake, direction */
static const u8 state_mode[6] = { FWD, REV, FLOAT, FLOAT, BRAKE, BRAKE };
static const u8 next_state[6][6] = {
    /*            ON       OFF      FLOAT    FWD      RWD      ALT */
    /* ON_FWD */ { ON_FWD, OFF_FWD, FLT_FWD, ON_FWD, ON_RWD, ON_RWD },
    /* ON_RWD */ { ON_RWD, OFF_RWD, FLT_RWD, ON_FWD, ON_RWD, ON_FWD },
    /* FLT_FWD */ { ON_FWD, OFF_FWD, FLT_FWD, FLT_FWD, FLT_RWD, FLT_RWD },
    /* FLT_RWD */ { ON_RWD, OFF_RWD, FLT_RWD, FLT_FWD, FLT_RWD, FLT_FWD },
    /* OFF_FWD */ { ON_FWD, OFF_FWD, FLT_FWD, OFF_FWD, OFF_RWD, OFF_RWD },
    /* OFF_RWD */ { ON_RWD, OFF_RWD, FLT_RWD, OFF_FWD, OFF_RWD, OFF_FWD },
};
static const u8 event_cmd[6][2] = {
    { 0x21, 0x80 }, { 0x21, 0x40 }, { 0x21, 0x00 }, { 0xE1, 0x80 }, { 0xE1, 0x00 }, { 0xE1, 0x40 },
};

/* Source 3 reduced to the state bits; "when bit 7 is set (the motor is on), bit 6 is ignored" (spec p. 6). */
static u8 state_bits(struct rcx *b, u8 port)
{
    u8 s = (u8)(status(b, port) & 0xC8);
    return (u8)(s & 0x80 ? s & ~0x40 : s);
}

static void reach(struct rcx *b, u8 port, u8 st)
{
    u8 m = (u8)(1u << port);
    cmd2(b, 0xE1, (u8)((st == ON_FWD || st == FLT_FWD || st == OFF_FWD ? 0x80 : 0x00) | m));
    cmd2(b, 0x21, (u8)((st <= ON_RWD ? 0x80 : st <= FLT_RWD ? 0x00 : 0x40) | m));
    ticks(b, 100);
}

static void six_state_table(void **state)
{
    unsigned from, ev, port;
    (void)state;
    for (port = 0; port < 3; port++)
        for (from = 0; from < 6; from++)
            for (ev = 0; ev < 6; ev++) {
                struct rcx *b = brick_new();
                u8 to = next_state[from][ev];
                reach(b, (u8)port, (u8)from);
                assert_int_equal(state_bits(b, (u8)port), state_status[from]);
                cmd2(b, event_cmd[ev][0], (u8)(event_cmd[ev][1] | (1u << port)));
                ticks(b, 60);
                if (state_bits(b, (u8)port) != state_status[to] ||
                    fake_hal_of(b)->motor_mode[port] != state_mode[to])
                    fail_msg("motor %u state %u event %u: status %02X mode %u, expected state %u", port, from, ev,
                             status(b, (u8)port), fake_hal_of(b)->motor_mode[port], to);
                brick_free(b);
            }
}

/* Milliseconds until motor `port` next changes on the hardware, at most `max`. */
static unsigned until_change(struct rcx *b, u8 port, unsigned max)
{
    struct fake_hal *h = fake_hal_of(b);
    u8 mode = h->motor_mode[port], level = h->motor_level[port];
    unsigned ms;
    for (ms = 1; ms <= max; ms++) {
        vm_tick(b);
        if (h->motor_mode[port] != mode || h->motor_level[port] != level)
            return ms;
    }
    return max + 1;
}

static void reversing_pause_is_60_ms(void **state)
{
    struct rcx *b = brick_counted();
    struct fake_hal *h = fake_hal_of(b);
    (void)state;
    ON(0x01);
    DIR_REV(0x01);                     /* ON_FWD -> ON_RWD */
    expect_motor(b, 0, BRAKE, 7);      /* held off at once */
    assert_int_equal(until_change(b, 0, 200), 60);
    expect_motor(b, 0, REV, 7);
    DIR_ALT(0x01);                     /* and back, through the alternate event */
    expect_motor(b, 0, BRAKE, 7);
    assert_int_equal(until_change(b, 0, 200), 60);
    expect_motor(b, 0, FWD, 7);

    cmd2(b, 0x77, 0x01);               /* a global invert reverses the effective direction too */
    expect_motor(b, 0, BRAKE, 7);
    assert_int_equal(until_change(b, 0, 200), 60);
    expect_motor(b, 0, REV, 7);
    cmd2(b, 0x77, 0x81);
    ticks(b, 60);

    DIR_REV(0x01);                     /* stopping during the pause ends it: no reverse drive afterwards */
    ticks(b, 30);
    FLT(0x01);
    expect_motor(b, 0, FLOAT, 0);
    assert_int_equal(until_change(b, 0, 200), 201);

    ON(0x01);                          /* from float: straight on, no pause */
    expect_motor(b, 0, REV, 7);
    DIR_FWD(0x01);
    ticks(b, 20);
    POWER(0x01, 3);                    /* requests during the pause wait for its end */
    DIR_REV(0x01);
    DIR_FWD(0x01);
    expect_motor(b, 0, BRAKE, 7);
    assert_int_equal(until_change(b, 0, 200), 40);
    expect_motor(b, 0, FWD, 3);
    assert_int_equal(h->motor_calls, 14);
    brick_free(b);
}

static void motor_scheme_of_page_98(void **state)
{
    struct rcx *b = brick_new();
    u8 global[3];
    unsigned i;
    (void)state;
    ON(0x07);
    DIR_REV(0x02);
    POWER(0x07, 2);
    ticks(b, 100);
    outputs_program_start(b);          /* forward, brake, max power */
    for (i = 0; i < 3; i++) {
        assert_int_equal(status(b, (u8)i), 0x4F);
        expect_motor(b, (u8)i, BRAKE, 7);
    }
    FLT(0x07);                         /* float clears the brake bit, so stopping must set it */
    ON(0x07);
    DIR_REV(0x04);
    POWER(0x07, 4);
    ticks(b, 100);
    outputs_program_stop(b);           /* all brake, direction and power kept */
    assert_int_equal(status(b, 0), 0x4C);
    assert_int_equal(status(b, 2), 0x44);
    expect_motor(b, 0, BRAKE, 7);
    expect_motor(b, 2, BRAKE, 7);

    FLT(0x07);
    MAX_POWER(0x07, 6);
    memcpy(global, b->out.global, sizeof global);
    outputs_remote(b, 0xF9, 0xF4);     /* A forward, C reverse held on the remote; B untouched; bits 3-7 are
                                        * no buttons and must not reach past motor C's register */
    assert_memory_equal(global, b->out.global, sizeof global);
    assert_int_equal(status(b, 0), 0x8E);  /* power shown capped by the maximum */
    assert_int_equal(status(b, 1), 0x0C);
    assert_int_equal(status(b, 2), 0x86);
    expect_motor(b, 0, FWD, 6);
    expect_motor(b, 1, FLOAT, 0);
    expect_motor(b, 2, REV, 6);
    MAX_POWER(0x07, 7);
    outputs_remote(b, 0, 0);           /* released: all forward, brake, max power */
    for (i = 0; i < 3; i++) {
        assert_int_equal(status(b, (u8)i), 0x4F);
        expect_motor(b, (u8)i, BRAKE, 7);
    }

    ON(0x07);
    outputs_revoked(b, 0x04);          /* the sound resource: motors unaffected */
    for (i = 0; i < 3; i++)
        expect_motor(b, (u8)i, FWD, 7);
    outputs_revoked(b, 0x09);          /* A and C (spec p. 106: 0x01 A, 0x02 B, 0x08 C) */
    expect_motor(b, 0, BRAKE, 7);
    expect_motor(b, 1, FWD, 7);
    expect_motor(b, 2, BRAKE, 7);
    outputs_revoked(b, 0x02);
    expect_motor(b, 1, BRAKE, 7);
    brick_free(b);
}

/* A program started from the host (nqc -run: StartTask 0) begins with its outputs forward, braked, at full power, as
 * Run starts one (reference-firmware.md, "Observed"); other tasks, and StartTask from a program, leave them. */
static void start_task_0_from_the_host_brakes(void **state)
{
    static const u8 task1[] = { 0x71, 0x00 };              /* task 1 starts task 0 */
    static const u8 idle[] = { 0x43, 0x02, 0x64, 0x00 };   /* Wait 100 */
    struct rcx *b = brick_new();
    unsigned i;
    (void)state;
    assert_int_equal(brick_download(b, 1, 0, idle, sizeof idle), 0);
    assert_int_equal(brick_download(b, 1, 1, task1, sizeof task1), 0);
    ON(0x07);
    DIR_REV(0x02);
    POWER(0x07, 3);
    cmd2(b, 0x71, 1);                  /* StartTask 1 from the host: outputs untouched ... */
    brick_run_ms(b, 10, 10);           /* ... and task 1 starts task 0 from a program: untouched too */
    assert_int_equal(b->task[0].state, RCX_TASK_WAITING);
    assert_int_equal(status(b, 0), 0x8B);
    assert_int_equal(status(b, 1), 0x83);
    cmd2(b, 0x71, 0);                  /* StartTask 0 from the host */
    for (i = 0; i < 3; i++) {
        assert_int_equal(status(b, (u8)i), 0x4F);
        expect_motor(b, (u8)i, BRAKE, 7);
    }
    brick_free(b);
}

static void bad_operands_change_nothing(void **state)
{
    static const struct { const char *what; u8 bytes[4]; u8 len; } rows[] = {
        { "SetPower 8", { 0x13, 0x07, 0x02, 0x08 }, 4 },
        { "SetPower -1", { 0x13, 0x07, 0x02, 0xFF }, 4 },       /* 255 as an 8-bit constant: above 7 */
        { "SetPower from a variable holding -1", { 0x13, 0x07, 0x00, 0x05 }, 4 },
        { "SetMaxPower 8", { 0xA3, 0x07, 0x02, 0x08 }, 4 },
        { "OnOffFloat verb 3", { 0x21, 0xC7 }, 2 },
        { "OnOffFloat no motor (bits 3-5)", { 0x21, 0xB8 }, 2 },
        { "SetFwdSetRwdRewDir verb 3", { 0xE1, 0xC7 }, 2 },
        { "ConnectDisconnect verb 3", { 0x67, 0xC7 }, 2 },
        { "SetNormSetInvAltDir no motor", { 0x77, 0x38 }, 2 },
    };
    unsigned i;
    (void)state;
    for (i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        struct rcx *b = brick_new();
        struct rcx_outputs before;
        struct fake_hal hal_before;
        u8 setvar[5] = { 0x14, 5, 2, 0xFF, 0xFF };
        brick_cmd(b, setvar, 5, NULL);  /* variable 5 = -1 */
        ON(0x03);
        POWER(0x07, 5);
        ticks(b, 100);
        memcpy(&before, &b->out, sizeof before);
        memcpy(&hal_before, fake_hal_of(b), sizeof hal_before);
        brick_cmd(b, rows[i].bytes, rows[i].len, NULL);
        ticks(b, 100);
        if (memcmp(&before, &b->out, sizeof before) != 0)
            fail_msg("%s changed the outputs", rows[i].what);
        if (memcmp(&hal_before, fake_hal_of(b), sizeof hal_before) != 0)
            fail_msg("%s reached the hardware", rows[i].what);
        brick_free(b);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(power_on_brakes),
        cmocka_unit_test(start_task_0_from_the_host_brakes),
        cmocka_unit_test(effective_output),
        cmocka_unit_test(hardware_told_only_of_changes),
        cmocka_unit_test(six_state_table),
        cmocka_unit_test(reversing_pause_is_60_ms),
        cmocka_unit_test(motor_scheme_of_page_98),
        cmocka_unit_test(bad_operands_change_nothing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
