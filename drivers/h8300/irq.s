; Interrupt entry points, and the code that runs around SLEEP in standby.
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

	irq_entry _rcx_frt_irq, _rcx_frt_isr	; FRT compare match A (FDA2): the 1 ms tick
	irq_entry _rcx_adi_irq, _rcx_adi_isr	; A/D scan end (FDBC)
	irq_entry _rcx_rxi_irq, _rcx_rxi_isr	; SCI byte received (FDB6)
	irq_entry _rcx_eri_irq, _rcx_eri_isr	; SCI receive error (FDB4)
	irq_entry _rcx_txi_irq, _rcx_txi_isr	; SCI transmit data register empty (FDB8)
	irq_entry _rcx_tei_irq, _rcx_tei_isr	; SCI transmission ended (FDBA)

; Copied to on-chip RAM at FD80 (16 bytes, up to FD8F) by hal_power_off and called there: while external
; RAM is in power-save (P5.2 = 1) no instruction or data may come from it. Interrupts must be enabled for
; the IRQ1 request (On-Off) to end the standby; the final rts doubles as the IRQ1 handler.
	.section .text
	.global	_rcx_standby_code
	.global	_rcx_standby_code_end
_rcx_standby_code:
	bset	#2,@0xba:8		; P5.2: external RAM to power-save
	andc	#0x7f,ccr
	sleep
	orc	#0x80,ccr
	bclr	#2,@0xba:8		; external RAM awake
	rts
_rcx_standby_code_end:
