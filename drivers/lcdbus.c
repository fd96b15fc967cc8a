/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The LCD controller's two-wire bus, bit-banged (rcx-hardware.md §3.6): data change while SCL is low, MSB first,
 * each byte followed by an acknowledge clock. The pins come from the port's hw_pins.h: single bset/bclr
 * instructions on the brick (other bits of the same port belong to interrupt handlers), a recorder in the host tests.
 * The PCF8566 is a standard-mode (100 kHz) I2C part: HW_SCL_HI_PACED keeps SCL low 4.7 µs and high 4.0 µs, and the
 * same holds SCL high 4.0 µs after the START and before the STOP (tests/drivers/h8machine.c times every edge).
 */
#include "hw.h"
#include "hw_pins.h"

HW_LCD_HELPER

void hw_lcd_send(const u8 *frame, u8 n)
{
    HW_SDA_LO();       /* START: SDA falls while SCL is high ... */
    HW_SCL_HI_PACED(); /* ... and stays so (SCL is already high) */
    HW_SCL_LO();
    while (n--) {
        u8 v = *frame++, i = 9;

        /* Eight bits, then the acknowledge clock with SDA driven low, a ninth bit 0 shifted in: that is the level
         * the controller pulls it to, so nothing fights over the line and SDA never has to become an input (the
         * acknowledge itself is not needed). */
        do {
            HW_SDA_MSB(v); /* SDA = bit 7 of v, v shifted left */
            HW_SCL_HI_PACED();
            HW_SCL_LO();
        } while (--i);
    }
    HW_SCL_HI_PACED(); /* STOP: SDA rises while SCL is high; SDA is low after the last acknowledge clock */
    HW_SDA_HI();
}
