; SPDX-License-Identifier: MPL-2.0
; The unpacker of the firmware download (format: drivers/pack/pack.h; the packer and its reference unpacker:
; drivers/pack/pack.c). It is no part of the running image: drivers/pack/rcxpack.c downloads it right after the
; knock string, at _rcx_head_end, where crt0.s's `bra` from the entry lands, and the packed rest of the image right
; after it. It copies itself to its own addresses on-chip (linker/openrcx.ld: the part of the stack no code uses
; before main), as the unpacked image overwrites the place it was downloaded to; moves the packed bytes up; unpacks
; them to _rcx_head_end - image end; and jumps to _rcx_head_end, the start-up code (crt0.s) the image begins with.
; Interrupts are masked (crt0.s's first instruction).

	.section .unpack,"x"
	.global	_rcx_unpacker
	.global	_rcx_unpack

_rcx_unpacker:
	mov.w	#_rcx_standby_stub+16,r7 ; a stack for its calls (FD80-FD8F), as crt0.s's
	mov.w	#_rcx_head_end,r5	; where this section was downloaded
	mov.w	#_rcx_unpacker,r6
0:	mov.w	@r5+,r0			; words: both ends are even (linker/openrcx.ld)
	mov.w	r0,@r6
	adds	#2,r6
	cmp.b	#_rcx_unpacker_end_lo,r6l ; the section is shorter than 256 bytes
	bne	0b			; r5 then = _rcx_packed_start
	.word	0x5A00,1f		; jmp @1f to the copy; as data, so that ld --relax does not make it a bra (to here)

1:	; Move the downloaded bytes after this section up by F000 - C000, as if the largest download (16 384 bytes,
	; up to _rcx_download_end) had been loaded so that it ends at F000: unpacking from _rcx_head_end up then stays
	; behind the packed bytes it has still to read (rcxpack checks that it does, for each image). Words, from the
	; top down, as the two ranges overlap. Never above EFFF: from F000 on, every write also hits the motor latch.
	mov.w	r5,r2
	mov.w	#_rcx_download_end,r0
	mov.w	#_rcx_ram_end,r5
2:	subs	#2,r0
	mov.w	@r0,r3
	mov.w	r3,@-r5
	cmp.w	r2,r0
	bne	2b
	mov.w	#_rcx_head_end,r6
	mov.w	#_rcx_image_end,r1
	mov.b	#0x80,r3l		; no bits yet

; Unpacks from r5 to r6 up to r1 (r3l = 0x80), then starts the image. r4l counts the bytes of an item less one.
_rcx_unpack:
	bsr	8f
	bcs	4f
	mov.b	@r5+,r2l		; 0, byte: a literal
	sub.b	r4l,r4l
	bra	5f
4:	bsr	7f			; 1, G(g), byte b, G(v): v+1 bytes from 256*g - b bytes back
	mov.b	r4l,r0h
	neg.b	r0h
	mov.b	@r5+,r0l
	add.w	r6,r0
	bsr	7f
3:	mov.b	@r0+,r2l
5:	mov.b	r2l,@r6
	adds	#1,r6
	add.b	#0xFF,r4l		; carry while r4l was not 0
	bcs	3b
	cmp.w	r1,r6
	bne	_rcx_unpack
	jmp	@_rcx_head_end

; r4l = the next interlaced Elias gamma number: after its leading 1, a 0 before each of its bits, and a 1 at the end.
7:	mov.b	#1,r4l
6:	bsr	8f
	bcs	9f
	bsr	8f
	rotxl.b	r4l
	bra	6b

; C = the next bit. r3l holds the bits left above a 1 that marks their end: when only that marker is left, the
; next byte comes in, with the marker shifted back in at bit 0.
8:	shll.b	r3l
	bne	9f
	mov.b	@r5+,r3l
	rotxl.b	r3l
9:	rts
	.align	1
