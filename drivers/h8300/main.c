/* SPDX-License-Identifier: MPL-2.0 */
/*
 * OpenRCX on the brick: start-up, the main loop, and the interrupt that keeps time (rcx-hardware.md 3.2-3.5,
 * 3.9). The interrupt only drives the motor latch, reads the A/D (switching each active sensor's power off around
 * its conversion) and stores results; the main loop feeds everything to the runtime (src/runtime.h), which must
 * never run inside an interrupt.
 */
#include "runtime.h"
#include "h8.h"
#include "drivers.h"

/* Byte codes per rt_run call: as many as run before the next tick, whose interrupt ends the run (rcx.yield): the
 * millisecond's work waits for at most one chunk of byte codes (RCX_RUN_CHUNK), a received byte for at most a
 * tick, and a lone task does not pay for the loop's checks every few byte codes. */
#define RUN_BUDGET 0xFFFF

/*
 * The brick never goes deaf (issue 21, docs/timing.md): every pass of the main loop looks at the IR link and the
 * buttons and gives rt_run() its turn, whatever the program costs. A pass feeds the scans that were waiting when it
 * began (all but the last late: cheap, feed_scan), and counts up to TICKS_PER_PASS of the milliseconds owed (rt_tick
 * is cheap and bounded: the clock keeps time). While a scan or a millisecond is still owed the tasks get a slice of
 * one chunk (RUN_SLICE), not the run until the next tick, so that the loop is soon back: a program that asks for more
 * than the CPU can do gets fewer event evaluations (one a pass) and runs slower. TICKS_BACKLOG only guards against a step the loop never returns from.
 */
#define TICKS_PER_PASS 4
#define RUN_SLICE RCX_RUN_CHUNK
#define TICKS_BACKLOG 100

static struct rcx_brick brick;

/* Shared with the interrupt (irq.s): on-chip RAM, where it reaches them in fewer states; bytes in the page that
 * 8-bit addresses reach. */
volatile u8 drv_ms_ticks RCX_EIGHT;
volatile u8 drv_ad_done RCX_EIGHT;
volatile u8 drv_ad_seen RCX_EIGHT;
volatile u8 drv_woken RCX_EIGHT;
volatile u8 drv_quiet RCX_EIGHT;
volatile u16 drv_ad_slot[DRV_AD_SLOTS][DRV_AD_SLOT / 2] RCX_ONCHIP;
struct hw_motors drv_motors RCX_ONCHIP;
u8 drv_sensor_power RCX_EIGHT;

/* The main loop's own: on-chip too, external RAM is left to the program memory. */
static struct hw_debounce buttons RCX_EIGHT;
static u8 button_pins RCX_EIGHT;                 /* the button bits of P4 and P7 when last looked at */
static u8 battery_count RCX_EIGHT;              /* samples in battery_sum, in steps of 0x20: the eighth wraps to 0 */
static u16 battery_sum RCX_ONCHIP;

/* Never returns (crt0.s): nothing of its caller's to keep, so no registers saved (OS_Task). */
int main(void) __attribute__((OS_Task));

/* What irq.s takes for granted. */
RCX_STATIC_ASSERT(slots_in_a_byte, DRV_AD_SLOTS * DRV_AD_SLOT == 0x40 && DRV_AD_SLOT == 8);
RCX_STATIC_ASSERT(phase_after_the_pattern, offsetof(struct hw_motors, phase) == 8);
RCX_STATIC_ASSERT(what_needs_the_clock_is_bytes, sizeof(((struct rcx *)0)->sound.count) == 1 &&
                  sizeof(((struct rcx *)0)->out.pause) == 3 && sizeof(((struct rcx *)0)->remote.tx_len) == 1);

#define BUTTON_PINS() ((u8)((P4DR & 0x06) | (P7PIN & 0xC0))) /* On-Off, Run; View, Prgm (hw_buttons) */

/* The buttons as their pins show them now, the pins noted for the main loop's next look (millisecond). */
static __attribute__((noinline)) u8 buttons_now(void)
{
    u8 pins = BUTTON_PINS();

    button_pins = pins;
    return hw_buttons(pins, pins);
}

/* FRT at 500 kHz, cleared on compare match A at 499: 1.000 ms per period (rcx-hardware.md §6). The buttons'
 * present state becomes the debounced one, without edges: last, with the interrupts still masked by both callers
 * (and the tick interrupt leaves the buttons alone), so that `irq` is not kept across a call. */
RCX_HIGH_CODE void drv_tick_start(u8 irq)
{
    FRT_TIER = 0;
    FRT_TCR = FRT_TCR_CLK_DIV32;
    H8_BCLR(4, 0x97);               /* TOCR.OCRS (FRT_TOCR_OCRS): FF94 addresses OCRA */
    FRT_OCR = 499;
    FRT_FRC = 0;
    (void)FRT_TCSR;                 /* a flag is only cleared by writing 0 after reading it as 1 */
    FRT_TCSR = FRT_TCSR_CCLRA;
    if (irq)
        FRT_TIER = FRT_TIER_OCIAE;
    buttons.cand = 0;
    buttons.state = buttons_now();
}

