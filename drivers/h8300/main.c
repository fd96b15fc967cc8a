/*
 * OpenRCX on the brick: start-up, the main loop, and the interrupt that keeps time (rcx-hardware.md 3.2-3.5,
 * 3.9). The interrupt only drives the motor latch, switches sensor power around the A/D scan and stores results;
 * the main loop feeds everything to the runtime (src/runtime.h), which must never run inside an interrupt.
 */
#include "runtime.h"
#include "h8.h"
#include "drivers.h"

/* Byte codes per rt_run call: as many as run before the next tick, whose interrupt ends the run (rcx.yield): the
 * millisecond's work waits for at most one chunk of byte codes (RCX_RUN_CHUNK), a received byte for at most a
 * tick, and a lone task does not pay for the loop's checks every few byte codes. */
#define RUN_BUDGET 0xFFFF

#define AD_SLOTS 4 /* scans the main loop may fall behind before samples are lost */
#define AD_SLOT 8  /* bytes of a scan: ad_done and ad_seen count in these, so that they are offsets in ad_slot */

/* Milliseconds handled per main-loop pass, and the backlog at which time is given up: if the per-millisecond work
 * ever takes longer than a millisecond, byte codes and IR packets still get their turn and the clock runs slow,
 * instead of the loop catching up for ever. */
#define TICKS_PER_PASS 4
#define TICKS_BACKLOG 100

static struct rcx_brick brick;

/* Shared with the interrupt: on-chip RAM, where it reaches them in fewer states; bytes in the page that 8-bit
 * addresses reach. */
static volatile u16 ms_ticks RCX_ONCHIP;         /* counted by the tick interrupt */
static volatile u8 ad_done RCX_EIGHT;            /* scans completed, times AD_SLOT (modulo 256) */
/* The last scans: ADDRA-ADDRD (inputs 2, 1, 0 and the battery) as the registers hold them (raw10 << 6). */
static volatile u16 ad_slot[AD_SLOTS][AD_SLOT / 2] RCX_ONCHIP;
struct hw_motors drv_motors RCX_ONCHIP;
u8 drv_sensor_power RCX_EIGHT;

/* The main loop's own: on-chip too, external RAM is left to the program memory. */
static struct hw_debounce buttons RCX_EIGHT;
static u8 ad_seen RCX_EIGHT;                     /* scans fed to the runtime, times AD_SLOT */
static u8 battery_count RCX_EIGHT;
static u16 battery_sum RCX_ONCHIP;

void rcx_timer_isr(void);
int main(void);

/* The results of the scan that just ended, as the next sample of every input. */
static void ad_store(void)
{
    volatile u16 *s = (volatile u16 *)((volatile u8 *)ad_slot + (ad_done & (AD_SLOTS * AD_SLOT - 1)));

    *s++ = AD_ADDR(0); /* unrolled: this runs in the tick interrupt */
    *s++ = AD_ADDR(1);
    *s++ = AD_ADDR(2);
    *s = AD_ADDR(3);
    ad_done += AD_SLOT;
}

/*
 * The FRT compare match A (the tick) and the end of an A/D scan share this handler; each entry serves one of them,
 * and the CPU comes back at once for the other if it is pending too.
 *
 * Every millisecond the motor pattern moves on and the A/D scans AN0-AN3 afresh (66 µs). With an active sensor
 * (light, rotation) its power is off for the scan, and the A/D interrupt takes the results and powers it again.
 * With passive inputs only, no interrupt is needed: the scan started a millisecond ago is read here.
 */
void rcx_timer_isr(void)
{
    u8 power = drv_sensor_power;

    if (!((u8)~AD_ADCSR & (AD_ADF | AD_ADIE))) { /* both set */
        /* About 70 µs after the tick, with active sensors: the scan stopped before it starts over, the sensors
         * powered. */
        AD_ADCSR = 0; /* ADF read as 1 above and written 0; ADST off */
        ad_store();
        P6DR |= power;
        return;
    }
    H8_BCLR(3, 0x91); /* TCSR.OCFA (FRT_TCSR_OCFA) read as 1, written 0: acknowledged */
    ms_ticks++;
    brick.vm.yield = 1;
    MOTOR_LATCH = hw_motor_step(&drv_motors);
    P6DR &= (u8)~P6_SENSORS; /* and so it stays for inputs that no longer want power */
    if (!power && (AD_ADCSR & AD_ADF))
        ad_store();
    (void)AD_ADCSR;
    AD_ADCSR = 0; /* ADF, when set, read as 1 and written 0 */
    AD_ADCSR = power ? AD_SCAN_AN0_AN3 | AD_ADIE : AD_SCAN_AN0_AN3;
}

