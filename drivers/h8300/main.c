/*
 * OpenRCX on the brick: start-up, the main loop, and the two interrupts that keep time (rcx-hardware.md 3.2-3.5,
 * 3.9). Interrupt handlers only drive the motor latch, switch sensor power around the A/D scan and store results;
 * the main loop feeds everything to the runtime (src/runtime.h), which must never run inside an interrupt.
 */
#include "runtime.h"
#include "h8.h"
#include "drivers.h"

/* Byte codes per rt_run call: small enough that the loop comes back to the clock well within a millisecond. */
#define RUN_BUDGET 8

#define AD_SLOTS 4 /* scans the main loop may fall behind before samples are lost */

/* Milliseconds handled per main-loop pass, and the backlog at which time is given up: if the per-millisecond work
 * ever takes longer than a millisecond, byte codes and IR packets still get their turn and the clock runs slow,
 * instead of the loop catching up for ever. */
#define TICKS_PER_PASS 4
#define TICKS_BACKLOG 100

static struct rcx_brick brick;

/* Shared with interrupt handlers: on-chip RAM, where the handlers reach them in fewer states. */
static volatile u16 ms_ticks RCX_ONCHIP;             /* counted by the tick interrupt */
static volatile u8 ad_done RCX_ONCHIP;               /* scans completed by the A/D interrupt */
struct scan {
    u16 raw[4]; /* inputs 0-2 and the battery, as the A/D data registers hold them (raw10 << 6) */
};
static volatile struct scan ad_slot[AD_SLOTS] RCX_ONCHIP; /* the last scans */
struct hw_motors drv_motors RCX_ONCHIP;
u8 drv_sensor_power RCX_ONCHIP;

static struct hw_debounce buttons;
static u8 ad_seen;
static u16 battery_sum;
static u8 battery_count;

void rcx_frt_isr(void);
void rcx_adi_isr(void);
int main(void);

/* The results of the scan that just ended, as the next sample of every input. */
static void ad_store(void)
{
    volatile struct scan *s = &ad_slot[ad_done & (AD_SLOTS - 1)];

    s->raw[0] = AD_ADDR(hw_ad_channel(0));
    s->raw[1] = AD_ADDR(hw_ad_channel(1));
    s->raw[2] = AD_ADDR(hw_ad_channel(2));
    s->raw[3] = AD_ADDR(HW_AD_BATTERY);
    ad_done++;
}

/*
 * Every millisecond the motor pattern moves on and the A/D scans AN0-AN3 afresh (66 µs). With an active sensor
 * (light, rotation) its power is off for the scan, and the A/D interrupt takes the results and powers it again.
 * With passive inputs only, no interrupt is needed: the scan started a millisecond ago is read here.
 */
void rcx_frt_isr(void)
{
    u8 power = drv_sensor_power;

    FRT_TCSR &= (u8)~FRT_TCSR_OCFA; /* read as 1, written 0: acknowledged */
    ms_ticks++;
    MOTOR_LATCH = hw_motor_step(&drv_motors);
    P6DR &= (u8)~P6_SENSORS; /* and so it stays for inputs that no longer want power */
    if (!power && (AD_ADCSR & AD_ADF))
        ad_store();
    (void)AD_ADCSR;
    AD_ADCSR = 0; /* ADF, when set, read as 1 and written 0 */
    AD_ADCSR = power ? AD_SCAN_AN0_AN3 | AD_ADIE : AD_SCAN_AN0_AN3;
}

/* About 70 µs after the tick, with active sensors: the scan stopped before it starts over, the sensors powered. */
void rcx_adi_isr(void)
{
    (void)AD_ADCSR;
    AD_ADCSR = 0; /* ADF read as 1 and written 0; ADST off */
    ad_store();
    P6DR |= drv_sensor_power;
}

