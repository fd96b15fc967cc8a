/* SPDX-License-Identifier: MPL-2.0 */
/* Host disassembler in the style of `nqc -L`, driven by the layout column of rcx_opcodes.def. */
#ifndef RCX_DISASM_H
#define RCX_DISASM_H

#include <stdio.h>
#include "rcx_types.h"

/* Format the instruction at code[pc] into buf (mnemonic and operands); returns its length in bytes,
 * or 0 when it is truncated by the end of the code. */
unsigned rcx_disasm_one(const u8 *code, unsigned size, unsigned pc, char *buf, size_t bufsize);

/* A whole code object, one line per instruction: offset, mnemonic and operands, hex bytes. */
void rcx_disasm_listing(FILE *out, const u8 *code, unsigned size);

#endif
