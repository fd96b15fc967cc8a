/* SPDX-License-Identifier: MPL-2.0 */
/* H8/300 instruction-set simulator for host tools (h8sim.h). Encodings and flags: the H8/300 programming manual. */
#include <stdio.h>
#include <string.h>
#include "h8sim.h"

#define F_C 0x01
#define F_V 0x02
#define F_Z 0x04
#define F_N 0x08
#define F_H 0x20
#define F_I 0x80

#define RETURN_MAGIC 0x0002 /* inside the ROM's vector table: never a real return address */

/* ---- memory and its cost ---- */

enum region { EXTERNAL, ONCHIP, IO };

static enum region region(uint16_t a)
{
    if (a < 0x8000 || (a >= 0xFD80 && a < 0xFF80))
        return ONCHIP; /* mask ROM or on-chip RAM */
    return a >= 0xFF88 ? IO : EXTERNAL;
}

#define P5DDR 0xFFB8
#define P5DR 0xFFBA
#define P5_RAM 0x04 /* P5.2: 0 = external RAM awake, 1 = power-save */

/* An access to external RAM (not the motor latch at FF80-FF87) while P5.2 is not an output at 0. */
static void ram_access(struct h8 *h, uint16_t a, const char *what)
{
    if (h->ram_guard && a >= 0x8000 && a < 0xFD80 && !h->ram_fault[0] &&
        (!(h->mem[P5DDR] & P5_RAM) || (h->mem[P5DR] & P5_RAM)))
        snprintf(h->ram_fault, sizeof h->ram_fault, "external RAM %s at %04X while P5.2 is %s (pc %04X)", what, a,
                 h->mem[P5DDR] & P5_RAM ? "high (power-save)" : "not an output", h->pc);
}

static uint8_t rd8(struct h8 *h, uint16_t a)
{
    ram_access(h, a, "read");
    h->states += region(a) == ONCHIP ? 2 : 3;
    if (h->io_read && a >= 0xFF88)
        return h->io_read(h, a, h->mem[a]);
    return h->mem[a];
}

static void latch(struct h8 *h, uint16_t a, uint8_t v)
{
    if (h->latch_write && ((a >= 0xF000 && a < 0xFB80) || (a >= 0xFF80 && a < 0xFF88)))
        h->latch_write(h, v);
}

static void wr8(struct h8 *h, uint16_t a, uint8_t v)
{
    uint8_t was = h->mem[a];
    ram_access(h, a, "written");
    h->states += region(a) == ONCHIP ? 2 : 3;
    h->mem[a] = v;
    latch(h, a, v);
    if (h->io_write && a >= 0xFF88)
        h->io_write(h, a, was);
}

static int aligned(struct h8 *h, uint16_t a)
{
    if (a & 1)
        snprintf(h->error, sizeof h->error, "word access at odd address %04X (pc %04X)", a, h->pc);
    return !(a & 1);
}

uint16_t h8_read16(const struct h8 *h, uint16_t a)
{
    return (uint16_t)(h->mem[a] << 8 | h->mem[(uint16_t)(a + 1)]);
}

void h8_write16(struct h8 *h, uint16_t a, uint16_t v)
{
    h->mem[a] = (uint8_t)(v >> 8);
    h->mem[(uint16_t)(a + 1)] = (uint8_t)v;
}

/* A word on an 8-bit bus (external RAM, the register field) is two byte accesses. */
static uint16_t rd16(struct h8 *h, uint16_t a)
{
    ram_access(h, a, "read");
    h->states += region(a) == ONCHIP ? 2 : 6;
    aligned(h, a);
    if (h->io_read && a >= 0xFF88)
        return (uint16_t)(h->io_read(h, a, h->mem[a]) << 8 | h->io_read(h, (uint16_t)(a + 1), h->mem[(uint16_t)(a + 1)]));
    return h8_read16(h, a);
}

