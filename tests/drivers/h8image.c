#define _POSIX_C_SOURCE 200809L /* popen */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "h8image.h"

#define SYMS 2048

static struct { char name[64]; uint16_t addr; char code; } sym[SYMS];
static int nsym;

long h8_sym(const char *name)
{
    int i;
    for (i = 0; i < nsym; i++)
        if (!strcmp(sym[i].name, name))
            return sym[i].addr;
    return -1;
}

int h8_image_load(struct h8 *h, const char *image, const char *nm)
{
    char line[512], type[8], name[64];
    unsigned long addr;
    long lo, hi;
    FILE *f;

    h8_reset(h);
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
    lo = h8_sym("_rcx_bss_start");
    hi = h8_sym("_rcx_bss_end");
    if (lo < 0 || hi < lo) {
        fprintf(stderr, "%s: no .bss symbols\n", image);
        return -1;
    }
    memset(h->mem + lo, 0, (size_t)(hi - lo));
    lo = h8_sym("_rcx_onchip_start");
    hi = h8_sym("_rcx_onchip_top"); /* crt0.s clears on-chip RAM up to the top, the .eight variables included */
    if (hi < 0)
        hi = h8_sym("_rcx_onchip_end");
    if (lo >= 0 && hi >= lo)
        memset(h->mem + lo, 0, (size_t)(hi - lo));
    hi = h8_sym("_rcx_stack_top"); /* and starts the stack there, below the .eight variables */
    if (hi > 0)
        h->r[7] = (uint16_t)hi;
    return 0;
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
