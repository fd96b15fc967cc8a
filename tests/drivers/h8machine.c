/* SPDX-License-Identifier: MPL-2.0 */
/* The brick's peripherals around the H8/300 simulator (h8machine.h). Registers: rcx-hardware.md 1.6, 3.3, 3.8, 3.9;
 * buttons and standby: 3.5, 3.11. */
#include <stdio.h>
#include <string.h>
#include "h8image.h"
#include "h8machine.h"

#define FRT_TIER 0xFF90
#define FRT_TCSR 0xFF91
#define FRT_FRC 0xFF92
#define FRT_OCR 0xFF94
#define OCIAE 0x08
#define OCFA 0x08
#define SCI_SCR 0xFFDA
#define SCI_TDR 0xFFDB
#define SCI_SSR 0xFFDC
#define SCI_RDR 0xFFDD
#define TIE 0x80
#define RIE 0x40
#define RE 0x10
#define TEIE 0x04
#define TDRE 0x80
#define RDRF 0x40
#define ORER 0x20
#define ERRORS 0x38
#define TEND 0x04
#define AD_ADDRA 0xFFE0
#define AD_ADCSR 0xFFE8
#define ADF 0x80
#define ADIE 0x40
#define ADST 0x20
#define SCAN 0x10
#define CKS 0x08
#define P6DDR 0xFFB9
#define P4DR 0xFFB7
#define P7PIN 0xFFBE
#define P6DR 0xFFBB
#define TMR0_TCR 0xFFC8
#define LCD_SCL 0x20
#define LCD_SDA 0x40
#define SYSCR 0xFFC4
#define SSBY 0x80
#define ISCR 0xFFC6
#define IER 0xFFC7
#define IRQ0_ENTRY 6 /* the index of FD94 in ramvec[]; FD96 (IRQ1) follows */

/* Where each interrupt's entry lives: our own stand-in for the ROM's trampoline, one per RAM vector. */
#define ENTRY(n) (0x0100 + 16 * (n))
static const uint16_t ramvec[] = { 0xFDA2, 0xFDB4, 0xFDB6, 0xFDB8, 0xFDBA, 0xFDBC, /* OCIA ERI RXI TXI TEI ADI */
                                   0xFD94, 0xFD96 };                                /* IRQ0 IRQ1 */

static struct h8machine *self; /* the hooks get the struct h8, first member of the machine */

static void tx_start(struct h8machine *m)
{
    uint8_t *ssr = &m->h.mem[SCI_SSR];
    m->tx_byte = m->h.mem[SCI_TDR];
    m->tx_at = m->h.states + H8M_BYTE;
    *ssr = (uint8_t)((*ssr | TDRE) & ~TEND);
    if (m->nsent < H8M_TX) {
        m->sent[m->nsent] = m->tx_byte;
        m->sent_at[m->nsent++] = m->h.states;
    }
}

static uint8_t ssr_read; /* SSR flags read as 1: only those can be cleared by writing 0 */

static uint8_t io_read(struct h8 *h, uint16_t a, uint8_t held)
{
    (void)h;
    if (a == SCI_SSR)
        ssr_read |= held;
    if (a == P4DR) /* On-Off and Run read 0 while pressed */
        return (uint8_t)((held & ~0x06) | (self->held & H8M_ONOFF ? 0 : 0x02) | (self->held & H8M_RUN ? 0 : 0x04));
    if (a == P7PIN)
        return (uint8_t)((self->held & H8M_VIEW ? 0 : 0x40) | (self->held & H8M_PRGM ? 0 : 0x80));
    if (a == AD_ADCSR && (held & ADF))
        self->ad_read = 1;
    return held;
}

