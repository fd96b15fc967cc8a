/* SPDX-License-Identifier: MPL-2.0 */
/* The packer and the reference unpacker of the image's download (format: pack.h). */
#include <stdlib.h>
#include <string.h>
#include "pack.h"

#define MIN_MATCH 2
#define MAX_MATCH 256      /* v = 255, the largest 8-bit gamma */
#define MAX_G 255          /* -g must fit the unpacker's byte */
#define MAX_OFFSET (256ul * MAX_G)

/* ---- Unpacking: the steps of unpack.s on a copy of memory ---- */

struct reader {
    uint8_t *mem;
    size_t r, r_end;        /* next packed byte, end of the packed bytes */
    size_t w, w_start, w_end;
    unsigned bits;          /* unpack.s's r3l: bits left, above a 1 that marks their end */
    const char *error;
};

static int next_bit(struct reader *s)
{
    unsigned c = s->bits >> 7 & 1;
    s->bits = s->bits << 1 & 0xFF;
    if (s->bits == 0) { /* the marker went out: take the next bit byte, and the marker back in at bit 0 */
        unsigned b;
        if (s->r >= s->r_end) {
            s->error = "stream ends inside an item";
            return 0;
        }
        b = s->mem[s->r++];
        s->bits = (b << 1 | c) & 0xFF;
        c = b >> 7;
    }
    return (int)c;
}

static unsigned read_gamma(struct reader *s)
{
    unsigned v = 1;
    while (!next_bit(s) && !s->error)
        v = (v << 1 | (unsigned)next_bit(s)) & 0xFF;
    return v;
}

static void put(struct reader *s, size_t from)
{
    if (s->w >= s->w_end)
        s->error = "match runs past the end of the output";
    else if (s->w >= s->r && s->r < s->r_end)
        s->error = "output overtakes packed bytes not read yet";
    else
        s->mem[s->w++] = s->mem[from];
}

static void run(struct reader *s)
{
    s->bits = 0x80;
    while (s->w < s->w_end && !s->error) {
        if (!next_bit(s)) {
            if (s->r >= s->r_end)
                s->error = "stream ends inside an item";
            else
                put(s, s->r++);
        } else {
            unsigned g = read_gamma(s), v, b;
            size_t from;
            if (s->r >= s->r_end)
                s->error = "stream ends inside an item";
            if (s->error)
                return;
            b = s->mem[s->r++];
            v = read_gamma(s);
            if (g == 0 || 256ul * g - b > s->w - s->w_start) {
                s->error = "match reaches before the output";
                return;
            }
            from = s->w - (256ul * g - b);
            do
                put(s, from++);
            while (v-- != 0 && !s->error);
        }
    }
    if (!s->error && s->r != s->r_end)
        s->error = "bytes left after the output is complete";
}

const char *unpack(const uint8_t *in, size_t len, uint8_t *out, size_t n)
{
    struct reader s = {0};
    s.mem = malloc(n + len + 1);
    if (!s.mem)
        return "out of memory";
    memcpy(s.mem + n, in, len);
    s.r = n;
    s.r_end = n + len;
    s.w_end = n;
    run(&s);
    memcpy(out, s.mem, n);
    free(s.mem);
    return s.error;
}

const char *pack_check_in_place(const struct pack_layout *l, const uint8_t *image, const uint8_t *unpacker,
                                const uint8_t *packed, size_t len)
{
    static uint8_t mem[0x10000];
    size_t shift = l->ram_end - l->download_end;
    struct reader s = {0};

    if (!(l->base <= l->head_end && l->head_end <= l->packed_start && l->head_end < l->image_end &&
          l->image_end <= l->ram_end && l->packed_start <= l->download_end && l->download_end <= l->ram_end &&
          l->ram_end <= sizeof mem))
        return "layout symbols out of order";
    if (l->packed_start + len > l->download_end)
        return "download larger than the unpacker moves up (the image budget)";
    memset(mem, 0xA5, sizeof mem); /* RAM holds garbage */
    memcpy(mem + l->base, image, l->head_end - l->base);
    memcpy(mem + l->head_end, unpacker, l->packed_start - l->head_end);
    memcpy(mem + l->packed_start, packed, len);
    memmove(mem + l->packed_start + shift, mem + l->packed_start, l->download_end - l->packed_start);
    s.mem = mem;
    s.r = l->packed_start + shift;
    s.r_end = s.r + len;
    s.w = s.w_start = l->head_end;
    s.w_end = l->image_end;
    run(&s);
    if (s.error)
        return s.error;
    if (memcmp(mem + l->base, image, l->image_end - l->base))
        return "unpacked bytes differ from the image";
    return NULL;
}

