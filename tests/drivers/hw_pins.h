/* SPDX-License-Identifier: MPL-2.0 */
/* The LCD bus pins in the host tests: every change is recorded, and where the brick waits (test_lcdbus.c decodes
 * the waveform). */
#ifndef RCX_HW_PINS_H
#define RCX_HW_PINS_H

void pins_set(int line, int level); /* line 0 = SCL, 1 = SDA */
void pins_wait(void);               /* the brick's pause of standard-mode I2C's length */

#define HW_SCL_LO() pins_set(0, 0)
#define HW_SDA_HI() pins_set(1, 1)
#define HW_SDA_LO() pins_set(1, 0)
#define HW_SDA_MSB(v) (pins_set(1, (v) >> 7), (v) = (u8)((v) << 1)) /* SDA = bit 7 of v, v shifted left */
#define HW_SCL_HI_PACED() (pins_wait(), pins_set(0, 1), pins_wait()) /* after SCL's low time, before its high's end */
#define HW_LCD_HELPER

#endif