/* For use with the tick interrupt off (power-off and wake-up): each compare match is one millisecond. */
RCX_HIGH_CODE void drv_wait_ms(u8 ms)
{
    do {
        while (!(FRT_TCSR & FRT_TCSR_OCFA))
            ;
        H8_BCLR(3, 0x91); /* TCSR.OCFA */
    } while (--ms);
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

/*
 * The oldest scan not yet fed, as one sample per input; 0 when it is the pass's last (drv_ad_done was `until` when
 * the pass began). One per call: the main loop feeds the scans there when the pass began, not until the ring is empty,
 * since the interrupt stores a scan every millisecond while an input moves, and were feeding one to take longer, such
 * a loop would never end (issue 21). A scan with newer ones behind it in the pass is fed late (rt_sensors_late): its
 * values and rotation steps count, its events hear only of the pass's last, so the ring empties fast. A scan the
 * interrupt did not store (see irq.s) was one the runtime said would change nothing (rt_sensors_resting).
 */
static RCX_HIGH_CODE __attribute__((noinline)) u8 feed_scan(u8 until)
{
    static u16 s[3] RCX_ONCHIP; /* the scan being fed, copied out of reach of the interrupt */
    u16 *p;
    u8 i, seen = drv_ad_seen, done, late;
    const volatile u16 *slot;

    /* With the interrupt held off, every slot may be read: the one it would rewrite next too (all eight scans kept),
     * and if it has rewritten the oldest already, that one is skipped. */
    h8_irq_disable();
    done = drv_ad_done;
    if ((u8)(done - seen) > DRV_AD_SLOTS * DRV_AD_SLOT)
        seen = (u8)(done - DRV_AD_SLOTS * DRV_AD_SLOT);
    slot = (const volatile u16 *)((const volatile u8 *)drv_ad_slot + (seen & (DRV_AD_SLOTS * DRV_AD_SLOT - 1)));
    /* Non-zero: newer scans of the pass wait, the events hear of the last (which may have been rewritten: then this
     * one is the last). */
    late = (u8)(until - seen - DRV_AD_SLOT);
    if (late > DRV_AD_SLOTS * DRV_AD_SLOT)
        late = 0;
    rt_sensors_late(&brick, late);
    /* Input i is channel 2 - i (hw_ad_channel): copied in reverse. */
    p = s + 3;
    i = 3;
    do
        *--p = *slot++;
    while (--i);
    h8_irq_enable();
    do
        *p = ad_raw10(*p);
    while (++p < s + 3);
    rt_sensor_scan(&brick, s);
    /* Only now: the interrupt compares a scan with this one only once it has been fed. */
    drv_ad_seen = (u8)(seen + DRV_AD_SLOT);
    return late;
}

/* The battery: averaged over 8 samples, steadier, and one conversion to millivolts instead of many; a sample every
 * 8 ms (BATTERY_EVERY) is plenty for that, and every 40 ms on average while the main loop skips quiet milliseconds
 * (their counts jump over the 8 ms marks). ADDRD is read as it is: whether from the scan running or the one before does
 * not matter. */
#define BATTERY_EVERY 7 /* + 1 ms */
static __attribute__((noinline)) void battery_sample(void)
{
    battery_sum += ad_raw10(AD_ADDR(HW_AD_BATTERY));
    battery_count = (u8)(battery_count + 0x20);
    if (!battery_count) {
        rt_battery(&brick, hw_battery_mv(battery_sum >> 3));
        battery_sum = 0;
    }
}

/* The buttons' pins changed, or a change is being timed: debounced, and each new state to the runtime. */
static __attribute__((noinline)) void buttons_changed(void)
{
    u8 changed, i, bit;

    changed = hw_debounce(&buttons, buttons_now(), drv_ms_ticks); /* the pins read just now */
    for (i = 0, bit = 1; i < HW_BUTTONS; i++, bit <<= 1)
        if (changed & bit)
            rt_button(&brick, i, (u8)(buttons.state & bit)); /* non-zero: down */
}

/* One millisecond of the runtime: the buttons, then the clock. Inline in the main loop, which runs it a thousand
 * times a second: the buttons' work, rarely needed, is a call of its own. */
static inline void millisecond(void)
{
    /* The same pins as last time, and no change being timed: the debounced state is what they show. */
    if (BUTTON_PINS() != button_pins || buttons.cand)
        buttons_changed();
    rt_tick(&brick);
}

/* rt_quiet(), unless the buttons or a transmission of another mode want the milliseconds. Out of line: the main loop
 * asks twice. */
static __attribute__((noinline)) u8 quiet_ms(void)
{
    u8 quiet = rt_quiet(&brick);

    if (buttons.cand | drv_sci_mode)
        quiet = 0;
    return quiet;
}

int main(void)
{
    u8 seen, i, owed, step, quiet = 0;

    /* No code: the arena's size as an absolute symbol, for drivers/size.sh and the free-memory check. */
    __asm__ __volatile__(".global\t_rcx_arena_size\n\t.set\t_rcx_arena_size, %c0" ::"i"(sizeof brick.vm.arena));
    H8_BCLR(7, 0xc4);               /* SYSCR.SSBY (H8_SYSCR_SSBY): the ROM leaves it set, and SLEEP in the idle loop
                                     * must be a light sleep */
    P4DR = 0x01;                    /* IR short range until the IR layer says otherwise */
    /* No code: where the tick interrupt (irq.s) sets rcx.yield. */
    __asm__ __volatile__(".global\t_drv_yield\n\t.set\t_drv_yield, _brick+%c0" ::"i"(offsetof(struct rcx_brick, vm.yield)));
    __asm__ __volatile__(".global\t_drv_sensors_rest\n\t.set\t_drv_sensors_rest, _brick+%c0"
                         ::"i"(offsetof(struct rcx_brick, vm.sensors_rest)));
    /* What the tick interrupt looks at while the tasks run through quiet milliseconds. */
    __asm__ __volatile__(".global\t_drv_sound_count\n\t.set\t_drv_sound_count, _brick+%c0\n\t"
                         ".global\t_drv_pause\n\t.set\t_drv_pause, _brick+%c1\n\t"
                         ".global\t_drv_tx_len\n\t.set\t_drv_tx_len, _brick+%c2"
                         ::"i"(offsetof(struct rcx_brick, vm.sound.count)), "i"(offsetof(struct rcx_brick, vm.out.pause)),
                         "i"(offsetof(struct rcx_brick, vm.remote.tx_len)));
    RCX_RAMVEC(RCX_VEC_OCIA) = (u16)(unsigned)rcx_timer_irq;
    drv_outputs_on();
    rt_init(&brick, (u16)(unsigned)brick.vm.arena);
    drv_tick_start(1);
    seen = drv_ms_ticks;
    h8_irq_enable();

    for (;;) {
        drv_woken = 0; /* what comes in from now on wakes the quiet milliseconds' sleep below */
        sci_drain(&brick); /* each returns at once when it has nothing to do */
        sci_service();
        if ((u8)(drv_ms_ticks - seen) > TICKS_BACKLOG)
            seen = (u8)(drv_ms_ticks - TICKS_PER_PASS);
        /* Quiet milliseconds slept through or run through: all but the last counted at once. */
        i = (u8)(drv_ms_ticks - seen);
        if (i > 1) {
            if (--i > quiet)
                i = quiet;
            rt_skip(&brick, i);
            seen = (u8)(seen + i);
        }
        /* The scans waiting when the pass began, all of them: the last worked out in full, those before it late,
         * which costs them their events' evaluation (the events hear of the last), so that a pass is bounded (at
         * most DRV_AD_SLOTS scans, all but one cheap) and the ring empties, however costly the events: no rotation
         * step is lost. Then the milliseconds owed. The millisecond that ends a 10 ms step (timers, events, the
         * display's frame every other step) has a pass of its own, without scans: the two costliest parts of a pass
         * are never added up. */
        step = seen != drv_ms_ticks && brick.vm.ms == 9;
        if (!step) {
            i = drv_ad_done;
            while (drv_ad_seen != drv_ad_done && feed_scan(i))
                ;
        }
        for (i = 0; i < TICKS_PER_PASS && seen != drv_ms_ticks; i++) {
            if (brick.vm.ms == 9 && !step) /* a step's end, in a pass that may have fed scans or ticked */
                break;
            if (!(u8)(++seen & BATTERY_EVERY))
                battery_sample();
            millisecond();
            if (step)
                break;
        }
        /* Cleared before the clock is read: a tick from now on ends the run. Run even when milliseconds or a scan
         * are still owed: commands are answered and the tasks get a slice in every pass. */
        brick.vm.yield = 0;
        owed = seen != drv_ms_ticks || drv_ad_seen != drv_ad_done;
        /* Tasks run on through quiet milliseconds: the tick interrupt lets that many pass without ending the run
         * (rcx.yield) as long as they start nothing that needs the clock (irq.s), and an interrupt that leaves
         * work ends it. Not this time if such an interrupt came since the inputs were read: rcx.yield, which it
         * set, was cleared above, but drv_woken tells. */
        quiet = brick.vm.runmask && !drv_woken ? quiet_ms() : 0;
        drv_quiet = quiet;
        /* Nothing ran and nothing is owed (a scan left for the next pass must not wait out a sleep): sleep until
         * the next interrupt (at most 1 ms away), which saves the batteries. Through quiet milliseconds it sleeps
         * on, as long as no sample or byte comes in. In both cases the milliseconds are counted at once above, all
         * but the last, which rt_tick() takes as usual. The buttons are looked at then: a press is seen at most
         * 9 ms later, and the debouncing times it as before from there. */
        if (!rt_run(&brick, owed ? RUN_SLICE : RUN_BUDGET) && !owed && seen == drv_ms_ticks) {
            quiet = quiet_ms();
            do
                h8_sleep();
            while ((u8)(drv_ms_ticks - seen) <= quiet && !drv_woken);
        }
        drv_quiet = 0;
    }
}
