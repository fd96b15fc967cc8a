; SPDX-License-Identifier: MPL-2.0
; Interrupt entry points, and the code that runs around SLEEP in standby.
;
; The ROM's vector for each interrupt pushes r6, calls the address stored in the RAM vector table
; (FD92-FDBE) with jsr, pops r6 and returns with rte. So an entry point stored there is a subroutine
; ending in rts, and must keep r0-r5 intact. A C function keeps r4-r6 itself; the entry saves the
; call-clobbered r0-r3 around it, and all entries restore them through one shared tail. The C handler
; must clear the peripheral's interrupt flag. Two handlers serve the five interrupts in use, the SCI's finding out
; from the flags what happened (sci.c).

	.section .text
	.global	_rcx_timer_irq
	.global	_rcx_sci_irq
	.global	_rcx_irq_rts		; no code: where the tests (tests/drivers/test_h8load.c) see an interrupt end

; The FRT compare match A (FDA2, the 1 ms tick), written here because it runs a thousand times a second whatever
; the brick is doing. Every millisecond the motor latch takes the next byte of the pattern hal_motor worked out
; (drv_motors, hw.h), and the inputs' A/D results go to the next slot of drv_ad_slot for the main loop (main.c: it
; must never run the runtime inside an interrupt), which reads the battery's from ADDRD itself. A scan equal to the
; last one is not stored when the main loop has fed everything and the runtime said that such a scan changes nothing
; (rcx.sensors_rest, vm/sensors.h): nearly always, on an idle brick. The main loop is woken (and the tasks' run
; ended) only once three scans wait: inputs that move every millisecond then cost it a pass every 3 ms, not every
; one, and are worked out no later than firm0328 samples them (every 3 ms: reference-firmware.md). The ring holds 8.
;
; Passive inputs and the battery come from a scan of AN0-AN3 that runs on by itself: in scan mode the converter
; starts over after each pass (66 us) until ADST is cleared, each data register holding its channel's latest
; result, never older than a pass. The tick reads them as they are, without stopping it, and starts the scan only
; if it is not running with a pass made (start-up, wake-up, or stopped below). That costs the idle tick nothing (no
; A/D interrupt, no restart); the price is the converter's own supply current while the brick is on (about 0.5 mA
; typical in the tables of later H8 parts; the H8/3292's was not found). Reading a register while the scan writes
; it is safe: a word read (high byte first, rcx-hardware.md 3.3) takes the low byte from the copy latched with the
; high one.
;
; An active sensor (light, rotation) must be read unpowered, a few us after its own power is removed, as brickOS
; reads it (its rotation thresholds are tuned for that: rcx-hardware.md 3.3). At such a tick the scan is stopped,
; then for each active input in turn: its power off, at once a single conversion of its channel (CKS 0), the end
; awaited (ADF, 259-266 states), its power on again. Its input is sampled from tD = 10-17 states after the start
; for tSPL = 63 states: held 82-89 states (5.1-5.6 us) after the power went off (the write to ADCSR is the next
; instruction, 9 states on), and it is off for about 20 us in each millisecond (brickOS: 20-30 us, the LEGO ROM
; some 70). Each such input costs the tick about 300 states, during which other interrupts wait (at most some
; 60 us with three: a byte takes 4.6 ms at 2400 Bd). Then the slot is stored, with the single results for
; the active inputs and the scan's for the others, and the scan started again. Its passes convert the active inputs'
; channels while they are powered: those results are never used, as the tick converts them afresh before storing.
_rcx_timer_irq:
	mov.w	r0,@-r7
	mov.w	r1,@-r7
	mov.w	r2,@-r7
	mov.w	r3,@-r7
	bclr	#3,@0x91:8		; TCSR.OCFA, read as 1: acknowledged
	mov.b	@_drv_ms_ticks:8,r1l
	inc	r1l
	mov.b	r1l,@_drv_ms_ticks:8
	mov.b	@_drv_quiet:8,r1l	; quiet milliseconds the main loop lets the tasks run through ...
	beq	1f
	mov.b	@_drv_sound_count:16,r2l ; ... unless they started what needs the clock: a note, a reversing
	mov.b	@_drv_pause:16,r2h	; pause, a transmission (src/runtime.h)
	or.b	r2h,r2l
	mov.b	@_drv_pause+1:16,r2h
	or.b	r2h,r2l
	mov.b	@_drv_pause+2:16,r2h
	or.b	r2h,r2l
	mov.b	@_drv_tx_len:16,r2h
	or.b	r2h,r2l
	bne	1f
	dec	r1l
	mov.b	r1l,@_drv_quiet:8
	bra	2f
1:	mov.b	#1,r1l
	mov.b	r1l,@_drv_yield:16	; rcx.yield: vm_run returns at its next check