/* FRT at 500 kHz, cleared on compare match A at 499: 1.000 ms per period (rcx-hardware.md §6). */
void drv_tick_start(u8 irq)
{
    FRT_TIER = 0;
    FRT_TCR = FRT_TCR_CLK_DIV32;
    FRT_TOCR &= (u8)~FRT_TOCR_OCRS; /* FF94 addresses OCRA */
    FRT_OCR = 499;
    FRT_FRC = 0;
    (void)FRT_TCSR;                 /* a flag is only cleared by writing 0 after reading it as 1 */
    FRT_TCSR = FRT_TCSR_CCLRA;
    if (irq)
        FRT_TIER = FRT_TIER_OCIAE;
}

/* For use with the tick interrupt off (power-off and wake-up): each compare match is one millisecond. */
void drv_wait_ms(u8 ms)
{
    while (ms) {
        if (FRT_TCSR & FRT_TCSR_OCFA) {
            FRT_TCSR &= (u8)~FRT_TCSR_OCFA;
            ms--;
        }
    }
}

void drv_buttons_resync(void)
{
    buttons.state = hw_buttons(P4DR, P7PIN);
    buttons.cand = 0;
    buttons.count = 0;
}

/* The scans completed since the last call, oldest first, as one sample per input per millisecond. */
static void feed_samples(void)
{
    struct scan s;
    u8 i;

    while (ad_seen != ad_done) {
        if ((u8)(ad_done - ad_seen) >= AD_SLOTS)
            ad_seen = (u8)(ad_done - (AD_SLOTS - 1)); /* the oldest slot may be rewritten any moment: skipped */
        h8_irq_disable();
        s = *(struct scan *)&ad_slot[ad_seen & (AD_SLOTS - 1)];
        h8_irq_enable();
        ad_seen++;
        for (i = 0; i < 3; i++)
            rt_sensor_sample(&brick, i, hw_ad_raw10(s.raw[i]));
        /* The battery is averaged over 64 ms: steadier, and one conversion to millivolts instead of 64. */
        battery_sum += hw_ad_raw10(s.raw[3]);
        if (++battery_count == 64) {
            rt_battery(&brick, hw_battery_mv(battery_sum >> 6));
            battery_sum = 0;
            battery_count = 0;
        }
    }
}

static void poll_buttons(void)
{
    u8 changed = hw_debounce(&buttons, hw_buttons(P4DR, P7PIN)), i;

    for (i = 0; changed; i++, changed >>= 1)
        if (changed & 1)
            rt_button(&brick, i, (u8)((buttons.state >> i) & 1));
}

int main(void)
{
    u16 seen;
    u8 i;

    /* No code: the arena's size as an absolute symbol, for drivers/size.sh and the free-memory check. */
    __asm__ __volatile__(".global\t_rcx_arena_size\n\t.set\t_rcx_arena_size, %c0" ::"i"(sizeof brick.vm.arena));
    H8_SYSCR &= (u8)~H8_SYSCR_SSBY; /* the ROM leaves it set: SLEEP in the idle loop must be a light sleep */
    P4DR = 0x01;                    /* IR short range until the IR layer says otherwise */
    RCX_RAMVEC(RCX_VEC_OCIA) = (u16)(unsigned)rcx_frt_irq;
    RCX_RAMVEC(RCX_VEC_ADI) = (u16)(unsigned)rcx_adi_irq;
    drv_outputs_on();
    sci_start(0);
    rt_init(&brick, (u16)(unsigned)brick.vm.arena);
    drv_buttons_resync();
    drv_tick_start(1);
    seen = ms_ticks;
    h8_irq_enable();

    for (;;) {
        sci_drain(&brick);
        sci_service();
        if ((u16)(ms_ticks - seen) > TICKS_BACKLOG)
            seen = (u16)(ms_ticks - TICKS_PER_PASS);
        for (i = 0; i < TICKS_PER_PASS && seen != ms_ticks; i++) {
            seen++;
            feed_samples();
            poll_buttons();
            rt_tick(&brick);
        }
        /* Nothing ran: sleep until the next interrupt (at most 1 ms away), which saves the batteries. */
        if (!rt_run(&brick, RUN_BUDGET) && seen == ms_ticks)
            h8_sleep();
    }
}