static void wr16(struct h8 *h, uint16_t a, uint16_t v)
{
    uint8_t was = h->mem[a], was1 = h->mem[(uint16_t)(a + 1)];
    ram_access(h, a, "written");
    h->states += region(a) == ONCHIP ? 2 : 6;
    aligned(h, a);
    h8_write16(h, a, v);
    latch(h, a, (uint8_t)(v >> 8));
    latch(h, (uint16_t)(a + 1), (uint8_t)v);
    if (h->io_write && a >= 0xFF88) {
        h->io_write(h, a, was);
        h->io_write(h, (uint16_t)(a + 1), was1);
    }
}

static uint16_t fetch(struct h8 *h)
{
    ram_access(h, h->pc, "fetched");
    uint16_t w = rd16(h, h->pc);
    h->pc = (uint16_t)(h->pc + 2);
    return w;
}

/* The extra instruction fetch a branch, jump, call or return makes at where it continues. */
static void prefetch(struct h8 *h)
{
    ram_access(h, h->pc, "fetched");
    h->states += region(h->pc) == EXTERNAL ? 6 : 2;
}

/* ---- registers and flags ---- */

static uint8_t rb(const struct h8 *h, int c)
{
    return (uint8_t)(c & 8 ? h->r[c & 7] : h->r[c & 7] >> 8);
}

static void wb(struct h8 *h, int c, uint8_t v)
{
    uint16_t *r = &h->r[c & 7];
    *r = (uint16_t)(c & 8 ? (*r & 0xFF00) | v : (*r & 0x00FF) | v << 8);
}

static void nz8(struct h8 *h, uint8_t v)
{
    h->ccr = (uint8_t)((h->ccr & ~(F_N | F_Z | F_V)) | (v & 0x80 ? F_N : 0) | (v ? 0 : F_Z));
}

static void nz16(struct h8 *h, uint16_t v)
{
    h->ccr = (uint8_t)((h->ccr & ~(F_N | F_Z | F_V)) | (v & 0x8000 ? F_N : 0) | (v ? 0 : F_Z));
}

/* a + b + c or a - b - c, with every flag; `keepz`: Z only ever cleared (ADDX, SUBX) */
static uint8_t alu8(struct h8 *h, uint8_t a, uint8_t b, int c, int sub, int keepz)
{
    unsigned r = sub ? (unsigned)a - b - c : (unsigned)a + b + c;
    uint8_t f = (uint8_t)(h->ccr & ~(F_H | F_N | F_V | F_C | (keepz ? 0 : F_Z)));
    unsigned hh = sub ? (unsigned)(a & 15) - (b & 15) - c : (unsigned)(a & 15) + (b & 15) + c;
    if (hh & 0x10)
        f |= F_H;
    if (r & 0x100)
        f |= F_C;
    if ((sub ? (a ^ b) & (a ^ r) : ~(a ^ b) & (a ^ r)) & 0x80)
        f |= F_V;
    if (r & 0x80)
        f |= F_N;
    if (keepz ? (r & 0xFF) != 0 : (r & 0xFF) == 0)
        f = (uint8_t)(keepz ? f & ~F_Z : f | F_Z);
    h->ccr = f;
    return (uint8_t)r;
}

static uint16_t alu16(struct h8 *h, uint16_t a, uint16_t b, int sub)
{
    unsigned long r = sub ? (unsigned long)a - b : (unsigned long)a + b;
    unsigned long hh = sub ? (unsigned long)(a & 0xFFF) - (b & 0xFFF) : (unsigned long)(a & 0xFFF) + (b & 0xFFF);
    uint8_t f = (uint8_t)(h->ccr & ~(F_H | F_N | F_Z | F_V | F_C));
    if (hh & 0x1000)
        f |= F_H;
    if (r & 0x10000)
        f |= F_C;
    if ((sub ? (a ^ b) & (a ^ r) : ~(a ^ b) & (a ^ r)) & 0x8000)
        f |= F_V;
    if (r & 0x8000)
        f |= F_N;
    if (!(r & 0xFFFF))
        f |= F_Z;
    h->ccr = f;
    return (uint16_t)r;
}

