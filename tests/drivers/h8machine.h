/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The whole brick around the simulated CPU (h8sim.h): the image's main() runs with the peripherals the firmware
 * uses, so that time, interrupts and sleep are the image's own. Modelled: the FRT compare match A (the tick), the
 * A/D converter (single and scan mode, the scan repeating until stopped; when each input is sampled, and whether
 * its sensor's power was off then), the SCI at 2400 Bd 8O1 with the brick hearing its own transmission, SLEEP until
 * the next interrupt, and the ROM's interrupt entry (push r6, call the RAM vector, pop r6, rte: rcx-hardware.md §6)
 * as code of its own in the on-chip ROM's place. Everything else reads back what was written.
 * Buttons (h8m_button) and the IRQ0/IRQ1 pins they drive, software standby and the wake-up from it, and the LCD
 * bus's frames (decoded from the port writes) too; h8machine.c says what of that is assumed.
 */
#ifndef H8MACHINE_H
#define H8MACHINE_H

#include "h8sim.h"

#define H8M_CLOCK 16000000ull
#define H8M_MS (H8M_CLOCK / 1000)
#define H8M_BYTE (H8M_CLOCK * 11 / 2400) /* start, 8 data, parity, stop */
#define H8M_RX 512
#define H8M_COMMAND_MAX 206 /* bytes of a command h8m_command() sends: a download block of 200 (src/ir.h, IR_RX_MAX) */
#define H8M_TX 4096
#define H8M_CHANGES 64
#define H8M_LCD 16
/* The LCD bus's timing, as intervals of struct h8machine's lcd_least (standard-mode I2C names). */
enum { H8M_LCD_HIGH, H8M_LCD_LOW, H8M_LCD_SETUP, H8M_LCD_HOLD, H8M_LCD_HD_STA, H8M_LCD_SU_STA, H8M_LCD_SU_STO,
       H8M_LCD_BUF, H8M_LCD_TIMES };
/* Buttons, as bits of `held` and of h8m_button (rcx-hardware.md §3.5). */
#define H8M_ONOFF 0x01 /* P4.1, IRQ1 */
#define H8M_RUN 0x02   /* P4.2, IRQ0 */
#define H8M_VIEW 0x04  /* P7.6 */
#define H8M_PRGM 0x08  /* P7.7 */
/* What a channel converts while its sensor is powered: the line near the battery's rail, full scale. */
#define H8M_AD_POWERED 1023

/* One sensor input's power (P6.n as an output at 1 powers the sensor on ANn) and how its channel was sampled, in
 * states. A removal is a falling edge of P6DDR.n & P6DR.n; a sampling is unpowered if the power was off from its
 * start to its end (the hold, when the sample-and-hold keeps the level converted). */
struct h8m_sensor {
    unsigned offs;                          /* removals */
    unsigned long long off_at;              /* the last one (0: never) */
    unsigned samples, unpowered;            /* samplings of the channel; those with the power off all through */
    unsigned missed;                        /* power applied again without an unpowered sampling since its removal */
    unsigned long long delay_max;           /* the longest from a removal to the end of the first unpowered
                                             * sampling after it */
    unsigned long long off_max;             /* the longest removal (until the power came back) */
    int sampled;                            /* an unpowered sampling since the last removal */
};

struct h8machine {
    struct h8 h;
    unsigned long long tick_at;             /* the next compare match, 0 while the FRT is not set up */
    unsigned long long ad_at;               /* the end of the running conversion, 0 if none */
    unsigned long long ad_spl_from, ad_spl_at; /* its input sampling; ad_spl_at 0 once taken */
    uint8_t ad_ch;                          /* its channel */
    uint8_t ad_read;                        /* ADF read as 1: writing 0 to it clears it */
    uint16_t ad_held;                       /* the level it sampled (raw10) */
    uint16_t ad_raw[4];                     /* raw10 of AN0-AN3 (inputs 3, 2, 1, battery) */
    int ad_broken;                          /* if set, a conversion started never ends: a fault no converter has,
                                             * but the firmware must not hang on it */
    void (*ad_input)(struct h8machine *m, unsigned ch); /* if set, called as each sampling of channel ch ends,
                                             * before ad_raw[ch] is taken */
    uint8_t sensor_power;                   /* bit n: P6.n an output at 1, the sensor on ANn powered */
    struct h8m_sensor sensor[3];            /* AN0-AN2 (inputs 3, 2, 1) */
    unsigned long long tx_at;               /* the end of the byte being sent, 0 if the transmitter is idle */
    uint8_t tx_byte;
    unsigned long long rx_at[H8M_RX];       /* bytes to receive, at the end of their frame */
    uint8_t rx_byte[H8M_RX];
    unsigned rx_head, rx_tail;
    uint8_t sent[H8M_TX];                   /* every byte sent, and when its transmission started */
    unsigned long long sent_at[H8M_TX];
    unsigned nsent;
    unsigned long long slept;               /* states spent in SLEEP */
    unsigned long long ms_seen;             /* compare matches so far */
    uint8_t last_op;                        /* the host's last opcode, for its toggle bit */
    uint8_t held;                           /* buttons down now (H8M_ONOFF ...) */
    unsigned long long change_at[H8M_CHANGES]; /* button changes to come (h8m_button), in no particular order */
    uint8_t change_button[H8M_CHANGES], change_down[H8M_CHANGES];
    unsigned nchanges;
    uint8_t irq_latched;                    /* falling edges on IRQ0/IRQ1 not yet accepted (bit n: IRQn) */
    int latch_needs_ier;                    /* the other reading of the manual: an edge latches only while IER
                                             * enables it (default: whatever IER holds) */
    int inhibit;                            /* the last instruction wrote CCR: no interrupt before the next */
    int standby;                            /* in software standby: no clock, the peripherals reset */
    unsigned long long settle_at;           /* the end of the oscillator's settling once woken, 0 before */
    unsigned standbys;                      /* software standbys entered */
    unsigned long long standby_states;      /* states spent in standby, settling included */
    uint8_t tone_tcr;                       /* the last value written to TMR0's TCR (0: no tone) ... */
    unsigned long long tone_at;             /* ... and when */
    uint8_t latch;                          /* the motor latch as last written ... */
    unsigned long long latch_at;            /* ... and when it last changed */
    int resched;                            /* a register was written: the next event may have moved (a conversion
                                             * the converter starts itself comes at an event, which re-plans anyway) */
    uint8_t sleep_io[128];                  /* FF80-FFFF as the SLEEP that entered the last standby found them */
    uint8_t lcd[H8M_LCD];                   /* the last complete frame on the LCD bus (START to STOP) */
    unsigned lcd_len, lcd_frames;
    uint8_t lcd_rx[H8M_LCD];                /* the frame being sent */
    unsigned lcd_n, lcd_bits;
    int lcd_in;
    /* Its timing (h8machine.c lcd_bus): when each line last changed, the last STOP, the START until SCL first
     * falls; the shortest of each interval (in states, H8M_LCD_HIGH ...; lcd_timed bit k: lcd_least[k] is set),
     * how many broke their standard-mode limit and what the first was. */
    unsigned long long lcd_scl_at, lcd_sda_at, lcd_stop_at, lcd_start_at;
    long long lcd_least[H8M_LCD_TIMES];
    unsigned lcd_timed, lcd_faults;
    char lcd_fault[120];
};

/* Load the image, run its start-up code, reset the peripherals; main() is next. 0 on success. */
int h8m_boot(struct h8machine *m, const char *image, const char *nm);
/* Press (down != 0) or release `button` at `at` (states). 0, or -1 if too many changes are waiting. */
int h8m_button(struct h8machine *m, uint8_t button, int down, unsigned long long at);
/* Run until h.states reaches `until`. 0, or -1 with h.error set. */
int h8m_run(struct h8machine *m, unsigned long long until);
/* Queue bytes from the host's IR tower, the first received at `at` (or as soon as the last queued one). */
void h8m_receive(struct h8machine *m, const uint8_t *bytes, unsigned n, unsigned long long at);
/* A command as a packet (55 FF 00, each byte and its complement, the sum and its complement), received from now on.
 * Returns when its last byte is received. */
unsigned long long h8m_command(struct h8machine *m, const uint8_t *cmd, unsigned n);
/* Run until the brick has sent a reply of `len` bytes (opcode included) starting at sent[from], and its last byte
 * has left, at most `limit` states from now. The reply's bytes go to `reply` (if not NULL). 0, or -1 on timeout or
 * a malformed reply. */
int h8m_reply(struct h8machine *m, unsigned from, unsigned len, uint8_t *reply, unsigned long long limit);
/* h8m_command, then h8m_reply; the states from the command's last byte to the start of the reply's first in
 * `latency` (if not NULL). 0 or -1. */
int h8m_transact(struct h8machine *m, const uint8_t *cmd, unsigned n, uint8_t *reply, unsigned len,
                 unsigned long long *latency);
/* Download `code` as task n (BeginOfTask, one ContinueDL block) the way nqc does, each command waiting for its reply;
 * opcodes alternate their toggle bit as a host's repeats must. 0 on success (both replies 0). */
int h8m_download_task(struct h8machine *m, uint8_t n, const uint8_t *code, unsigned len);

/* Inputs that change every millisecond (issue 21), as raw10 values for ad_input: a rotation sensor `step` steps on
 * (phases 0-1-2-3 by level, rcx-hardware.md §3.3), and a light sensor at millisecond `ms` of a sweep from 300 to 900
 * and back in 400 ms, with noise of +-20 each millisecond. */
uint16_t h8m_rotation_raw(unsigned long long step);
uint16_t h8m_light_sweep_raw(unsigned long long ms);

#endif
