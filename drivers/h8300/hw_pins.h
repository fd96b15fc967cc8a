/* LCD bus pins on the brick: P6.5 = SCL, P6.6 = SDA (P6DR = FFBB), one atomic instruction each. */
#ifndef RCX_HW_PINS_H
#define RCX_HW_PINS_H

#include "h8.h"

#define HW_SCL_HI() H8_BSET(5, 0xbb)
#define HW_SCL_LO() H8_BCLR(5, 0xbb)
#define HW_SDA_HI() H8_BSET(6, 0xbb)
#define HW_SDA_LO() H8_BCLR(6, 0xbb)
/* SDA = bit 7 of the byte variable v, and v shifted left by one: the bit goes through the carry. */
#define HW_SDA_MSB(v) __asm__ __volatile__("shll.b\t%X0\n\tbst\t#6,@0xbb:8" : "+r"(v) : : "memory", "cc")

#endif