static int cond(const struct h8 *h, int cc)
{
    int c = h->ccr & F_C, v = !!(h->ccr & F_V), z = h->ccr & F_Z, n = !!(h->ccr & F_N);
    int t;
    switch (cc >> 1) {
    case 0: t = 1; break;                 /* BRA / BRN */
    case 1: t = !(c || z); break;         /* BHI / BLS */
    case 2: t = !c; break;                /* BCC / BCS */
    case 3: t = !z; break;                /* BNE / BEQ */
    case 4: t = !v; break;                /* BVC / BVS */
    case 5: t = !n; break;                /* BPL / BMI */
    case 6: t = n == v; break;            /* BGE / BLT */
    default: t = !z && n == v; break;     /* BGT / BLE */
    }
    return cc & 1 ? !t : t;
}

/* shifts and rotates of 10-13 xx: xx bit 7 picks the second form */
static uint8_t shift(struct h8 *h, int op, int alt, uint8_t v)
{
    int c = h->ccr & F_C, out;
    uint8_t r, vflag = 0;
    switch (op) {
    case 0x10: out = v >> 7; r = (uint8_t)(v << 1); vflag = alt && ((v ^ r) & 0x80); break; /* SHLL / SHAL */
    case 0x11: out = v & 1; r = (uint8_t)(alt ? (v >> 1) | (v & 0x80) : v >> 1); break;     /* SHLR / SHAR */
    case 0x12: out = v >> 7; r = (uint8_t)(v << 1 | (alt ? out : c)); break;                /* ROTXL / ROTL */
    default: out = v & 1; r = (uint8_t)(v >> 1 | ((alt ? out : c) << 7)); break;            /* ROTXR / ROTR */
    }
    nz8(h, r);
    h->ccr = (uint8_t)((h->ccr & ~(F_C | F_V)) | (out ? F_C : 0) | (vflag ? F_V : 0));
    return r;
}

/* bit instructions 60-77 on a byte value; returns the new value (unchanged for tests and loads) */
static uint8_t bitop(struct h8 *h, int op, int bit, uint8_t v)
{
    int inv = bit & 8, b = bit & 7, c = h->ccr & F_C, x = (v >> b) & 1;
    if (inv && op >= 0x74)
        x = !x;
    switch (op) {
    case 0x60: case 0x70: return (uint8_t)(v | 1 << b);
    case 0x61: case 0x71: return (uint8_t)(v ^ 1 << b);
    case 0x62: case 0x72: return (uint8_t)(v & ~(1 << b));
    case 0x63: case 0x73: h->ccr = (uint8_t)(x ? h->ccr & ~F_Z : h->ccr | F_Z); return v;
    case 0x67: return (uint8_t)(((inv ? !c : c) ? v | 1 << b : v & ~(1 << b)));   /* BST / BIST */
    case 0x74: c = c | x; break;                                                 /* BOR */
    case 0x75: c = c ^ x; break;                                                 /* BXOR */
    case 0x76: c = c & x; break;                                                 /* BAND */
    default: c = x; break;                                                       /* BLD */
    }
    h->ccr = (uint8_t)((h->ccr & ~F_C) | (c ? F_C : 0));
    return v;
}

static int unknown(struct h8 *h, uint16_t at, uint16_t w)
{
    snprintf(h->error, sizeof h->error, "instruction %04X at %04X not simulated", w, at);
    return -1;
}

/*
 * 7B5C 598F, EEPMOV (H8/300 programming manual): while R4L is not 0, the byte at @R5 to @R6, R5 and R6 up by one,
 * R4L down by one. Flags unchanged. States 8 + 4n on-chip: the 2 words fetched, and source and destination each
 * accessed n + 1 times (the last read and write are not done here, only their states counted, at where R5 and R6
 * end). One step of the simulator, so no interrupt is taken in the middle, as on the chip (the H8/300 accepts none
 * during EEPMOV).
 */
