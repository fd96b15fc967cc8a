/*
 * Switching off and on, with the whole firmware image in the simulated brick (h8machine.h): the power-down timer
 * and the On-Off button put the brick into software standby, and one press of On-Off wakes it (issue 9, item 3:
 * firm0328 wakes on the first press). Also the state one standby may leave for the next: the IRQ1 sense and enable,
 * and a falling edge latched while the brick was on (the press that switched it off, contact bounce).
 *
 * Usage: test_standby <image (COFF; image.srec beside it)> <h8300 nm>
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>
#include "h8machine.h"

static struct h8machine m;
static const char *image_path, *nm_path;

#define SECOND H8M_CLOCK
#define HOLD (150 * H8M_MS)       /* a press as a person makes it */
#define LATENCY_MAX (30 * H8M_MS) /* a ping's answer, as test_h8machine.c bounds it */
#define P5DR 0xFFBA
#define SYSCR 0xFFC4
#define MOTOR_LATCH 0xFF80

static int boot(void **state)
{
    (void)state;
    if (h8m_boot(&m, image_path, nm_path) || h8m_run(&m, 300 * H8M_MS))
        return -1;
    return 0;
}

/* Down at `at` for `hold`; with `bounce`, each change of the contact comes as three, 100 µs apart. */
static void press(uint8_t button, unsigned long long at, unsigned long long hold, int bounce)
{
    unsigned i, n = bounce ? 3 : 1;
    for (i = 0; i < n; i++) {
        assert_int_equal(h8m_button(&m, button, !(i & 1), at + i * H8M_MS / 10), 0);
        assert_int_equal(h8m_button(&m, button, i & 1, at + hold + i * H8M_MS / 10), 0);
    }
}

static void ping_answered(void)
{
    static const uint8_t ping[] = { 0x10 };
    uint8_t reply;
    unsigned long long lat;
    assert_int_equal(h8m_transact(&m, ping, 1, &reply, 1, &lat), 0);
    assert_int_equal(reply & 0xF7, 0xE7); /* spec p. 13: ~0x10 */
    assert_true(lat < LATENCY_MAX);
}

/* Switched off: software standby (rcx-hardware.md §3.11), external RAM in power-save, the LCD controller told to
 * switch off (START 7C 40 STOP, §3.6), the motors floating. */
static void assert_off(void)
{
    assert_true(m.standby);
    assert_true(m.h.asleep);
    assert_true(m.h.mem[SYSCR] & 0x80);
    assert_true(m.h.mem[P5DR] & 0x04);
    assert_int_equal(m.lcd_len, 2);
    assert_int_equal(m.lcd[0], 0x7C);
    assert_int_equal(m.lcd[1], 0x40);
    assert_int_equal(m.h.mem[MOTOR_LATCH], 0);
}

/* Off, and it stays off for `t` even when Run, View or Prgm is pressed: a ping meanwhile is not heard. */
static void stays_off(unsigned long long t)
{
    static const uint8_t ping[] = { 0x10 };
    unsigned from = m.nsent, standbys = m.standbys;
    unsigned long long at = m.h.states;

    assert_off();
    press(H8M_RUN, at + t / 4, HOLD, 0);
    press(H8M_VIEW, at + t / 2, HOLD, 0);
    press(H8M_PRGM, at + t * 3 / 4, HOLD, 0);
    h8m_command(&m, ping, 1);
    assert_int_equal(h8m_run(&m, at + t), 0);
    assert_off();
    assert_int_equal(m.standbys, standbys);
    assert_int_equal(m.nsent, from);
}

/* One press of On-Off: awake within the oscillator's settling (8.2 ms) and a little, the tick running again once it
 * is released, and a ping answered. */
static void one_press_wakes(int bounce)
{
    unsigned long long at = m.h.states + 10 * H8M_MS, ticks;
    unsigned frames = m.lcd_frames;

    press(H8M_ONOFF, at, HOLD, bounce);
    assert_int_equal(h8m_run(&m, at + 10 * H8M_MS), 0);
    assert_false(m.standby);
    assert_int_equal(h8m_run(&m, at + HOLD + 50 * H8M_MS), 0);
    assert_false(m.standby);
    assert_true(m.lcd_frames > frames); /* the display back on, showing what it showed */
    assert_int_equal(m.lcd[1] & 0x7F, 0x48);
    ticks = m.ms_seen;
    assert_int_equal(h8m_run(&m, m.h.states + 100 * H8M_MS), 0);
    assert_true(m.ms_seen - ticks >= 99);
    ping_answered();
    assert_false(m.standby);
}

/* One press of On-Off switches the brick off within a second (the key click is heard first). */
static void one_press_switches_off(int bounce)
{
    unsigned long long at = m.h.states + 10 * H8M_MS;
    unsigned standbys = m.standbys;

    press(H8M_ONOFF, at, HOLD, bounce);
    assert_int_equal(h8m_run(&m, at + SECOND), 0);
    assert_int_equal(m.standbys, standbys + 1);
    assert_off();
}

/* PBPowerDownTime 1 (spec p. 35, reply 0x46), then nothing: off after a minute. */
static void off_after_a_minute(void)
{
    static const uint8_t minute[] = { 0xB1, 0x01 };
    uint8_t reply;
    unsigned long long t0;
    unsigned standbys = m.standbys;

    assert_int_equal(h8m_transact(&m, minute, sizeof minute, &reply, 1, NULL), 0);
    assert_int_equal(reply & 0xF7, 0x46);
    t0 = m.h.states;
    assert_int_equal(h8m_run(&m, t0 + 59 * SECOND), 0);
    assert_false(m.standby);
    assert_int_equal(h8m_run(&m, t0 + 61 * SECOND), 0);
    assert_int_equal(m.standbys, standbys + 1);
    assert_off();
}

static void power_down_time_switches_off_and_one_press_wakes(void **state)
{
    (void)state;
    off_after_a_minute();
    stays_off(5 * SECOND);
    one_press_wakes(0);
    /* And again from there: whatever the first standby left behind does not shorten or lengthen the next. */
    one_press_switches_off(0);
    stays_off(2 * SECOND);
    one_press_wakes(0);
}

static void on_off_switches_off_and_on_twice(void **state)
{
    (void)state;
    one_press_switches_off(0);
    stays_off(2 * SECOND);
    one_press_wakes(0);
    one_press_switches_off(0);
    stays_off(2 * SECOND);
    one_press_wakes(0);
}

/* A contact that bounces: every press and release is three edges, each latching IRQ1 where it is edge-sensed. */
static void bouncing_on_off_switches_off_and_on_twice(void **state)
{
    (void)state;
    one_press_switches_off(1);
    stays_off(2 * SECOND);
    one_press_wakes(1);
    one_press_switches_off(1);
    stays_off(2 * SECOND);
    one_press_wakes(1);
}

/* The same where an edge latches only while IER enables IRQ1 (h8machine.c: the other reading of the manual). */
static void bouncing_on_off_with_latch_needing_ier(void **state)
{
    m.latch_needs_ier = 1;
    bouncing_on_off_switches_off_and_on_twice(state);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(power_down_time_switches_off_and_one_press_wakes, boot),
        cmocka_unit_test_setup(on_off_switches_off_and_on_twice, boot),
        cmocka_unit_test_setup(bouncing_on_off_switches_off_and_on_twice, boot),
        cmocka_unit_test_setup(bouncing_on_off_with_latch_needing_ier, boot),
    };
    if (argc != 3)
        return 2;
    image_path = argv[1];
    nm_path = argv[2];
    return cmocka_run_group_tests(tests, NULL, NULL);
}
