/* SPDX-License-Identifier: MPL-2.0 */
#define _POSIX_C_SOURCE 200809L /* popen */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "h8image.h"

#define SYMS 2048

static struct { char name[64]; uint16_t addr; char code; } sym[SYMS];
static int nsym;

int h8_image_args(int argc, char **argv, const char **image, const char **nm)
{
    if (argc != 3) {
        fprintf(stderr, "usage: %s <firmware image> <h8300 nm>\n", argv[0]);
        return 2;
    }
    *image = argv[1];
    *nm = argv[2];
    return 0;
}

long h8_sym(const char *name)
{
    int i;
    for (i = 0; i < nsym; i++)
        if (!strcmp(sym[i].name, name))
            return sym[i].addr;
    return -1;
}

int h8_image_read(struct h8 *h, const char *image, const char *nm)
{
    char line[512], type[8], name[64];
    unsigned long addr;
    FILE *f;

    h8_reset(h);
    /* The ROM drives P5.2 low from its first instructions (rcx-hardware.md 2.4): external RAM awake, and it must
     * stay so for as long as anything is fetched from it. */
    h->mem[0xFFB8] = 0x04;
    h->ram_guard = 1;
    snprintf(line, sizeof line, "%s.srec", image);
    if (h8_load_srec(h, line)) {
        fprintf(stderr, "cannot read %s (make firmware)\n", line);
        return -1;
    }
    snprintf(line, sizeof line, "'%s' '%s'", nm, image);
    f = popen(line, "r");
    if (!f) {
        fprintf(stderr, "cannot run %s\n", line);
        return -1;
    }
    nsym = 0;
    while (fgets(line, sizeof line, f) && nsym < SYMS)
        if (sscanf(line, "%lx %7s %63s", &addr, type, name) == 3) {
            strcpy(sym[nsym].name, name);
            sym[nsym].code = (char)((type[0] == 'T' || type[0] == 't') && name[0] == '_');
            sym[nsym++].addr = (uint16_t)addr;
        }
    if (pclose(f) != 0 || !nsym) {
        fprintf(stderr, "%s %s failed\n", nm, image);
        return -1;
    }
    return 0;
}

unsigned long long h8_unpack_states;

int h8_image_start(struct h8 *h)
{
    long entry = h8_sym("_start"), main_at = h8_sym("_main"), top = h8_sym("_rcx_stack_top");
    long head_end = h8_sym("_rcx_head_end");
    unsigned long n;
    uint16_t was = 0;

    if (entry < 0 || main_at < 0 || top < 0) {
        fprintf(stderr, "image without _start, _main or _rcx_stack_top\n");
        return -1;
    }
    /* As the ROM calls it: with jsr, on the ROM's stack in on-chip RAM. */
    h->r[7] = 0xFF7C;
    h8_write16(h, h->r[7], 0x0000);
    h->pc = (uint16_t)entry;
    h->states = 0;
    h8_unpack_states = 0;
    for (n = 0; h->pc != (uint16_t)main_at; n++) {
        if (h->pc == (uint16_t)head_end && was >= 0xF000) /* back from the unpacker, which runs on-chip */
            h8_unpack_states = h->states;
        was = h->pc;
        if (n == 3000000ul || h->pc < 0x8000) {
            fprintf(stderr, "crt0: main not reached (pc %04X)\n", h->pc);
            return -1;
        }
        if (h8_step(h)) {
            fprintf(stderr, "crt0: %s\n", h->error);
            return -1;
        }
    }
    h->r[7] = (uint16_t)top; /* as when main was called, less crt0's return address */
    return 0;
}

int h8_image_load(struct h8 *h, const char *image, const char *nm)
{
    return h8_image_read(h, image, nm) || h8_image_start(h) ? -1 : 0;
}

const char *h8_func_at(uint16_t pc)
{
    int i, best = -1;
    for (i = 0; i < nsym; i++)
        if (sym[i].code && sym[i].addr <= pc && (best < 0 || sym[i].addr > sym[best].addr))
            best = i;
    return best < 0 ? "?" : sym[best].name + 1;
}

long h8_run(struct h8 *h, const char *name, uint16_t r0, uint16_t r1, uint16_t r2, const uint16_t *stack, int nstack)
{
    long a = h8_sym(name), r;
    if (a < 0) {
        fprintf(stderr, "symbol %s not in the image\n", name);
        exit(1);
    }
    r = h8_call(h, (uint16_t)a, r0, r1, r2, stack, nstack, 50000000ul);
    if (r < 0 && h->error[0]) {
        fprintf(stderr, "%s: %s\n", name, h->error);
        exit(1);
    }
    return r;
}
