/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Outputs (spec pp. 6, 8, 27, 38, 42-43, 64, 72, 98-99; sources 3 and 17): the motor registers the byte codes set,
 * and the effective output handed to hal_motor().
 */
#ifndef RCX_OUTPUTS_H
#define RCX_OUTPUTS_H

#include "rcx_types.h"

struct rcx;

/* Motor register bits: source 3 (per motor) and source 17 (global), spec pp. 6 and 8. */
#define RCX_MOTOR_POWER 0x07
#define RCX_MOTOR_FWD 0x08
#define RCX_MOTOR_BRAKE 0x40
#define RCX_MOTOR_ON 0x80

/* A motor driven in one direction is held braked this long before it is driven the other way (spec p. 99). */
#define OUTPUTS_REVERSE_PAUSE_MS 60

struct rcx_outputs {
    u8 motor[3];   /* on/off, brake/float, direction, power as set by the program */
    u8 global[3];  /* connected (off: brake or float), direction normal, max power */
    u8 applied[3]; /* what hal_motor() was last told, as a status byte: on, forward, power; or off: brake or 0 */
    u8 pause[3];   /* milliseconds left of a reversing pause */
};
#define outputs_applied(b, i) ((b)->out.applied[i]) /* the state now on the wire, as rcx_outputs.applied */

void outputs_init(struct rcx *b);          /* power-on and switching off: connected; forward, brake, full power */
void outputs_changed(struct rcx *b);       /* registers were written: recompute and apply */
void outputs_tick(struct rcx *b);          /* every 1 ms */
u8 outputs_status(const struct rcx *b, u8 motor);  /* source 3 */
/* Source 17: firm0328 always sets bits 4-5 (reference-firmware.md); bit 6 is not part of this layout. A macro: shorter
 * than a call. */
#define outputs_global_status(b, motor) ((u8)(((b)->out.global[motor] & 0x8F) | 0x30))

/* Registers of the motors in `list` (bit 0 A, 1 B, 2 C; with OUTPUTS_GLOBAL the global ones): the bits of
 * OUTPUTS_CHANGE's `clear` cleared, then those of its `flip` flipped; then the result is applied. */
#define OUTPUTS_GLOBAL 0x08
#define OUTPUTS_CHANGE(clear, flip) ((u16)((clear) << 8 | (flip)))
void outputs_update(struct rcx *b, u8 list, u16 change);

/* The motor scheme of spec p. 98, for the user interface and the remote control. */
void outputs_program_start(struct rcx *b); /* Run pressed: forward, brake, max power */
void outputs_program_stop(struct rcx *b);  /* Run pressed again, or program changed: brake */
void outputs_remote(struct rcx *b, u8 fwd_mask, u8 rev_mask); /* remote motor buttons held (0, 0 = released) */
void outputs_revoked(struct rcx *b, u8 resources); /* access lost: affected motors brake (0x01 A, 0x02 B, 0x08 C) */

#endif
