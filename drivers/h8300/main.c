/*
 * OpenRCX on the brick: the byte-code machine driven by a 1 ms tick from the free-running timer.
 * Minimal for now: no IR, buttons, display, sensors or motors yet (they come with the full drivers).
 */
#include "rcx.h"
#include "h8.h"

static struct rcx brick;

/* Milliseconds counted by the compare-match interrupt; the main loop catches up with them. A word
 * access is one instruction, so reading it cannot be torn by the interrupt. */
static volatile u16 ms_ticks;

void rcx_frt_irq(void); /* irq.s: the entry point in the RAM vector table */
void rcx_frt_isr(void); /* called by rcx_frt_irq */
int main(void);         /* called by crt0.s */

void rcx_frt_isr(void)
{
    FRT_TCSR &= (u8)~FRT_TCSR_OCFA; /* read as 1, write 0: acknowledged */
    ms_ticks++;
}

/* FRT at 500 kHz, cleared on compare match A at 499: one interrupt per 500 counts = 1.000 ms. */
static void tick_start(void)
{
    FRT_TIER = 0;
    RCX_RAMVEC(RCX_VEC_OCIA) = (u16)(unsigned)rcx_frt_irq;
    FRT_TCR = FRT_TCR_CLK_DIV32;
    FRT_TOCR &= (u8)~FRT_TOCR_OCRS; /* FF94 addresses OCRA */
    FRT_OCR = 499;
    FRT_FRC = 0;
    (void)FRT_TCSR;                 /* a flag is only cleared by writing 0 after reading it as 1 */
    FRT_TCSR = FRT_TCSR_CCLRA;
    FRT_TIER = FRT_TIER_OCIAE;
}

int main(void)
{
    u16 seen;

    H8_SYSCR &= (u8)~H8_SYSCR_SSBY; /* a SLEEP must be a light sleep, not standby */
    vm_init(&brick, (u16)(unsigned)brick.arena);
    tick_start();
    seen = ms_ticks;
    h8_irq_enable();

    for (;;) {
        vm_run(&brick, 16);
        while (seen != ms_ticks) {
            seen++;
            vm_tick(&brick);
        }
    }
}
