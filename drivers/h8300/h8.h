/* SPDX-License-Identifier: MPL-2.0 */
/*
 * H8/3292 on-chip registers and RCX addresses used by the drivers (rcx-hardware.md 1.4, 1.6, 3).
 * 16-bit registers go through a temporary latch: access them as words only.
 * DDRs are write-only: every write goes through a shadow (drivers/h8300/hal.c).
 */
#ifndef RCX_H8_H
#define RCX_H8_H

#include "rcx_types.h"

#define H8_REG8(addr) (*(volatile u8 *)(addr))
#define H8_REG16(addr) (*(volatile u16 *)(addr))

/* Single-instruction bit set/clear on a register of page FFxx. gcc compiles `reg |= bit` as load, modify, store;
 * where an interrupt handler writes other bits of the same register, only bset/bclr cannot undo its change. */
#define H8_BSET(bit, addr) __asm__ __volatile__("bset\t#" #bit ",@" #addr ":8" ::: "memory")
#define H8_BCLR(bit, addr) __asm__ __volatile__("bclr\t#" #bit ",@" #addr ":8" ::: "memory")
/* A byte written to a register of page FFxx with 8-bit addressing: where a register is written twice, gcc keeps its
 * address in a register (4 bytes, and one more register to save) instead. */
#define H8_WRITE8(addr, v) __asm__ __volatile__("mov.b\t%X0,@" #addr ":8" ::"r"((u8)(v)) : "memory")

/* Free-running timer (FRT): the 1 ms tick. */
#define FRT_TIER H8_REG8(0xFF90)
#define FRT_TCSR H8_REG8(0xFF91)
#define FRT_FRC H8_REG16(0xFF92)
#define FRT_OCR H8_REG16(0xFF94)  /* OCRA or OCRB, as TOCR.OCRS selects */
#define FRT_TCR H8_REG8(0xFF96)
#define FRT_TOCR H8_REG8(0xFF97)
#define FRT_TIER_OCIAE 0x08
#define FRT_TCSR_OCFA 0x08
#define FRT_TCSR_CCLRA 0x01
#define FRT_TCR_CLK_DIV32 0x02    /* 16 MHz / 32 = 500 kHz */
#define FRT_TOCR_OCRS 0x10

/* Ports. P4: 0 IR range (out), 1 On-Off, 2 Run. P5: 0/1 SCI, 2 external RAM power-save. P6: 0-2 sensor power
 * (input 3, 2, 1), 3 kept high while awake, 4 speaker, 5 LCD SCL, 6 LCD SDA, 7 IR carrier. P7: 6 View, 7 Prgm. */
#define P4DDR H8_REG8(0xFFB5)
#define P4DR H8_REG8(0xFFB7)
#define P5DDR H8_REG8(0xFFB8)
#define P5DR H8_REG8(0xFFBA)
#define P6DDR H8_REG8(0xFFB9)
#define P6DR H8_REG8(0xFFBB)
#define P7PIN H8_REG8(0xFFBE)
#define P6_SENSORS 0x07
#define P6_AWAKE 0x08
#define P6_SPEAKER 0x10
#define P6_SCL 0x20
#define P6_SDA 0x40
#define P6_CARRIER 0x80

/* 8-bit timers: TMR0 = speaker, TMR1 = IR carrier. */
#define TMR0_TCR H8_REG8(0xFFC8)
#define TMR0_TCSR H8_REG8(0xFFC9)
#define TMR0_TCORA H8_REG8(0xFFCA)
#define TMR0_TCNT H8_REG8(0xFFCC) /* non-zero at a jump to the ROM's reset: come up awake (rcx-hardware.md 2.4) */
#define TMR1_TCR H8_REG8(0xFFD0)
#define TMR1_TCSR H8_REG8(0xFFD1)
#define TMR1_TCORA H8_REG8(0xFFD2)
#define TMR1_TCORB H8_REG8(0xFFD3)
#define TMR1_TCNT H8_REG8(0xFFD4)

