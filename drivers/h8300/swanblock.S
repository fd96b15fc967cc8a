/* SPDX-License-Identifier: MPL-2.0 */
; The brick's swan_block() (vm/swanblock.c, whose C is the reference and runs on the host): a download's block
; written, its instructions looked at for Swan code up to the first found, and the last block ending the download.
; An opcode is told Swan's by one bit of a 32-byte map (_swan_bits, below) where the C searches Swan's 27 rows: some
; 230 states an instruction instead of 2 500, so that a block of 200 one-byte byte codes holds the main loop about
; 3 ms, not 31 (issue 21 item 3); and in fewer bytes than gcc 3.4's code with rcx_op_params(), whose only caller on
; the brick this was. rcx_swan_find() below reads the map with the same five instructions: kept in line here, where a
; call would cost every instruction of the walk some 20 states more.
; tests/drivers/test_h8swan.c runs it against the C on random downloads, and the map against rcx_swan_find().
;
; void swan_block(struct rcx *b, const u8 *src, u16 count)
;
; Registers in the walk: r0 what is being worked out (the map's byte, the operand bytes); r1 = whole (the walk stops
; there); r2 = p; r3l = the opcode; r4 scratch; r5 = b; r6 = code (the object's first byte); at @r7: end (one past
; the bytes written). r4-r6 are gcc's to keep: saved by ___rcx_save6, given back by ___rcx_ret_a6 (tails.s).

#include "swanblock.h"

#if RCX_SWAN
	.section .text
	.global	_swan_block
	.global	_swan_bits

_swan_block:
	jsr	@___rcx_save6
	mov.w	r0,r5			; b
	mov.w	r2,r4			; count
	mov.b	@(SB_DL_OBJ,r0),r3l
	mov.b	#0,r3h
	add.w	r3,r3
	add.w	r0,r3
	mov.w	@r3,r6			; obj_start[dl.obj]
	add.w	r0,r6
	add.b	#SB_ARENA & 0xFF,r6l
	addx	#SB_ARENA >> 8,r6h	; code
	mov.w	@(SB_DL_FILLED,r0),r3
	mov.w	r6,r0
	add.w	r3,r0
	sub.w	r2,r0			; end - count: where the block goes (r1 = src, r2 = count)
	jsr	@_memcpy		; (gives r0 back as it was: drivers/libc/string.s)
	mov.w	@(SB_DL_SCAN,r5),r2	; the walk goes on where it stopped ...
	cmp.w	r6,r0
	bne	1f
	sub.w	r2,r2			; ... but from the start at the first block (written at code), no Swan code
	mov.b	r2l,@(SB_DL_SWAN,r5)	; found yet
1:	add.w	r4,r0
	mov.w	r0,@-r7			; end
	add.w	r6,r2			; p
	mov.w	r0,r1			; whole = end, ...
	mov.w	@(SB_DL_LAST,r5),r3
	beq	2f
	add.b	#-7,r1l			; ... but for the last 7 bytes while more blocks come (an instruction, 8 bytes
	addx	#-1,r1h			; at most, that starts there may have the rest of its bytes in the next)
2:	mov.b	@(SB_DL_SWAN,r5),r3l
	beq	walk
	sub.w	r1,r1			; Swan code found: nothing more to look for until the next download
