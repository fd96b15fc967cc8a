; Interrupt entry points for C handlers.
;
; The ROM's vector for each interrupt pushes r6, calls the address stored in the RAM vector table
; (FD92-FDBE) with jsr, pops r6 and returns with rte. So an entry point stored there is a subroutine
; ending in rts, and must keep r0-r5 intact. A C function keeps r4-r6 itself; the wrapper saves the
; call-clobbered r0-r3 around it. The C handler must clear the peripheral's interrupt flag.

	.macro	irq_entry entry, handler
	.section .text
	.global	\entry
\entry:
	mov.w	r0,@-r7
	mov.w	r1,@-r7
	mov.w	r2,@-r7
	mov.w	r3,@-r7
	jsr	@\handler
	mov.w	@r7+,r3
	mov.w	@r7+,r2
	mov.w	@r7+,r1
	mov.w	@r7+,r0
	rts
	.endm

	irq_entry _rcx_frt_irq, _rcx_frt_isr	; FRT compare match A (RAM vector FDA2): the 1 ms tick
