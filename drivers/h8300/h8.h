/*
 * H8/3292 on-chip registers and RCX RAM locations used by the drivers (rcx-hardware.md 1.4, 1.6, 3.9).
 * 16-bit registers go through a temporary latch: access them as words only.
 */
#ifndef RCX_H8_H
#define RCX_H8_H

#include "rcx_types.h"

#define H8_REG8(addr) (*(volatile u8 *)(addr))
#define H8_REG16(addr) (*(volatile u16 *)(addr))

/* Free-running timer (FRT). */
#define FRT_TIER H8_REG8(0xFF90)  /* interrupt enables */
#define FRT_TCSR H8_REG8(0xFF91)  /* flags (write 0 after reading 1 to clear), CCLRA */
#define FRT_FRC H8_REG16(0xFF92)  /* counter */
#define FRT_OCR H8_REG16(0xFF94)  /* OCRA or OCRB, as TOCR.OCRS selects */
#define FRT_TCR H8_REG8(0xFF96)   /* clock select */
#define FRT_TOCR H8_REG8(0xFF97)  /* output compare control */

#define FRT_TIER_OCIAE 0x08
#define FRT_TCSR_OCFA 0x08
#define FRT_TCSR_CCLRA 0x01
#define FRT_TCR_CLK_DIV32 0x02    /* 16 MHz / 32 = 500 kHz */
#define FRT_TOCR_OCRS 0x10

/* System. */
#define H8_SYSCR H8_REG8(0xFFC4)
#define H8_SYSCR_SSBY 0x80        /* SLEEP would enter software standby; the ROM leaves it set */
#define H8_IER H8_REG8(0xFFC7)    /* IRQ0-2 enables */

/* RAM interrupt-vector table read by the ROM's trampolines: one word per source, holding the
 * address of a subroutine (ending in rts; see irq.s). */
#define RCX_RAMVEC(addr) H8_REG16(addr)
#define RCX_VEC_OCIA 0xFDA2       /* FRT compare match A */

/* Interrupt mask bit in CCR. */
#define h8_irq_enable() __asm__ __volatile__("andc\t#0x7f,ccr" ::: "memory")
#define h8_irq_disable() __asm__ __volatile__("orc\t#0x80,ccr" ::: "memory")

#endif
