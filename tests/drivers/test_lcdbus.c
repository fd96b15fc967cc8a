/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The LCD bus (drivers/lcdbus.c, rcx-hardware.md §3.6) compiled against recording pins, its waveform decoded as
 * the controller would see it: START and STOP conditions, data sampled on the rising clock edge, MSB first, nine
 * clocks per byte, and SDA never changing while SCL is high except for START and STOP. And its pace, where
 * standard-mode I2C needs more than the instructions themselves take (the brick's timing is measured in
 * tests/drivers/h8machine.c): the brick pauses in every SCL low before it rises, and after every SCL rise and the
 * START before the next change.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <string.h>
#include <cmocka.h>
#include "hw.h"
#include "hw_pins.h"

#define EVENTS 8192
#define WAIT 2 /* the `line` of a pause */

static u8 line[2];                 /* SCL, SDA now */
static struct { u8 line, level; } ev[EVENTS];
static unsigned nev;

static void record(int which, int level)
{
    assert_true(nev < EVENTS);
    ev[nev].line = (u8)which;
    ev[nev].level = (u8)level;
    nev++;
}

void pins_set(int which, int level)
{
    record(which, level);
}

void pins_wait(void)
{
    record(WAIT, 0);
}

/* Decode the recording from an idle bus (both high). Returns the number of bytes between START and STOP;
 * fails the test on any protocol violation. `acks` receives the SDA level of each ninth clock. A clock pulse
 * counts when SCL falls again without SDA having moved meanwhile (otherwise it framed a STOP). `paused`: a pause
 * since the last edge of SCL or the START. */
static unsigned decode(u8 *bytes, u8 *acks, unsigned max)
{
    unsigned i, nbytes = 0, bits = 0, starts = 0, stops = 0;
    u8 cur = 0, pulse = 0, paused = 0; /* pulse: SCL rose since START or the last bit */

    line[0] = line[1] = 1;
    for (i = 0; i < nev; i++) {
        u8 l = ev[i].line, v = ev[i].level;
        if (l == WAIT) {
            paused = 1;
            continue;
        }
        if (line[l] == v)
            continue; /* no edge */
        if (l == 1 && line[0]) { /* SDA moves while SCL is high: only START or STOP may do that */
            if (!v) {
                assert_int_equal(starts, 0);
                starts++;
                paused = 0; /* SCL must stay high a while after the START */
            } else {
                assert_int_equal(starts, 1);
                assert_int_equal(bits, 0); /* a STOP only between bytes */
                assert_true(paused);       /* SCL high a while before it */
                stops++;
            }
        } else if (l == 0 && !v && pulse) { /* falling clock after a pulse: the bit SDA held during it */
            pulse = 0;
            assert_int_equal(starts, 1);
            assert_int_equal(stops, 0);
            assert_true(paused); /* SCL high a while */
            if (bits < 8) {
                cur = (u8)(cur << 1 | line[1]);
                bits++;
            } else {
                assert_true(nbytes < max);
                bytes[nbytes] = cur;
                acks[nbytes] = line[1];
                nbytes++;
                bits = 0;
                cur = 0;
            }
            paused = 0;
        } else if (l == 0 && !v) { /* the first fall, after the START */
            assert_true(paused);
            paused = 0;
        } else if (l == 0 && v) {
            assert_int_equal(stops, 0); /* no clock after the STOP */
            assert_true(paused);        /* SCL low a while */
            pulse = starts != 0;
            paused = 0;
        }
        line[l] = v;
    }
    assert_int_equal(starts, 1);
    assert_int_equal(stops, 1);
    assert_int_equal(line[0], 1); /* idle again: both high */
    assert_int_equal(line[1], 1);
    return nbytes;
}

static void send_and_decode(const u8 *frame, u8 n)
{
    u8 got[32], acks[32];
    nev = 0;
    hw_lcd_send(frame, n);
    assert_int_equal(decode(got, acks, sizeof got), n);
    assert_memory_equal(got, frame, n);
    for (u8 i = 0; i < n; i++)
        assert_int_equal(acks[i], 0); /* SDA is held low, the controller's own acknowledge level */
}

static void frames_go_out_bit_exact(void **state)
{
    u8 image[9] = { 0xFF, 0x00, 0xA5, 0x5A, 0x80, 0x01, 0x7E, 0x81, 0xC3 }, frame[HW_LCD_FRAME_MAX];
    (void)state;
    send_and_decode(frame, hw_lcd_on_frame(image, frame));
    send_and_decode(frame, hw_lcd_off_frame(frame));
    for (unsigned v = 0; v < 256; v++) { /* every byte value */
        u8 one[9] = { 0 };
        one[(u8)v % 9] = (u8)v;
        send_and_decode(frame, hw_lcd_on_frame(one, frame));
    }
}

static void an_empty_frame_is_start_and_stop(void **state)
{
    u8 dummy = 0, got[1], acks[1];
    (void)state;
    nev = 0;
    hw_lcd_send(&dummy, 0);
    assert_int_equal(decode(got, acks, 1), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(frames_go_out_bit_exact),
        cmocka_unit_test(an_empty_frame_is_start_and_stop),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
