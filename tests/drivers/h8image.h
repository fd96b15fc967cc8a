/* SPDX-License-Identifier: MPL-2.0 */
/* The firmware image in the simulator (h8sim.h): its S-records, and its symbols as `nm` prints them. */
#ifndef H8IMAGE_H
#define H8IMAGE_H

#include "h8sim.h"

/* Spare RAM for arguments and results, 512 bytes: not used by the image (FB80-FD7F, reserved on the brick; the
 * image's section .high runs in F000-FB7F). */
#define H8_SCRATCH 0xFB80

/* Load `image`.srec and the symbols of `image` (COFF) through the `nm` tool, then start it: h8_image_start().
 * 0 on success; on failure a message is printed. */
int h8_image_load(struct h8 *h, const char *image, const char *nm);
/* Only the loading: the bytes of `image`.srec at their load addresses, as the ROM leaves them, and the symbols. */
int h8_image_read(struct h8 *h, const char *image, const char *nm);
/* The image's own start-up code, run from the entry as the ROM calls it until it calls main: the unpacker
 * (unpack.s) puts the image in place from the packed download, then crt0.s copies section .high to F000, zeroes
 * the motor latch, clears .bss and the on-chip variables. The stack pointer is then left at the top of the stack
 * (_rcx_stack_top), for h8_call(). 0 on success; on failure a message is printed. */
int h8_image_start(struct h8 *h);
/* The states the last h8_image_start() took from the entry until the unpacker had finished (0: it never did). */
extern unsigned long long h8_unpack_states;
/* The command line of a test of the image, <firmware image> <h8300 nm>: 0 with *image and *nm set, or 2 after a
 * usage message (the test's exit status). */
int h8_image_args(int argc, char **argv, const char **image, const char **nm);
/* The address of a symbol (C name with its leading underscore), -1 if absent. */
long h8_sym(const char *name);
/* The function whose code holds `pc` (the nearest code symbol at or below it), "?" if none. */
const char *h8_func_at(uint16_t pc);
/* h8_call() of a symbol, exiting with a message when the simulator fails or the symbol is missing. */
long h8_run(struct h8 *h, const char *name, uint16_t r0, uint16_t r1, uint16_t r2, const uint16_t *stack, int nstack);

#endif