/*
 * The LCD bus (rcx-hardware.md §3.6) as the controller hears it: START and STOP are SDA changing while SCL stays
 * high; a bit is taken as SCL rises, eight to a byte and then the acknowledge clock.
 * And its timing, held to standard-mode I2C (the PCF8566 is a 100 kHz part): every edge is timed in CPU states. A
 * port write lands in the instruction's write cycle, its last bus cycle (H8/300 manual, bus states of each
 * instruction: the next instruction's fetch comes before the read and write of bset/bclr/bst/mov), so `states` at
 * the hook is when the cycle ends; where in its 3 states the pin changes is not known (and the first byte of a word
 * written to FFBA lands 3 states before the second). Conservatively an interval counts from the end of its first
 * write to the start of its last: 3 states less than the hooks' difference. Both lines changing in one write is
 * a fault within a frame (their order is undefined); outside one (start-up, standby, waking) it is not checked.
 * The levels are P6DR's (P6DDR is not looked at: the drivers keep both lines outputs while they use the bus).
 */
static const struct { const char *what; long long least; } lcd_limit[H8M_LCD_TIMES] = {
    [H8M_LCD_HIGH] = { "SCL high", 64 },          /* tHIGH 4.0 us at 62.5 ns a state */
    [H8M_LCD_LOW] = { "SCL low", 76 },            /* tLOW 4.7 us */
    [H8M_LCD_SETUP] = { "SDA set-up", 4 },        /* tSU;DAT 250 ns, before SCL rises */
    [H8M_LCD_HOLD] = { "SDA hold", 0 },           /* tHD;DAT 0, after SCL falls */
    [H8M_LCD_HD_STA] = { "START hold", 64 },      /* tHD;STA 4.0 us, to the first SCL fall */
    [H8M_LCD_SU_STA] = { "START set-up", 76 },    /* tSU;STA 4.7 us, SCL high before SDA falls */
    [H8M_LCD_SU_STO] = { "STOP set-up", 64 },     /* tSU;STO 4.0 us, SCL high before SDA rises */
    [H8M_LCD_BUF] = { "bus free", 76 },           /* tBUF 4.7 us, from a STOP to the next START */
};

static void lcd_time(struct h8machine *m, int k, unsigned long long from)
{
    long long t = (long long)(m->h.states - from) - 3;
    if (!(m->lcd_timed & 1u << k) || t < m->lcd_least[k])
        m->lcd_least[k] = t;
    m->lcd_timed |= 1u << k;
    if (t < lcd_limit[k].least && !m->lcd_faults++)
        snprintf(m->lcd_fault, sizeof m->lcd_fault, "%s %lld states (at least %lld) at state %llu, the write before pc %04X",
                 lcd_limit[k].what, t, lcd_limit[k].least, m->h.states, m->h.pc);
}

static void lcd_bus(struct h8machine *m, uint8_t was, uint8_t now)
{
    uint8_t moved = (uint8_t)((was ^ now) & (LCD_SCL | LCD_SDA));
    unsigned long long t = m->h.states;

    if (!moved)
        return;
    if (moved == (LCD_SCL | LCD_SDA)) {
        if (m->lcd_in && !m->lcd_faults++)
            snprintf(m->lcd_fault, sizeof m->lcd_fault, "SCL and SDA changed in one write at state %llu, before pc %04X",
                     t, m->h.pc);
    } else if (moved == LCD_SDA && (now & LCD_SCL)) {
        lcd_time(m, now & LCD_SDA ? H8M_LCD_SU_STO : H8M_LCD_SU_STA, m->lcd_scl_at);
        if (now & LCD_SDA) {
            if (m->lcd_in) {
                memcpy(m->lcd, m->lcd_rx, m->lcd_n);
                m->lcd_len = m->lcd_n;
                m->lcd_frames++;
            }
            m->lcd_in = 0;
            m->lcd_stop_at = t;
        } else {
            if (m->lcd_stop_at)
                lcd_time(m, H8M_LCD_BUF, m->lcd_stop_at);
            m->lcd_in = 1;
            m->lcd_n = m->lcd_bits = 0;
            m->lcd_start_at = t; /* until SCL first falls */
        }
    } else if (m->lcd_in && moved == LCD_SDA) {
        lcd_time(m, H8M_LCD_HOLD, m->lcd_scl_at);
    } else if (m->lcd_in && (now & LCD_SCL)) {
        lcd_time(m, H8M_LCD_LOW, m->lcd_scl_at);
        lcd_time(m, H8M_LCD_SETUP, m->lcd_sda_at);
        if (m->lcd_bits < 8 && m->lcd_n < H8M_LCD)
            m->lcd_rx[m->lcd_n] = (uint8_t)(m->lcd_rx[m->lcd_n] << 1 | !!(now & LCD_SDA));
        if (++m->lcd_bits == 9) {
            m->lcd_bits = 0;
            m->lcd_n += m->lcd_n < H8M_LCD;
        }
    } else if (m->lcd_in) {
        lcd_time(m, H8M_LCD_HIGH, m->lcd_scl_at);
        if (m->lcd_start_at)
            lcd_time(m, H8M_LCD_HD_STA, m->lcd_start_at);
        m->lcd_start_at = 0;
    }
    if (moved & LCD_SCL)
        m->lcd_scl_at = t;
    if (moved & LCD_SDA)
        m->lcd_sda_at = t;
}