2:
	sub.b	r1h,r1h
	mov.b	@_drv_motors+8:16,r1l	; drv_motors.phase, 0-7
	mov.b	@(_drv_motors,r1),r2l
	mov.b	r2l,@0x80:8		; the motor latch
	inc	r1l
	and.b	#7,r1l
	mov.b	r1l,@_drv_motors+8:16
	mov.b	@0xe8:8,r0l		; ADCSR: B3 = ADF, ADST, SCAN, AN0-AN3: the scan runs, a pass made
	mov.b	@_drv_sensor_power:8,r0h ; the active inputs: bit n for ANn, as their power bits in P6DR
	beq	.Lpassive
.Lactive:
	sub.b	r1l,r1l
	mov.b	r1l,@0xe8:8		; ADCSR 0: the scan stops
	mov.b	@0xe8:8,r1l		; ADF read again, now that no pass can end: the next write clears it
	mov.b	#0x20,r1h		; ADST, single mode, CKS 0, AN0
.Lnext:
	btst	r1h,r0h			; bit n of the mask, n = the channel in r1h
	beq	2f
	bclr	r1h,@0xbb:8		; P6DR: the sensor unpowered ...
	mov.b	r1h,@0xe8:8		; ... and its channel converted at once
	sub.b	r2l,r2l
1:	mov.b	@0xe8:8,r1l
	bmi	3f			; until ADF, or 256 looks (some 0.4 ms): a converter that never ends (none
	dec	r2l			; does; brickEmu did) must not hold the brick in its tick
	bne	1b
3:	bset	r1h,@0xbb:8		; powered again
2:	inc	r1h
	cmp.b	#0x23,r1h
	bne	.Lnext
.Lpassive:
	cmp.b	#0xb3,r0l		; the scan had made a pass: the passive inputs' results are there
	bne	.Lrestart
.Lscan:
	sub.b	r1h,r1h
	mov.b	@_drv_ad_done:8,r1l
	mov.b	@_drv_ad_seen:8,r2l
	cmp.b	r1l,r2l
	bne	.Lstore			; the main loop has scans to feed yet
	mov.b	@_drv_sensors_rest:16,r2l
	beq	.Lstore
	add.b	#0xf8,r1l		; the slot before: - DRV_AD_SLOT
	and.b	#0x3f,r1l		; DRV_AD_SLOTS * DRV_AD_SLOT - 1
	mov.w	@0xffe0:16,r2
	mov.w	@(_drv_ad_slot,r1),r3
	cmp.w	r2,r3
	bne	.Lstore
	mov.w	@0xffe2:16,r2
	mov.w	@(_drv_ad_slot+2,r1),r3
	cmp.w	r2,r3
	bne	.Lstore
	mov.w	@0xffe4:16,r2
	mov.w	@(_drv_ad_slot+4,r1),r3
	cmp.w	r2,r3
	beq	.Lstored		; the same as the scan before
.Lstore:				; ADDRA-ADDRC into slot drv_ad_done / 8 of drv_ad_slot
	mov.b	@_drv_ad_done:8,r1l
	and.b	#0x3f,r1l
	mov.w	@0xffe0:16,r2
	mov.w	r2,@(_drv_ad_slot,r1)
	mov.w	@0xffe2:16,r2
	mov.w	r2,@(_drv_ad_slot+2,r1)
	mov.w	@0xffe4:16,r2
	mov.w	r2,@(_drv_ad_slot+4,r1)
	mov.b	@_drv_ad_done:8,r1l
	add.b	#8,r1l			; DRV_AD_SLOT
	mov.b	r1l,@_drv_ad_done:8
	mov.b	@_drv_ad_seen:8,r2l
	sub.b	r2l,r1l
	cmp.b	#16,r1l			; one or two scans wait: the run (or the sleep) goes on
	bls	.Lstored
	mov.b	#1,r1l
	mov.b	r1l,@_drv_woken:8	; the main loop has scans to feed
	mov.b	r1l,@_drv_yield:16
.Lstored:
	mov.b	r0h,r0h
	beq	.Lreturn
.Lrestart:				; active inputs (the scan was stopped for them), or no scan running with a pass made
	mov.b	#0x33,r1l		; ADST, SCAN, AN0-AN3 (ADF, if read as 1, cleared)
	mov.b	r1l,@0xe8:8
.Lreturn:
	mov.w	@r7+,r3
	mov.w	@r7+,r2
	mov.w	@r7+,r1
	mov.w	@r7+,r0
_rcx_irq_rts:
	rts

_rcx_sci_irq:				; SCI receive error, byte received, TDR empty, sent (FDB4-FDBA)
	mov.w	r0,@-r7
	mov.w	r1,@-r7
	mov.w	r2,@-r7
	mov.w	r3,@-r7
	jsr	@_rcx_sci_isr
	bra	.Lreturn

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
