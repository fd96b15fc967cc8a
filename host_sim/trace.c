/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The trace: one JSON object per line, {"t": simulated ms, "brick": n, ...}, in time order. A sound line is written
 * when the tone ends (its length is known only then): "ms" long, started at "from".
 */
#include <stdarg.h>
#include <string.h>
#include "sim.h"

static void vline(struct sim_brick *b, sim_us at, const char *fmt, va_list ap)
{
    FILE *f = b->sim->trace;
    if (!f)
        return;
    fprintf(f, "{\"t\":%llu,\"brick\":%d,", at / 1000, b->index);
    vfprintf(f, fmt, ap);
    fputs("}\n", f);
}

void trace_line(struct sim_brick *b, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vline(b, b->sim->room.now, fmt, ap);
    va_end(ap);
}

void trace_flush_sound(struct sim_brick *b)
{
    if (b->sound_hz)
        trace_line(b, "\"sound\":%u,\"ms\":%llu,\"from\":%llu", b->sound_hz,
                   (b->sim->room.now - b->sound_start) / 1000, b->sound_start / 1000);
    b->sound_hz = 0;
}

/* Segments a-g of each digit as byte << 3 | bit (rcx-hardware.md §3.6); digit 0 is the program number, 1-4 the
 * main number from the right. */
static const unsigned char digit_seg[5][7] = {
    { 1 << 3 | 4, 2 << 3 | 5, 2 << 3 | 7, 1 << 3 | 7, 4 << 3 | 7, 4 << 3 | 5, 1 << 3 | 5 },
    { 0 << 3 | 4, 4 << 3 | 1, 4 << 3 | 3, 0 << 3 | 7, 5 << 3 | 7, 5 << 3 | 5, 0 << 3 | 5 },
    { 1 << 3 | 0, 5 << 3 | 1, 5 << 3 | 3, 1 << 3 | 3, 6 << 3 | 7, 6 << 3 | 5, 1 << 3 | 1 },
    { 3 << 3 | 0, 8 << 3 | 1, 8 << 3 | 3, 3 << 3 | 3, 8 << 3 | 7, 8 << 3 | 5, 3 << 3 | 1 },
    { 3 << 3 | 4, 7 << 3 | 1, 7 << 3 | 3, 3 << 3 | 7, 7 << 3 | 7, 7 << 3 | 5, 3 << 3 | 5 },
};
/* Decimal point right of digits 2, 3, 4 (formats 000.0, 00.00, 0.000), and the sign's g segment. */
static const unsigned char point_seg[5] = { 0, 0, 5 << 3 | 6, 6 << 3 | 6, 8 << 3 | 6 };
#define SIGN_SEG (7 << 3 | 6)

static int seg(const unsigned char *image, unsigned s)
{
    return image[s >> 3] >> (s & 7) & 1;
}

/* Seven-segment shapes, bit 0 = a ... bit 6 = g; the alternatives are the 6, 7 and 9 with and without tails. */
static char digit_char(const unsigned char *image, unsigned d)
{
    static const struct { unsigned char pattern; char c; } font[] = {
        { 0x00, ' ' }, { 0x3F, '0' }, { 0x06, '1' }, { 0x5B, '2' }, { 0x4F, '3' }, { 0x66, '4' }, { 0x6D, '5' },
        { 0x7D, '6' }, { 0x7C, '6' }, { 0x07, '7' }, { 0x27, '7' }, { 0x7F, '8' }, { 0x6F, '9' }, { 0x67, '9' },
        { 0x40, '-' },
    };
    unsigned i, p = 0;
    for (i = 0; i < 7; i++)
        p |= (unsigned)seg(image, digit_seg[d][i]) << i;
    for (i = 0; i < sizeof font / sizeof font[0]; i++)
        if (font[i].pattern == p)
            return font[i].c;
    return '?';
}

void trace_lcd_number(const unsigned char *image, char *num, char *prog)
{
    unsigned d, n = 0;
    if (seg(image, SIGN_SEG))
        num[n++] = '-';
    for (d = 4; d >= 1; d--) {
        char c = digit_char(image, d);
        if (c != ' ')
            num[n++] = c;
        if (point_seg[d] && seg(image, point_seg[d]))
            num[n++] = '.';
    }
    num[n] = 0;
    prog[0] = digit_char(image, 0);
    prog[prog[0] != ' '] = 0;
}