static int eepmov(struct h8 *h, uint16_t at, uint16_t w1)
{
    if (w1 != 0x7B5C || fetch(h) != 0x598F)
        return unknown(h, at, w1);
    for (; h->r[4] & 0xFF; h->r[4]--) {
        wr8(h, h->r[6], rd8(h, h->r[5]));
        h->r[5]++;
        h->r[6]++;
    }
    h->states += (region(h->r[5]) == ONCHIP ? 2 : 3) + (region(h->r[6]) == ONCHIP ? 2 : 3);
    return h->error[0] ? -1 : 0;
}

/* 7C-7F: a bit instruction on memory, the operation in the second word */
static int membit(struct h8 *h, uint16_t at, uint16_t w1)
{
    uint16_t w2 = fetch(h);
    uint16_t a = (w1 >> 8) >= 0x7E ? (uint16_t)(0xFF00 | (w1 & 0xFF)) : h->r[(w1 >> 4) & 7];
    int op = w2 >> 8, writes = (w1 >> 8) == 0x7D || (w1 >> 8) == 0x7F;
    int bit = op <= 0x63 ? rb(h, (w2 >> 4) & 15) & 7 : (w2 >> 4) & 15;
    uint8_t v, nv;
    if (!(op >= 0x60 && op <= 0x63) && op != 0x67 && !(op >= 0x70 && op <= 0x77))
        return unknown(h, at, w2);
    v = rd8(h, a);
    nv = bitop(h, op, bit, v);
    if (writes)
        wr8(h, a, nv);
    return 0;
}

