; SPDX-License-Identifier: MPL-2.0
; OpenRCX start-up code. The linker script puts section .start first, so _start is the byte at 0x8000
; that the ROM calls (with jsr) once a download has been unlocked.
;
; State at entry (rcx-hardware.md 2.3 and 6): interrupts enabled, SP in on-chip RAM with a return
; address into the ROM on top, ROM handlers still in some RAM vectors, IRQ0 enabled. Only the entry and the knock
; string are downloaded as they run: the download then holds the unpacker (unpack.s) and the rest of the image
; packed, which the unpacker puts in place before it comes back to _rcx_head_end, so .data needs no copy. Section .high (linker/openrcx.ld), downloaded last, runs at F000: it is
; copied there first, as .bss starts where it was loaded; then .bss, which holds garbage, is cleared. Nothing here
; may call code in .high before the copy.

	.section .start,"x"
	.global	_start
	.global	_rcx_knock
	.global	_rcx_irq_ignore
	.global	_rcx_head_end

_start:
	orc	#0x80,ccr		; mask interrupts until the drivers are ready
	bra	1f

; The ROM refuses to start an image that does not contain this text inside 0x8000-0xCBFF. Right after the
; entry it sits at a fixed address (0x8004), whatever the start-up code becomes, and within two S1 records.
	.align	1
_rcx_knock:
	.ascii	"Do you byte, when I knock?"
	.byte	0
	.align	1

; Downloaded: the unpacker (section .unpack), which copies itself on-chip, then unpacks from here on and jumps here.
_rcx_head_end:
1:	mov.w	#_rcx_standby_stub+16,r7 ; a stack below all that is cleared (FD80-FD8F: standby code later)
	sub.b	r0l,r0l
	mov.b	r0l,@0xc7:8		; IER (FFC7) = 0: IRQ0-2 off

	; Every RAM interrupt vector (FD92-FDBE) -> a bare rts, so that no ROM handler runs again.
	mov.w	#_rcx_ramvec_start,r0
	mov.w	#_rcx_irq_ignore,r1
	mov.w	#_rcx_ramvec_end,r2
	bsr	_rcx_fill

	; Copy .high to F000 (words: the script aligns its start, end and load address). Each of these writes also
	; reaches the motor latch, which is zeroed by the very next instruction: the motors see each stray pattern for
	; well under a microsecond (they would see them for some 2 ms if it were zeroed after the copy), and float after.
	mov.w	#_rcx_high_load,r0
	mov.w	#_rcx_high_start,r1
	mov.w	#_rcx_high_end,r2
	sub.b	r4l,r4l
	bra	6f
5:	mov.w	@r0+,r3
	mov.w	r3,@r1
	mov.b	r4l,@_rcx_motor_latch:8	; motor latch (FF80) = 0: all outputs float
	adds	#2,r1
6:	cmp.w	r2,r1
	bne	5b

	; Clear .bss (it starts where .high was loaded), and on-chip RAM from its variables up: the stack and the
	; .eight variables above it. The linker script aligns all ends to words.
	sub.w	r1,r1
	mov.w	#_rcx_bss_start,r0
	mov.w	#_rcx_bss_end,r2
	bsr	_rcx_fill
	mov.w	#_rcx_onchip_start,r0
	mov.w	#_rcx_onchip_top,r2
	bsr	_rcx_fill

	mov.w	#_rcx_stack_top,r7	; own stack at the top of on-chip RAM; never return to the ROM
	jsr	@_main
4:	orc	#0x80,ccr		; main does not return; if it did, stop quietly
	bra	4b

; Words from r0 up to r2 (exclusive) = r1.
_rcx_fill:
	bra	3f
2:	mov.w	r1,@r0
	adds	#2,r0
3:	cmp.w	r2,r0
	bne	2b
	rts

; Target of unused RAM vectors. The ROM's trampoline saved r6, calls the vector with jsr and ends
; in rte, so a handler is a subroutine.
_rcx_irq_ignore:
	rts
	.align	1
