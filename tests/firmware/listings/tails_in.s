; SPDX-License-Identifier: MPL-2.0
; Input of firmware_tails: gcc-shaped function endings for drivers/h8300/tails/as, run with
; --rcx-shared-tails=_d:_e:_f:_a6:_k (the expected result: tails_out.s).
	.section .text
; a call right before the return
_a:
	jsr	@_g
	rts
; a call, then registers popped (no shared epilogue here: not in the list)
_b:
	mov.w	r4,@-r7
	mov.w	r5,@-r7
	jsr	@_g
	mov.w	@r7+,r5
	mov.w	@r7+,r4
	rts
; a call through a register that is popped after it: left as it is
_c:
	mov.w	r4,@-r7
	jsr	@r4
	mov.w	@r7+,r4
	rts
; a call through a register right before the return
_r:
	jsr	@r2
	rts
; shared: after a call, r6-r4 popped (the shared copy is shorter than the pops and a jump); r4, r5 pushed and
; the first argument kept in r4: ___rcx_save5_r4
_d:
	mov.w	r4,@-r7
	mov.w	r5,@-r7
	mov.w	r0,r4
	jsr	@_g
	mov.w	@r7+,r6
	mov.w	@r7+,r5
	mov.w	@r7+,r4
	rts
; shared: r4-r6 pushed first thing (the shared prologue), two bytes of locals popped after the registers
_e:
	mov.w	r4,@-r7
	mov.w	r5,@-r7
	mov.w	r6,@-r7
	mov.w	r0,r1
	mov.w	@r7+,r6
	mov.w	@r7+,r5
	mov.w	@r7+,r4
	adds	#2,r7
	rts
; shared: a call's stack argument popped before the registers; the prologue after 2 bytes of locals
_a6:
	subs	#2,r7
	mov.w	r4,@-r7
	mov.w	r5,@-r7
	mov.w	r6,@-r7
	adds	#2,r7
	mov.w	@r7+,r6
	mov.w	@r7+,r5
	mov.w	@r7+,r4
	rts
; a label inside the epilogue (a branch target): only what follows it is shared
_f:
	mov.w	@r7+,r6
.L1:
	mov.w	@r7+,r5
	mov.w	@r7+,r4
	rts
; not in the list: left as it is (its prologue too)
_h:
	mov.w	r4,@-r7
	mov.w	r5,@-r7
	mov.w	r6,@-r7
	mov.w	@r7+,r6
	mov.w	@r7+,r5
	mov.w	@r7+,r4
	rts
; long jumps (gcc's jump round a jmp, when the place is out of a branch's reach): the opposite branch to the place
; when the listing shows it in reach (.L5), else to an identical jmp within reach; a jmp to a label where a jmp
; follows jumps there itself (outside the list too)
_j:
	cmp.b	#1,r0l
	bne	.Lh8BR1
	jmp	@.L5
.Lh8BR1:
	cmp.b	#2,r0l
	bls	.Lh8BR2
	jmp	@_g
.Lh8BR2:
	cmp.b	#3,r0l
	beq	.Lh8BR3
	jmp	@_h
.Lh8BR3:
	rts
.L5:
	jmp	@_g
	.section .hitext
; in the list, but not in .text: only the call becomes a jump
_k:
	mov.w	@r7+,r5
	mov.w	@r7+,r4
	rts
_m:
	jsr	@_g
	rts
	.end