/*
 * The A/D converter (rcx-hardware.md §3.3; the H8/300 family's hardware manuals, "A/D conversion timing"). Setting
 * ADST starts a conversion; its input is sampled from the start delay tD on for tSPL, and its result is in the data
 * register and ADF set 259-266 states after the write (CKS = 0; 131-134 with CKS = 1). tD depends on where the
 * write falls in the converter's clock: 10-17 states (6-9), tSPL is 63 (31). Single mode converts the channel CH
 * and stops (ADST cleared). Scan mode converts AN0 up to CH (group 0; AN4 up with CH bit 2), 256 states (128) a
 * conversion after the first, sets ADF at the end of each pass and starts over, until ADST is cleared; a
 * conversion stopped that way leaves its data register as it was. Figures: the tables of the family (the
 * H8/325's text; tD, tSPL from a sibling whose totals are the 266 and 134 states of the H8/3297's); assumed: in a
 * scan's later conversions the sampling comes as in the first, right after 7 (3) states of delay.
 */
static void ad_convert(struct h8machine *m, unsigned long long from) /* m->ad_ch, its sampling from `from` on */
{
    int fast = m->h.mem[AD_ADCSR] & CKS;
    m->ad_spl_from = from;
    m->ad_spl_at = from + (fast ? 31 : 63);
    m->ad_at = m->ad_spl_at + (fast ? 94 : 186);
}

/* The sampling ends: the level is held. A sensor input's is full scale if its power was on at any time since the
 * sampling started (its removal is later than that, or it is on now: no change since the end can have come yet). */
static void ad_sample(struct h8machine *m)
{
    unsigned ch = m->ad_ch;
    if (m->ad_input)
        m->ad_input(m, ch);
    m->ad_held = ch < 4 ? m->ad_raw[ch] : 0;
    if (ch < 3) {
        struct h8m_sensor *s = &m->sensor[ch];
        s->samples++;
        if ((m->sensor_power >> ch & 1) || s->off_at > m->ad_spl_from) {
            m->ad_held = H8M_AD_POWERED;
        } else {
            s->unpowered++;
            if (s->offs && !s->sampled) {
                s->sampled = 1;
                if (m->ad_spl_at - s->off_at > s->delay_max)
                    s->delay_max = m->ad_spl_at - s->off_at;
            }
        }
    }
    m->ad_spl_at = 0;
}

static void ad_end(struct h8machine *m)
{
    uint8_t *csr = &m->h.mem[AD_ADCSR];
    h8_write16(&m->h, (uint16_t)(AD_ADDRA + 2 * (m->ad_ch & 3)), (uint16_t)(m->ad_held << 6));
    if (!(*csr & SCAN)) {
        *csr = (uint8_t)((*csr | ADF) & ~ADST);
        m->ad_at = 0;
        return;
    }
    if ((m->ad_ch & 3) == (*csr & 3)) {
        *csr |= ADF;
        m->ad_ch = *csr & 4;
    } else {
        m->ad_ch++;
    }
    ad_convert(m, m->ad_at + (*csr & CKS ? 3 : 7));
}

/* The samplings and conversion ends due by now, in order. */
static void ad_due(struct h8machine *m)
{
    while (m->ad_at && (m->ad_spl_at ? m->ad_spl_at : m->ad_at) <= m->h.states) {
        if (m->ad_spl_at)
            ad_sample(m);
        else
            ad_end(m);
    }
}

