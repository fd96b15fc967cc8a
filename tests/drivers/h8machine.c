/* The brick's peripherals around the H8/300 simulator (h8machine.h). Registers: rcx-hardware.md 1.6, 3.3, 3.8, 3.9. */
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
#define AD_SCAN_STATES (4 * 266) /* four conversions at φ/... 266 states each (CKS = 0) */
#define P4DR 0xFFB7
#define P7PIN 0xFFBE

/* Where each interrupt's entry lives: our own stand-in for the ROM's trampoline, one per RAM vector. */
#define ENTRY(n) (0x0100 + 16 * (n))
static const uint16_t ramvec[] = { 0xFDA2, 0xFDB4, 0xFDB6, 0xFDB8, 0xFDBA, 0xFDBC }; /* OCIA ERI RXI TXI TEI ADI */

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
    if (a == P4DR)
        return (uint8_t)(held | 0x06); /* On-Off and Run released */
    if (a == P7PIN)
        return 0xC0;                   /* View and Prgm released */
    return held;
}

static void io_write(struct h8 *h, uint16_t a, uint8_t was)
{
    struct h8machine *m = self;
    uint8_t now = h->mem[a];

    if (a == FRT_FRC || a == FRT_FRC + 1)
        m->tick_at = h->states + 32ull * (h8_read16(h, FRT_OCR) + 1u); /* φ/32, cleared at the match */
    else if (a == AD_ADCSR)
        m->ad_at = now & ADST ? (m->ad_at ? m->ad_at : h->states + AD_SCAN_STATES) : 0;
    else if (a == SCI_SSR) {
        /* A flag is cleared by writing 0 after reading it as 1; software cannot set one (flags: bits 7-3). */
        now = (uint8_t)((was & 0xF8 & ~(ssr_read & ~now)) | (was & 0x06) | (now & 0x01)); /* TEND, MPB read-only */
        h->mem[a] = now;
        ssr_read = 0;
        if ((was & TDRE) && !(now & TDRE) && !m->tx_at)
            tx_start(m); /* TDR written: into the shift register at once when it is free */
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

/* The peripherals' events due by now. */
static void events(struct h8machine *m)
{
    struct h8 *h = &m->h;
    unsigned i;

    if (m->tick_at && h->states >= m->tick_at) {
        h->mem[FRT_TCSR] |= OCFA;
        m->tick_at += 32ull * (h8_read16(h, FRT_OCR) + 1u);
        m->ms_seen++;
    }
    if (m->ad_at && h->states >= m->ad_at) {
        if (m->ad_input)
            m->ad_input(m);
        for (i = 0; i < 4; i++)
            h8_write16(h, (uint16_t)(AD_ADDRA + 2 * i), (uint16_t)(m->ad_raw[i] << 6));
        h->mem[AD_ADCSR] = (uint8_t)((h->mem[AD_ADCSR] | ADF) & ~ADST); /* one pass, as brickEmu's */
        m->ad_at = 0;
    }
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
}

static unsigned long long next_event(const struct h8machine *m)
{
    unsigned long long t = ~0ull;
    if (m->tick_at && m->tick_at < t)
        t = m->tick_at;
    if (m->ad_at && m->ad_at < t)
        t = m->ad_at;
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
        if (h->states >= next) {
            events(m);
            next = next_event(m);
        }
        if (!(h->ccr & 0x80) && (irq = pending(h)) >= 0)
            h8_interrupt(h, ENTRY(irq));
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
        if (h->trace) {
            uint16_t pc = h->pc;
            unsigned long long before = h->states;
            if (h8_step(h))
                return -1;
            h->trace(h, pc, (unsigned)(h->states - before));
        } else if (h8_step(h)) {
            return -1;
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
    uint8_t p[3 + 2 * 64 + 2], op = cmd[0];
    unsigned i, k = 0, sum = 0;

    if (n && (op & 0xF7) == (m->last_op & 0xF7))
        op = (uint8_t)(m->last_op ^ 0x08); /* a new command with the same opcode: the other toggle */
    m->last_op = op;
    p[k++] = 0x55;
    p[k++] = 0xFF;
    p[k++] = 0x00;
    for (i = 0; i < n && i < 64; i++) {
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
    if (m->sent[from] != 0x55 || m->sent[from + 1] != 0xFF || m->sent[from + 2] != 0x00) {
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
    for (i = 0; i < 3; i++)
        m->ad_raw[i] = 1023;           /* nothing connected */
    m->ad_raw[3] = 300;                /* 8.4 V */
    m->h.io_read = io_read;
    m->h.io_write = io_write;
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