walk:	cmp.w	r1,r2
	bcc	walked			; p >= whole (unsigned, as the C's pointers)
	mov.b	@r2,r3l			; the opcode, all eight bits
	mov.b	r3l,r0l
	shlr	r0l
	shlr	r0l
	shlr	r0l
	mov.b	#0,r0h
	mov.b	@(_swan_bits,r0),r0l
	btst	r3l,r0l			; bit op & 7 of byte op >> 3
	bne	swan
	mov.b	r3l,r0l			; the operand bytes, as rcx_op_params(): the row of the opcode with the toggle
	shlr	r0l			; bit folded out, ((op >> 1) & 0x78) | (op & 7) ...
	and.b	#0x78,r0l
	mov.b	r3l,r4l
	and.b	#7,r4l
	or.b	r4l,r0l
	mov.b	#0,r0h
	mov.b	@(_rcx_opflags,r0),r0l
	bne	1f			; ... its low three bits, or for an unknown opcode the nominal count: the
	mov.b	r4l,r0l			; opcode's low three bits, 6 and 7 meaning 0 and 1 (spec p. 5)
	cmp.b	#6,r0l
	bcs	1f
	add.b	#-6,r0l
1:	and.b	#7,r0l
	cmp.b	#6,r0l
	bcc	check			; 6 or 7: SCheckDo or LCheckDo (0x85, 0x95, toggled or not), and no other
step:	add.b	r0l,r2l
	addx	#0,r2h
	adds	#1,r2
	bra	walk

check:	mov.w	r2,r4			; a test of source 43 or 44, its two sources there
	adds	#2,r4
	mov.w	@r7,r3
	cmp.w	r3,r4
	bcc	step
	mov.b	@(1,r2),r3l
	bsr	source
	bls	swan
	mov.b	@r4,r3l
	bsr	source
	bls	swan
	bra	step

source:	and.b	#0x3F,r3l		; ls: source 43 or 44 (SWAN_SOURCE)
	add.b	#-43,r3l
	cmp.b	#1,r3l
	rts

walked:	sub.w	r6,r2
	mov.w	r2,@(SB_DL_SCAN,r5)
	bra	scanned
swan:	mov.b	#1,r3l
	mov.b	r3l,@(SB_DL_SWAN,r5)
scanned:
	mov.w	@(SB_DL_LAST,r5),r3
	bne	out			; more blocks to come
	mov.b	r3l,@(SB_DL_ACTIVE,r5)	; the last block: the code may run from now on, ...
	mov.w	@(SB_DL_FILLED,r5),r6
	mov.w	r6,@r7			; ... its final size (mem_resize's fourth argument, on the stack) ...
	mov.b	@(SB_DL_OBJ,r5),r4l
	mov.b	r4l,r1l
	mov.b	#1,r2l
	mov.w	r5,r0
	jsr	@_mem_resize
	mov.b	#0,r4h			; ... then its slot's kind (see the C)
	mov.b	#SB_SLOT_OBJS,r2l
	divxu	r2l,r4			; r4l = the slot
	mov.b	r4l,r3l
	mulxu	r2l,r3			; its first object
	add.w	r3,r3
	add.w	r5,r3
	mov.w	@(SB_SLOT_OBJS * 2,r3),r0
	mov.w	@r3,r3
	sub.w	r3,r0			; the slot's code
	mov.b	#0,r4h
	add.w	r5,r4
	mov.b	@(SB_DL_SWAN,r5),r3l
	bne	set			; Swan code: a Swan program
	cmp.w	r6,r0
	bne	out			; other code in the slot: the kind it had (kept by those objects)
set:	mov.b	r3l,@(SB_SWAN,r4)
out:	jmp	@___rcx_ret_a6		; (end off the stack)

; const struct rcx_swan_row *rcx_swan_find(u8 op) (vm/swandec.c, whose C is the reference): the row of Swan's opcode
; op, or NULL. The map first: the byte codes run_slow() runs (vm/interp.c) are RCX 2.0's, told so in some 90 states.
; Then the row: the families' first (op & 0xF8 their first opcode), then the single opcodes' (all eight bits), where
; the map says there is one. Registers: r0 the map's byte, then the row; r1l what is compared, r1h the families left;
; r2l a row's opcode; r3l = op.
	.global	_rcx_swan_find
_rcx_swan_find:
	mov.b	r0l,r3l
	shlr	r0l
	shlr	r0l
	shlr	r0l
	mov.b	#0,r0h
	mov.b	@(_swan_bits,r0),r0l
	btst	r3l,r0l
	beq	none
	mov.w	#_rcx_swan_rows,r0
	mov.b	r3l,r1l
	and.b	#0xF8,r1l
	mov.b	#SB_SWAN_FAMILIES,r1h
1:	mov.b	@r0,r2l
	cmp.b	r2l,r1l
	beq	2f
	adds	#2,r0
	dec	r1h
	bne	1b
	mov.b	r3l,r1l			; past the families (r1h goes on from 0: the row comes first)
	bra	1b
none:	sub.w	r0,r0
2:	rts

; One bit an opcode, bit op & 7 of byte op >> 3: set for Swan's opcodes, the RCX_SWAN_OP rows of
; include/rcx_opcodes.def (a family of eight starts at a multiple of 8: one whole byte).
#define RCX_OP(code, id, name, lasm, params, avail, reply, layout)
#define SWAN_BITS_8(code) 0xFF
#define SWAN_BITS_1(code) (1 << ((code) & 7))
#define RCX_SWAN_OP(code, n, id, lasm, params, kind, layout) \
	.set	swan_byte, swan_byte | ((((code) >> 3) == swan_i) & SWAN_BITS_##n(code))
_swan_bits:
	.set	swan_i, 0
	.rept	32
	.set	swan_byte, 0
#include "rcx_opcodes.def"
	.byte	swan_byte
	.set	swan_i, swan_i + 1
	.endr
#endif
