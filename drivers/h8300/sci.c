/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The IR link (rcx-hardware.md 3.8): the SCI at 2400 Bd 8O1 (or 4800) with the carrier from TMR1, both interrupt
 * driven. Received bytes, with an error mark, go into a ring the main loop drains into rt_ir_byte; the brick hears
 * its own transmission and those echoes are delivered too (the IR layer counts them). Transmission runs from a ring
 * filled by hal_ir_send.
 */
#include "runtime.h"
#include "hal.h"
#include "h8.h"
#include "drivers.h"

#define TX_SIZE 64 /* a power of two: a whole short reply; longer ones wait in hal_ir_send for room */

/* On-chip: the interrupts come 240 times a second; the indexes in the page of 8-bit addresses. */
struct hw_rx drv_rx RCX_ONCHIP;
static volatile u8 tx_head RCX_EIGHT, tx_tail RCX_EIGHT, tx_active RCX_EIGHT;
static volatile u8 tx_buf[TX_SIZE] RCX_ONCHIP; /* volatile: filled before the head moves, read by the interrupt */
/* The slot of free-running index i. A u8 offset added to the array: then gcc addresses it as @(tx_buf, reg), 4 bytes
 * less than for tx_buf[i & (TX_SIZE - 1)]. */
#define TX_SLOT(i) (*(tx_buf + (u8)((i) & (TX_SIZE - 1))))
u8 drv_sci_mode RCX_EIGHT;

/*
 * All four SCI interrupts. A received byte comes first; a parity, framing or overrun error passes it on marked,
 * so that the IR layer drops its packet. Otherwise the transmitter: with TIE set, the transmit data register is
 * empty (end of transmission implies it too); with TIE clear, only the end of transmission can have called.
 * Each entry serves one cause; the CPU comes back at once for another that is pending.
 */
void rcx_sci_isr(void)
{
    u8 ssr = SCI_SSR, t;

    if ((u8)(ssr << 1) >= 0x10) { /* any of RDRF, ORER, FER and PER: bits 6-3, shifted up to 7-4 */
        t = SCI_RDR;
        SCI_SSR &= (u8)~(SCI_SSR_ERRORS | SCI_SSR_RDRF);
        hw_rx_put(&drv_rx, t, (u8)(ssr & SCI_SSR_ERRORS)); /* any error bit: non-zero */
        drv_woken = 1;
        drv_yield = 1;
        return;
    }
    if (!(SCI_SCR & SCI_SCR_TIE)) { /* transmission ended */
        H8_BCLR(2, 0xda); /* SCR.TEIE */
        tx_active = 0;
        return;
    }
    t = tx_tail;
    if (t == tx_head) { /* all handed over: wait for the last one to leave */
        SCI_SCR = (u8)((SCI_SCR & ~SCI_SCR_TIE) | SCI_SCR_TEIE);
        return;
    }
    SCI_TDR = TX_SLOT(t);
    tx_tail = (u8)(t + 1);
    tx_active = 1; /* set here too, so an end-of-transmission interrupt left over from before cannot clear it */
    H8_BCLR(7, 0xdc); /* SSR.TDRE: read as 1 and written 0 */
}

void sci_start(u8 mode)
{
    u16 i;
    u8 tcr;

    SCI_SCR = 0;
    SCI_SMR = SCI_SMR_8O1; /* async: CKE stays 00, otherwise SCK would drive P5.2, the RAM power-save line */
    SCI_BRR = hw_sci_brr(mode);
    /* TMR1's TCR, TCSR, TCORA and TCORB are consecutive, in the order of struct hw_carrier: the settings go
     * straight in. The timer then starts again from 0 (TxD idles high meanwhile: the LED stays dark). */
    hw_carrier(mode, (struct hw_carrier *)(unsigned)0xFFD0);
    tcr = TMR1_TCR;
    TMR1_TCR = 0;
    TMR1_TCNT = 0;
    H8_BCLR(1, 0xc3);     /* STCR.ICKS1 = 0: TMR1 counts φ/8 */
    TMR1_TCR = tcr;       /* the carrier runs all the time; the LED only lights while TxD is low */
    RCX_RAMVEC(RCX_VEC_ERI) = (u16)(unsigned)rcx_sci_irq;
    RCX_RAMVEC(RCX_VEC_RXI) = (u16)(unsigned)rcx_sci_irq;
    RCX_RAMVEC(RCX_VEC_TXI) = (u16)(unsigned)rcx_sci_irq;
    RCX_RAMVEC(RCX_VEC_TEI) = (u16)(unsigned)rcx_sci_irq;
    SCI_SSR &= (u8)~(SCI_SSR_ERRORS | SCI_SSR_RDRF);
    /* One bit time at the new rate (417 µs at 2400 Bd) before enabling, as the SCI requires. A pass is adds, cmp.w
     * and bls from external RAM: 24 states (three words fetched on the 8-bit bus, the branch fetching one more),
     * 510 µs, and 425 µs even at the 20 states a pass that the issue counted (the 300 passes before: 450, 375 µs).
     * tests/drivers/test_h8machine.c measures the whole wait from the write to BRR. */
    for (i = 0; i < 340; i++)
        __asm__ __volatile__("");
    /* TE stays on: TxD then idles high, and the LED dark, while the carrier runs. */
    SCI_SCR = SCI_SCR_TE | SCI_SCR_RE | SCI_SCR_RIE;
    drv_sci_mode = mode;
}

RCX_HIGH_CODE void sci_stop(void)
{
    SCI_SCR = 0;
    TMR1_TCR = 0;
    TMR1_TCSR = 0;
    tx_head = tx_tail;
    tx_active = 0;
}

RCX_HIGH_CODE u8 hal_ir_busy(struct rcx *b)
{
    (void)b;
    return (u8)((u8)(tx_head ^ tx_tail) | tx_active); /* non-zero: busy (hal.h) */
}

void hal_ir_send(struct rcx *b, const u8 *data, u8 len, u8 mode)
{
    (void)b;
    mode &= HAL_IR_4800 | HAL_IR_76KHZ | HAL_IR_DUTY25;
    if (mode != drv_sci_mode) {
        while (hal_ir_busy(0))
            ;
        sci_start(mode);
    }
    while (len--) {
        u8 h = tx_head;

        while ((u8)(h - tx_tail) >= TX_SIZE)
            ; /* the transmit interrupt makes room */
        TX_SLOT(h) = *data++;
        tx_head = (u8)(h + 1);
        H8_BSET(7, 0xda); /* SCR.TIE: one instruction, as the handlers change SCR too */
    }
}

RCX_HIGH_CODE void hal_ir_range(struct rcx *b, u8 far)
{
    (void)b;
    if (far)
        H8_BCLR(0, 0xb7); /* P4.0 = 0: long range */
    else
        H8_BSET(0, 0xb7);
}

/* Another mode is for one transmission (a program's serial packet); the host talks at the default settings. */
RCX_HIGH_CODE void sci_service(void)
{
    if (drv_sci_mode && !hal_ir_busy(0))
        sci_start(0);
}

void sci_drain(struct rcx_brick *k)
{
    static u8 byte RCX_EIGHT;
    u8 got;

    while ((got = hw_rx_get(&drv_rx, &byte)) != 0)
        rt_ir_byte(k, byte, (u8)(got - 1)); /* 2: with an error */
}
