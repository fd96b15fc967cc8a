/* SPDX-License-Identifier: MPL-2.0 */
; The brick's loop over the running tasks (vm_run(), vm/interp.c): one byte code per running task in turn, or a lone
; task's many in a row. It runs the byte codes that are most of a busy program itself: SJump, and SetVar/SumVar/
; SubVar with a constant or a global variable as the source; any other, and an irregular case of these (a truncated
; instruction, a jump reaching the end of the code or leaving it, an operand out of range), through run_slow(). gcc
; 3.4 cannot keep a task switch, or a lone task's position, in registers; here a switch costs a look-up of the
; task's code object, and a lone task keeps its position in registers from one byte code to the next.
;
; u16 rcx_run_fast(struct rcx *b, u16 count)
;   count at least 1; b->runmask is not 0. Visits the running tasks from task b->rr on, round after round (a lone
;   task: RF_RUN_CHUNK byte codes a round at most), and returns the byte codes left of count once it has run `count`,
;   or nothing runs any more, or b->yield is set (looked at after each round and each run_slow()); b->rr is then the
;   task after the last one run, as vm_run() leaves it.
;
; Registers: r6 = b, r5 = the task, r4h = byte codes the task may still run in this turn (1, or up to RF_RUN_CHUNK
; for a lone task), r4l = its code object's number in the task's own body (prog * 18 + 8 + n; the opcode while a byte
; code runs), r3 = runmask >> n (then >> n + 1); during a turn: r1 = the byte code's address, r2 = the end of the
; code (both absolute), r0 and r3 scratch. On the stack (F_*): what is left of count besides r4h, where the code
; starts, its obj_start entry, r3 and r4l kept over a turn, prog * 18 + 8 (task 0's body).
; Only relative branches and jumps written as data: ld --relax rewrites no instruction here (see unpack.s).

#include "runfast.h"

#define F_CODE 0
#define F_AT 2
#define F_MASK 4
#define F_BASE 6
#define F_OBJ 7
#define F_LEFT 8

	.section .text
	.global	_rcx_run_fast

_rcx_run_fast:
	mov.w	r4,@-r7
	mov.w	r5,@-r7
	mov.w	r6,@-r7
	mov.w	r1,@-r7			; F_LEFT: count
	mov.w	r0,r6
	mov.b	@(RF_PROG,r6),r0l
	mov.b	#RF_SLOT_OBJS,r0h
	mulxu.b	r0h,r0
	add.b	#RF_SUBS,r0l
	mov.b	r0l,r0h
	mov.w	r0,@-r7			; F_BASE, F_OBJ
	mov.w	r0,@-r7			; F_MASK
	mov.w	r0,@-r7			; F_AT
	mov.w	r0,@-r7			; F_CODE
	mov.b	@(RF_RR,r6),r1l		; tasks to pass over in the first round
	bra	round
round0:	sub.b	r1l,r1l
round:	mov.b	@(F_BASE,r7),r4l
	mov.w	@(RF_RUNMASK,r6),r3
	mov.w	#RF_TASK,r5
	add.w	r6,r5
	bra	2f
1:	shlr	r3h
	rotxr	r3l
	inc	r4l
	add.b	#RF_TASK_SIZE,r5l
	addx	#0,r5h
2:	dec	r1l
	bpl	1b
	mov.w	r3,r3
	beq	round0			; no running task from b->rr on
step:	shlr	r3h			; r3 = runmask >> n, not 0
	rotxr	r3l
	bcs	visit
next:	inc	r4l
	add.b	#RF_TASK_SIZE,r5l
	addx	#0,r5h
	bra	step

insub:	mov.b	@(F_BASE,r7),r1l	; a subroutine: prog * 18 + sub
	add.b	#-RF_SUBS,r1l
	add.b	r1l,r0l
	bra	object

alone:	mov.w	@(F_LEFT,r7),r0		; a lone task's turn: what is left, up to RF_RUN_CHUNK (then a look at yield)
	mov.b	#RF_RUN_CHUNK,r4h
	mov.w	#RF_RUN_CHUNK,r2
	cmp.w	r2,r0
	bcc	1f
	mov.b	r0l,r4h
1:	sub.b	r4h,r0l
	subx	#0,r0h
	mov.w	r0,@(F_LEFT,r7)
	sub.w	r3,r3			; no other task after this one
	bra	visit1
visit:	mov.w	@(F_LEFT,r7),r0		; a turn of one byte code
	subs	#1,r0
	mov.w	r0,@(F_LEFT,r7)
	mov.b	#1,r4h
visit1:	mov.w	r3,@(F_MASK,r7)
	mov.b	r4l,@(F_OBJ,r7)
	mov.b	@(RF_SUB,r5),r0l
	cmp.b	#RF_NO_SUB,r0l
	bne	insub
	mov.b	r4l,r0l
object:	mov.b	#0,r0h
	add.w	r0,r0
	add.w	r6,r0			; &b->obj_start[object]
	mov.w	r0,@(F_AT,r7)
	mov.w	@r0+,r3			; where its code starts in the arena
	mov.w	@r0,r2			; and ends
	mov.w	@(RF_PC,r5),r1
	mov.w	r2,r0
	sub.w	r3,r0
	cmp.w	r0,r1
	bcc	vended			; none left: run_slow() ends the code
	mov.w	#RF_ARENA,r0
	add.w	r6,r0
	add.w	r0,r3
	add.w	r0,r2
	add.w	r3,r1
	mov.w	r3,@(F_CODE,r7)
	bra	dispatch

srcvar:	mov.b	r0h,r0h			; RF_SRC_VAR: a global variable's value
	bne	slow5
	mov.b	r3h,r3h
	bne	slow5
	cmp.b	#RF_GLOBALS,r3l
	bcc	slow5
	add.w	r3,r3
	add.w	r6,r3
	mov.w	@(RF_GLOBAL,r3),r3
	bra	vref

slow5:	add.b	#-5,r1l			; back to the opcode
	addx	#-1,r1h
	.word	0x5A00,slow		; jmp @slow
vended:	.word	0x5A00,ended		; jmp @ended

var:	add.b	#5,r1l			; v op= source: 5 bytes, and the code goes on after them
	addx	#0,r1h
	cmp.w	r2,r1
	bcc	slow5
	mov.b	@(-4,r1),r0l		; the variable
	cmp.b	#RF_GLOBALS+RF_LOCALS,r0l
	bcc	slow5
	mov.b	@(-3,r1),r0h		; the source
	mov.b	@(-2,r1),r3l
	mov.b	@(-1,r1),r3h
	cmp.b	#RF_SRC_CONST,r0h
	bne	srcvar			; else the constant
vref:	cmp.b	#RF_GLOBALS,r0l
	bcs	1f
	mov.b	@(RF_LOCAL_BASE,r5),r0h	; 32-47: global v + t->local_base (at most 191)
	add.b	r0h,r0l
1:	mov.b	#0,r0h
	add.w	r0,r0
	add.w	r6,r0			; the variable at @(RF_GLOBAL,r0)
apply:	cmp.b	#RF_OP_SUM_VAR,r4l
	beq	3f
	cmp.b	#RF_OP_SET_VAR,r4l
	beq	2f			; SetVar: the value itself
	not	r3l			; SubVar: v + (0 - value), as vm_run() on the host
	not	r3h
	adds	#1,r3
3:	mov.b	@(RF_GLOBAL+1,r0),r4l	; big-endian: the low byte second
	add.b	r4l,r3l
	mov.b	@(RF_GLOBAL,r0),r4l
	addx	r4l,r3h
2:	mov.w	r3,@(RF_GLOBAL,r0)
	bra	done

dispatch:
	mov.b	@r1,r4l			; all eight bits: 0x2C and 0x2F are Swan's, not SumVar and SJump
	cmp.b	#RF_OP_SJUMP,r4l
	beq	sjump
#if RCX_SWAN
	cmp.b	#RF_SW_SUM_GB,r4l	; Swan's x++ (sumgb g, 1) before RCX 2.0's: as fast as SumVar's
	beq	gform
#endif
	cmp.b	#RF_OP_SUM_VAR,r4l
	beq	var
	cmp.b	#RF_OP_SET_VAR,r4l
	beq	var
	cmp.b	#RF_OP_SUB_VAR,r4l
	beq	var
#if !RCX_SWAN
	bra	slow			; any other
#else
; Swan's assignments and sums on a global, as SetVar/SumVar/SubVar: 0x2B 0x48 0x49 op g k8, 0x2C op g H L (a word, high
; byte first), 0x2D 0xC8 0xC9 op g T v8 (a constant or a global source). r4l becomes that opcode for apply, r0 the
; global's offset, r3 the value; r1 moves on only once the instruction is known to end before the code does. Every
; form is checked for four bytes and one more byte code after them (a k8 form with exactly one byte after it runs
; through run_slow(), as any other opcode that comes here). 0x48 (x++) is decoded here, the others at decode.
gform:	mov.w	r1,r3
	adds	#2,r3
	adds	#2,r3
	cmp.w	r2,r3
	bcc	sslow
	mov.b	@(1,r1),r0l		; g
	mov.b	@(2,r1),r3l		; k8, the word's high byte, or T
	sub.b	r3h,r3h
	cmp.b	#RF_SW_SUM_GB,r4l
	bne	gdec
	mov.b	#RF_OP_SUM_VAR,r4l
	adds	#2,r1
	adds	#1,r1
