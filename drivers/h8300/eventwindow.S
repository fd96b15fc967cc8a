/* SPDX-License-Identifier: MPL-2.0 */
; The brick's events_window() (vm/events.c, whose C is the reference and runs on the host): the range lo ... hi
; (exclusive) of an input's value in which none of its events can change, from each event of the input (key) in its
; state; and events_look_again(), which leaves every input without one. In some 40 bytes fewer than gcc 3.4's code,
; where the image is near its size budget (issue 21).
; tests/drivers/test_h8window.c runs these against the C on random events.
;
; void events_window(struct rcx *b, struct rcx_sensor *in, u8 key)
;
; Registers: r0 = the event; r1 = in; r2l = key, r2h = the events left; r3 = l (r3l first the bytes compared);
; r4 = u; r5 = lo; r6 = hi (r4-r6 saved: gcc keeps them).

#include "sensorfeed.h"

	.section .text
	.global	_events_window
	.global	_events_look_again

_events_window:
	mov.w	r4,@-r7
	mov.w	r5,@-r7
	mov.w	r6,@-r7
	add.b	#SF_EVENT & 0xFF,r0l
	addx	#SF_EVENT >> 8,r0h	; b->event
	mov.w	#0x8000,r5		; lo = -32768
	mov.w	#0x7FFF,r6		; hi = 32767
	mov.b	#16,r2h			; RCX_EVENTS
loop:	mov.b	@r0,r3l			; source
	cmp.b	r2l,r3l
	bne	next
	mov.b	@(EV_TYPE,r0),r3l
	cmp.b	#8,r3l
	bcs	none			; types 0-7: every sample
	mov.b	@(EV_STATE,r0),r3l
	mov.w	@(EV_UPPER,r0),r4	; u (mov keeps C)
	cmp.b	#2,r3l
	bhi	empty			; undefined, calibrating: the next sample, then worked out again
	beq	high
	shlr	r3l			; C: normal (1), else low (0)
	mov.w	@(EV_LOWER,r0),r3	; l
	bcc	low
	subs	#1,r3			; normal: lower - 1 ...
	add.b	#1,r4l
	addx	#0,r4h			; ... upper + 1, unless upper is 32767 (V: it was)
	bvc	lohi
	subs	#1,r4
lohi:	cmp.w	r5,r3
	ble	hionly
	mov.w	r3,r5			; lo = l when above
hionly:	cmp.w	r6,r4
	bge	next
	mov.w	r4,r6			; hi = u when below
next:	add.b	#EV_SIZE,r0l
	addx	#0,r0h
	dec	r2h
	bne	loop
done:	mov.w	r5,@(SF_LO,r1)
	mov.w	r6,@(SF_HI,r1)
	mov.w	@r7+,r6
	mov.w	@r7+,r5
	mov.w	@r7+,r4
	rts

high:	mov.w	r4,r3			; high: l = upper, u = 32767 (hi as it is)
	mov.w	r6,r4
	bra	lohi
low:	mov.w	r3,r4			; low: u = lower, l = -32768 (lo as it is)
	bra	hionly
none:	mov.w	#SF_WINDOW_NONE,r5	; lo EVENTS_WINDOW_NONE, hi -32768: the rest need not be looked at
empty:	mov.w	#0x8000,r6		; (empty: hi -32768 and lo as it is, not EVENTS_WINDOW_NONE but by a wrap)
	bra	done

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
