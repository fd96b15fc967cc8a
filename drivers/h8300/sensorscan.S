/* SPDX-License-Identifier: MPL-2.0 */
; The brick's sensor_scan() with sensors_at_rest() in it, and events_look_again() (vm/sensors.c, vm/events.c, whose C
; is the reference and runs on the host), in fewer bytes than gcc 3.4's code, where the image is near its size budget
; (issue 21). tests/drivers/test_h8feed.c runs them against the C.
;
; void sensor_scan(struct rcx *b, const u16 *raw)
;
; Registers: r4 = the input; r5 = b; r6 = raw (r4-r6 saved: gcc keeps them, and sensor_feed() too).
; sensors_at_rest() is only called from here on the brick: the three feeds, then rest = every input steady. An
; input's quiet is SENSOR_MOVING (0) or SENSOR_STEADY | raw, so steady is bit 15: the high bytes' AND, bit 7.

#include "sensorfeed.h"

	.section .text
	.global	_sensor_scan
	.global	_events_look_again

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
	.word	0x5A00,_sensor_feed	; jmp (ld --relax leaves it): its rts returns to the bsr

; void events_look_again(struct rcx *b): every input moving, with no window (lo 0, hi -32768); b->sensors_rest 0.
_events_look_again:
	sub.w	r2,r2
	mov.b	r2l,@(SF_REST,r0)
	mov.w	#0x8000,r3
	mov.b	#3,r1l			; RCX_SENSORS
1:	mov.w	r2,@(SF_SENSOR+SF_QUIET,r0) ; SENSOR_MOVING
	mov.w	r2,@(SF_SENSOR+SF_LO,r0)
	mov.w	r3,@(SF_SENSOR+SF_HI,r0)
	add.b	#SF_SIZE,r0l
	addx	#0,r0h
	dec	r1l
	bne	1b
	rts
