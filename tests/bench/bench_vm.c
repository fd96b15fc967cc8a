/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Host interpreter throughput for the x++ loop of reference-firmware.md ("sumv var,1 ; jmp back": two byte codes
 * per iteration) with 1 and with 10 tasks.
 *   bench_vm            time each case for about a second and print byte codes per second
 *   bench_vm --count N T  run exactly N byte codes with T tasks and print nothing (for callgrind)
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "brick.h"

static struct rcx *setup(unsigned tasks)
{
    struct rcx *b = brick_new();
    unsigned n;
    for (n = 0; n < tasks; n++) {
        /* sumv var[n], 1 ; jmp -6 (back to the sumv) */
        const u8 code[] = { 0x24, (u8)n, 0x02, 0x01, 0x00, 0x27, 0x86 };
        if (brick_download(b, 1, (u8)n, code, sizeof code) != 0) {
            fprintf(stderr, "download failed\n");
            exit(1);
        }
    }
    for (n = 0; n < tasks; n++)
        brick_start(b, (u8)n);
    return b;
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec / 1e9;
}

int main(int argc, char **argv)
{
    static const unsigned cases[] = { 1, 10 };
    unsigned c;
    unsigned long fixed = 0;
    unsigned only = 0;
    int counting = 0;

    if (argc == 4 && strcmp(argv[1], "--count") == 0) {
        fixed = strtoul(argv[2], NULL, 10);
        only = (unsigned)strtoul(argv[3], NULL, 10);
        counting = 1;
    }
    for (c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        struct rcx *b;
        if (only && cases[c] != only)
            continue;
        b = setup(cases[c]);
        unsigned long done = 0;
        double start = now(), elapsed;

        if (counting) {
            while (done < fixed)
                done += vm_run(b, (u16)(fixed - done > 1000 ? 1000 : fixed - done));
        } else {
            do {
                unsigned i;
                for (i = 0; i < 1000; i++) {
                    done += vm_run(b, 1000); /* 1000 byte codes, then one simulated millisecond */
                    vm_tick(b);
                }
                elapsed = now() - start;
            } while (elapsed < 1.0);
            printf("host interpreter, %2u task%s: %6.1f million byte codes/s (x = %d)\n", cases[c],
                   cases[c] == 1 ? " " : "s", done / elapsed / 1e6, b->global[0]);
        }
        brick_free(b);
    }
    return 0;
}
