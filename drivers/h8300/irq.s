; Interrupt entry points, and the code that runs around SLEEP in standby.
;
; The ROM's vector for each interrupt pushes r6, calls the address stored in the RAM vector table
; (FD92-FDBE) with jsr, pops r6 and returns with rte. So an entry point stored there is a subroutine
; ending in rts, and must keep r0-r5 intact. A C function keeps r4-r6 itself; the entry saves the
; call-clobbered r0-r3 around it, and all entries restore them through one shared tail. The C handler
; must clear the peripheral's interrupt flag. Two handlers serve the six interrupts in use, each finding
; out from the flags what happened (main.c, sci.c).

	.section .text
	.global	_rcx_timer_irq
	.global	_rcx_sci_irq

_rcx_timer_irq:				; FRT compare match A (FDA2, the 1 ms tick), A/D end (FDBC)
	mov.w	r0,@-r7
	mov.w	r1,@-r7
	mov.w	r2,@-r7
	mov.w	r3,@-r7
	jsr	@_rcx_timer_isr
	bra	_rcx_irq_return

_rcx_sci_irq:				; SCI receive error, byte received, TDR empty, sent (FDB4-FDBA)
	mov.w	r0,@-r7
	mov.w	r1,@-r7
	mov.w	r2,@-r7
	mov.w	r3,@-r7
	jsr	@_rcx_sci_isr
_rcx_irq_return:
	mov.w	@r7+,r3
	mov.w	@r7+,r2
	mov.w	@r7+,r1
	mov.w	@r7+,r0
	rts

; Copied to on-chip RAM at FD80 (16 bytes, up to FD8F) by hal_power_off and called there: while external
; RAM is in power-save (P5.2 = 1) no instruction or data may come from it. Interrupts must be enabled for
; the IRQ1 request (On-Off) to end the standby; the final rts doubles as the IRQ1 handler.
; An IRQ1 request may be waiting already: a falling edge of On-Off latched while the brick was on (the press
; that switched it off, contact bounce). After andc the CPU runs one more instruction before it takes an
; interrupt; were that the sleep, such a request would end the standby at once. So the bset comes between:
; the request is taken (by the rts) before the sleep, and only a new press wakes the brick.
	.section .text
	.global	_rcx_standby_code

_rcx_standby_code:
	andc	#0x7f,ccr
	bset	#2,@0xba:8		; P5.2: external RAM to power-save
	sleep
	orc	#0x80,ccr
	bclr	#2,@0xba:8		; external RAM awake
	rts
_rcx_standby_code_end:
	.if	_rcx_standby_code_end - _rcx_standby_code - 16
	.error	"the standby code must be 16 bytes (hal.c copies that many, its rts at FD8E)"
	.endif