/* ADCSR written. ADF is cleared by writing 0 after reading it as 1, never set by software. */
static void ad_write(struct h8machine *m, uint8_t was, uint8_t now)
{
    unsigned long long t = m->h.states;
    uint8_t adf = (uint8_t)(was & ADF & ~(m->ad_read && !(now & ADF) ? ADF : 0));
    m->ad_read = 0;
    m->h.mem[AD_ADCSR] = (uint8_t)((now & ~ADF) | adf);
    if (!(now & ADST) || m->ad_broken) {
        m->ad_at = m->ad_spl_at = 0;
    } else if (!(was & ADST)) {
        m->ad_ch = now & SCAN ? now & 4 : now & 7;
        ad_convert(m, t + (now & CKS ? 6 + (3 - t % 4) : 10 + (7 - t % 8)));
    }
}

/* P6.0-P6.2 (P6DR or P6DDR) written: the samplings that ended before it go with the power as it was. */
static void sensor_power(struct h8machine *m)
{
    struct h8 *h = &m->h;
    uint8_t now = h->mem[P6DDR] & h->mem[P6DR] & 7, off = m->sensor_power & ~now, on = now & ~m->sensor_power;
    unsigned ch;

    ad_due(m);
    for (ch = 0; ch < 3; ch++) {
        struct h8m_sensor *s = &m->sensor[ch];
        if (off >> ch & 1) {
            s->offs++;
            s->off_at = h->states;
            s->sampled = 0;
        } else if (on >> ch & 1 && s->offs) {
            s->missed += !s->sampled;
            if (h->states - s->off_at > s->off_max)
                s->off_max = h->states - s->off_at;
        }
    }
    m->sensor_power = now;
}

static void io_write(struct h8 *h, uint16_t a, uint8_t was)
{
    struct h8machine *m = self;
    uint8_t now = h->mem[a];

    m->resched = 1;
    if (a == P6DR || a == P6DDR)
        sensor_power(m);
    if (a == P6DR)
        lcd_bus(m, was, now);
    else if (a == TMR0_TCR) {
        m->tone_tcr = now;
        m->tone_at = h->states;
    }
    else if (a == FRT_FRC || a == FRT_FRC + 1)
        m->tick_at = h->states + 32ull * (h8_read16(h, FRT_OCR) + 1u); /* φ/32, cleared at the match */
    else if (a == AD_ADCSR)
        ad_write(m, was, now);
    else if (a == SCI_SSR) {
        /* A flag is cleared by writing 0 after reading it as 1; software cannot set one (flags: bits 7-3). */
        now = (uint8_t)((was & 0xF8 & ~(ssr_read & ~now)) | (was & 0x06) | (now & 0x01)); /* TEND, MPB read-only */
        h->mem[a] = now;
        ssr_read = 0;
        if ((was & TDRE) && !(now & TDRE) && !m->tx_at)
            tx_start(m); /* TDR written: into the shift register at once when it is free */
    }
}

/* Every write to F000-FB7F or FF80-FF87 reaches the motor latch (rcx-hardware.md §3.2). */
static void latch_write(struct h8 *h, uint8_t v)
{
    struct h8machine *m = self;
    if (v != m->latch) {
        m->latch = v;
        m->latch_at = h->states;
    }
}

static void receive_due(struct h8machine *m)
{
    uint8_t *ssr = &m->h.mem[SCI_SSR];
    while (m->rx_tail != m->rx_head && m->rx_at[m->rx_tail % H8M_RX] <= m->h.states) {
        if (m->h.mem[SCI_SCR] & RE) {
            if (*ssr & RDRF) {
                *ssr |= ORER;
            } else {
                m->h.mem[SCI_RDR] = m->rx_byte[m->rx_tail % H8M_RX];
                *ssr |= RDRF;
            }
        }
        m->rx_tail++;
    }
}

