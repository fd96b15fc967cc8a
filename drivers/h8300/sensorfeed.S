/* SPDX-License-Identifier: MPL-2.0 */
; The brick's sensor_feed() (vm/sensors.c, whose C is the reference and runs on the host): one sample of an input
; worked out, as the C does it, in about half the states of gcc 3.4's code and in fewer bytes. A moving light sensor in
; percent mode and a turning rotation sensor in angle mode are the samples the brick works out every millisecond
; (issue 21); their paths here read each field once, with the percentage a division by 156 (divxu) instead of the C's
; multiplies, and the boolean and the mode with a few compares. The temperature modes call the C
; sensor_temperature(). tests/drivers/test_h8feed.c runs this against the C on random inputs. Before it, sensor_scan():
; each input fed by falling into it.
;
; void sensor_feed(struct rcx *b, struct rcx_sensor *s, u16 raw)
;
; Registers: r1 = s throughout; r2 = raw (10 bits once past the steady check); r0h = the mode and r0l = the new
; boolean from the boolean's part on; r4 = the value from the mode's part on; r3 scratch; b on the stack (2(r7),
; under r4).
; Booleans are 0 or 1, and raw and past[] 10-bit values, as the C keeps them. Calls to C are jsr written as data:
; ld --relax then rewrites no instruction here (see unpack.s); r4 survives them (gcc keeps r4-r6).

#include "sensorfeed.h"

	.section .text
	.global	_sensor_scan
	.global	_sensor_feed

; void sensor_scan(struct rcx *b, const u16 *raw): the three inputs fed (vm/sensors.c), then sensors_at_rest() in it.
; Registers: r4 = the input; r5 = b; r6 = raw (r4-r6 saved: gcc keeps them, and sensor_feed() too).
; sensors_at_rest() is only called from here on the brick: rest = every input steady. An input's quiet is
; SENSOR_MOVING (0) or SENSOR_STEADY | raw, so steady is bit 15: the high bytes' AND, bit 7.
_sensor_scan:
	mov.w	r4,@-r7
	mov.w	r5,@-r7
	mov.w	r6,@-r7
	mov.w	r0,r5
	mov.w	r1,r6
	mov.w	#SF_SENSOR,r4
	add.w	r0,r4			; b->sensor
	bsr	feed
	bsr	feed
	bsr	feed
	mov.b	@(SF_SENSOR+SF_QUIET,r5),r0l ; high bytes: SENSOR_STEADY in bit 7
	mov.b	@(SF_SENSOR+SF_SIZE+SF_QUIET,r5),r1l
	and.b	r1l,r0l
	mov.b	@(SF_SENSOR+2*SF_SIZE+SF_QUIET,r5),r1l
	and.b	r1l,r0l
	rotl	r0l
	and.b	#1,r0l
	mov.b	r0l,@(SF_REST,r5)	; sensors_rest: 1 when all three are steady
	mov.w	@r7+,r6
	mov.w	@r7+,r5
	mov.w	@r7+,r4
	rts

feed:	mov.w	r5,r0			; sensor_feed(b, input, *raw++), then the next input
	mov.w	r4,r1
	mov.w	@r6+,r2
	add.b	#SF_SIZE,r4l
	addx	#0,r4h
					; on into sensor_feed: its rts returns to the bsr

_sensor_feed:
	bset	#7,r2h			; raw | SENSOR_STEADY
	mov.w	@r1,r3
	cmp.w	r3,r2
	bne	1f
	rts				; steady: nothing can change

	; The boolean's less common cases (out of the way: raw above 562, mostly, falls through to bdone).
notoff:	mov.w	#460,r3			; BOOL_ON_BELOW
	cmp.w	r3,r2
	bcc	keep
on:	mov.b	#1,r0l
	bra	bdone
dyn:	sub.b	r3h,r3h			; r3 = slope
	sub.w	r2,r4			; then - raw
	add.w	r3,r2
	mov.b	r2h,r0l
	sub.w	r3,r2
	cmp.b	#4,r0l
	bcc	off			; raw > 1023 - slope
	add.w	r3,r4
	blt	off			; raw - then > slope
	cmp.w	r3,r2
	bcs	on			; raw < slope
	sub.w	r3,r4
	sub.w	r3,r4
	bgt	on			; then - raw > slope
keep:	mov.b	@(SF_BOOLEAN,r1),r0l
	bra	bdone

1:	mov.w	r0,@-r7			; b
	mov.w	r4,@-r7
	mov.w	r2,@r1			; quiet = raw | SENSOR_STEADY, SENSOR_MOVING below unless raw = last = past[1]
	and.b	#3,r2h			; raw, 10 bits
	adds	#2,r1
	adds	#2,r1			; at raw (SF_RAW), then past[0], past[1]
	mov.w	@r1+,r3			; last ...
	mov.w	@r1+,r4			; then: past[0]
	mov.w	@r1+,r0			; past[1] ...
	mov.w	r3,@-r1			; ... last is past[1] ...
	mov.w	r0,@-r1			; ... and past[1] past[0]
	mov.w	r2,@-r1
	subs	#2,r1
	subs	#2,r1			; s again
	cmp.w	r2,r3
	bne	2f
	cmp.w	r2,r0
	beq	3f
