/* SPDX-License-Identifier: MPL-2.0 */
/*
 * hal.h on the brick: motors, sensor power, speaker, LCD, standby and the hand-back to the ROM
 * (rcx-hardware.md 2.4, 3.1-3.7, 3.11, 3.12). No ROM routine is called; the only jump into the ROM is its reset.
 */
#include "rcx_string.h"
#include "rcx.h"
#include "hal.h"
#include "h8.h"
#include "drivers.h"

/* P6DDR is write-only: the shadow is its value. Bit 4 (speaker) is an output only while a tone plays. */
#define P6DDR_AWAKE (P6_SENSORS | P6_AWAKE | P6_SCL | P6_SDA | P6_CARRIER)
static u8 p6ddr RCX_EIGHT;
#define p6ddr_set(v) (P6DDR = p6ddr = (u8)(v))

/* On-chip, like all the drivers' variables: external RAM is left to the program memory. */
static u16 tone_hz RCX_ONCHIP;
/* The last LCD frame: the image it shows (from byte 4) is sent again after standby. */
static u8 lcd_frame[HW_LCD_FRAME_MAX] RCX_ONCHIP;

#define STANDBY_CODE ((u8 *)0xFD80)
#define STANDBY_RTS 0xFD8E           /* the last instruction of the standby code, also the IRQ1 handler */

RCX_HIGH_CODE void hal_motor(struct rcx *b, u8 port, u8 mode, u8 level)
{
    (void)b;
    hw_motor_set(&drv_motors, port, mode, level); /* the tick interrupt writes the latch within 1 ms */
}

/* The tick interrupt removes each input's power in the mask for its conversion and applies it again after (irq.s);
 * an input no longer in the mask is unpowered here, at once. */
RCX_HIGH_CODE void hal_sensor_power(struct rcx *b, u8 input, u8 on)
{
    u8 bit, power;

    (void)b;
    if (input > 2)
        return;
    bit = hw_sensor_power_bit[input];
    power = (u8)(drv_sensor_power & ~bit);
    h8_irq_disable(); /* P6DR is the interrupts' too */
    P6DR &= (u8)~bit;
    if (on)
        power |= bit;
    drv_sensor_power = power;
    h8_irq_enable();
}

void hal_sound(struct rcx *b, u16 hz)
{
    static struct hw_tone t RCX_EIGHT;
    u8 ok;

    (void)b;
    if (hz == tone_hz)
        return; /* the same tone again: restarting the timer would only add a click */
    tone_hz = hz;
    ok = hw_tone(hz, &t); /* before the timer is stopped: nothing kept across the call */
    TMR0_TCR = 0;
    if (!ok) {
        p6ddr_set((u8)(p6ddr & ~P6_SPEAKER)); /* as the ROM leaves a silent speaker: pin released */
        return;
    }
    TMR0_TCORA = t.tcora;
    TMR0_TCNT = 0; /* TCSR toggles the output on compare match A: set once by drv_outputs_on */
    H8_STCR = (u8)((H8_STCR & ~0x01) | t.icks0);
    p6ddr_set((u8)(p6ddr | P6_SPEAKER));
    TMR0_TCR = t.tcr;
}

RCX_HIGH_CODE void hal_lcd(struct rcx *b, const u8 *image)
{
    (void)b;
    hw_lcd_send(lcd_frame, hw_lcd_on_frame(image, lcd_frame));
}

/* Start-up and wake-up: the state of rcx-hardware.md 3.12, and the IR link at its default settings. The tick is
 * started separately. */
void drv_outputs_on(void)
{
    MOTOR_LATCH = 0;
    P4DDR = 0x01;                 /* range out (its level is the IR layer's: kept through standby); buttons in */
    P5DR = 0;
    P5DDR = 0x04;                 /* RAM power-save line out, at 0 = RAM awake */
    P6DR = P6_AWAKE | P6_SCL | P6_SDA; /* sensors unpowered, LCD bus idle, carrier pin low */
    p6ddr_set(P6DDR_AWAKE);
    TMR0_TCR = 0;
    TMR0_TCSR = 0x03;
    tone_hz = 0;
    H8_BCLR(7, 0xe9);             /* ADCR.TRGE: no external trigger */
    AD_ADCSR = 0;
    hal_lcd(0, lcd_frame + 4); /* the image it showed, copied onto itself */
    sci_start(0);
}

