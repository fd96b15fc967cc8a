; SPDX-License-Identifier: MPL-2.0
; memcpy, memmove, memset and memcmp for the freestanding firmware (rcx_string.h): the portable code calls
; them and gcc emits calls to memcpy/memset for struct copies. In assembler because a C loop needs more
; registers than gcc's calling convention leaves free and pays for saving them; memcpy and memmove use the
; CPU's block move where they can, since compacting the program memory moves up to the whole arena.
; string.c is the same in C, the reference on the host; tests/drivers/test_h8image.c checks these against
; the host's.
;
; Arguments in r0, r1, r2 (dst or a, src or c or b, n), result in r0; r0-r3 may be clobbered.

	.section .text
	.global	_memcpy
	.global	_memmove
	.global	_memset
	.global	_memcmp

; Overlapping regions: copied upwards when the destination lies below the source, downwards otherwise.
; Upwards is the H8/300's block move EEPMOV (@R5+ to @R6+, R4L bytes): about 6 states a byte in external RAM
; against some 40 for a loop, so that compacting the program memory holds the main loop a few ms at most (issue 21,
; docs/timing.md). 255 bytes at most an instruction, during which no interrupt is taken (1 550 states). memcpy
; (no overlap) moves upwards too.
_memmove:
	cmp.w	r1,r0
	beq	9f			; in place: nothing to move
	bhi	.Lcopy_down
_memcpy:
	mov.w	r4,@-r7
	mov.w	r5,@-r7
	mov.w	r6,@-r7
	mov.w	r1,r5
	mov.w	r0,r6
	mov.b	r2l,r4l			; n mod 256 first (up to 1 550 states without interrupts)
	add.b	r2h,r2h			; then n / 256 twice 128 (n < 16 KB: the arena is smaller)
1:	eepmov
	mov.b	#128,r4l
	dec	r2h
	bpl	1b
	mov.w	@r7+,r6
	mov.w	@r7+,r5
	mov.w	@r7+,r4
9:	rts

.Lcopy_down:
	add.w	r2,r1			; r1, r3: one past the ends
	mov.w	r0,r3
	add.w	r2,r3
	bra	2f
1:	subs	#1,r1
	mov.b	@r1,r2l
	mov.b	r2l,@-r3
2:	cmp.w	r0,r3
	bne	1b
	rts

; memset runs from F000 (section .high, linker/openrcx.ld), where it costs no program memory: it is called only
; once crt0.s has copied .high there.
	.section .hitext,"x"
_memset:
	mov.w	r0,r3
	add.w	r0,r2			; r2 = end
	bra	2f
1:	mov.b	r1l,@r3
	adds	#1,r3
2:	cmp.w	r2,r3
	bne	1b
	rts

	.section .text
; <0, 0 or >0 as the first differing byte (unsigned) of a is below, equal to or above b's.
_memcmp:
	add.w	r0,r2			; r2 = end of a
1:	cmp.w	r2,r0
	beq	3f
	mov.b	@r0+,r3l
	mov.b	@r1+,r3h
	cmp.b	r3h,r3l
	beq	1b
	mov.w	#1,r0
	bhi	2f			; a's byte above: 1 (mov.w leaves the carry alone)
	mov.w	#-1,r0
2:	rts
3:	sub.w	r0,r0
	rts