static int step(struct h8 *h)
{
    uint16_t at = h->pc, w = fetch(h), ea;
    int op = w >> 8, lo = w & 0xFF, hi4 = lo >> 4, lo4 = lo & 15;
    uint16_t *rs = &h->r[hi4 & 7], *rd = &h->r[lo4 & 7];

    h->error[0] = 0;
    h->insns++;
    if (op >= 0x80) { /* immediate byte forms */
        int r = op & 15;
        uint8_t d = rb(h, r);
        switch (op >> 4) {
        case 0x8: wb(h, r, alu8(h, d, (uint8_t)lo, 0, 0, 0)); break;
        case 0x9: wb(h, r, alu8(h, d, (uint8_t)lo, h->ccr & F_C, 0, 1)); break;
        case 0xA: alu8(h, d, (uint8_t)lo, 0, 1, 0); break;
        case 0xB: wb(h, r, alu8(h, d, (uint8_t)lo, h->ccr & F_C, 1, 1)); break;
        case 0xC: d |= lo; nz8(h, d); wb(h, r, d); break;
        case 0xD: d ^= lo; nz8(h, d); wb(h, r, d); break;
        case 0xE: d &= lo; nz8(h, d); wb(h, r, d); break;
        default: nz8(h, (uint8_t)lo); wb(h, r, (uint8_t)lo); break;
        }
        return h->error[0] ? -1 : 0;
    }
    if (op >= 0x20 && op < 0x40) { /* MOV.B @aa:8 */
        ea = (uint16_t)(0xFF00 | lo);
        if (op < 0x30) {
            uint8_t v = rd8(h, ea);
            nz8(h, v);
            wb(h, op & 15, v);
        } else {
            nz8(h, rb(h, op & 15));
            wr8(h, ea, rb(h, op & 15));
        }
        return 0;
    }
    if (op >= 0x40 && op < 0x50) { /* Bcc d:8 */
        if (cond(h, op & 15))
            h->pc = (uint16_t)(h->pc + (int8_t)lo);
        prefetch(h);
        return 0;
    }
    switch (op) {
    case 0x00: return lo ? unknown(h, at, w) : 0; /* NOP */
    case 0x01:
        if (lo != 0x80)
            return unknown(h, at, w);
        if (!h->may_sleep) {
            snprintf(h->error, sizeof h->error, "SLEEP at %04X", at);
            return -1;
        }
        h->asleep = 1; /* until an interrupt: the caller's to model */
        return 0;
    case 0x02: wb(h, lo4, h->ccr); return 0;
    case 0x03: h->ccr = rb(h, lo4); return 0;
    case 0x04: h->ccr |= (uint8_t)lo; return 0;
    case 0x05: h->ccr ^= (uint8_t)lo; return 0;
    case 0x06: h->ccr &= (uint8_t)lo; return 0;
    case 0x07: h->ccr = (uint8_t)lo; return 0;
    case 0x08: wb(h, lo4, alu8(h, rb(h, lo4), rb(h, hi4), 0, 0, 0)); return 0;
    case 0x09: *rd = alu16(h, *rd, *rs, 0); return 0;
    case 0x0A: {
            uint8_t v = (uint8_t)(rb(h, lo4) + 1);
            if (hi4)
                return unknown(h, at, w);
            wb(h, lo4, v);
            nz8(h, v);
            h->ccr = (uint8_t)(h->ccr | (v == 0x80 ? F_V : 0));
        }
        return 0;
    case 0x0B: *rd = (uint16_t)(*rd + (hi4 & 8 ? 2 : 1)); return 0; /* ADDS */
    case 0x0C: nz8(h, rb(h, hi4)); wb(h, lo4, rb(h, hi4)); return 0;
    case 0x0D: nz16(h, *rs); *rd = *rs; return 0;
    case 0x0E: wb(h, lo4, alu8(h, rb(h, lo4), rb(h, hi4), h->ccr & F_C, 0, 1)); return 0;
    case 0x10: case 0x11: case 0x12: case 0x13:
        wb(h, lo4, shift(h, op, hi4 & 8, rb(h, lo4)));
        return 0;
    case 0x14: wb(h, lo4, (uint8_t)(rb(h, lo4) | rb(h, hi4))); nz8(h, rb(h, lo4)); return 0;
    case 0x15: wb(h, lo4, (uint8_t)(rb(h, lo4) ^ rb(h, hi4))); nz8(h, rb(h, lo4)); return 0;
    case 0x16: wb(h, lo4, (uint8_t)(rb(h, lo4) & rb(h, hi4))); nz8(h, rb(h, lo4)); return 0;
    case 0x17:
        if (hi4 & 8)
            wb(h, lo4, alu8(h, 0, rb(h, lo4), 0, 1, 0)); /* NEG */
        else {
            wb(h, lo4, (uint8_t)~rb(h, lo4));
            nz8(h, rb(h, lo4));
        }
        return 0;
    case 0x18: wb(h, lo4, alu8(h, rb(h, lo4), rb(h, hi4), 0, 1, 0)); return 0;
    case 0x19: *rd = alu16(h, *rd, *rs, 1); return 0;
    case 0x1A: {
            uint8_t v = (uint8_t)(rb(h, lo4) - 1);
            if (hi4)
                return unknown(h, at, w);
            wb(h, lo4, v);
            nz8(h, v);
            h->ccr = (uint8_t)(h->ccr | (v == 0x7F ? F_V : 0));
        }
        return 0;
    case 0x1B: *rd = (uint16_t)(*rd - (hi4 & 8 ? 2 : 1)); return 0; /* SUBS */
    case 0x1C: alu8(h, rb(h, lo4), rb(h, hi4), 0, 1, 0); return 0;
    case 0x1D: alu16(h, *rd, *rs, 1); return 0;
    case 0x1E: wb(h, lo4, alu8(h, rb(h, lo4), rb(h, hi4), h->ccr & F_C, 1, 1)); return 0;
    case 0x50: *rd = (uint16_t)((*rd & 0xFF) * rb(h, hi4)); h->states += 12; return 0; /* MULXU */
    case 0x51: { /* DIVXU: RdL = quotient, RdH = remainder */
            uint8_t d = rb(h, hi4);
            h->states += 12;
            if (!d)
                return unknown(h, at, w);
            if (*rd / d > 0xFF) {
                snprintf(h->error, sizeof h->error, "DIVXU overflow at %04X", at);
                return -1;
            }
            *rd = (uint16_t)((*rd % d) << 8 | *rd / d);
            return 0;
        }
    case 0x54: h->pc = rd16(h, h->r[7]); h->r[7] = (uint16_t)(h->r[7] + 2); h->states += 2; prefetch(h); return 0;
    case 0x55: /* BSR */
        h->r[7] = (uint16_t)(h->r[7] - 2);
        wr16(h, h->r[7], h->pc);
        h->pc = (uint16_t)(h->pc + (int8_t)lo);
        prefetch(h);
        return 0;
    case 0x56: /* RTE */
        h->ccr = (uint8_t)rd16(h, h->r[7]);
        h->pc = rd16(h, (uint16_t)(h->r[7] + 2));
        h->r[7] = (uint16_t)(h->r[7] + 4);
        h->states += 2;
        prefetch(h);
        return 0;
    case 0x59: h->pc = *rs; prefetch(h); return 0; /* JMP @Rn */
    case 0x5A: h->pc = fetch(h); h->states += 2; return 0;
    case 0x5B: h->pc = rd16(h, (uint16_t)lo); h->states += 2; prefetch(h); return 0;
    case 0x5D: case 0x5E: case 0x5F: { /* JSR */
            uint16_t to = op == 0x5D ? *rs : op == 0x5E ? fetch(h) : rd16(h, (uint16_t)lo);
            h->r[7] = (uint16_t)(h->r[7] - 2);
            wr16(h, h->r[7], h->pc);
            h->pc = to;
            if (op == 0x5E)
                h->states += 2;
            else
                prefetch(h);
            return 0;
        }
    case 0x60: case 0x61: case 0x62: case 0x63:
        wb(h, lo4, bitop(h, op, rb(h, hi4) & 7, rb(h, lo4)));
        return 0;
    case 0x67: case 0x70: case 0x71: case 0x72: case 0x73: case 0x74: case 0x75: case 0x76: case 0x77:
        wb(h, lo4, bitop(h, op, hi4, rb(h, lo4)));
        return 0;
    case 0x68: case 0x6C: case 0x6E: { /* MOV.B @Rn, @Rn+ / @-Rn, @(d:16,Rn) */
            uint16_t *ar = &h->r[hi4 & 7];
            int store = hi4 & 8;
            if (op == 0x6E)
                ea = (uint16_t)(*ar + fetch(h));
            else if (op == 0x6C && store)
                ea = *ar = (uint16_t)(*ar - 1);
            else
                ea = *ar;
            if (store) {
                nz8(h, rb(h, lo4));
                wr8(h, ea, rb(h, lo4));
            } else {
                uint8_t v = rd8(h, ea);
                nz8(h, v);
                if (op == 0x6C)
                    *ar = (uint16_t)(*ar + 1);
                wb(h, lo4, v);
            }
            if (op == 0x6C)
                h->states += 2;
            return 0;
        }
    case 0x69: case 0x6D: case 0x6F: { /* MOV.W, the same forms; 6D with r7 is push and pop */
            uint16_t *ar = &h->r[hi4 & 7];
            int store = hi4 & 8;
            if (op == 0x6F)
                ea = (uint16_t)(*ar + fetch(h));
            else if (op == 0x6D && store)
                ea = *ar = (uint16_t)(*ar - 2);
            else
                ea = *ar;
            if (store) {
                nz16(h, *rd);
                wr16(h, ea, *rd);
            } else {
                uint16_t v = rd16(h, ea);
                nz16(h, v);
                if (op == 0x6D)
                    *ar = (uint16_t)(*ar + 2);
                *rd = v;
            }
            if (op == 0x6D)
                h->states += 2;
            return h->error[0] ? -1 : 0;
        }
    case 0x6A: case 0x6B: /* MOV @aa:16 */
        ea = fetch(h);
        if (hi4 != 0 && hi4 != 8)
            return unknown(h, at, w);
        if (op == 0x6A) {
            if (hi4) {
                nz8(h, rb(h, lo4));
                wr8(h, ea, rb(h, lo4));
            } else {
                uint8_t v = rd8(h, ea);
                nz8(h, v);
                wb(h, lo4, v);
            }
        } else if (hi4) {
            nz16(h, *rd);
            wr16(h, ea, *rd);
        } else {
            *rd = rd16(h, ea);
            nz16(h, *rd);
        }
        return h->error[0] ? -1 : 0;
    case 0x79:
        if (hi4)
            return unknown(h, at, w);
        *rd = fetch(h);
        nz16(h, *rd);
        return 0;
    case 0x7B:
        return eepmov(h, at, w);
    case 0x7C: case 0x7D: case 0x7E: case 0x7F:
        return membit(h, at, w);
    default:
        return unknown(h, at, w);
    }
}