/* For standby: everything quiet and unpowered, the display switched off, then the pins as the LEGO ROM's own
 * shutdown leaves them (rcx-hardware.md 3.11), which is what LEGO shipped for a brick that is off for weeks: sensor
 * power, P6.3, the speaker and the LCD lines inputs; the carrier pin P6.7, the SCI pins P5.0/P5.1 and the range pin
 * P4.0 outputs at 0 (nothing floats, the IR LED stays dark); TMR0's output setting off. drv_outputs_on undoes it. */
static void outputs_off(void)
{
    FRT_TIER = 0;                 /* no tick: no motor pattern, no A/D cycle */
    AD_ADCSR = 0;
    MOTOR_LATCH = 0;
    sci_stop();
    TMR0_TCR = 0;
    TMR0_TCSR = 0;                /* tone_hz: drv_outputs_on clears it on waking */
    P6DR = P6_SCL | P6_SDA;       /* sensors, carrier and P6.3 low; LCD bus idle */
    p6ddr_set((u8)(p6ddr & ~(P6_SPEAKER | P6_AWAKE)));
    hw_lcd_send(lcd_frame, hw_lcd_off_frame(lcd_frame)); /* the image from byte 4 on stays */
    p6ddr_set(P6_CARRIER);
    P6DR = 0;
    P5DR = 0;                     /* P5.2 too: the RAM stays awake until the standby code */
    P5DDR = 0x07;
    P4DR &= (u8)~0x01;
}

/* On-Off up for 20 ms in a row. */
static RCX_HIGH_CODE void wait_onoff_released(void)
{
    u8 up = 0;

    while (up < 20) {
        drv_wait_ms(1);
        up = (u8)(P4DR & 0x02 ? up + 1 : 0);
    }
}

/*
 * Software standby (§3.11) until On-Off is pressed. The code around SLEEP runs from on-chip RAM with the stack
 * there too, because external RAM is in power-save meanwhile; the IRQ1 handler is that code's final rts, which is
 * all waking up needs. Programs, variables, datalog and watch stay in RAM; the peripherals are set up again.
 */
void hal_power_off(struct rcx *b)
{
    u8 range = P4DR;       /* P4.0, the IR range: the IR layer's, kept through standby */

    (void)b;
    h8_irq_disable();
    outputs_off();
    wait_onoff_released(); /* else the release would wake the brick again at once */
    memcpy(STANDBY_CODE, rcx_standby_code, 16); /* irq.s checks the size */
    RCX_RAMVEC(RCX_VEC_IRQ1) = STANDBY_RTS; /* and so it stays: IRQ1 is only enabled here */
    H8_BSET(1, 0xc6);      /* ISCR.IRQ1SC (H8_IRQ1): falling edge */
    H8_WRITE8(0xc4, (H8_SYSCR & 0x0F) | H8_SYSCR_SSBY | H8_SYSCR_STS4); /* SYSCR */
    H8_WRITE8(0xc7, H8_IRQ1); /* IER */
    rcx_standby_stub();
    H8_WRITE8(0xc7, 0);
    H8_BCLR(7, 0xc4);      /* SYSCR.SSBY (H8_SYSCR_SSBY) */
    drv_tick_start(0);     /* whether standby kept the timers is not known: set everything up again */
    /* On at once, while the button may still be held, as firm0328 comes on. The contact settles first (20 ms after
     * the oscillator's 8 ms): the state it then shows is taken without an edge (drv_tick_start), a release is no
     * button event, and the debouncing filters what bounce there is later. */
    drv_wait_ms(20);
    P4DR = range;
    drv_outputs_on();
    drv_tick_start(1);
    h8_irq_enable();
}