gref:	mov.b	#0,r0h			; the global at @(RF_GLOBAL,r0)
	add.w	r0,r0
	add.w	r6,r0
	bra	apply
gdec:	.word	0x5A00,decode		; jmp @decode
sslow:	.word	0x5A00,slow		; jmp @slow
#endif

sjump:	mov.w	r1,r3
	adds	#1,r3			; the distance's field
	cmp.w	r2,r3
	bcc	slow			; not in the code
	mov.b	@r3,r0l
	bmi	back
	add.b	r0l,r3l
	addx	#0,r3h
	cmp.w	r2,r3
	bcc	slow			; to the end or past it
	mov.w	r3,r1
	dec	r4h
	bne	dispatch
	bra	leave
back:	and.b	#0x7F,r0l
	sub.b	r0l,r3l
	subx	#0,r3h
	mov.w	@(F_CODE,r7),r0
	cmp.w	r0,r3
	bcs	slow			; before the start
	mov.w	r3,r1
done:	dec	r4h
	bne	dispatch		; a lone task runs on

leave:	mov.w	@(F_CODE,r7),r0		; the turn is over: the task's pc
	sub.w	r0,r1
	mov.w	r1,@(RF_PC,r5)
	mov.b	@(F_OBJ,r7),r4l
	mov.w	@(F_LEFT,r7),r0
	beq	over			; count run
	mov.w	@(F_MASK,r7),r3
	beq	1f
	.word	0x5A00,next		; jmp @next: more running tasks after this one
