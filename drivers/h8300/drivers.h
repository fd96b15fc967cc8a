/* What the brick's driver files share (drivers/h8300/). */
#ifndef RCX_DRIVERS_H
#define RCX_DRIVERS_H

#include "rcx_types.h"
#include "h8.h"
#include "hw.h"

struct rcx_brick;

/* main.c: the tick and A/D interrupt, and the button debouncer. */
extern struct hw_motors drv_motors; /* hal_motor writes, the tick interrupt reads */
extern u8 drv_sensor_power RCX_EIGHT; /* P6 bits of the inputs with active sensors */
void drv_tick_start(u8 irq);        /* FRT: 1 ms period; with irq, the tick interrupt and the A/D cycle run; the
                                     * buttons' present state is taken as the debounced one, without edges */
void drv_wait_ms(u8 ms);            /* busy wait on the FRT, interrupts masked or not */
void rcx_timer_isr(void);           /* FRT compare match A and A/D end */

/* sci.c: the IR link. */
void sci_start(u8 mode);            /* SCI and carrier for hal_ir_send's mode bits, receiver on */
void sci_stop(void);
void sci_service(void);             /* main loop: back to the default settings after another mode's transmission */
void sci_drain(struct rcx_brick *k); /* main loop: received bytes to the runtime */
void rcx_sci_isr(void);             /* byte received (with or without error), transmit data empty, sent */

/* hal.c: the other outputs. */
void drv_outputs_on(void);          /* ports, motors, speaker, LCD (with the image it showed), A/D, IR link */

/* irq.s: entry points for the RAM vector table, and the standby code copied to on-chip RAM. */
void rcx_irq_ignore(void);
void rcx_timer_irq(void);           /* FRT compare match A and A/D end: rcx_timer_isr */
void rcx_sci_irq(void);             /* the four SCI interrupts: rcx_sci_isr */
extern const u8 rcx_standby_code[];  /* 16 bytes */
void rcx_standby_stub(void);        /* linker/openrcx.ld: where the standby code runs (FD80) */

#endif