/*
 * Buttons and the IRQ pins. On-Off drives IRQ1 and Run IRQ0 (rcx-hardware.md §3.5); ISCR bit n = 1 makes IRQn
 * edge-sensed: a falling edge (a press) latches a request until the CPU accepts it; bit n = 0 makes it level-sensed:
 * requested while the pin is low. IER bit n lets the request through to the CPU. Assumed, as the H8/3297 manual's
 * block diagram is read here: the edge latches whatever IER holds (latch_needs_ier selects the other reading), and a
 * change of ISCR keeps a latched edge. With contact bounce a press is several edges, so both matter.
 */
static unsigned long long next_change(const struct h8machine *m)
{
    unsigned long long t = ~0ull;
    unsigned i;
    for (i = 0; i < m->nchanges; i++)
        if (m->change_at[i] < t)
            t = m->change_at[i];
    return t;
}

static uint8_t irq_pins_low(const struct h8machine *m)
{
    return (uint8_t)((m->held & H8M_ONOFF ? 0x02 : 0) | (m->held & H8M_RUN ? 0x01 : 0));
}

/* The changes due by now, oldest first. */
static void buttons_due(struct h8machine *m)
{
    unsigned long long t;
    while ((t = next_change(m)) <= m->h.states) {
        unsigned i = 0, n = m->nchanges - 1;
        uint8_t low = irq_pins_low(m);
        while (m->change_at[i] != t)
            i++;
        if (m->change_down[i])
            m->held |= m->change_button[i];
        else
            m->held &= (uint8_t)~m->change_button[i];
        low = (uint8_t)(irq_pins_low(m) & ~low & m->h.mem[ISCR]); /* falling edges, where edge-sensed */
        m->irq_latched |= m->latch_needs_ier ? low & m->h.mem[IER] : low;
        m->change_at[i] = m->change_at[n]; /* the last one takes its place */
        m->change_button[i] = m->change_button[n];
        m->change_down[i] = m->change_down[n];
        m->nchanges = n;
    }
}

/* IRQ0-1 requests that IER lets through, as a bit mask. */
static uint8_t irq_requests(const struct h8machine *m)
{
    uint8_t iscr = m->h.mem[ISCR];
    return (uint8_t)(((m->irq_latched & iscr) | (irq_pins_low(m) & ~iscr)) & m->h.mem[IER] & 0x03);
}

int h8m_button(struct h8machine *m, uint8_t button, int down, unsigned long long at)
{
    if (m->nchanges == H8M_CHANGES)
        return -1;
    m->change_at[m->nchanges] = at;
    m->change_button[m->nchanges] = button;
    m->change_down[m->nchanges++] = (uint8_t)!!down;
    return 0;
}

/*
 * Software standby (H8/3297 hardware manual, power-down modes; rcx-hardware.md §3.11): SLEEP with SYSCR.SSBY set
 * stops the clock, and the on-chip supporting modules (FRT, TMR0/1, SCI, A/D) are initialised: their registers take
 * their reset values, a byte being sent or received is lost. Ports, RAM and CPU registers keep their contents. An
 * IRQ0/1 request that IER enables and the CPU does not mask (NMI is not wired on the RCX: not modelled) starts the
 * oscillator; after the settling time SYSCR.STS selects, the clock runs again and the interrupt is taken. Assumed:
 * a request that is gone by then (a level-sensed pin released) leaves the chip in standby.
 */
static void standby_enter(struct h8machine *m)
{
    static const struct { uint16_t a; uint8_t v; } reset[] = {
        { 0xFF90, 0x01 }, { 0xFF91, 0x00 }, { 0xFF92, 0x00 }, { 0xFF93, 0x00 }, { 0xFF94, 0xFF }, { 0xFF95, 0xFF },
        { 0xFF96, 0x00 }, { 0xFF97, 0xE0 },                                         /* FRT (OCRA, as OCRS = 0) */
        { 0xFFC8, 0x00 }, { 0xFFC9, 0x10 }, { 0xFFCA, 0xFF }, { 0xFFCB, 0xFF }, { 0xFFCC, 0x00 }, /* TMR0 */
        { 0xFFD0, 0x00 }, { 0xFFD1, 0x10 }, { 0xFFD2, 0xFF }, { 0xFFD3, 0xFF }, { 0xFFD4, 0x00 }, /* TMR1 */
        { 0xFFD8, 0x00 }, { 0xFFD9, 0xFF }, { 0xFFDA, 0x00 }, { 0xFFDB, 0xFF }, { 0xFFDC, 0x84 }, { 0xFFDD, 0x00 },
        { 0xFFE8, 0x00 }, { 0xFFE9, 0x7F },                                         /* SCI, A/D */
    };
    unsigned i;

    memcpy(m->sleep_io, m->h.mem + 0xFF80, sizeof m->sleep_io); /* before the modules are reset */
    m->standby = 1;
    m->standbys++;
    m->settle_at = 0;
    m->tick_at = m->ad_at = m->ad_spl_at = m->tx_at = 0;
    for (i = 0; i < sizeof reset / sizeof reset[0]; i++)
        m->h.mem[reset[i].a] = reset[i].v;
    memset(m->h.mem + AD_ADDRA, 0, 8);
}