/* Interrupt exception handling: PC and CCR pushed (a word each, CCR in both bytes), I set, the vector read from
 * on-chip ROM, then the fetch at the handler. About 14 states with the stack on-chip, as on the RCX. */
void h8_interrupt(struct h8 *h, uint16_t handler)
{
    h->r[7] = (uint16_t)(h->r[7] - 2);
    wr16(h, h->r[7], h->pc);
    h->r[7] = (uint16_t)(h->r[7] - 2);
    wr16(h, h->r[7], (uint16_t)(h->ccr << 8 | h->ccr));
    h->ccr |= F_I;
    h->states += 2 + 4; /* the vector, internal states */
    h->pc = handler;
    prefetch(h);
    prefetch(h);
    h->asleep = 0;
}

void h8_reset(struct h8 *h)
{
    memset(h, 0, sizeof *h);
    h->r[7] = 0xFF80;
    h->ccr = F_I;
}

static int hexval(const char *s, int n)
{
    int v = 0;
    while (n--) {
        int c = *s++;
        v = v * 16 + (c >= '0' && c <= '9' ? c - '0' : c >= 'A' && c <= 'F' ? c - 'A' + 10 : c - 'a' + 10);
    }
    return v;
}

int h8_load_srec(struct h8 *h, const char *path)
{
    char line[600];
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    while (fgets(line, sizeof line, f)) {
        int n, a, i;
        if (line[0] != 'S' || line[1] != '1')
            continue;
        n = hexval(line + 2, 2) - 3;
        a = hexval(line + 4, 4);
        for (i = 0; i < n; i++)
            h->mem[(a + i) & 0xFFFF] = (uint8_t)hexval(line + 8 + 2 * i, 2);
    }
    fclose(f);
    return 0;
}

