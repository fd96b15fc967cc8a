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
static u8 p6ddr;

static u16 tone_hz;
static u8 lcd_shown[HAL_LCD_BYTES]; /* sent again after standby */

#define STANDBY_CODE ((u8 *)0xFD80)
#define STANDBY_RTS 0xFD8E           /* the last instruction of the standby code, also the IRQ1 handler */

static void p6ddr_set(u8 v)
{
    p6ddr = v;
    P6DDR = v;
}

void hal_motor(struct rcx *b, u8 port, u8 mode, u8 level)
{
    (void)b;
    hw_motor_set(&drv_motors, port, mode, level); /* the tick interrupt writes the latch within 1 ms */
}

/* The A/D interrupt applies the mask after each scan; the tick interrupt removes power before the next, and
 * for good once an input is no longer in the mask. */
void hal_sensor_power(struct rcx *b, u8 input, u8 on)
{
    (void)b;
    if (input > 2)
        return;
    if (on)
        drv_sensor_power |= hw_sensor_power_bit[input];
    else
        drv_sensor_power &= (u8)~hw_sensor_power_bit[input];
}

void hal_sound(struct rcx *b, u16 hz)
{
    struct hw_tone t;

    (void)b;
    if (hz == tone_hz)
        return; /* the same tone again: restarting the timer would only add a click */
    tone_hz = hz;
    TMR0_TCR = 0;
    if (!hw_tone(hz, &t)) {
        p6ddr_set((u8)(p6ddr & ~P6_SPEAKER)); /* as the ROM leaves a silent speaker: pin released */
        return;
    }
    TMR0_TCORA = t.tcora;
    TMR0_TCNT = 0;
    TMR0_TCSR = 0x03; /* toggle the output on compare match A */
    H8_STCR = (u8)((H8_STCR & ~0x01) | t.icks0);
    p6ddr_set((u8)(p6ddr | P6_SPEAKER));
    TMR0_TCR = t.tcr;
}

void hal_lcd(struct rcx *b, const u8 *image)
{
    u8 frame[HW_LCD_FRAME_MAX];

    (void)b;
    memcpy(lcd_shown, image, HAL_LCD_BYTES);
    hw_lcd_send(frame, hw_lcd_on_frame(image, frame));
}

/* Start-up and wake-up: the state of rcx-hardware.md 3.12. The IR link and the tick are started separately. */
void drv_outputs_on(void)
{
    u8 frame[HW_LCD_FRAME_MAX];

    MOTOR_LATCH = 0;
    P4DDR = 0x01;                 /* range out (its level is the IR layer's: kept through standby); buttons in */
    P5DR = 0;
    P5DDR = 0x04;                 /* RAM power-save line out, at 0 = RAM awake */
    P6DR = P6_AWAKE | P6_SCL | P6_SDA; /* sensors unpowered, LCD bus idle, carrier pin low */
    p6ddr_set(P6DDR_AWAKE);
    TMR0_TCR = 0;
    TMR0_TCSR = 0x03;
    tone_hz = 0;
    AD_ADCR &= 0x7F;              /* no external trigger */
    AD_ADCSR = 0;
    hw_lcd_send(frame, hw_lcd_on_frame(lcd_shown, frame));
}

void drv_outputs_off(u8 lcd)
{
    u8 frame[4];

    FRT_TIER = 0;                 /* no tick: no motor pattern, no A/D cycle */
    AD_ADCSR = 0;
    MOTOR_LATCH = 0;
    sci_stop();
    TMR0_TCR = 0;
    tone_hz = 0;
    P6DR = P6_SCL | P6_SDA;       /* sensors, carrier and P6.3 low; LCD bus idle */
    p6ddr_set((u8)(p6ddr & ~(P6_SPEAKER | P6_AWAKE)));
    if (lcd) {
        hw_lcd_send(frame, hw_lcd_off_frame(frame));
        P6DR = 0;                 /* bus lines low: no current into the controller in standby */
    }
}

/* On-Off up for 20 ms in a row. */
static void wait_onoff_released(void)
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
    (void)b;
    h8_irq_disable();
    drv_outputs_off(1);
    wait_onoff_released(); /* else the release would wake the brick again at once */
    memcpy(STANDBY_CODE, rcx_standby_code, (u16)(rcx_standby_code_end - rcx_standby_code));
    RCX_RAMVEC(RCX_VEC_IRQ1) = STANDBY_RTS;
    H8_ISCR |= H8_IRQ1;    /* falling edge */
    H8_SYSCR = (u8)((H8_SYSCR & 0x0F) | H8_SYSCR_SSBY | H8_SYSCR_STS4);
    H8_IER = H8_IRQ1;
    rcx_standby_stub();
    H8_IER = 0;
    RCX_RAMVEC(RCX_VEC_IRQ1) = (u16)(unsigned)rcx_irq_ignore;
    H8_SYSCR &= (u8)~H8_SYSCR_SSBY;
    drv_tick_start(0);     /* whether standby kept the timers is not known: set everything up again */
    wait_onoff_released(); /* the press that woke the brick is not a button event */
    drv_outputs_on();
    sci_start(0);
    drv_buttons_resync();
    drv_tick_start(1);
    h8_irq_enable();
}

/*
 * Back to the ROM for a firmware download (§2.4): everything off, TCNT0 non-zero so that the ROM's reset code
 * comes up awake instead of asleep, then the jump through the reset vector. The ROM re-initialises the LCD.
 */
void hal_enter_rom(struct rcx *b)
{
    (void)b;
    h8_irq_disable();
    H8_IER = 0;
    drv_outputs_off(0);
    TMR0_TCNT = 1;
    __asm__ __volatile__("jmp\t@@0:8");
}
