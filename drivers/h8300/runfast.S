; The brick's loop for several running tasks: one byte code per running task in turn, as vm_run() would run them,
; for the byte codes run_task()'s fast path handles (vm/interp.c): SJump, and SetVar/SumVar/SubVar with a constant
; or a global variable as the source. gcc 3.4 cannot keep a task switch in registers; here it costs a look-up of the
; task's code object and a few instructions. Any other byte code, or an irregular one (a truncated instruction, a
; jump reaching the end of the code or leaving it, an operand out of range), is left untouched to run_task().
;
; u16 rcx_run_fast(struct rcx *b, u16 count)
;   count 1-255; b->runmask has at least two tasks and stays as it is (none of these byte codes changes it).
;   Visits the running tasks from task b->rr on, round after round, and stops
;   - after `count` byte codes, or after the last running task of a round once b->yield is set: b->rr is then the
;     task after the last one run, as vm_run() leaves it; returns the byte codes left of count (high byte 0);
;   - at a running task whose byte code it leaves to run_task(): b->rr is then that task (vm_run()'s search finds
;     it first); returns 0x100 + the byte codes left.
; Meant for .high (F000 up: as fast, and no program memory), where it does not fit yet: in .text for now.
;
; Registers: r6 = b, r5 = the task, r4l = its code object's number in the task's own body (prog * 18 + 8 + n),
; r4h = byte codes left, r3 = runmask >> n (then >> n + 1), @r7's byte = prog * 18 + 8 (task 0's body).
; Only relative branches: ld --relax rewrites no instruction here (see unpack.s).

#include "runfast.h"

	.section .text
	.global	_rcx_run_fast

_rcx_run_fast:
	mov.w	r4,@-r7
	mov.w	r5,@-r7
	mov.w	r6,@-r7
	mov.w	r0,r6
	mov.b	r1l,r4h
	mov.b	@(RF_PROG,r6),r0l
	mov.b	#RF_SLOT_OBJS,r0h
	mulxu.b	r0h,r0
	add.b	#RF_SUBS,r0l
	mov.b	r0l,r0h
	mov.w	r0,@-r7			; its high byte: task 0's code object
	mov.b	@(RF_RR,r6),r1l		; tasks to pass over in the first round
	bra	round
round0:	sub.b	r1l,r1l
round:	mov.b	@r7,r4l
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

insub:	mov.b	@r7,r1l			; a subroutine: prog * 18 + sub
	add.b	#-RF_SUBS,r1l
	add.b	r1l,r0l
	bra	object

visit:	mov.b	@(RF_SUB,r5),r0l
	cmp.b	#RF_NO_SUB,r0l
	bne	insub
	mov.b	r4l,r0l
object:	mov.b	#0,r0h
	add.w	r0,r0
	add.w	r6,r0			; &b->obj_start[object]
	mov.w	@r0+,r1			; where its code starts in the arena
	mov.w	@r0,r2			; and ends
	sub.w	r1,r2
	mov.w	@(RF_PC,r5),r0
	sub.w	r0,r2			; bytes from the opcode to the end
	bls	slow			; none: run_task() ends the code
	add.w	r0,r1
	add.w	r6,r1			; the opcode at @(RF_ARENA,r1)
	mov.b	r2h,r2h
	beq	1f
	mov.b	#0xFF,r2l		; 255 or more: the same to the tests below
1:	mov.b	@(RF_ARENA,r1),r2h
	and.b	#~RF_TOGGLE,r2h
	cmp.b	#RF_OP_SUM_VAR,r2h
	beq	var
	cmp.b	#RF_OP_SJUMP,r2h
	beq	sjump
	cmp.b	#RF_OP_SET_VAR,r2h
	beq	var
	cmp.b	#RF_OP_SUB_VAR,r2h
	beq	var
slow:	mov.b	#1,r1h			; b->rr: this task
out:	mov.w	@r7+,r0
	sub.b	r0h,r4l
	mov.b	r4l,@(RF_RR,r6)
	mov.b	r4h,r0l
	mov.b	r1h,r0h
	mov.w	@r7+,r6
	mov.w	@r7+,r5
	mov.w	@r7+,r4
	rts

sjump:	dec	r2l			; bytes from the distance to the end
	beq	slow
	mov.b	@(RF_ARENA+1,r1),r1l
	bmi	back
	cmp.b	r2l,r1l
	bcc	slow			; to the end or past it
	adds	#1,r0
	mov.b	#0,r1h
	add.w	r1,r0
	bra	jumped
back:	and.b	#0x7F,r1l
	mov.b	#0,r1h
	adds	#1,r0
	sub.w	r1,r0
	bcs	slow			; before the start
jumped:	mov.w	r0,@(RF_PC,r5)

done:	dec	r4h
	beq	over
	mov.w	r3,r3
	beq	1f
	.word	0x5A00,next		; jmp @next: more running tasks after this one (out of a branch's reach; as
					; data, so that ld --relax leaves it alone)
1:	mov.b	@(RF_YIELD,r6),r0l
	bne	over
	.word	0x5A00,round0		; jmp @round0
over:	inc	r4l			; b->rr: the task after this one
	sub.b	r1h,r1h
	bra	out

var:	cmp.b	#6,r2l			; v op= source: 5 bytes, and the code goes on after them
	bcs	slow
	mov.b	@(RF_ARENA+1,r1),r2l	; the variable
	cmp.b	#RF_GLOBALS+RF_LOCALS,r2l
	bcc	slow
	mov.b	@(RF_ARENA+3,r1),r0l
	mov.b	@(RF_ARENA+4,r1),r0h
	mov.b	@(RF_ARENA+2,r1),r1l	; the source
	cmp.b	#RF_SRC_CONST,r1l
	beq	1f			; the constant
	cmp.b	#RF_SRC_VAR,r1l
	bne	slow
	mov.b	r0h,r0h
	bne	slow
	cmp.b	#RF_GLOBALS,r0l
	bcc	slow
	add.w	r0,r0
	add.w	r6,r0
	mov.w	@(RF_GLOBAL,r0),r0	; a global variable's value
1:	mov.w	@(RF_PC,r5),r1		; it runs: the pc moves on
	add.b	#5,r1l
	addx	#0,r1h
	mov.w	r1,@(RF_PC,r5)
	mov.b	r2l,r1l
	mov.b	#0,r1h
	add.w	r1,r1
	cmp.b	#2*RF_GLOBALS,r1l
	bcc	local
	add.w	r6,r1			; the variable at @(RF_GLOBAL,r1)
apply:	cmp.b	#RF_OP_SET_VAR,r2h
	beq	1f			; SetVar: the value itself
	cmp.b	#RF_OP_SUM_VAR,r2h
	beq	2f
	not	r0l			; SubVar: v + (0 - value), as run_task()
	not	r0h
	adds	#1,r0
2:	mov.w	@(RF_GLOBAL,r1),r2
	add.w	r2,r0
1:	mov.w	r0,@(RF_GLOBAL,r1)
	bra	done
local:	add.w	r5,r1			; t + RF_LOCAL + 2 * (v - 32), less RF_GLOBAL
	add.b	#(RF_LOCAL-2*RF_GLOBALS-RF_GLOBAL)&0xFF,r1l
	addx	#((RF_LOCAL-2*RF_GLOBALS-RF_GLOBAL)>>8)&0xFF,r1h
	bra	apply