/* Time in standby up to `to` at most (0), or 0 states and the wake-up (1) once the settling is over. */
static int standby_wait(struct h8machine *m, unsigned long long to)
{
    struct h8 *h = &m->h;
    if (!m->settle_at && irq_requests(m) && !(h->ccr & 0x80)) {
        static const unsigned sts[8] = { 8192, 16384, 32768, 65536, 131072, 131072, 131072, 131072 };
        m->settle_at = h->states + sts[h->mem[SYSCR] >> 4 & 7];
    }
    if (m->settle_at && h->states >= m->settle_at) {
        m->settle_at = 0;
        if (irq_requests(m)) {
            m->standby = 0;
            return 1;
        }
    }
    if (m->settle_at && m->settle_at < to)
        to = m->settle_at;
    m->standby_states += to - h->states;
    h->states = to;
    return 0;
}

/* The peripherals' events due by now. */
static void events(struct h8machine *m)
{
    struct h8 *h = &m->h;

    if (m->tick_at && h->states >= m->tick_at) {
        h->mem[FRT_TCSR] |= OCFA;
        m->tick_at += 32ull * (h8_read16(h, FRT_OCR) + 1u);
        m->ms_seen++;
    }
    ad_due(m);
    if (m->tx_at && h->states >= m->tx_at) {
        uint8_t echo = m->tx_byte;
        m->tx_at = 0;
        h8m_receive(m, &echo, 1, h->states); /* the brick hears itself */
        if (!(h->mem[SCI_SSR] & TDRE))
            tx_start(m);
        else
            h->mem[SCI_SSR] |= TEND;
    }
    receive_due(m);
    buttons_due(m);
}

static unsigned long long next_event(const struct h8machine *m)
{
    unsigned long long t = next_change(m);
    if (m->tick_at && m->tick_at < t)
        t = m->tick_at;
    if (m->ad_at && (m->ad_spl_at ? m->ad_spl_at : m->ad_at) < t)
        t = m->ad_spl_at ? m->ad_spl_at : m->ad_at;
    if (m->tx_at && m->tx_at < t)
        t = m->tx_at;
    if (m->rx_tail != m->rx_head && m->rx_at[m->rx_tail % H8M_RX] < t)
        t = m->rx_at[m->rx_tail % H8M_RX];
    return t;
}

/* The highest-priority interrupt requested and enabled (lowest vector number first), -1 if none. */
static int pending(const struct h8 *h)
{
    uint8_t ssr = h->mem[SCI_SSR], scr = h->mem[SCI_SCR], ad = h->mem[AD_ADCSR];
    if ((h->mem[FRT_TCSR] & OCFA) && (h->mem[FRT_TIER] & OCIAE))
        return 0;
    if ((ssr & ERRORS) && (scr & RIE))
        return 1;
    if ((ssr & RDRF) && (scr & RIE))
        return 2;
    if ((ssr & TDRE) && (scr & TIE))
        return 3;
    if ((ssr & TEND) && (scr & TEIE))
        return 4;
    if ((ad & ADF) && (ad & ADIE))
        return 5;
    return -1;
}

