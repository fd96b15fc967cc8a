/* SPDX-License-Identifier: MPL-2.0 */
/*
 * A small H8/300 instruction-set simulator for host tools: runs functions of the firmware image as the brick
 * would and counts the states they take. Peripherals are not modelled (their registers read back what was
 * written); an instruction it does not know stops it with a message instead of guessing.
 *
 * Timing model (after the H8/300 manual's scheme: states = instruction words fetched, data accesses and internal
 * states): every access costs what its address costs on the RCX (rcx-hardware.md 1.1): external RAM on the 8-bit
 * bus 3 states per byte, so 6 per instruction word or data word; on-chip RAM and ROM 2 per access (byte or word); the
 * on-chip registers 3 per byte, 6 per word (their field has an 8-bit bus too). A taken or untaken branch, a jump, call or return fetches one more word where it continues.
 * Internal states: 2 for jsr/jmp to an absolute address, returns, pushes and pops, 12 for mulxu and divxu.
 * Wait states: none. Interrupts are taken when a caller says so (h8_interrupt); h8machine.h models the peripherals
 * that request them.
 */
#ifndef H8SIM_H
#define H8SIM_H

#include <stdint.h>

struct h8 {
    uint16_t r[8];
    uint8_t ccr;
    uint16_t pc;
    uint8_t mem[65536];
    unsigned long long states, insns;
    char error[160];        /* set when the simulator stopped on something it cannot run */
    /* Called after each instruction with its address and the states it took (profiles), if set. */
    void (*trace)(struct h8 *h, uint16_t pc, unsigned states);
    /* Peripherals (h8machine.h), if set: what a read of register `a` (FF88-FFFF) returns, given what memory
     * holds; and a register just written (its old value `was`, the new one in mem). */
    uint8_t (*io_read)(struct h8 *h, uint16_t a, uint8_t held);
    void (*io_write)(struct h8 *h, uint16_t a, uint8_t was);
    /* If set: a byte written where the motor latch also takes it (F000-FB7F and FF80-FF87, rcx-hardware.md 1.1). */
    void (*latch_write)(struct h8 *h, uint8_t v);
    int may_sleep;          /* SLEEP sets asleep (for the caller to wake) instead of stopping with an error */
    int asleep;
    /* If set: external RAM (8000-FD7F) may only be read, written or fetched from while its power-save line P5.2 is
     * an output driven low (P5DDR FFB8 and P5DR FFBA bit 2, rcx-hardware.md 2.4, 3.1, 3.11): on a real brick it
     * answers garbage otherwise. The first access that breaks the rule is kept in ram_fault and stops the run. */
    int ram_guard;
    char ram_fault[160];
};

void h8_reset(struct h8 *h);
int h8_load_srec(struct h8 *h, const char *path);            /* 0 on success */
int h8_step(struct h8 *h);                                    /* 0 ok, -1 stopped (error set) */
int h8_step_traced(struct h8 *h);                             /* the same, then h->trace (if set) with its states */
void h8_interrupt(struct h8 *h, uint16_t handler);            /* the CPU's interrupt exception, to `handler` */
/* Call the function at `addr` with r0-r2 as gcc passes its first arguments and `nstack` words pushed after
 * them (stack[0] nearest the return address); runs until it returns, at most `max_insns`. Returns r0, or -1 in
 * h->error set on failure. */
long h8_call(struct h8 *h, uint16_t addr, uint16_t r0, uint16_t r1, uint16_t r2,
             const uint16_t *stack, int nstack, unsigned long max_insns);
uint16_t h8_read16(const struct h8 *h, uint16_t a);
void h8_write16(struct h8 *h, uint16_t a, uint16_t v);

#endif