int h8_step(struct h8 *h)
{
    int rc = step(h);

    if (!h->ram_fault[0])
        return rc;
    snprintf(h->error, sizeof h->error, "%s", h->ram_fault);
    return -1;
}

int h8_step_traced(struct h8 *h)
{
    uint16_t pc = h->pc;
    unsigned long long before = h->states;

    if (h8_step(h))
        return -1;
    if (h->trace)
        h->trace(h, pc, (unsigned)(h->states - before));
    return 0;
}

long h8_call(struct h8 *h, uint16_t addr, uint16_t r0, uint16_t r1, uint16_t r2,
             const uint16_t *stack, int nstack, unsigned long max_insns)
{
    int i;
    h->r[0] = r0;
    h->r[1] = r1;
    h->r[2] = r2;
    for (i = nstack - 1; i >= 0; i--) {
        h->r[7] = (uint16_t)(h->r[7] - 2);
        h8_write16(h, h->r[7], stack[i]);
    }
    h->r[7] = (uint16_t)(h->r[7] - 2);
    h8_write16(h, h->r[7], RETURN_MAGIC);
    h->pc = addr;
    while (h->pc != RETURN_MAGIC) {
        if (!max_insns--) {
            snprintf(h->error, sizeof h->error, "no return after the instruction limit (pc %04X)", h->pc);
            return -1;
        }
        if (h->pc < 0x8000) {
            snprintf(h->error, sizeof h->error, "jump into the ROM (%04X)", h->pc);
            return -1;
        }
        if (h8_step_traced(h))
            return -1;
    }
    h->r[7] = (uint16_t)(h->r[7] + 2 * nstack);
    return h->r[0];
}