int h8m_run(struct h8machine *m, unsigned long long until)
{
    struct h8 *h = &m->h;
    unsigned long long next = next_event(m);

    self = m;
    while (h->states < until) {
        int irq;
        uint8_t op;
        if (h->states >= next) {
            events(m);
            next = next_event(m);
        }
        if (m->standby && !standby_wait(m, next < until ? next : until))
            continue;
        /* IRQ0 and IRQ1 come first (vectors 4 and 5); an edge's latch is cleared as it is accepted. */
        if (!m->inhibit && !(h->ccr & 0x80) && (irq = irq_requests(m)) != 0) {
            irq = irq & 1 ? 0 : 1;
            m->irq_latched &= (uint8_t)~(1u << irq);
            h8_interrupt(h, ENTRY(IRQ0_ENTRY + irq));
        } else if (!m->inhibit && !(h->ccr & 0x80) && (irq = pending(h)) >= 0) {
            h8_interrupt(h, ENTRY(irq));
        }
        if (h->asleep) {
            unsigned long long to = next < until ? next : until;
            if (to == ~0ull) {
                snprintf(h->error, sizeof h->error, "asleep with nothing to wake it (pc %04X)", h->pc);
                return -1;
            }
            m->slept += to - h->states;
            h->states = to;
            continue;
        }
        /* LDC, ORC, XORC and ANDC: the CPU runs the next instruction before it takes an interrupt. */
        op = h->mem[h->pc];
        m->inhibit = op >= 0x03 && op <= 0x07;
        if (h8_step_traced(h))
            return -1;
        if (m->resched) { /* a timer set up, a conversion or a transmission started: not only at the next event */
            m->resched = 0;
            next = next_event(m);
        }
        if (h->asleep && (h->mem[SYSCR] & SSBY)) {
            standby_enter(m);
            next = next_event(m);
        }
    }
    return 0;
}

void h8m_receive(struct h8machine *m, const uint8_t *bytes, unsigned n, unsigned long long at)
{
    unsigned long long t = at;
    if (m->rx_head != m->rx_tail && m->rx_at[(m->rx_head - 1) % H8M_RX] + H8M_BYTE > t)
        t = m->rx_at[(m->rx_head - 1) % H8M_RX] + H8M_BYTE;
    while (n-- && m->rx_head - m->rx_tail < H8M_RX) {
        m->rx_at[m->rx_head % H8M_RX] = t;
        m->rx_byte[m->rx_head++ % H8M_RX] = *bytes++;
        t += H8M_BYTE;
    }
}

unsigned long long h8m_command(struct h8machine *m, const uint8_t *cmd, unsigned n)
{
    uint8_t p[3 + 2 * H8M_COMMAND_MAX + 2], op = cmd[0];
    unsigned i, k = 0, sum = 0;

    if (n && (op & 0xF7) == (m->last_op & 0xF7))
        op = (uint8_t)(m->last_op ^ 0x08); /* a new command with the same opcode: the other toggle */
    m->last_op = op;
    p[k++] = 0x55;
    p[k++] = 0xFF;
    p[k++] = 0x00;
    for (i = 0; i < n && i < H8M_COMMAND_MAX; i++) {
        uint8_t b = i ? cmd[i] : op;
        p[k++] = b;
        p[k++] = (uint8_t)~b;
        sum += b;
    }
    p[k++] = (uint8_t)sum;
    p[k++] = (uint8_t)~sum;
    h8m_receive(m, p, k, m->h.states + H8M_BYTE);
    return m->rx_at[(m->rx_head - 1) % H8M_RX];
}

int h8m_reply(struct h8machine *m, unsigned from, unsigned len, uint8_t *reply, unsigned long long limit)
{
    unsigned total = 3 + 2 * (len + 1), i, sum = 0;
    unsigned long long end = m->h.states + limit;

    while (m->nsent < from + total || m->tx_at) {
        if (m->h.states >= end || h8m_run(m, m->h.states + H8M_MS / 4)) {
            fprintf(stderr, "reply: timeout? %llu %llu from %u nsent %u\n", m->h.states, end, from, m->nsent);
            return -1;
        }
    }
    if (m->nsent != from + total || m->sent[from] != 0x55 || m->sent[from + 1] != 0xFF || m->sent[from + 2] != 0x00) {
        fprintf(stderr, "reply: header at %u, nsent %u:", from, m->nsent);
        for (i = from; i < m->nsent; i++)
            fprintf(stderr, " %02x", m->sent[i]);
        fprintf(stderr, "\n");
        return -1;
    }
    for (i = 0; i <= len; i++) {
        uint8_t b = m->sent[from + 3 + 2 * i];
        if ((m->sent[from + 4 + 2 * i] ^ b) != 0xFF)
            return -1;
        if (i < len) {
            sum += b;
            if (reply)
                reply[i] = b;
        } else if (b != (uint8_t)sum) {
            return -1;
        }
    }
    return 0;
}

