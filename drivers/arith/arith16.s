; SPDX-License-Identifier: MPL-2.0
; The 16-bit helpers gcc calls on the brick (arith.h): ___mulhi3, ___udivhi3, ___umodhi3, ___divhi3 and
; ___modhi3, with rcx_udiv32_16 as the core of the divisions. Written in assembler because the
; H8/300 does them in a few instructions that C cannot express (the carry through a register pair,
; mulxu): a third of the bytes of arith.c's C versions, which remain the reference on the host.
; tests/drivers/test_h8image.c runs these as linked against arith.c's C functions.
;
; Branches between helpers go to local labels: drivers/arith/check_arith.cmake refuses a helper that
; refers to another by name (for C helpers that would mean a call, possibly recursive).
;
; gcc's convention: operands in r0 and r1, result in r0; r0-r3 may be clobbered, r4-r6 are kept.
; Semantics (arith.h): division by zero gives quotient 0 and the dividend as remainder; the most
; negative value divided by -1 gives itself, remainder 0; signed division truncates toward zero and the
; remainder takes the dividend's sign.

	.section .text
	.global	___mulhi3
	.global	___udivhi3
	.global	___umodhi3
	.global	___divhi3
	.global	___modhi3
	.global	_rcx_udiv32_16

; a * b mod 2^16 = a0 b0 + (a1 b0 + a0 b1) * 256, a1 and b1 the high bytes: three byte multiplies.
___mulhi3:
	mov.b	r0h,r2l
	mulxu.b	r1l,r2			; r2 = a1 b0
	mov.b	r1h,r3l
	mulxu.b	r0l,r3			; r3 = b1 a0
	add.b	r3l,r2l			; the cross products, mod 256
	mulxu.b	r1l,r0			; r0 = a0 b0
	add.b	r2l,r0h
	rts

; a % b: the remainder the division leaves in r2.
___umodhi3:
	bsr	.Ludiv
	mov.w	r2,r0
	rts

; a / b, remainder in r2 (for ___umodhi3 and the signed helpers). A divisor below 256 takes two divxu
; (the high byte, then the remainder and the low byte); a larger one leaves a quotient below 256, so
; eight steps of the long division do.
___udivhi3:
.Ludiv:
	sub.w	r2,r2
	mov.b	r0h,r2l			; r2 = a's high byte
	mov.b	r1h,r1h
	bne	1f
	mov.b	r1l,r1l
	beq	2f
	divxu.b	r1l,r2			; r2l = quotient's high byte, r2h = remainder
	mov.b	r2l,r3l
	mov.b	r2h,r0h
	divxu.b	r1l,r0			; r0l = quotient's low byte, r0h = remainder
	mov.b	r0h,r2l
	sub.b	r2h,r2h
	mov.b	r3l,r0h
	rts
1:	mov.b	r0l,r0h			; the low byte goes through the eight steps
	sub.b	r0l,r0l
	mov.b	#8,r3l
	bra	.Lsteps
2:	mov.w	r0,r2			; by zero: quotient 0, remainder a
	sub.w	r0,r0
	rts

; (hi:lo) / d with hi < d, in C rcx_udiv32_16(lo = r0, d = r1, hi = r2): quotient in r0, remainder in
; r2; r3h is kept. Sixteen steps of long division: the dividend shifts left through r2:r0, the
; quotient bits come in at the bottom of r0. A bit shifted out of r2 makes the partial remainder 17 bits
; long, certainly not below d; the subtraction modulo 2^16 is still exact, as the result is below d.
_rcx_udiv32_16:
	mov.b	#16,r3l
.Lsteps:
1:	shll.b	r0l
	rotxl.b	r0h
	rotxl.b	r2l
	rotxl.b	r2h
	bcs	2f
	cmp.w	r1,r2
	bcs	3f			; below d: quotient bit 0
2:	sub.w	r1,r2
	bset	#0,r0l
3:	dec.b	r3l
	bne	1b
	rts

; Signed: the unsigned division of the magnitudes, the sign applied after; bit 7 of r3h holds it.
___divhi3:
	mov.b	r0h,r3h
	xor.b	r1h,r3h			; the quotient is negative when the signs differ
	bsr	_rcx_udivs16
	bra	_rcx_sign16

___modhi3:
	mov.b	r0h,r3h			; the remainder has the dividend's sign
	bsr	_rcx_udivs16
	mov.w	r2,r0
_rcx_sign16:
	btst	#7,r3h
	beq	1f
_rcx_neg16:				; r0 = -r0
	not.b	r0l
	not.b	r0h
	adds	#1,r0
1:	rts

; |a| / |b| into r0, |a| % |b| into r2, r3h kept.
_rcx_udivs16:
	btst	#7,r0h
	beq	1f
	bsr	_rcx_neg16
1:	btst	#7,r1h
	beq	.Ludiv
	not.b	r1l
	not.b	r1h
	adds	#1,r1
	bra	.Ludiv