2:	sub.w	r0,r0
	mov.w	r0,@r1			; quiet = SENSOR_MOVING

	; The boolean (boolean_of()) into r0l: absolute with slope 0, else from the change since then (r4).
3:	mov.b	@(SF_MODE,r1),r0h	; the mode, kept in r0h
	mov.b	r0h,r3l
	and.b	#0x1F,r3l		; slope
	bne	dyn
	mov.w	#562,r3			; BOOL_OFF_ABOVE (a moving light sensor is mostly above)
	cmp.w	r3,r2
	bls	notoff			; at most 562: on, or as it was
off:	sub.b	r0l,r0l

	; The value, in r4, by mode (slope left out): percent and angle first, then the lower modes.
bdone:	mov.b	r0h,r3l
	and.b	#0xE0,r3l
	bpl	low
	cmp.b	#0x80,r3l
	bne	nperc
	mov.w	r2,r3			; percent: (1023 - raw) * 25 / 156, 100 below raw 393
	xor.b	#0xFF,r3l
	xor.b	#3,r3h			; x = 1023 - raw
	mov.w	r3,r4
	add.w	r4,r4
	add.w	r3,r4
	add.w	r4,r4
	add.w	r4,r4
	add.w	r4,r4
	add.w	r3,r4			; 25 x
	mov.b	#156,r3l
	divxu.b	r3l,r4			; r4l = 25 x / 156: 101 to 163 for raw below 393
	cmp.b	#100,r4l
	bls	1f
	mov.b	#100,r4l
1:	sub.b	r4h,r4h
vd1:	bra	vdone

nperc:	cmp.b	#0xE0,r3l
	beq	angle
temp:	mov.w	r0,@-r7			; Celsius, Fahrenheit: sensor_temperature(mode, raw)
	mov.w	r1,@-r7
	mov.b	r3l,r0l
	mov.w	r2,r1
	.word	0x5E00,_sensor_temperature ; jsr
	mov.w	r0,r4
	mov.w	@r7+,r1
	mov.w	@r7+,r0
	bra	vdone

low:	beq	mraw
	mov.b	r0l,r4l			; boolean mode
	sub.b	r4h,r4h
	cmp.b	#0x20,r3l
	beq	vd1
	mov.w	@(SF_VALUE,r1),r4
	mov.b	@(SF_BOOLEAN,r1),r3h	; the boolean before
	cmp.b	#0x40,r3l
	bne	per
	xor.b	r0l,r3h
	shlr	r3h			; transitions: C = a change of the boolean
	bra	addc
per:	cmp.b	r3h,r0l			; periods: C = a 1 -> 0
addc:	addx	#0,r4l
	addx	#0,r4h
	bra	vdone
mraw:	mov.w	r2,r4
	bra	vdone

angle:	mov.w	@(SF_VALUE,r1),r4	; angle (turn()): the count moved by the step of phase
	mov.w	r2,r3
	add.w	r3,r3
	add.w	r3,r3
	mov.b	r3h,r3l
	sub.b	r3h,r3h			; raw / 64
	mov.b	@(_sensor_phase_of,r3),r3l
	cmp.b	#4,r3l
	beq	vdone			; no valid level
	mov.b	@(SF_PHASE,r1),r3h	; the phase before
	mov.b	r3l,@(SF_PHASE,r1)
	cmp.b	#4,r3h
	beq	vdone
	sub.b	r3h,r3l			; the change of phase, mod 4
	btst	#0,r3l
	beq	vdone			; 0, or 2: no direction
	adds	#1,r4			; 1: a step up
	btst	#1,r3l
	beq	vdone
	subs	#2,r4			; 3: a step down

	; Stored; then the events that watch the input, when the value left lo ... hi.
vdone:	mov.b	r0l,@(SF_BOOLEAN,r1)
	mov.w	r4,@(SF_VALUE,r1)
	mov.b	@(SF_WATCHED,r1),r3h
	beq	out
	mov.w	@(SF_LO,r1),r2
	cmp.w	r2,r4
	ble	ev
	mov.w	@(SF_HI,r1),r2
	cmp.w	r2,r4
	blt	out
ev:	mov.w	@(2,r7),r0		; b
	mov.b	@(SF_LATE,r0),r3l
	beq	eval
	sub.w	r2,r2			; late: the events look at the next sample
	mov.w	r2,@r1			; quiet = SENSOR_MOVING
	mov.b	#0x80,r2h
	mov.w	r2,@(SF_HI,r1)		; hi = -32768
	bra	out
eval:	mov.w	r1,r4
	mov.b	r3h,r1l			; watched
	mov.b	@(SF_NUMBER,r4),r2l
	inc	r2l			; EVENTS_KEY(number), kept for the second call
	mov.w	r2,@-r7
	.word	0x5E00,_events_evaluate	; jsr
	mov.w	@r7+,r2
	mov.w	@(SF_LO,r4),r0		; lo EVENTS_WINDOW_NONE: an event looks at every sample (types 0-7), it still
	add.b	#1,r0l			; does: no window to work out (V: lo + 1 overflowed, lo was 32767)
	addx	#0,r0h
	bvs	out
	mov.w	r4,r1
	mov.w	@(2,r7),r0
	.word	0x5E00,_events_window	; jsr
out:	mov.w	@r7+,r4
	adds	#2,r7
	rts
