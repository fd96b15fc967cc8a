/* The firmware image in the simulator (h8sim.h): its S-records, and its symbols as `nm` prints them. */
#ifndef H8IMAGE_H
#define H8IMAGE_H

#include "h8sim.h"

#define H8_SCRATCH 0xF800 /* spare RAM for arguments and results: not used by the image (the motor latch area) */

/* Load `image`.srec and the symbols of `image` (COFF) through the `nm` tool; clear .bss and the on-chip variables
 * and set the stack pointer as crt0.s does. 0 on success; on failure a message is printed. */
int h8_image_load(struct h8 *h, const char *image, const char *nm);
/* The address of a symbol (C name with its leading underscore), -1 if absent. */
long h8_sym(const char *name);
/* The function whose code holds `pc` (the nearest code symbol at or below it), "?" if none. */
const char *h8_func_at(uint16_t pc);
/* h8_call() of a symbol, exiting with a message when the simulator fails or the symbol is missing. */
long h8_run(struct h8 *h, const char *name, uint16_t r0, uint16_t r1, uint16_t r2, const uint16_t *stack, int nstack);

#endif
