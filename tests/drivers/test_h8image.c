/*
 * The firmware image's own code, run in the H8/300 simulator (h8sim.c) and compared with the same C compiled for
 * the host: the arithmetic helpers gcc calls (drivers/arith) and the drivers' logic (drivers/hw.c). This catches
 * what the host cannot: 16-bit int, the H8 compiler's code, the helpers as linked. It also checks the simulator,
 * which the firmware benchmark (tests/bench/firmware.sh) relies on.
 *
 * Usage: test_h8image <image (COFF; image.srec beside it)> <h8300 nm>
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "hal.h"
#include "arith.h"
#include "hw.h"
#include "h8image.h"

static struct h8 h;
static const char *image_path, *nm_path;

static int load(void **state)
{
    (void)state;
    return h8_image_load(&h, image_path, nm_path);
}

static uint32_t rnd_state = 12345;
static u16 rnd(void)
{
    rnd_state = rnd_state * 1103515245u + 12345u;
    return (u16)(rnd_state >> 12);
}

/* Operands that matter for 16-bit arithmetic, then random ones. */
static u16 operand(unsigned i)
{
    static const u16 edge[] = { 0, 1, 2, 3, 7, 10, 255, 256, 257, 1000, 0x7FFF, 0x8000, 0x8001, 0xFFFE, 0xFFFF };
    return i < sizeof edge / sizeof edge[0] ? edge[i] : rnd();
}

static void arithmetic_helpers_as_linked(void **state)
{
    (void)state;
    for (unsigned i = 0; i < 300; i++)
        for (unsigned j = 0; j < 60; j++) {
            u16 a = operand(i), b = operand(j);
            if (h8_sym("___mulhi3") >= 0)
                assert_int_equal((u16)h8_run(&h, "___mulhi3", a, b, 0, NULL, 0), rcx_mul16(a, b));
            if (h8_sym("___udivhi3") >= 0)
                assert_int_equal((u16)h8_run(&h, "___udivhi3", a, b, 0, NULL, 0), rcx_divu16(a, b));
            if (h8_sym("___umodhi3") >= 0)
                assert_int_equal((u16)h8_run(&h, "___umodhi3", a, b, 0, NULL, 0), rcx_modu16(a, b));
            if (h8_sym("___divhi3") >= 0)
                assert_int_equal((u16)h8_run(&h, "___divhi3", a, b, 0, NULL, 0), (u16)rcx_divs16((s16)a, (s16)b));
            if (h8_sym("___modhi3") >= 0)
                assert_int_equal((u16)h8_run(&h, "___modhi3", a, b, 0, NULL, 0), (u16)rcx_mods16((s16)a, (s16)b));
        }
}

static void battery_conversion_as_compiled(void **state)
{
    (void)state;
    for (unsigned raw = 0; raw < 1100; raw++)
        assert_int_equal((u16)h8_run(&h, "_hw_battery_mv", (u16)raw, 0, 0, NULL, 0), hw_battery_mv((u16)raw));
    assert_int_equal((u16)h8_run(&h, "_hw_battery_mv", 0xFFFF, 0, 0, NULL, 0), hw_battery_mv(0xFFFF));
}

static void tones_as_compiled(void **state)
{
    (void)state;
    for (unsigned hz = 0; hz <= 20100; hz += (hz < 1000 ? 1 : 7)) {
        struct hw_tone t;
        u8 ok = hw_tone((u16)hz, &t);
        memset(h.mem + H8_SCRATCH, 0xAA, 3);
        assert_int_equal((u8)h8_run(&h, "_hw_tone", (u16)hz, H8_SCRATCH, 0, NULL, 0), ok);
        if (ok) {
            assert_int_equal(h.mem[H8_SCRATCH], t.tcr);
            assert_int_equal(h.mem[H8_SCRATCH + 1], t.tcora);
            assert_int_equal(h.mem[H8_SCRATCH + 2], t.icks0);
        }
    }
}

static void ir_settings_as_compiled(void **state)
{
    (void)state;
    for (unsigned mode = 0; mode < 256; mode++) {
        struct hw_carrier c;
        hw_carrier((u8)mode, &c);
        h8_run(&h, "_hw_carrier", (u16)mode, H8_SCRATCH, 0, NULL, 0);
        assert_int_equal(h.mem[H8_SCRATCH], c.tcr);
        assert_int_equal(h.mem[H8_SCRATCH + 1], c.tcsr);
        assert_int_equal(h.mem[H8_SCRATCH + 2], c.tcora);
        assert_int_equal(h.mem[H8_SCRATCH + 3], c.tcorb);
        assert_int_equal((u8)h8_run(&h, "_hw_sci_brr", (u16)mode, 0, 0, NULL, 0), hw_sci_brr((u8)mode));
    }
}