/* System. */
#define H8_STCR H8_REG8(0xFFC3)   /* bit 0 ICKS0 (TMR0 clock), bit 1 ICKS1 (TMR1 clock) */
#define H8_SYSCR H8_REG8(0xFFC4)
#define H8_ISCR H8_REG8(0xFFC6)
#define H8_IER H8_REG8(0xFFC7)
#define H8_SYSCR_SSBY 0x80        /* SLEEP enters software standby; the ROM leaves it set */
#define H8_SYSCR_STS4 0x40        /* STS = 100: 131 072 states (8.2 ms) of oscillator settling on wake */
#define H8_IRQ1 0x02              /* On-Off */

/* SCI (IR link). */
#define SCI_SMR H8_REG8(0xFFD8)
#define SCI_BRR H8_REG8(0xFFD9)
#define SCI_SCR H8_REG8(0xFFDA)
#define SCI_TDR H8_REG8(0xFFDB)
#define SCI_SSR H8_REG8(0xFFDC)
#define SCI_RDR H8_REG8(0xFFDD)
#define SCI_SMR_8O1 0x30
#define SCI_SCR_TIE 0x80
#define SCI_SCR_RIE 0x40
#define SCI_SCR_TE 0x20
#define SCI_SCR_RE 0x10
#define SCI_SCR_TEIE 0x04
#define SCI_SSR_TDRE 0x80
#define SCI_SSR_RDRF 0x40
#define SCI_SSR_ERRORS 0x38       /* ORER, FER, PER */

/* A/D: ADDRA-D hold AN0-AN3 (inputs 3, 2, 1 and the battery). */
#define AD_ADDR(n) H8_REG16(0xFFE0 + 2 * (n))
#define AD_ADCSR H8_REG8(0xFFE8)
#define AD_ADCR H8_REG8(0xFFE9)
#define AD_ADF 0x80
#define AD_ADIE 0x40
#define AD_SCAN_AN0_AN3 0x33      /* ADST | SCAN | channels 0-3, 266 states each */

/* Motor latch: write-only, any address of FF80-FF87 (8-bit absolute addressing) reaches it. */
#define MOTOR_LATCH H8_REG8(0xFF80)

/* RAM interrupt-vector table read by the ROM's trampolines: the address of a subroutine ending in rts. */
#define RCX_RAMVEC(addr) H8_REG16(addr)
#define RCX_VEC_IRQ1 0xFD96
#define RCX_VEC_OCIA 0xFDA2
#define RCX_VEC_ERI 0xFDB4
#define RCX_VEC_RXI 0xFDB6
#define RCX_VEC_TXI 0xFDB8
#define RCX_VEC_TEI 0xFDBA
#define RCX_VEC_ADI 0xFDBC

#define h8_irq_enable() __asm__ __volatile__("andc\t#0x7f,ccr" ::: "memory")
#define h8_irq_disable() __asm__ __volatile__("orc\t#0x80,ccr" ::: "memory")
#define h8_sleep() __asm__ __volatile__("sleep" ::: "memory")

/* Placement in on-chip RAM (FDC0 up, below the stack): fast, and kept while external RAM sleeps. */
#define RCX_ONCHIP __attribute__((section(".onchip")))
/* Bytes in on-chip RAM at FF60-FF7F, above the stack: the page of the 8-bit absolute addresses, so that gcc reads
 * and writes them with 2-byte instructions instead of 4 (section .eight, linker/openrcx.ld). Cleared at start;
 * no initial values (the section is not downloaded). */
#define RCX_EIGHT __attribute__((eightbit_data))
/* Rarely run code, and its constants, placed with the code that runs at F000 (section .high, linker/openrcx.ld): it
 * costs no program memory there. Only for what runs after the start-up code has copied it up. */
#define RCX_HIGH_CODE __attribute__((section(".hitext")))
#define RCX_HIGH_DATA __attribute__((section(".hidata")))

#endif