/*
 * What the ROM's start-up code finds after a real reset, for every register the drivers set (values after reset in
 * the H8/3297-series hardware manual): a jump to the reset vector is not a reset, and the ROM cannot assume any of
 * them otherwise. Runs of consecutive registers: the low byte of the first address (page FF00, or FD00 for the
 * ROM's port shadows below 0x90), how many, then their values in address order, which for the 16-bit FRC and OCRA
 * is high byte first, as their temporary latch wants. The SCI is stopped before its mode changes; every register is
 * read before it is written, so that the flags it shows set are cleared by the 0 written.
 */
#if RCX_SWAN
#undef RCX_HIGH_DATA
#define RCX_HIGH_DATA /* in .rodata: with Swan's programs F000-FB7F has no room for it */
#endif
static const u8 rom_state[] RCX_HIGH_DATA = {
    0xDA, 3, 0x00, 0xFF, 0x84,  /* SCI SCR, TDR, SSR */
    0xD8, 2, 0x00, 0xFF,        /* SCI SMR, BRR */
    0x90, 8, 0x01, 0x00, 0x00, 0x00, 0xFF, 0xFF, 0x00, 0xE0, /* FRT TIER, TCSR, FRC, OCRA, TCR, TOCR */
    0xB5, 1, 0x00,              /* P4DDR (P3 is the data bus: never touched) */
    /* P4DR, P5DDR, P6DDR, P5DR, P6DR; but P5.2, the external RAM's power-save line, stays an output at 0: this code
     * and table run from external RAM, which a floating P5.2 could put to sleep under them, and the ROM's own first
     * instructions run before it drives the line again (rcx-hardware.md 2.4). */
    0xB7, 5, 0x00, 0xFC, 0x00, 0xF8, 0x00,
    0xC3, 2, 0xF8, 0x0B,        /* STCR, SYSCR (no standby on SLEEP; the ROM sets its own) */
    /* ISCR, IER, TMR0 TCR, TCSR, TCORA, TCORB, and TCNT, the one exception: non-zero, so that the ROM comes up
     * awake and ready for a download instead of asleep (rcx-hardware.md 2.4). */
    0xC6, 7, 0xF8, 0xF8, 0x00, 0x10, 0xFF, 0xFF, 0x01,
    0xD0, 5, 0x00, 0x10, 0xFF, 0xFF, 0x00, /* TMR1 TCR, TCSR, TCORA, TCORB, TCNT */
    0xE8, 2, 0x00, 0x7F,        /* A/D ADCSR, ADCR */
    /* The ROM's copies of the write-only port directions (rcx-hardware.md 1.2), which the start-up code's stack
     * and the standby code overwrote: P1 and P2 as the ROM set them (the address bus), P5 with its P5.2 output, the
     * others as just reset. */
    0x80, 7, 0xFF, 0xFF, 0x00, 0x00, 0x04, 0x00, 0x00,
    0
};

/*
 * Back to the ROM for a firmware download (§2.4): everything off and as after a reset, then the jump through the
 * reset vector. The ROM re-initialises the LCD, its variables and the RAM vectors itself.
 */
RCX_HIGH_CODE void hal_enter_rom(struct rcx *b)
{
    const u8 *p = rom_state;
    u8 a, n;

    (void)b;
    h8_irq_disable();
    MOTOR_LATCH = 0;
    for (;;) { /* not while ((a = *p++) != 0): gcc would then read the first byte twice */
        volatile u8 *r;

        a = *p++;
        if (!a)
            break;
        r = (volatile u8 *)(unsigned)(0xFF00 | a);
        if (a < 0x90)
            r -= 0x200; /* FDxx */
        n = *p++;
        do {
            (void)*r;
            *r++ = *p++;
        } while (--n);
    }
    __asm__ __volatile__("jmp\t@@0:8");
}
