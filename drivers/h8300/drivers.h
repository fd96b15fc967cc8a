/* SPDX-License-Identifier: MPL-2.0 */
/* What the brick's driver files share (drivers/h8300/). */
#ifndef RCX_DRIVERS_H
#define RCX_DRIVERS_H

#include "rcx_types.h"
#include "h8.h"
#include "hw.h"

struct rcx_brick;

/* main.c: what the tick interrupt (irq.s) shares with the main loop, and the button debouncer. */
extern struct hw_motors drv_motors; /* hal_motor writes, the tick interrupt reads */
extern u8 drv_sensor_power RCX_EIGHT; /* P6 bits of the inputs with active sensors */
#define DRV_AD_SLOTS 8 /* scans the main loop may fall behind before samples are lost */
#define DRV_AD_SLOT 8  /* bytes of a scan: drv_ad_done counts in these, so that it is an offset in drv_ad_slot */
extern volatile u16 drv_ad_slot[DRV_AD_SLOTS][DRV_AD_SLOT / 2]; /* ADDRA-ADDRD (inputs 2, 1, 0, the battery) as
                                                                  the registers hold them (raw10 << 6) */
extern volatile u8 drv_ad_done RCX_EIGHT; /* scans stored, times DRV_AD_SLOT (modulo 256) */
extern volatile u8 drv_ad_seen RCX_EIGHT; /* scans fed to the runtime, times DRV_AD_SLOT */
extern volatile u8 drv_ms_ticks RCX_EIGHT; /* counted by the tick interrupt (modulo 256) */
extern volatile u8 drv_quiet RCX_EIGHT;    /* ticks the tick interrupt lets pass without ending the run */
extern volatile u8 drv_yield;              /* rcx.yield of the brick (main.c) */
extern volatile u8 drv_woken RCX_EIGHT;    /* set by an interrupt that left the main loop something to feed: a scan
                                              stored, a byte received (the main loop clears it) */
void drv_tick_start(u8 irq);        /* FRT: 1 ms period; with irq, the tick interrupt and the A/D cycle run; the
                                     * buttons' present state is taken as the debounced one, without edges */
void drv_wait_ms(u8 ms);            /* busy wait on the FRT, interrupts masked or not; ms at least 1 */

/* sci.c: the IR link. */
void sci_start(u8 mode);            /* SCI and carrier for hal_ir_send's mode bits, receiver on */
void sci_stop(void);
void sci_service(void);             /* main loop: back to the default settings after another mode's transmission */
void sci_drain(struct rcx_brick *k); /* main loop: received bytes to the runtime */
extern struct hw_rx drv_rx;          /* the receive ring */
extern u8 drv_sci_mode RCX_EIGHT;    /* the mode the SCI and carrier are set to */
void rcx_sci_isr(void);             /* byte received (with or without error), transmit data empty, sent */

/* hal.c: the other outputs. */
void drv_outputs_on(void);          /* ports, motors, speaker, LCD (with the image it showed), A/D, IR link */

/* irq.s: entry points for the RAM vector table, and the standby code copied to on-chip RAM. */
void rcx_irq_ignore(void);
void rcx_timer_irq(void);           /* FRT compare match A (the tick) */
void rcx_sci_irq(void);             /* the four SCI interrupts: rcx_sci_isr */
extern const u8 rcx_standby_code[];  /* 16 bytes */
void rcx_standby_stub(void);        /* linker/openrcx.ld: where the standby code runs (FD80) */

#endif