1:	mov.b	@(RF_YIELD,r6),r0l	; the end of a round
	bne	over
	mov.w	@(RF_RUNMASK,r6),r0	; a lone task runs on from here
	mov.w	r0,r3
	subs	#1,r0
	and.b	r3l,r0l
	and.b	r3h,r0h
	mov.w	r0,r0
	bne	2f
	.word	0x5A00,alone		; jmp @alone
2:	.word	0x5A00,round0		; jmp @round0

slow:	mov.w	@(F_CODE,r7),r0		; the task's pc where the byte code is
	sub.w	r0,r1
	mov.w	r1,@(RF_PC,r5)
	mov.b	@(F_OBJ,r7),r4l
ended:	mov.w	r5,r1			; run_slow(b, t, &b->obj_start[object])
	mov.w	@(F_AT,r7),r2
	mov.w	r6,r0
	.word	0x5E00,_run_slow	; jsr @_run_slow (r4-r6 survive it)
	dec	r4h
	mov.w	@(F_LEFT,r7),r0
	add.b	r4h,r0l			; all that is left
	addx	#0,r0h
	mov.w	r0,@(F_LEFT,r7)
	sub.b	r4h,r4h
	mov.w	r0,r0
	beq	over
	mov.w	@(RF_RUNMASK,r6),r0
	beq	over			; nothing runs any more
	mov.b	@(RF_YIELD,r6),r0l
	bne	over
	mov.b	@(F_BASE,r7),r0l	; on with the running tasks after n, as they are now
	mov.b	r4l,r1l
	sub.b	r0l,r1l
	inc	r1l
	.word	0x5A00,round		; jmp @round

over:	inc	r4l			; b->rr: the task after this one
	mov.w	@r7+,r0			; F_CODE
	mov.w	@r7+,r0			; F_AT
	mov.w	@r7+,r0			; F_MASK
	mov.w	@r7+,r0			; F_BASE
	sub.b	r0h,r4l
	mov.b	r4l,@(RF_RR,r6)
	mov.w	@r7+,r0			; F_LEFT
	add.b	r4h,r0l			; the byte codes left
	addx	#0,r0h
	mov.w	@r7+,r6
	mov.w	@r7+,r5
	mov.w	@r7+,r4
	rts

#if RCX_SWAN
; The rest of Swan's global forms (gform): 0x49 0xC8 0xC9 and 0x2B-0x2D, and any other opcode, which goes to run_slow().
decode:	mov.b	r4l,r0h			; the opcode
	mov.b	#RF_OP_SET_VAR,r4l	; 0x2B 0x2C 0x2D: SetVar
	cmp.b	#RF_SW_SET_GB,r0h
	beq	k8
	cmp.b	#RF_SW_SET_G,r0h
	beq	src
	cmp.b	#RF_SW_SET_GW,r0h
	beq	word
	mov.b	#RF_OP_SUM_VAR,r4l	; 0x49 0xC8 0xC9: the low bit subtracts (SubVar 0x34 is SumVar 0x24 + 0x10),
	bld	#0,r0h			; bit 7 takes a source
	bst	#4,r4l
	bclr	#0,r0h
	cmp.b	#RF_SW_SUM_GB,r0h
	beq	k8
	cmp.b	#RF_SW_SUM_G,r0h
	beq	src
dslow:	.word	0x5A00,slow		; jmp @slow
word:	mov.b	r3l,r3h			; the word, high byte first
	mov.b	@(3,r1),r3l
	bra	gnext
src:	mov.b	r3l,r0h			; T, and v8 (r3h is 0)
	mov.b	@(3,r1),r3l
	cmp.b	#RF_SRC_CONST,r0h
	beq	gnext
	cmp.b	#RF_SRC_GLOBAL,r0h
	bne	dslow
	add.w	r3,r3
	add.w	r6,r3
	mov.w	@(RF_GLOBAL,r3),r3
gnext:	adds	#1,r1			; four bytes
k8:	adds	#2,r1			; three bytes
	adds	#1,r1
	.word	0x5A00,gref		; jmp @gref
#endif