int h8m_transact(struct h8machine *m, const uint8_t *cmd, unsigned n, uint8_t *reply, unsigned len,
                 unsigned long long *latency)
{
    unsigned from = m->nsent;
    unsigned long long last = h8m_command(m, cmd, n);

    if (h8m_reply(m, from, len, reply, last - m->h.states + H8M_CLOCK))
        return -1;
    if (latency)
        *latency = m->sent_at[from] - last;
    return 0;
}

int h8m_boot(struct h8machine *m, const char *image, const char *nm)
{
    unsigned i;

    memset(m, 0, sizeof *m);
    if (h8_image_load(&m->h, image, nm))
        return -1;
    for (i = 0; i < sizeof ramvec / sizeof ramvec[0]; i++) {
        static const uint8_t entry[] = { 0x6D, 0xF6, 0x6B, 0x06, 0, 0, 0x5D, 0x60, 0x6D, 0x76, 0x56, 0x70 };
        uint8_t *p = m->h.mem + ENTRY(i);
        memcpy(p, entry, sizeof entry); /* mov.w r6,@-r7; mov.w @vec,r6; jsr @r6; mov.w @r7+,r6; rte */
        p[4] = (uint8_t)(ramvec[i] >> 8);
        p[5] = (uint8_t)ramvec[i];
    }
    m->h.mem[SCI_SSR] = TDRE | TEND; /* the SCI's state after reset */
    /* As the ROM hands over (rcx-hardware.md §2.3, §6), where crt0.s (run above) leaves them alone. */
    m->h.mem[ISCR] = 0x03;             /* IRQ0 and IRQ1 edge-sensed */
    m->h.mem[SYSCR] = 0xCB;            /* SSBY set */
    for (i = 0; i < 3; i++)
        m->ad_raw[i] = 1023;           /* nothing connected */
    m->ad_raw[3] = 300;                /* 8.4 V */
    m->h.io_read = io_read;
    m->h.io_write = io_write;
    m->h.latch_write = latch_write;
    m->h.may_sleep = 1;
    m->h.states = 0;
    return 0;
}

int h8m_download_task(struct h8machine *m, uint8_t n, const uint8_t *code, unsigned len)
{
    uint8_t begin[6] = { 0x25, 0, 0, 0, 0, 0 }, block[64], reply[2];
    unsigned i, sum = 0;

    if (len > sizeof block - 6)
        return -1;
    begin[2] = n;
    begin[4] = (uint8_t)len;
    block[0] = 0x45;
    block[1] = block[2] = 0; /* block 0: the last */
    block[3] = (uint8_t)len;
    block[4] = 0;
    for (i = 0; i < len; i++)
        sum += block[5 + i] = code[i];
    block[5 + len] = (uint8_t)sum;
    if (h8m_transact(m, begin, sizeof begin, reply, 2, NULL) || reply[1])
        return -1;
    if (h8m_transact(m, block, 6 + len, reply, 2, NULL) || reply[1])
        return -1;
    return 0;
}

uint16_t h8m_rotation_raw(unsigned long long step)
{
    static const uint16_t level[4] = { 1000, 860, 400, 640 };
    return level[step & 3];
}

uint16_t h8m_light_sweep_raw(unsigned long long ms)
{
    unsigned p = (unsigned)(ms % 400), noise = ((uint32_t)ms * 2654435761u >> 24) % 41;
    return (uint16_t)((p < 200 ? 300 + 3 * p : 900 - 3 * (p - 200)) + noise - 20);
}