static __attribute__((noinline)) u8 buttons_now(void)
{
    return hw_buttons(P4DR, P7PIN);
}

/* FRT at 500 kHz, cleared on compare match A at 499: 1.000 ms per period (rcx-hardware.md §6). The buttons'
 * present state becomes the debounced one, without edges. */
void drv_tick_start(u8 irq)
{
    buttons.state = buttons_now();
    buttons.cand = 0;
    buttons.count = 0;
    FRT_TIER = 0;
    FRT_TCR = FRT_TCR_CLK_DIV32;
    H8_BCLR(4, 0x97);               /* TOCR.OCRS (FRT_TOCR_OCRS): FF94 addresses OCRA */
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
            H8_BCLR(3, 0x91); /* TCSR.OCFA */
            ms--;
        }
    }
}

/* hw_ad_raw10 as the H8/300 does it in 8 instructions: gcc makes a 16-bit shift by 6 a loop of 24. */
static inline u16 ad_raw10(u16 addr)
{
    u16 r;
    __asm__("mov.b\t%t1,%s0\n\tsub.b\t%t0,%t0\n\tshll.b\t%s1\n\trotxl.b\t%s0\n\trotxl.b\t%t0\n\t"
            "shll.b\t%s1\n\trotxl.b\t%s0\n\trotxl.b\t%t0"
            : "=&r"(r), "+r"(addr) : : "cc");
    return r;
}

/* The scans completed since the last call, oldest first, as one sample per input per millisecond. */
static void feed_samples(void)
{
    static u16 s[4] RCX_ONCHIP; /* the scan being fed (raw10), copied out of reach of the interrupt */
    u16 *p;
    u8 i;

    while (ad_seen != ad_done) {
        const volatile u16 *slot;

        if ((u8)(ad_done - ad_seen) >= AD_SLOTS * AD_SLOT) /* the oldest slot may be rewritten any moment: */
            ad_seen = (u8)(ad_done - (AD_SLOTS - 1) * AD_SLOT); /* skipped */
        slot = (const volatile u16 *)((const volatile u8 *)ad_slot + (ad_seen & (AD_SLOTS * AD_SLOT - 1)));
        p = s;
        i = 4;
        h8_irq_disable();
        do
            *p++ = ad_raw10(*slot++);
        while (--i);
        h8_irq_enable();
        ad_seen += AD_SLOT;
        p = &s[hw_ad_channel(0)];
        for (i = 0; i < 3; i++)
            rt_sensor_sample(&brick, i, *p--);
        /* The battery is averaged over 64 ms: steadier, and one conversion to millivolts instead of 64. */
        battery_sum += s[HW_AD_BATTERY];
        if (++battery_count == 64) {
            rt_battery(&brick, hw_battery_mv(battery_sum >> 6));
            battery_sum = 0;
            battery_count = 0;
        }
    }
}

/* One millisecond of the runtime: the samples, the buttons, then the clock. */
static __attribute__((noinline)) void millisecond(void)
{
    u8 changed, state, i;

    feed_samples();
    changed = hw_debounce(&buttons, buttons_now());
    state = buttons.state;
    for (i = 0; changed; i++, changed >>= 1, state >>= 1)
        if (changed & 1)
            rt_button(&brick, i, (u8)(state & 1));
    rt_tick(&brick);
}

int main(void)
{
    u16 seen;
    u8 i;

    /* No code: the arena's size as an absolute symbol, for drivers/size.sh and the free-memory check. */
    __asm__ __volatile__(".global\t_rcx_arena_size\n\t.set\t_rcx_arena_size, %c0" ::"i"(sizeof brick.vm.arena));
    H8_SYSCR &= (u8)~H8_SYSCR_SSBY; /* the ROM leaves it set: SLEEP in the idle loop must be a light sleep */
    P4DR = 0x01;                    /* IR short range until the IR layer says otherwise */
    RCX_RAMVEC(RCX_VEC_OCIA) = (u16)(unsigned)rcx_timer_irq;
    RCX_RAMVEC(RCX_VEC_ADI) = (u16)(unsigned)rcx_timer_irq;
    drv_outputs_on();
    rt_init(&brick, (u16)(unsigned)brick.vm.arena);
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
            millisecond();
        }
        /* Cleared before the clock is read: a tick from now on ends the run. */
        brick.vm.yield = 0;
        if (seen != ms_ticks)
            continue;
        /* Nothing ran: sleep until the next interrupt (at most 1 ms away), which saves the batteries. */
        if (!rt_run(&brick, RUN_BUDGET) && seen == ms_ticks)
            h8_sleep();
    }
}