/* Random settings and steps on both sides; the state and every latch byte must agree. */
static void motor_patterns_as_compiled(void **state)
{
    struct hw_motors m;
    (void)state;
    memset(&m, 0, sizeof m);
    memset(h.mem + H8_SCRATCH, 0, sizeof m);
    for (unsigned i = 0; i < 3000; i++) {
        if (rnd() % 3 == 0) {
            u8 port = (u8)(rnd() % 4), mode = (u8)rnd(), level = (u8)(rnd() % 10);
            uint16_t stack[1] = { level };
            hw_motor_set(&m, port, mode, level);
            h8_run(&h, "_hw_motor_set", H8_SCRATCH, port, mode, stack, 1);
        }
        assert_int_equal((u8)h8_run(&h, "_hw_motor_step", H8_SCRATCH, 0, 0, NULL, 0), hw_motor_step(&m));
        assert_memory_equal(h.mem + H8_SCRATCH, &m, sizeof m);
    }
}

static void debounce_as_compiled(void **state)
{
    struct hw_debounce d;
    (void)state;
    memset(&d, 0, sizeof d);
    memset(h.mem + H8_SCRATCH, 0, sizeof d);
    for (unsigned i = 0; i < 5000; i++) {
        u8 raw = (u8)(rnd() % 16 < 13 ? d.state ^ (i / 37 % 2 ? 0x05 : 0) : rnd() & 15);
        assert_int_equal((u8)h8_run(&h, "_hw_debounce", H8_SCRATCH, raw, 0, NULL, 0), hw_debounce(&d, raw));
        assert_memory_equal(h.mem + H8_SCRATCH, &d, sizeof d);
    }
}

static void receive_ring_as_compiled(void **state)
{
    static struct hw_rx r;
    u8 byte;
    (void)state;
    memset(&r, 0, sizeof r);
    memset(h.mem + H8_SCRATCH, 0, sizeof r);
    for (unsigned i = 0; i < 4000; i++) {
        if (rnd() % 5 < 3) {
            u8 v = (u8)rnd(), e = (u8)(rnd() % 9 == 0);
            hw_rx_put(&r, v, e);
            h8_run(&h, "_hw_rx_put", H8_SCRATCH, v, e, NULL, 0);
        } else {
            u8 got = hw_rx_get(&r, &byte);
            h.mem[H8_SCRATCH + 0x100] = 0;
            assert_int_equal((u8)h8_run(&h, "_hw_rx_get", H8_SCRATCH, H8_SCRATCH + 0x100, 0, NULL, 0), got);
            if (got)
                assert_int_equal(h.mem[H8_SCRATCH + 0x100], byte);
        }
        assert_memory_equal(h.mem + H8_SCRATCH, (const void *)&r, sizeof r);
    }
}

static void lcd_frame_as_compiled(void **state)
{
    u8 image[9], frame[HW_LCD_FRAME_MAX];
    (void)state;
    for (unsigned i = 0; i < 9; i++)
        h.mem[H8_SCRATCH + i] = image[i] = (u8)rnd();
    assert_int_equal((u8)h8_run(&h, "_hw_lcd_on_frame", H8_SCRATCH, H8_SCRATCH + 0x20, 0, NULL, 0),
                     hw_lcd_on_frame(image, frame));
    assert_memory_equal(h.mem + H8_SCRATCH + 0x20, frame, sizeof frame);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(arithmetic_helpers_as_linked, load),
        cmocka_unit_test_setup(battery_conversion_as_compiled, load),
        cmocka_unit_test_setup(tones_as_compiled, load),
        cmocka_unit_test_setup(ir_settings_as_compiled, load),
        cmocka_unit_test_setup(motor_patterns_as_compiled, load),
        cmocka_unit_test_setup(debounce_as_compiled, load),
        cmocka_unit_test_setup(receive_ring_as_compiled, load),
        cmocka_unit_test_setup(lcd_frame_as_compiled, load),
    };
    if (argc != 3) {
        fprintf(stderr, "usage: %s <firmware image> <h8300 nm>\n", argv[0]);
        return 2;
    }
    image_path = argv[1];
    nm_path = argv[2];
    return cmocka_run_group_tests(tests, NULL, NULL);
}
