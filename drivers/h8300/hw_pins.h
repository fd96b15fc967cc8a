/* SPDX-License-Identifier: MPL-2.0 */
/* LCD bus pins on the brick: P6.5 = SCL, P6.6 = SDA (P6DR = FFBB), one atomic instruction each. */
#ifndef RCX_HW_PINS_H
#define RCX_HW_PINS_H

#include "h8.h"

#define HW_SCL_LO() H8_BCLR(5, 0xbb)
#define HW_SDA_HI() H8_BSET(6, 0xbb)
#define HW_SDA_LO() H8_BCLR(6, 0xbb)
/* SDA = bit 7 of the byte variable v, and v shifted left by one: the bit goes through the carry. */
#define HW_SDA_MSB(v) __asm__ __volatile__("shll.b\t%X0\n\tbst\t#6,@0xbb:8" : "+r"(v) : : "memory", "cc")

/*
 * SCL high at the pace of standard-mode I2C (rcx-hardware.md §3.6): not before it has been low 4.7 µs, and held
 * high 4.0 µs before the caller's next pin change. A call to scl_up (HW_LCD_HELPER), which touches no register, so
 * that hw_lcd_send stays a function that calls nothing for gcc. From external RAM, states: the caller's bclr, its
 * loop (add, bne: 18), shll 6, bst 18, bsr 14, 2 nops 12, bset 18: SCL low 86 states, 5.4 µs; then 2 nops 12, the
 * bsr to its own rts 14 + 16, that rts again 16, the caller's bclr or bset 18: SCL high 76 states, 4.75 µs. The bsr
 * to the next instruction is the densest delay without a register: 30 states in 2 bytes.
 */
#define HW_SCL_HI_PACED() __asm__ __volatile__("bsr\tscl_up" ::: "memory")
#define HW_LCD_HELPER                                                                                              \
    __asm__("\t.text\n"                                                                                            \
            "scl_up:\tnop\n\tnop\n\tbset\t#5,@0xbb:8\n\tnop\n\tnop\n\tbsr\t1f\n1:\trts");

#endif
