/* SPDX-License-Identifier: MPL-2.0 */
/*
 * For tests: what the RCX glass should show, built from the segment map of rcx-hardware.md §3.6 restated here, so
 * that expected LCD images are written as the text a person would read ("-1.23", "----") and never taken from the
 * display engine. Included by tests/unit/test_display.c and tests/io/test_io.c.
 */
#ifndef TEST_LCD_TEXT_H
#define TEST_LCD_TEXT_H

#include <string.h>
#include "hal.h"

#define LCD_SEG(byte, bit) ((byte) * 8 + (bit))

/* Segments a, b, c, d, e, f, g of positions 0 (program number) and 1-4 (1 rightmost). */
static const int lcd_map[5][7] = {
    { LCD_SEG(1, 4), LCD_SEG(2, 5), LCD_SEG(2, 7), LCD_SEG(1, 7), LCD_SEG(4, 7), LCD_SEG(4, 5), LCD_SEG(1, 5) },
    { LCD_SEG(0, 4), LCD_SEG(4, 1), LCD_SEG(4, 3), LCD_SEG(0, 7), LCD_SEG(5, 7), LCD_SEG(5, 5), LCD_SEG(0, 5) },
    { LCD_SEG(1, 0), LCD_SEG(5, 1), LCD_SEG(5, 3), LCD_SEG(1, 3), LCD_SEG(6, 7), LCD_SEG(6, 5), LCD_SEG(1, 1) },
    { LCD_SEG(3, 0), LCD_SEG(8, 1), LCD_SEG(8, 3), LCD_SEG(3, 3), LCD_SEG(8, 7), LCD_SEG(8, 5), LCD_SEG(3, 1) },
    { LCD_SEG(3, 4), LCD_SEG(7, 1), LCD_SEG(7, 3), LCD_SEG(3, 7), LCD_SEG(7, 7), LCD_SEG(7, 5), LCD_SEG(3, 5) },
};
static const int lcd_point_right_of[5] = { -1, -1, LCD_SEG(5, 6), LCD_SEG(6, 6), LCD_SEG(8, 6) };
#define LCD_SIGN_5 LCD_SEG(7, 6) /* position 5 has only a middle segment: the minus of a four-digit number */

/* Indicators. */
static const int lcd_input_selected[3] = { LCD_SEG(6, 0), LCD_SEG(5, 4), LCD_SEG(4, 4) };
static const int lcd_input_active[3] = { LCD_SEG(6, 1), LCD_SEG(5, 0), LCD_SEG(2, 4) };
static const int lcd_output_selected[3] = { LCD_SEG(7, 2), LCD_SEG(0, 6), LCD_SEG(1, 6) };
static const int lcd_output_fwd[3] = { LCD_SEG(3, 2), LCD_SEG(4, 2), LCD_SEG(2, 6) };  /* right arrows */
static const int lcd_output_rev[3] = { LCD_SEG(3, 6), LCD_SEG(1, 2), LCD_SEG(4, 6) };  /* left arrows */

/* The usual seven-segment shapes, as segment letters. */
static const char *const lcd_shapes[10] = {
    "abcdef", "bc", "abdeg", "abcdg", "bcfg", "acdfg", "acdefg", "abc", "abcdefg", "abcdfg",
};

static inline void lcd_on(unsigned char *img, int seg)
{
    img[seg / 8] |= (unsigned char)(1u << (seg % 8));
}

static inline int lcd_lit(const unsigned char *img, int seg)
{
    return (img[seg / 8] >> (seg % 8)) & 1;
}

static inline void lcd_digit(unsigned char *img, int pos, int d)
{
    const char *s;
    for (s = lcd_shapes[d]; *s; s++)
        lcd_on(img, lcd_map[pos][*s - 'a']);
}

/* The number area as it should read `text`, right-aligned: digits, '-' (middle segment only), ' ' blank, '.' a
 * decimal point right of the digit before it; a fifth character can only be the lone minus. */
static inline void lcd_text(unsigned char *img, const char *text)
{
    int i = (int)strlen(text) - 1, pos = 1;
    memset(img, 0, HAL_LCD_BYTES);
    for (; i >= 0; i--) {
        char c = text[i];
        if (c == '.') {
            lcd_on(img, lcd_point_right_of[pos]);
            continue;
        }
        if (c == '-')
            lcd_on(img, pos == 5 ? LCD_SIGN_5 : lcd_map[pos][6]);
        else if (c != ' ')
            lcd_digit(img, pos, c - '0');
        pos++;
    }
}

/* Every segment of the number area. */
static inline void lcd_number_mask(unsigned char *mask)
{
    int pos, s;
    memset(mask, 0, HAL_LCD_BYTES);
    for (pos = 1; pos <= 4; pos++)
        for (s = 0; s < 7; s++)
            lcd_on(mask, lcd_map[pos][s]);
    lcd_on(mask, LCD_SEG(5, 6));
    lcd_on(mask, LCD_SEG(6, 6));
    lcd_on(mask, LCD_SEG(8, 6));
    lcd_on(mask, LCD_SIGN_5);
}

/* 0 when the number area of `img` reads `text`; otherwise the first differing byte + 1. */
static inline int lcd_reads(const unsigned char *img, const char *text)
{
    unsigned char want[HAL_LCD_BYTES], mask[HAL_LCD_BYTES];
    int i;
    lcd_text(want, text);
    lcd_number_mask(mask);
    for (i = 0; i < HAL_LCD_BYTES; i++)
        if ((img[i] & mask[i]) != want[i])
            return i + 1;
    return 0;
}

/* Figure: 1 standing (body 0.1 + one leg 0.2), 2 walking (arms 0.0, body 0.1, two legs 0.3), 0 anything else. */
static inline int lcd_figure(const unsigned char *img)
{
    int arms = lcd_lit(img, LCD_SEG(0, 0)), body = lcd_lit(img, LCD_SEG(0, 1));
    int leg = lcd_lit(img, LCD_SEG(0, 2)), legs = lcd_lit(img, LCD_SEG(0, 3));
    if (body && leg && !arms && !legs)
        return 1;
    if (body && arms && legs && !leg)
        return 2;
    return 0;
}

#endif
