/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The LCD (spec pp. 51, 66, 97; source 14; rcx-hardware.md §3.6): views, indicators and marks composed into the
 * 9-byte segment image and handed to hal_lcd() when it changes.
 *
 * What the glass shows (reference-firmware.md, "The brick's face"): the program slot + 1 in the small digit; the
 * figure standing, or walking (alternating with standing every 260 ms) while any task runs or waits; a mark over
 * each input that reads pressed (its boolean, whatever its type); the arrow of each motor being driven (right =
 * forward); the "selected" mark of the viewed input or output; the IR mark for a moment around every IR exchange;
 * and the view's number in the four digits: the watch as hh.mm with both leading zeros (the glass has no colon, so
 * the decimal point of "00.00" separates hours from minutes, and blinks like a clock's), an input's value
 * (temperatures in tenths, with one decimal), an output's power + 1 while it runs and 0 while it does not, or the
 * user's source with 0-3 decimals. Other numbers drop their leading zeros; a minus sign sits left of the first
 * digit; magnitudes above 9999 show as "----".
 */
#ifndef RCX_DISPLAY_H
#define RCX_DISPLAY_H

#include "rcx_types.h"

struct rcx;

#define DISPLAY_BYTES 9
#define DISPLAY_REFRESH_MS 20  /* the image is recomposed this often (every other 10 ms step, vm_tick) and sent only
                                  when it differs: enough for the eye, and half of what the display costs an idle
                                  brick at every step */
#define DISPLAY_FRAME_STEPS 13 /* refreshes per frame of the walking figure: 260 ms; the watch's point is lit for
                                  three frames and dark for three (0.78 s each) */
#define DISPLAY_IR_STEPS 25    /* refreshes the IR mark stays lit after IR activity: 0.5 s */
#define DISPLAY_MAX 9999       /* larger magnitudes show as "----" */

/* Views (SelectDisplay, spec p. 66). */
enum display_view { DISPLAY_WATCH = 0, DISPLAY_INPUT_1, DISPLAY_INPUT_2, DISPLAY_INPUT_3,
                    DISPLAY_OUTPUT_A, DISPLAY_OUTPUT_B, DISPLAY_OUTPUT_C, DISPLAY_USER };

/* A segment: bit `bit` of image byte `byte` (rcx-hardware.md §3.6). */
#define DISPLAY_SEG(byte, bit) ((u8)((byte) << 3 | (bit)))

/* Marks the runtime switches with display_mark(). IR range: low arc alone = short, both arcs = long. */
#define DISPLAY_MARK_BATTERY DISPLAY_SEG(4, 0)  /* battery low "X" */
#define DISPLAY_MARK_IR_LOW DISPLAY_SEG(6, 2)
#define DISPLAY_MARK_IR_HIGH DISPLAY_SEG(6, 3)
#define DISPLAY_MARK_LOG_Q0 DISPLAY_SEG(2, 0)   /* datalog circle quarters, anticlockwise from top right */
#define DISPLAY_MARK_LOG_Q1 DISPLAY_SEG(2, 1)
#define DISPLAY_MARK_LOG_Q2 DISPLAY_SEG(2, 3)
#define DISPLAY_MARK_LOG_Q3 DISPLAY_SEG(2, 2)
#define DISPLAY_MARK_DOT0 DISPLAY_SEG(6, 4)     /* progress dots, dot 0 rightmost per §3.6 (brickEmu draws the reverse) */
#define DISPLAY_MARK_DOT1 DISPLAY_SEG(8, 0)
#define DISPLAY_MARK_DOT2 DISPLAY_SEG(8, 4)
#define DISPLAY_MARK_DOT3 DISPLAY_SEG(7, 0)
#define DISPLAY_MARK_DOT4 DISPLAY_SEG(7, 4)

struct rcx_display {
    u8 view;             /* enum display_view */
    u8 user_precision;   /* ViewSourceValue: decimal places 0-3 */
    u8 user_source;
    u8 digits_places1;   /* decimal places + 1 of the number digits[] shows (0 at power-on: nothing worked out yet) */
    u16 user_index;
    u8 phase;            /* refreshes into a cycle of six frames: the figure walks in the odd ones, the watch's
                            point is lit in the first three */
    u8 ir;               /* refreshes the IR mark stays lit; display_ir_activity() */
    u8 marks[DISPLAY_BYTES]; /* segments switched on by display_mark() */
    u8 shown[DISPLAY_BYTES]; /* the image hal_lcd() last received */
    u8 digits[DISPLAY_BYTES]; /* the segments of the view's number (vm/display.c), worked out from: */
    s16 digits_v;        /* the number (and digits_places1 above) */
};

/* SelectDisplay, View button, SetWatch (a view above DISPLAY_USER changes nothing). A macro: shorter than a call. */
#define display_view(b, v) do { u8 view_ = (v); if (view_ <= DISPLAY_USER) (b)->display.view = view_; } while (0)
/* ViewSourceValue: the user view of a source (precision above 3 changes nothing); nqc's SetUserDisplay sends only
 * this command, so it selects the user view as well. A macro, for its one caller: shorter than a call. */
#define display_user(b, precision, src, index) do { \
        u8 precision_ = (precision); \
        if (precision_ <= 3) { \
            (b)->display.user_precision = precision_; \
            (b)->display.user_source = (src); \
            (b)->display.user_index = (index); \
            (b)->display.view = DISPLAY_USER; \
        } \
    } while (0)
/* A DISPLAY_MARK_* (any segment; others change nothing) on or off. A macro: with the constant segment of a mark it
 * is a bit set or cleared. */
#define display_mark(b, seg, on) do { \
        u8 seg_ = (seg), mask_ = (u8)(1u << (seg_ & 7)); \
        if (seg_ < DISPLAY_BYTES * 8) { \
            if (on) \
                (b)->display.marks[seg_ >> 3] |= mask_; \
            else \
                (b)->display.marks[seg_ >> 3] &= (u8)~mask_; \
        } \
    } while (0)
void display_tick(struct rcx *b);                                   /* every 20 ms (vm_tick) */
/* The IR layer calls this for every packet received and every transmission it starts, so a user sees the brick
 * talking. A field store, not a call: it is made in the IR layer's busiest paths. */
#define display_ir_activity(b) ((b)->display.ir = DISPLAY_IR_STEPS)
u8 program_running(const struct rcx *b);                            /* nonzero: a task runs or waits */

#endif
