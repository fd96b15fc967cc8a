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

static struct hw_rx rx RCX_ONCHIP; /* on-chip: the receive interrupts come 240 times a second */
static volatile u8 tx_head, tx_tail, tx_active;
static volatile u8 tx_buf[TX_SIZE]; /* volatile: filled before the head moves, read by the interrupt */
static u8 mode_now;

void rcx_rxi_isr(void);
void rcx_eri_isr(void);
void rcx_txi_isr(void);
void rcx_tei_isr(void);

void rcx_rxi_isr(void)
{
    u8 byte = SCI_RDR;

    SCI_SSR &= (u8)~SCI_SSR_RDRF;
    hw_rx_put(&rx, byte, 0);
}

/* Parity, framing or overrun error: the byte is passed on marked, so that the IR layer drops its packet. */
void rcx_eri_isr(void)
{
    u8 byte = SCI_RDR;

    SCI_SSR &= (u8)~(SCI_SSR_ERRORS | SCI_SSR_RDRF);
    hw_rx_put(&rx, byte, 1);
}

void rcx_txi_isr(void)
{
    u8 t = tx_tail;

    if (t == tx_head) { /* all handed over: wait for the last one to leave */
        SCI_SCR = (u8)((SCI_SCR & ~SCI_SCR_TIE) | SCI_SCR_TEIE);
        return;
    }
    SCI_TDR = tx_buf[t & (TX_SIZE - 1)];
    tx_tail = (u8)(t + 1);
    tx_active = 1; /* set here too, so an end-of-transmission interrupt left over from before cannot clear it */
    SCI_SSR &= (u8)~SCI_SSR_TDRE;
}

void rcx_tei_isr(void)
{
    SCI_SCR &= (u8)~SCI_SCR_TEIE;
    tx_active = 0;
}

void sci_start(u8 mode)
{
    struct hw_carrier c;
    u16 i;

    SCI_SCR = 0;
    SCI_SMR = SCI_SMR_8O1; /* async: CKE stays 00, otherwise SCK would drive P5.2, the RAM power-save line */
    SCI_BRR = hw_sci_brr(mode);
    hw_carrier(mode, &c);
    TMR1_TCR = 0;
    TMR1_TCORA = c.tcora;
    TMR1_TCORB = c.tcorb;
    TMR1_TCSR = c.tcsr;
    TMR1_TCNT = 0;
    H8_STCR &= (u8)~0x02; /* ICKS1 = 0: TMR1 counts φ/8 */
    TMR1_TCR = c.tcr;     /* the carrier runs all the time; the LED only lights while TxD is low */
    RCX_RAMVEC(RCX_VEC_ERI) = (u16)(unsigned)rcx_eri_irq;
    RCX_RAMVEC(RCX_VEC_RXI) = (u16)(unsigned)rcx_rxi_irq;
    RCX_RAMVEC(RCX_VEC_TXI) = (u16)(unsigned)rcx_txi_irq;
    RCX_RAMVEC(RCX_VEC_TEI) = (u16)(unsigned)rcx_tei_irq;
    SCI_SSR &= (u8)~(SCI_SSR_ERRORS | SCI_SSR_RDRF);
    for (i = 0; i < 300; i++) /* one bit time (417 µs) with the new rate before enabling, as the SCI requires */
        __asm__ __volatile__("");
    /* TE stays on: TxD then idles high, and the LED dark, while the carrier runs. */
    SCI_SCR = SCI_SCR_TE | SCI_SCR_RE | SCI_SCR_RIE;
    mode_now = mode;
}

void sci_stop(void)
{
    SCI_SCR = 0;
    TMR1_TCR = 0;
    TMR1_TCSR = 0;
    tx_head = tx_tail;
    tx_active = 0;
}

u8 hal_ir_busy(struct rcx *b)
{
    (void)b;
    return (u8)(tx_head != tx_tail || tx_active);
}

void hal_ir_send(struct rcx *b, const u8 *data, u8 len, u8 mode)
{
    mode &= HAL_IR_4800 | HAL_IR_76KHZ | HAL_IR_DUTY25;
    if (mode != mode_now) {
        while (hal_ir_busy(b))
            ;
        sci_start(mode);
    }
    while (len--) {
        while ((u8)(tx_head - tx_tail) >= TX_SIZE)
            ; /* the transmit interrupt makes room */
        tx_buf[tx_head & (TX_SIZE - 1)] = *data++;
        tx_head++;
        H8_BSET(7, 0xda); /* SCR.TIE: one instruction, as the handlers change SCR too */
    }
}

void hal_ir_range(struct rcx *b, u8 far)
{
    (void)b;
    if (far)
        H8_BCLR(0, 0xb7); /* P4.0 = 0: long range */
    else
        H8_BSET(0, 0xb7);
}

/* Another mode is for one transmission (a program's serial packet); the host talks at the default settings. */
void sci_service(void)
{
    if (mode_now && !hal_ir_busy(0))
        sci_start(0);
}

void sci_drain(struct rcx_brick *k)
{
    u8 byte, got;

    while ((got = hw_rx_get(&rx, &byte)) != 0)
        rt_ir_byte(k, byte, (u8)(got == 2));
}
