; SPDX-License-Identifier: MPL-2.0
; The function endings shared by the C files that drivers/h8300/tails/as rewrites (--rcx-shared-tails): a function
; whose epilogue is one of these jumps here instead of holding its own copy. Each entry is the rest of its epilogue.

	.section .text
	.global	___rcx_ret_a6
	.global	___rcx_ret6
	.global	___rcx_ret5
	.global	___rcx_ret6_f2
	.global	___rcx_ret6_f4

___rcx_ret_a6:
	adds	#2,r7			; the stack arguments of the function's last call
___rcx_ret6:
	mov.w	@r7+,r6
___rcx_ret5:
	mov.w	@r7+,r5
	mov.w	@r7+,r4
	rts

___rcx_ret6_f4:				; 4 bytes of locals below the saved registers' ... above them: popped last
	mov.w	@r7+,r6
	mov.w	@r7+,r5
	mov.w	@r7+,r4
	adds	#2,r7
	adds	#2,r7
	rts

___rcx_ret6_f2:
	mov.w	@r7+,r6
	mov.w	@r7+,r5
	mov.w	@r7+,r4
	adds	#2,r7
	rts

; The shared prologue (a call here in place of pushing r4, r5, r6): the return address becomes the slot of r4.
	.global	___rcx_save6
___rcx_save6:
	mov.w	@r7,r3			; where the function goes on (r3 holds no argument)
	mov.w	r4,@r7
	mov.w	r5,@-r7
	mov.w	r6,@-r7
	jmp	@r3

; With room for 2 or 4 bytes of locals first (where the return address was, and 2 bytes more).
	.global	___rcx_save6_f4
	.global	___rcx_save6_f2
___rcx_save6_f4:
	mov.w	@r7,r3
	subs	#2,r7
	bra	1f
___rcx_save6_f2:
	mov.w	@r7,r3
1:	mov.w	r4,@-r7
	mov.w	r5,@-r7
	mov.w	r6,@-r7
	jmp	@r3

; r4, r5 pushed, and the first argument (r0) kept in r4 or r5.
	.global	___rcx_save5_r4
	.global	___rcx_save5_r5
___rcx_save5_r4:
	mov.w	@r7,r3
	mov.w	r4,@r7
	mov.w	r0,r4
	mov.w	r5,@-r7
	jmp	@r3
___rcx_save5_r5:
	mov.w	@r7,r3
	mov.w	r4,@r7
	mov.w	r5,@-r7
	mov.w	r0,r5
	jmp	@r3
