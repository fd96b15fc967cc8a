/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The firmware image's own code, run in the H8/300 simulator (h8sim.c) and compared with the same C compiled for
 * the host: the arithmetic helpers gcc calls (drivers/arith) and the drivers' logic (drivers/hw.c). This catches
 * what the host cannot: 16-bit int, the H8 compiler's code, the helpers as linked. It also checks the simulator,
 * which the firmware benchmark (tests/bench/firmware.sh) relies on.
 *
 * It also runs the image's start-up from its packed download, and its unpacker on streams of the host's packer.
 *
 * Usage: test_h8image <image (COFF; image.srec and image.bin beside it)> <h8300 nm>
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
#include "pack.h"

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

/* Random settings on both sides: the patterns (every latch byte of the 8 ms) must agree. The tick interrupt steps
 * through them (timer_interrupt_drives_motors_and_the_scan). */
static void motor_patterns_as_compiled(void **state)
{
    struct hw_motors m;
    (void)state;
    memset(&m, 0, sizeof m);
    memset(h.mem + H8_SCRATCH, 0, sizeof m);
    for (unsigned i = 0; i < 1000; i++) {
        u8 port = (u8)(rnd() % 4), mode = (u8)rnd(), level = (u8)(rnd() % 10);
        uint16_t stack[1] = { level };
        hw_motor_set(&m, port, mode, level);
        h8_run(&h, "_hw_motor_set", H8_SCRATCH, port, mode, stack, 1);
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
        u8 raw = (u8)(rnd() % 16 < 13 ? d.state ^ (i / 37 % 2 ? 0x05 : 0) : rnd() & 15), now = (u8)(i / 3 + i / 7);
        assert_int_equal((u8)h8_run(&h, "_hw_debounce", H8_SCRATCH, raw, now, NULL, 0), hw_debounce(&d, raw, now));
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

/* The memory functions of drivers/libc/string.s against the host's: every length up to 40 at every alignment of
 * both buffers, memmove in both directions of overlap. */
static void memory_functions_as_linked(void **state)
{
    uint8_t ref[0x100];
    const uint16_t base = H8_SCRATCH;
    (void)state;
    for (unsigned n = 0; n <= 40; n++)
        for (unsigned from = 0; from < 4; from++)
            for (unsigned to = 0; to < 48; to += (to < 8 ? 1 : 13)) {
                for (unsigned i = 0; i < sizeof ref; i++)
                    h.mem[base + i] = ref[i] = (uint8_t)rnd();
                /* memcpy: separate regions */
                assert_int_equal((u16)h8_run(&h, "_memcpy", base + 0x80 + to, base + from, n, NULL, 0),
                                 base + 0x80 + to);
                memcpy(ref + 0x80 + to, ref + from, n);
                assert_memory_equal(h.mem + base, ref, sizeof ref);
                /* memmove: overlapping, the destination above and below the source */
                assert_int_equal((u16)h8_run(&h, "_memmove", base + 0x10 + to, base + 0x10 + from, n, NULL, 0),
                                 base + 0x10 + to);
                memmove(ref + 0x10 + to, ref + 0x10 + from, n);
                assert_memory_equal(h.mem + base, ref, sizeof ref);
                assert_int_equal((u16)h8_run(&h, "_memmove", base + 0x10 + from, base + 0x10 + to, n, NULL, 0),
                                 base + 0x10 + from);
                memmove(ref + 0x10 + from, ref + 0x10 + to, n);
                assert_memory_equal(h.mem + base, ref, sizeof ref);
                /* memset, with a value whose high byte must not matter */
                assert_int_equal((u16)h8_run(&h, "_memset", base + 0x40 + to, 0x3300 | (from * 77), n, NULL, 0),
                                 base + 0x40 + to);
                memset(ref + 0x40 + to, (int)(from * 77) & 0xFF, n);
                assert_memory_equal(h.mem + base, ref, sizeof ref);
            }
}

/* Lengths past EEPMOV's 128-byte steps (string.s), from external RAM to external RAM, both directions of overlap. */
static void long_moves_as_linked(void **state)
{
    static const unsigned lengths[] = { 127, 128, 129, 255, 256, 257, 300, 1000 };
    static uint8_t ref[0x600];
    const uint16_t base = 0x9000;
    (void)state;
    for (unsigned i = 0; i < sizeof lengths / sizeof lengths[0]; i++)
        for (unsigned d = 1; d < 400; d += 133) {
            unsigned n = lengths[i];
            for (unsigned k = 0; k < sizeof ref; k++)
                h.mem[base + k] = ref[k] = (uint8_t)rnd();
            h8_run(&h, "_memmove", base + 8, base + 8 + d, n, NULL, 0);
            memmove(ref + 8, ref + 8 + d, n);
            assert_memory_equal(h.mem + base, ref, sizeof ref);
            h8_run(&h, "_memmove", base + 8 + d, base + 8, n, NULL, 0);
            memmove(ref + 8 + d, ref + 8, n);
            assert_memory_equal(h.mem + base, ref, sizeof ref);
            h8_run(&h, "_memcpy", base + 0x500 - n / 4, base + 8, n / 4, NULL, 0);
            memcpy(ref + 0x500 - n / 4, ref + 8, n / 4);
            assert_memory_equal(h.mem + base, ref, sizeof ref);
        }
}

/*
 * h8sim's EEPMOV as the H8/300 programming manual gives it: R4L bytes from @R5 up to @R6, R5 and R6 past them, R4L
 * 0, the flags kept, 8 + 4n states on-chip (source and destination accessed n + 1 times); external RAM 3 states a
 * byte. No byte moved for R4L = 0; R4H is not part of the count.
 */
static void eepmov_as_the_manual_says(void **state)
{
    static const uint8_t code[] = { 0x7B, 0x5C, 0x59, 0x8F };
    static const struct { uint16_t code, from, to; uint8_t n; unsigned states; } c[] = {
        { 0xFD80, 0xFE00, 0xFE80, 3, 8 + 4 * 3 },
        { 0xFD80, 0xFE00, 0xFE80, 0, 8 },
        { 0x9000, 0xA000, 0xA100, 100, 4 * 3 + 101 * 6 },
    };
    (void)state;
    for (unsigned i = 0; i < sizeof c / sizeof c[0]; i++) {
        struct h8 *m = calloc(1, sizeof *m);
        assert_non_null(m);
        h8_reset(m);
        memcpy(m->mem + c[i].code, code, sizeof code);
        for (unsigned k = 0; k < 128; k++)
            m->mem[c[i].from + k] = (uint8_t)(k * 7 + 1);
        m->pc = c[i].code;
        m->r[4] = (uint16_t)(0x3300 | c[i].n);
        m->r[5] = c[i].from;
        m->r[6] = c[i].to;
        m->ccr = 0x8F;
        m->states = 0;
        assert_int_equal(h8_step(m), 0);
        assert_int_equal(m->pc, c[i].code + 4);
        assert_int_equal(m->r[4], 0x3300);
        assert_int_equal(m->r[5], c[i].from + c[i].n);
        assert_int_equal(m->r[6], c[i].to + c[i].n);
        assert_int_equal(m->ccr, 0x8F);
        assert_memory_equal(m->mem + c[i].to, m->mem + c[i].from, c[i].n);
        assert_int_equal(m->mem[c[i].to + c[i].n], 0);
        assert_int_equal(m->states, c[i].states);
        free(m);
    }
}

static int sign(long v)
{
    return v < 0 ? -1 : v > 0;
}

static void memcmp_as_linked(void **state)
{
    const uint16_t a = H8_SCRATCH, b = H8_SCRATCH + 0x40;
    (void)state;
    for (unsigned i = 0; i < 3000; i++) {
        unsigned n = rnd() % 24, at = n ? rnd() % n : 0;
        for (unsigned j = 0; j < 24; j++)
            h.mem[a + j] = h.mem[b + j] = (uint8_t)rnd();
        if (i % 3)
            h.mem[b + at] = (uint8_t)(i % 2 ? rnd() : h.mem[a + at] ^ 0x80); /* often one differing byte */
        assert_int_equal(sign((s16)h8_run(&h, "_memcmp", a, b, n, NULL, 0)), sign(memcmp(h.mem + a, h.mem + b, n)));
    }
}

/* Hand-written helpers must keep r4-r6 and the stack pointer as gcc's callers expect. */
static void helpers_keep_the_callers_registers(void **state)
{
    static const char *const helper[] = { "___mulhi3", "___udivhi3", "___umodhi3", "___divhi3", "___modhi3",
                                          "_memcpy", "_memmove", "_memset", "_memcmp" };
    (void)state;
    for (unsigned i = 0; i < sizeof helper / sizeof helper[0]; i++)
        for (unsigned j = 0; j < 20; j++) {
            uint16_t sp = h.r[7];
            h.r[4] = 0x4444;
            h.r[5] = 0x5555;
            h.r[6] = 0x6666;
            if (helper[i][1] == 'm' && helper[i][2] == 'e')
                h8_run(&h, helper[i], H8_SCRATCH, H8_SCRATCH + 0x40, rnd() % 32, NULL, 0);
            else
                h8_run(&h, helper[i], operand(j), operand(j + 3), 0, NULL, 0);
            assert_int_equal(h.r[4], 0x4444);
            assert_int_equal(h.r[5], 0x5555);
            assert_int_equal(h.r[6], 0x6666);
            assert_int_equal(h.r[7], sp);
        }
}

/* ---- The drivers' interrupt handlers (drivers/h8300/main.c, sci.c), their registers as plain memory ---- */

#define SCI_SCR 0xFFDA
#define SCI_TDR 0xFFDB
#define SCI_SSR 0xFFDC
#define SCI_RDR 0xFFDD

static uint16_t var(const char *name)
{
    long a = h8_sym(name);
    if (a < 0)
        fail_msg("symbol %s not in the image", name);
    return (uint16_t)a;
}

static void sci_interrupt_receives_bytes_and_errors(void **state)
{
    static const struct { uint8_t ssr, rdr, error; } got[] = {
        { 0xC4, 0x5A, 0 }, /* TDRE, RDRF, TEND: a byte */
        { 0xE4, 0x11, 1 }, /* and overrun */
        { 0x94, 0x22, 1 }, /* framing error */
        { 0x4C, 0x33, 1 }, /* parity error */
        { 0x40, 0x44, 0 },
    };
    uint16_t rx = var("_drv_rx"); /* struct hw_rx: head, tail, data[32], error[32] */
    (void)state;
    h.mem[SCI_SCR] = 0x70; /* TE, RE, RIE */
    for (unsigned i = 0; i < sizeof got / sizeof got[0]; i++) {
        h.mem[SCI_SSR] = got[i].ssr;
        h.mem[SCI_RDR] = got[i].rdr;
        h8_run(&h, "_rcx_sci_isr", 0, 0, 0, NULL, 0);
        assert_int_equal(h.mem[rx], i + 1);
        assert_int_equal(h.mem[rx + 2 + i], got[i].rdr);
        assert_int_equal(h.mem[rx + 2 + HW_RX_SIZE + i] != 0, got[i].error);
        assert_int_equal(h.mem[SCI_SSR], got[i].ssr & 0x87); /* RDRF and the error flags cleared */
        assert_int_equal(h.mem[SCI_SCR], 0x70);
    }
}

static void sci_interrupt_transmits_then_waits_for_the_end(void **state)
{
    uint16_t buf = var("_tx_buf"), head = var("_tx_head"), tail = var("_tx_tail"), active = var("_tx_active");
    (void)state;
    h.mem[buf + 63] = 0xAB; /* two bytes queued across the end of the ring */
    h.mem[buf] = 0xCD;
    h.mem[tail] = 63;
    h.mem[head] = 65;
    h.mem[active] = 0;
    h.mem[SCI_SCR] = 0xF0; /* TIE, TE, RE, RIE */
    h.mem[SCI_SSR] = 0x84; /* TDRE, TEND */
    h8_run(&h, "_rcx_sci_isr", 0, 0, 0, NULL, 0);
    assert_int_equal(h.mem[SCI_TDR], 0xAB);
    assert_int_equal(h.mem[tail], 64);
    assert_int_equal(h.mem[active], 1);
    assert_int_equal(h.mem[SCI_SSR], 0x04); /* TDRE cleared */
    assert_int_equal(h.mem[SCI_SCR], 0xF0);
    h.mem[SCI_SSR] = 0x80;
    h8_run(&h, "_rcx_sci_isr", 0, 0, 0, NULL, 0);
    assert_int_equal(h.mem[SCI_TDR], 0xCD);
    assert_int_equal(h.mem[tail], 65);
    assert_int_equal(h.mem[SCI_SSR], 0x00);
    h.mem[SCI_SSR] = 0x80; /* all handed over: the end of transmission enabled instead */
    h8_run(&h, "_rcx_sci_isr", 0, 0, 0, NULL, 0);
    assert_int_equal(h.mem[SCI_TDR], 0xCD);
    assert_int_equal(h.mem[tail], 65);
    assert_int_equal(h.mem[SCI_SCR], 0x74);
    assert_int_equal(h.mem[SCI_SSR], 0x80);
    assert_int_equal(h.mem[active], 1);
    h.mem[SCI_SSR] = 0x84; /* the last byte has left */
    h8_run(&h, "_rcx_sci_isr", 0, 0, 0, NULL, 0);
    assert_int_equal(h.mem[SCI_SCR], 0x70);
    assert_int_equal(h.mem[active], 0);
}

#define FRT_TCSR 0xFF91
#define P6DR 0xFFBB
#define AD_ADCSR 0xFFE8

/* The A/D data registers ADDRA-ADDRD with results of a scan. */
static void scan_results(uint16_t base)
{
    for (unsigned i = 0; i < 4; i++)
        h8_write16(&h, (uint16_t)(0xFFE0 + 2 * i), (uint16_t)((base + 100 * i) << 6));
}

/* Slot n of the A/D ring holds the scan of scan_results(base) (the registers in their order). */
static void assert_slot(unsigned n, uint16_t base)
{
    uint16_t slot = (uint16_t)(var("_drv_ad_slot") + 8 * (n & 7)); /* DRV_AD_SLOTS */
    for (unsigned i = 0; i < 3; i++) /* the inputs: the main loop reads the battery's register itself */
        assert_int_equal(h8_read16(&h, (uint16_t)(slot + 2 * i)), (uint16_t)((base + 100 * i) << 6));
}

/* A stand-in for the converter in single mode: a conversion started (ADST without SCAN) is over when ADCSR is next
 * read, its channel's data register then holding raw10 0x100 + the channel; P6DR as it was then is noted. */
static uint8_t p6_at_conversion[8];
static unsigned conversions;
static uint8_t single_conversion(struct h8 *sim, uint16_t a, uint8_t held)
{
    if (a == AD_ADCSR && (held & 0x30) == 0x20) {
        unsigned ch = held & 7;
        p6_at_conversion[ch] = sim->mem[P6DR];
        conversions++;
        h8_write16(sim, (uint16_t)(0xFFE0 + 2 * (ch & 3)), (uint16_t)((0x100 + ch) << 6));
        held = sim->mem[a] = (uint8_t)((held | 0x80) & ~0x20); /* ADF; ADST cleared */
    }
    return held;
}

static void timer_interrupt_drives_motors_and_the_scan(void **state)
{
    uint16_t ticks = var("_drv_ms_ticks"), done = var("_drv_ad_done"), power = var("_drv_sensor_power");
    uint16_t level[1] = { 7 };
    unsigned step; /* what ad_done counts a stored scan as */
    (void)state;
    h8_run(&h, "_hw_motor_set", var("_drv_motors"), 0, HAL_MOTOR_FWD, level, 1); /* A forward, full power */

    /* Passive inputs: the tick reads the scan, which runs on (ADF, ADST, SCAN, AN0-AN3: a pass made). Port 6 is
     * left as it is: an input that no longer wants power lost it when it left the mask (hal_sensor_power, below). */
    scan_results(10);
    h.mem[FRT_TCSR] = 0x09; /* OCFA, CCLRA */
    h.mem[AD_ADCSR] = 0xB3;
    h.mem[P6DR] = 0x68;
    h8_run(&h, "_rcx_timer_irq", 0, 0, 0, NULL, 0);
    assert_int_equal(h.mem[FRT_TCSR], 0x01);
    assert_int_equal(h.mem[ticks], 1);
    assert_int_equal(h.mem[0xFF80], 0x80); /* the motor latch */
    assert_int_equal(h.mem[P6DR], 0x68);   /* no sensor power */
    step = h.mem[done];
    assert_true(step != 0);
    assert_slot(0, 10);
    assert_int_equal(h.mem[AD_ADCSR], 0xB3); /* left running */

    /* No pass made yet, or no scan running (start-up, wake-up): nothing stored, the scan started. */
    h.mem[FRT_TCSR] = 0x09;
    h.mem[AD_ADCSR] = 0x33;
    h8_run(&h, "_rcx_timer_irq", 0, 0, 0, NULL, 0);
    assert_int_equal(h.mem[ticks], 2);
    assert_int_equal(h.mem[done], step);
    assert_int_equal(h.mem[AD_ADCSR], 0x33);
    h.mem[FRT_TCSR] = 0x09;
    h.mem[AD_ADCSR] = 0x80; /* ADF left set by whoever stopped it */
    h8_run(&h, "_rcx_timer_irq", 0, 0, 0, NULL, 0);
    assert_int_equal(h.mem[done], step);
    assert_int_equal(h.mem[AD_ADCSR], 0x33);

    /* Active sensors on inputs 1 and 3 (P6.2, P6.0; AN2, AN0): the scan stopped, each input converted alone with
     * its own power (only its) off, and powered again; the slot takes their results and the scan's for input 2,
     * and the scan starts again. */
    h.io_read = single_conversion;
    conversions = 0;
    h.mem[power] = 0x05;
    h.mem[P6DR] = 0x6D;
    scan_results(20);
    h.mem[FRT_TCSR] = 0x09;
    h.mem[AD_ADCSR] = 0xB3;
    h8_run(&h, "_rcx_timer_irq", 0, 0, 0, NULL, 0);
    assert_int_equal(h.mem[ticks], 4);
    assert_int_equal(conversions, 2);
    assert_int_equal(p6_at_conversion[0], 0x6C);
    assert_int_equal(p6_at_conversion[2], 0x69);
    assert_int_equal(h.mem[P6DR], 0x6D);  /* powered again */
    assert_int_equal(h.mem[done], 2 * step);
    assert_int_equal(h8_read16(&h, (uint16_t)(var("_drv_ad_slot") + 8)), 0x100 << 6);
    assert_int_equal(h8_read16(&h, (uint16_t)(var("_drv_ad_slot") + 10)), 120 << 6);
    assert_int_equal(h8_read16(&h, (uint16_t)(var("_drv_ad_slot") + 12)), 0x102 << 6);
    assert_int_equal(h.mem[AD_ADCSR], 0x33);

    /* The same with no pass of the scan made: the passive input's result would be stale, nothing stored. */
    conversions = 0;
    h.mem[FRT_TCSR] = 0x09;
    h.mem[AD_ADCSR] = 0x33;
    h8_run(&h, "_rcx_timer_irq", 0, 0, 0, NULL, 0);
    h.io_read = NULL;
    assert_int_equal(conversions, 2);
    assert_int_equal(h.mem[P6DR], 0x6D);
    assert_int_equal(h.mem[done], 2 * step);
    assert_int_equal(h.mem[AD_ADCSR], 0x33);
}

/* An input that leaves the mask of powered inputs is unpowered at once, the others keep what they have; one that
 * joins it is powered by the tick interrupt after its next conversion. */
static void sensor_power_leaves_with_the_input(void **state)
{
    uint16_t power = var("_drv_sensor_power");
    (void)state;
    h.mem[power] = 0x05; /* inputs 1 and 3 (P6.2, P6.0) */
    h.mem[P6DR] = 0x6D;
    h8_run(&h, "_hal_sensor_power", 0, 0, 0, NULL, 0); /* input 1 passive */
    assert_int_equal(h.mem[power], 0x01);
    assert_int_equal(h.mem[P6DR], 0x69);
    h8_run(&h, "_hal_sensor_power", 0, 1, 1, NULL, 0); /* input 2 active */
    assert_int_equal(h.mem[power], 0x03);
    assert_int_equal(h.mem[P6DR], 0x69);
}

/* A scan equal to the one before is not stored while the main loop has fed every scan and the runtime says that
 * such a scan changes nothing (rcx.sensors_rest); any other is. */
/* A tick whose scan (passive inputs) has completed. */
static void tick_with_a_scan_done(void)
{
    h.mem[FRT_TCSR] = 0x09; /* OCFA, CCLRA */
    h.mem[AD_ADCSR] = 0xB3; /* ADF, ADST, SCAN, AN0-AN3 */
    h8_run(&h, "_rcx_timer_irq", 0, 0, 0, NULL, 0);
}

static void timer_interrupt_leaves_out_scans_at_rest(void **state)
{
    uint16_t done = var("_drv_ad_done"), seen = var("_drv_ad_seen"), rest = var("_drv_sensors_rest");
    unsigned step;
    (void)state;
    h.mem[var("_drv_sensor_power")] = 0;
    scan_results(10);
    tick_with_a_scan_done();
    step = h.mem[done];
    assert_true(step != 0);
    assert_slot(0, 10);
    /* Not fed yet, then not at rest: stored. */
    h.mem[rest] = 1;
    tick_with_a_scan_done();
    assert_int_equal(h.mem[done], 2 * step);
    h.mem[seen] = h.mem[done];
    h.mem[rest] = 0;
    tick_with_a_scan_done();
    assert_int_equal(h.mem[done], 3 * step);
    /* Fed, at rest, the same: left out, the scan left running. */
    h.mem[seen] = h.mem[done];
    h.mem[rest] = 1;
    tick_with_a_scan_done();
    assert_int_equal(h.mem[done], 3 * step);
    assert_int_equal(h.mem[AD_ADCSR], 0xB3);
    /* Any input different: stored. The battery's register alone: left out (the main loop reads it itself). */
    for (unsigned i = 0; i < 3; i++) {
        h8_write16(&h, (uint16_t)(0xFFE0 + 2 * i), (uint16_t)((11 + 100 * i) << 6));
        tick_with_a_scan_done();
        assert_int_equal(h.mem[done], (4 + i) * step);
        h.mem[seen] = h.mem[done];
    }
    h8_write16(&h, 0xFFE6, 1 << 6);
    tick_with_a_scan_done();
    assert_int_equal(h.mem[done], 6 * step);
}

/* The image as linked, from 0x8000 to its end (openrcx.bin, objcopy's copy of the COFF image): what must run. */
static size_t image_bytes(uint8_t *out, size_t max)
{
    char path[512];
    size_t n;
    FILE *f;
    snprintf(path, sizeof path, "%s.bin", image_path);
    f = fopen(path, "rb");
    assert_non_null(f);
    n = fread(out, 1, max, f);
    fclose(f);
    return n;
}

/* The start-up code, run from the entry on the bytes as the ROM loads them (openrcx.srec: the head, the unpacker and
 * the rest packed): every byte of the image must be unpacked to its run address, section .high, unpacked last, then
 * copied to F000 where it runs (the loader puts nothing there), the motor latch zeroed after that copy (on the brick
 * every write to F000-FB7F reaches it), and .bss, which starts where .high was unpacked, cleared. */
/* The motor latch during start-up: how long it held something other than 0 (the copy to F000 writes it too). */
static uint8_t latch_now;
static unsigned long long latch_since, latch_driven, latch_longest;
static void latch_seen(struct h8 *hh, uint8_t v)
{
    if (latch_now) {
        unsigned long long held = hh->states - latch_since;
        latch_driven += held;
        if (held > latch_longest)
            latch_longest = held;
    }
    latch_now = v;
    latch_since = hh->states;
}

static void startup_unpacks_the_image_and_copies_code_to_f000(void **state)
{
    static uint8_t image[0x8000];
    long start, end, load, bss, bss_end, image_end, head_end, i;
    (void)state;
    assert_int_equal(h8_image_read(&h, image_path, nm_path), 0);
    start = h8_sym("_rcx_high_start");
    end = h8_sym("_rcx_high_end");
    load = h8_sym("_rcx_high_load");
    bss = h8_sym("_rcx_bss_start");
    bss_end = h8_sym("_rcx_bss_end");
    image_end = h8_sym("_rcx_image_end");
    head_end = h8_sym("_rcx_head_end");
    assert_true(start == 0xF000 && end <= 0xFB80 && load >= 0x8000 && bss_end > bss);
    assert_true(end - start >= 1024); /* a real part of the code runs there */
    assert_int_equal(load + (end - start), image_end);
    assert_int_equal(bss, load);
    assert_true(h8_func_at((uint16_t)start)[0] != '?'); /* code, with its symbols */
    assert_int_equal(image_bytes(image, sizeof image), image_end - 0x8000);

    /* The download: the entry and the knock string as they run, then other bytes (the unpacker, the packed rest),
     * fewer than the image has; nothing at F000. */
    assert_memory_equal(h.mem + 0x8000, image, (size_t)(head_end - 0x8000));
    for (i = image_end - 64; i < image_end; i++)
        assert_int_equal(h.mem[i], 0);
    assert_true(memcmp(h.mem + head_end, image + (head_end - 0x8000), 64) != 0);
    for (i = start; i < end; i++)
        assert_int_equal(h.mem[i], 0);

    h.mem[0xFF80] = 0xC3;                                       /* what the copy left in the latch */
    memset(h.mem + 0xC000, 0xA5, 0x3000);                       /* RAM past the largest download holds garbage */
    latch_now = 0;
    latch_driven = latch_longest = 0;
    h.latch_write = latch_seen;
    assert_int_equal(h8_image_start(&h), 0);
    h.latch_write = NULL;
    /* The copy to F000 drives the motors with whatever it writes: each pattern must be gone at once (well under
     * 1 µs, 16 states), not left for the whole copy (some 2 ms). */
    assert_int_equal(latch_now, 0);
    if (latch_longest > 16)
        fail_msg("the motor latch held a stray pattern for %llu states (%llu in all)", latch_longest, latch_driven);
    /* Every run address holds the image's byte: code and data from 0x8000, section .high at F000. */
    assert_memory_equal(h.mem + 0x8000, image, (size_t)(load - 0x8000));
    assert_memory_equal(h.mem + start, image + (load - 0x8000), (size_t)(end - start));
    assert_int_equal(h.mem[0xFF80], 0);
    for (i = bss; i < bss_end; i++)
        assert_int_equal(h.mem[i], 0);
    assert_int_equal(h.pc, h8_sym("_main"));
    assert_true(h8_unpack_states > 0);
    printf("start-up: unpacking %ld bytes took %llu states (%.1f ms at 16 MHz), main reached after %llu states\n",
           image_end - head_end, h8_unpack_states, h8_unpack_states / 16000.0, h.states);
    /* Functions there then run from F000 (h8bench, tests/bench/firmware.sh, calls rt_init and vm_direct there). */
}

/* The unpacker's loop (unpack.s, _rcx_unpack) on its own, in its place on-chip, on streams of the host's packer:
 * bytes with no repeats, long runs, the longest matches, far offsets. */
static void unpack_on_the_h8(const uint8_t *data, size_t n)
{
    static uint8_t packed[PACK_BOUND(0x3000)];
    const uint16_t from = 0xC000, to = 0x8100;
    long unpacker = h8_sym("_rcx_unpacker"), size = h8_sym("_rcx_unpacker_size"), loop = h8_sym("_rcx_unpack");
    long head_end = h8_sym("_rcx_head_end");
    size_t len = pack(data, n, packed), steps;

    assert_true(n > 0 && n <= 0x3000 && len <= 0x2F00);
    memcpy(h.mem + unpacker, h.mem + head_end, (size_t)size); /* the unpacker copies itself there */
    memcpy(h.mem + from, packed, len);
    memset(h.mem + to, 0xA5, n + 16);
    h.r[5] = from;
    h.r[6] = to;
    h.r[1] = (uint16_t)(to + n);
    h.r[3] = 0x80;
    h.r[7] = 0xFD90;
    h.pc = (uint16_t)loop;
    for (steps = 0; h.pc != (uint16_t)head_end; steps++) {
        assert_true(steps < 2000000 && h.pc >= unpacker && h.pc < unpacker + size);
        assert_int_equal(h8_step(&h), 0);
    }
    assert_memory_equal(h.mem + to, data, n);
    assert_int_equal(h.mem[to + n], 0xA5);
    assert_int_equal(h.r[5], from + len);
}

static void unpacker_loop_on_edge_cases(void **state)
{
    static uint8_t data[0x3000];
    size_t i;
    (void)state;
    assert_int_equal(h8_image_read(&h, image_path, nm_path), 0);
    data[0] = 0x5A;
    unpack_on_the_h8(data, 1);
    for (i = 0; i < 0x2000; i++)
        data[i] = (uint8_t)(rnd() >> 3);
    unpack_on_the_h8(data, 0x2000); /* no repeats worth a match: literals (9 bits a byte) */
    memset(data, 0, sizeof data);
    unpack_on_the_h8(data, sizeof data); /* one run: matches of 256 bytes at offset 1 */
    for (i = 0; i < sizeof data; i++)
        data[i] = i < 300 ? (uint8_t)rnd() : i < 0x2E00 ? (uint8_t)(i * 7) : data[i - 0x2D00];
    unpack_on_the_h8(data, sizeof data); /* offsets of more than 256 and of 11 KB */
}

/*
 * Issue 9: the hand-back to the ROM (GoIntoBootMode) leaves every register the drivers set as a reset leaves it,
 * since a jump to the reset vector is no reset. Values after reset from the H8/3297-series hardware manual (bits
 * that read as 1 included); TMR0's counter is left non-zero, the ROM's sign to come up awake (rcx-hardware.md 2.4),
 * and the ROM's shadows of the port directions at FD80 (rcx-hardware.md 1.2) agree with the ports again.
 */
static const struct { uint16_t addr; uint8_t value; const char *name; } after_reset[] = {
    { 0xFF90, 0x01, "FRT TIER" }, { 0xFF91, 0x00, "FRT TCSR" }, { 0xFF92, 0x00, "FRC high" },
    { 0xFF93, 0x00, "FRC low" }, { 0xFF94, 0xFF, "OCRA high" }, { 0xFF95, 0xFF, "OCRA low" },
    { 0xFF96, 0x00, "FRT TCR" }, { 0xFF97, 0xE0, "FRT TOCR" },
    { 0xFFB5, 0x00, "P4DDR" }, { 0xFFB7, 0x00, "P4DR" }, { 0xFFB8, 0xFC, "P5DDR (P5.2 stays an output)" }, { 0xFFB9, 0x00, "P6DDR" },
    { 0xFFBA, 0xF8, "P5DR" }, { 0xFFBB, 0x00, "P6DR" },
    { 0xFFC3, 0xF8, "STCR" }, { 0xFFC4, 0x0B, "SYSCR" }, { 0xFFC6, 0xF8, "ISCR" }, { 0xFFC7, 0xF8, "IER" },
    { 0xFFC8, 0x00, "TMR0 TCR" }, { 0xFFC9, 0x10, "TMR0 TCSR" }, { 0xFFCA, 0xFF, "TMR0 TCORA" },
    { 0xFFCB, 0xFF, "TMR0 TCORB" },
    { 0xFFD0, 0x00, "TMR1 TCR" }, { 0xFFD1, 0x10, "TMR1 TCSR" }, { 0xFFD2, 0xFF, "TMR1 TCORA" },
    { 0xFFD3, 0xFF, "TMR1 TCORB" }, { 0xFFD4, 0x00, "TMR1 TCNT" },
    { 0xFFD8, 0x00, "SCI SMR" }, { 0xFFD9, 0xFF, "SCI BRR" }, { 0xFFDA, 0x00, "SCI SCR" }, { 0xFFDB, 0xFF, "SCI TDR" },
    { 0xFFDC, 0x84, "SCI SSR" },
    { 0xFFE8, 0x00, "ADCSR" }, { 0xFFE9, 0x7F, "ADCR" },
    { 0xFF80, 0x00, "motor latch" },
    { 0xFD80, 0xFF, "P1DDR shadow" }, { 0xFD81, 0xFF, "P2DDR shadow" }, { 0xFD82, 0x00, "P3DDR shadow" },
    { 0xFD83, 0x00, "P4DDR shadow" }, { 0xFD84, 0x04, "P5DDR shadow" }, { 0xFD85, 0x00, "P6DDR shadow" },
    { 0xFD86, 0x00, "P7 shadow" },
};
#define RESET_VECTOR_TARGET 0x03AE /* what the ROM's vector at 0000 holds */

/* Registers filled at random, except P5.2, the external RAM's power-save line: an output at 0 while the brick runs
 * (the simulator stops on any external-RAM access otherwise). */
static void fill_registers(uint8_t fill, uint8_t step)
{
    for (unsigned i = 0; i < 128; i++)
        h.mem[0xFF80 + i] = (uint8_t)(fill ^ (step * i));
    h.mem[0xFFB8] |= 0x04;
    h.mem[0xFFBA] &= (uint8_t)~0x04;
}

static int reset_value_of(uint16_t a, uint8_t *v)
{
    for (unsigned i = 0; i < sizeof after_reset / sizeof after_reset[0]; i++)
        if (after_reset[i].addr == a) {
            *v = after_reset[i].value;
            return 1;
        }
    return 0;
}

/* The registers (FF80-FFFF) the drivers' set-up writes, found by running it over two different fillings. */
static void registers_the_drivers_write(uint8_t written[128])
{
    static const uint8_t fill[2] = { 0x5A, 0xA5 };
    memset(written, 0, 128);
    for (unsigned f = 0; f < 2; f++) {
        assert_int_equal(h8_image_load(&h, image_path, nm_path), 0);
        fill_registers(fill[f], 0);
        h8_run(&h, "_drv_outputs_on", 0, 0, 0, NULL, 0);
        h8_run(&h, "_drv_tick_start", 1, 0, 0, NULL, 0);
        h8_run(&h, "_sci_start", HAL_IR_4800 | HAL_IR_76KHZ | HAL_IR_DUTY25, 0, 0, NULL, 0);
        h8_run(&h, "_hal_sound", 0, 440, 0, NULL, 0);
        h8_run(&h, "_hal_ir_range", 0, 1, 0, NULL, 0);
        h8_run(&h, "_hal_sensor_power", 0, 1, 1, NULL, 0);
        for (unsigned i = 0; i < 128; i++)
            written[i] |= h.mem[0xFF80 + i] != fill[f];
    }
}

static void hand_back_leaves_registers_as_after_reset(void **state)
{
    uint8_t written[128], v;
    long rc;
    (void)state;
    registers_the_drivers_write(written);
    /* The brick as it runs: the drivers' settings, flags standing, the standby code at FD80. */
    assert_int_equal(h8_image_load(&h, image_path, nm_path), 0);
    fill_registers(0x5A, 1);
    memset(h.mem + 0xFD80, 0x6D, 16);
    h.mem[0] = RESET_VECTOR_TARGET >> 8;
    h.mem[1] = RESET_VECTOR_TARGET & 0xFF;
    rc = h8_call(&h, (uint16_t)h8_sym("_hal_enter_rom"), 0, 0, 0, NULL, 0, 100000);
    assert_int_equal(rc, -1);
    assert_string_equal(h.error, "jump into the ROM (03AE)");
    assert_true(h.ccr & 0x80); /* interrupts masked */
    for (unsigned i = 0; i < sizeof after_reset / sizeof after_reset[0]; i++) {
        if (h.mem[after_reset[i].addr] != after_reset[i].value)
            fail_msg("%s (%04X) is %02X after the hand-back, %02X after a reset", after_reset[i].name,
                     after_reset[i].addr, h.mem[after_reset[i].addr], after_reset[i].value);
    }
    assert_int_not_equal(h.mem[0xFFCC], 0); /* TMR0 TCNT: come up awake */
    for (unsigned i = 0; i < 128; i++) {
        uint16_t a = (uint16_t)(0xFF80 + i);
        if (written[i] && a != 0xFFCC && !reset_value_of(a, &v))
            fail_msg("the drivers write %04X, which the hand-back does not restore", a);
        if (!written[i] && !reset_value_of(a, &v) && a != 0xFFCC && h.mem[a] != (uint8_t)(0x5A ^ i))
            fail_msg("the hand-back wrote %04X, which the drivers never touch", a);
    }
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(startup_unpacks_the_image_and_copies_code_to_f000),
        cmocka_unit_test(unpacker_loop_on_edge_cases),
        cmocka_unit_test_setup(arithmetic_helpers_as_linked, load),
        cmocka_unit_test_setup(battery_conversion_as_compiled, load),
        cmocka_unit_test_setup(tones_as_compiled, load),
        cmocka_unit_test_setup(ir_settings_as_compiled, load),
        cmocka_unit_test_setup(motor_patterns_as_compiled, load),
        cmocka_unit_test_setup(debounce_as_compiled, load),
        cmocka_unit_test_setup(receive_ring_as_compiled, load),
        cmocka_unit_test_setup(lcd_frame_as_compiled, load),
        cmocka_unit_test_setup(memory_functions_as_linked, load),
        cmocka_unit_test_setup(long_moves_as_linked, load),
        cmocka_unit_test(eepmov_as_the_manual_says),
        cmocka_unit_test_setup(memcmp_as_linked, load),
        cmocka_unit_test_setup(helpers_keep_the_callers_registers, load),
        cmocka_unit_test_setup(sci_interrupt_receives_bytes_and_errors, load),
        cmocka_unit_test_setup(sci_interrupt_transmits_then_waits_for_the_end, load),
        cmocka_unit_test_setup(timer_interrupt_drives_motors_and_the_scan, load),
        cmocka_unit_test_setup(sensor_power_leaves_with_the_input, load),
        cmocka_unit_test_setup(timer_interrupt_leaves_out_scans_at_rest, load),
        cmocka_unit_test(hand_back_leaves_registers_as_after_reset),
    };
    if (h8_image_args(argc, argv, &image_path, &nm_path))
        return 2;
    return cmocka_run_group_tests(tests, NULL, NULL);
}