/* ---- Packing ---- */

static unsigned gamma_bits(unsigned long x)
{
    unsigned n = 1;
    while (x > 1) {
        x >>= 1;
        n += 2;
    }
    return n;
}

static unsigned match_bits(unsigned len, unsigned long off)
{
    return 1 + gamma_bits((off + 255) / 256) + 8 + gamma_bits(len - 1);
}

struct writer {
    uint8_t *out;
    size_t len, bit_at;
    unsigned bits_left;
};

static void put_bit(struct writer *w, unsigned b)
{
    if (w->bits_left == 0) {
        w->bit_at = w->len;
        w->out[w->len++] = 0;
        w->bits_left = 8;
    }
    w->bits_left--;
    if (b)
        w->out[w->bit_at] |= (uint8_t)(1u << w->bits_left);
}

static void put_gamma(struct writer *w, unsigned x)
{
    int top = 7;
    while (top > 0 && !(x >> top))
        top--;
    while (top-- > 0) {
        put_bit(w, 0);
        put_bit(w, x >> top & 1);
    }
    put_bit(w, 1);
}

size_t pack(const uint8_t *in, size_t n, uint8_t *out)
{
    /* cost[i]: fewest bits for in[0..i); len/off: the item that ends there (len 1: literal). */
    unsigned long *cost = malloc((n + 1) * sizeof *cost), *off = malloc((n + 1) * sizeof *off);
    unsigned *len = malloc((n + 1) * sizeof *len);
    long *prev = malloc((n + 1) * sizeof *prev), *head = malloc(65536 * sizeof *head);
    unsigned long best_off[MAX_MATCH + 1];
    struct writer w = {out, 0, 0, 0};
    size_t i, items = 0, *order = NULL;

    if (!cost || !off || !len || !prev || !head)
        goto out;
    for (i = 0; i < 65536; i++)
        head[i] = -1;
    for (i = 0; i <= n; i++)
        cost[i] = (unsigned long)-1;
    cost[0] = 0;
    for (i = 0; i < n; i++) {
        unsigned longest = 1, l;
        long j;
        if (cost[i] + 9 < cost[i + 1]) {
            cost[i + 1] = cost[i] + 9;
            len[i + 1] = 1;
        }
        if (i + 1 >= n)
            continue;
        /* Earlier places with the same two bytes, nearest first: the nearest for each length is the cheapest. */
        for (j = head[in[i] << 8 | in[i + 1]]; j >= 0 && i - (size_t)j <= MAX_OFFSET && longest < MAX_MATCH;
             j = prev[j]) {
            unsigned m = 2;
            while (i + m < n && m < MAX_MATCH && in[j + m] == in[i + m])
                m++;
            for (l = longest + 1; l <= m; l++)
                best_off[l] = i - (size_t)j;
            if (m > longest)
                longest = m;
        }
        prev[i] = head[in[i] << 8 | in[i + 1]];
        head[in[i] << 8 | in[i + 1]] = (long)i;
        for (l = MIN_MATCH; l <= longest; l++) {
            unsigned long c = cost[i] + match_bits(l, best_off[l]);
            if (c < cost[i + l]) {
                cost[i + l] = c;
                len[i + l] = l;
                off[i + l] = best_off[l];
            }
        }
    }
    /* The chosen items, from the end back, then written in order. */
    order = malloc((n + 1) * sizeof *order);
    if (!order)
        goto out;
    for (i = n; i > 0; i -= len[i])
        order[items++] = i;
    while (items-- > 0) {
        size_t end = order[items];
        if (len[end] == 1) {
            put_bit(&w, 0);
            w.out[w.len++] = in[end - 1];
        } else {
            unsigned g = (unsigned)((off[end] + 255) / 256);
            put_bit(&w, 1);
            put_gamma(&w, g);
            w.out[w.len++] = (uint8_t)(256u * g - off[end]);
            put_gamma(&w, len[end] - 1);
        }
    }
out:
    free(cost);
    free(off);
    free(len);
    free(prev);
    free(head);
    free(order);
    return w.len;
}
